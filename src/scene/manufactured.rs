//! `[manufactured]` and `[reference]`: plain data for a scene that carries
//! its own reference (MODEL §8, §11), with the range checks that need
//! nothing but the table itself. What the data mean, and the checks that
//! need the beam and the carriers (supports met, a unilateral contact kept
//! closed), are in `crate::manufactured`.
//!
//! ```toml
//! [[manufactured.term]]            # v*(x, t) = Σ amplitude · X(x) · T̂(t)
//! amplitude = 1e-3                 # m
//! x = [{ kind = "sine", half_waves = 1 }, { kind = "polynomial", coefficients = [1, 0.5] }]
//! t = [{ kind = "sine", frequency = 4 }]
//!
//! [manufactured.loss]              # optional: every mass carrier loses contact
//! start = 0.06                     # s
//! end = 0.09                       # s
//! gap = 2e-4                       # m, the largest gap in it
//! blend = 0.02                     # s, λ* falls to 0 over this before start
//! ```

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// Most terms in v* (each adds two load vectors to a step's work).
pub(crate) const MAX_TERMS: usize = 8;

/// Most coefficients of a polynomial factor (degree 8).
pub(crate) const MAX_COEFFICIENTS: usize = 9;

/// Largest |half_waves| of an x-sine: 100 half-waves need ≳ 400 Hermite
/// elements to resolve; more is no longer a smooth test function.
pub(crate) const MAX_HALF_WAVES: f64 = 100.0;

/// Largest |rate| of an x-exponential e^{rate·ξ}: e^{±30} spans 26 decades,
/// beyond which the source is round-off at one end.
pub(crate) const MAX_X_RATE: f64 = 30.0;

/// Largest |rate|·t_end of a t-exponential (same reason as [`MAX_X_RATE`]).
pub(crate) const MAX_T_EXPONENT: f64 = 30.0;

/// Largest frequency of a t-sine, Hz: a smooth test motion is resolved by
/// any step a run takes (ten steps a period at Δt = 1e-5 s).
pub(crate) const MAX_FREQUENCY: f64 = 1e4;

/// `[manufactured]`: a manufactured beam motion (MODEL §11).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ManufacturedSpec {
    /// The terms of v*(x, t) (`[[manufactured.term]]`), 1 ..= 8.
    #[serde(rename = "term")]
    pub terms: Vec<TermSpec>,
    /// A prescribed loss of contact of every mass carrier (`[manufactured.loss]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loss: Option<LossSpec>,
    /// The messenger wire's motion v_m*(x, t) (`[manufactured.messenger]`,
    /// needs a `[messenger]`); absent: v_m* = 0, the messenger held still
    /// by its source (`docs/verification.md`, two coupled wires).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub messenger: Option<MessengerMotionSpec>,
}

/// `[manufactured.messenger]`: the messenger's manufactured motion
/// v_m*(x, t) = Σ amplitude · X(x) · T̂(t), the same factor syntax as the
/// contact wire's terms; each x-shape is made to vanish at every messenger
/// support (`crate::manufactured`).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MessengerMotionSpec {
    /// The terms of v_m* (`[[manufactured.messenger.term]]`), 1 ..= 8.
    #[serde(rename = "term")]
    pub terms: Vec<TermSpec>,
}

/// One term `amplitude · X(x) · T̂(t)` of v* (positive up, MODEL §1).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TermSpec {
    /// Amplitude, m (finite, ≠ 0).
    pub amplitude: f64,
    /// The x-shape S(ξ), ξ = x/L: a product of factors (empty: 1). taut
    /// subtracts the polynomial that makes it meet the supports.
    #[serde(default)]
    pub x: Vec<XFactor>,
    /// The time part T(t): a product of factors (non-empty). taut uses
    /// T̂(t) = T(t) − T(0) − T'(0)·t, so the beam starts straight and at rest.
    pub t: Vec<TFactor>,
}

/// A factor of the x-shape, in ξ = x/L.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum XFactor {
    /// Σₖ cₖ ξᵏ (1 ..= 9 coefficients, dimensionless).
    Polynomial {
        /// c₀, c₁, ….
        coefficients: Vec<f64>,
    },
    /// sin(n π ξ + φ).
    Sine {
        /// n, half-waves over the span (|n| ≤ 100).
        half_waves: f64,
        /// φ, rad (default 0).
        #[serde(default)]
        phase: f64,
    },
    /// e^{a ξ}.
    Exponential {
        /// a, dimensionless (|a| ≤ 30).
        rate: f64,
    },
}

/// A factor of the time part, in t (s).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum TFactor {
    /// Σₖ cₖ tᵏ (1 ..= 9 coefficients, cₖ in s⁻ᵏ).
    Polynomial {
        /// c₀, c₁, ….
        coefficients: Vec<f64>,
    },
    /// sin(2π f t + φ).
    Sine {
        /// f, Hz (0 ..= 1e4).
        frequency: f64,
        /// φ, rad (default 0).
        #[serde(default)]
        phase: f64,
    },
    /// e^{a t}.
    Exponential {
        /// a, 1/s (|a|·t_end ≤ 30).
        rate: f64,
    },
}

/// `[manufactured.loss]`: every mass carrier leaves the beam on
/// (start, end) and rejoins it (MODEL §11).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LossSpec {
    /// Start of the loss t_a, s (> blend).
    pub start: f64,
    /// End of the loss t_b, s (> start, end + blend ≤ the run's end).
    pub end: f64,
    /// The largest gap, m (> 0), at the middle of the loss.
    pub gap: f64,
    /// Width τ over which λ* falls to 0 before t_a and rises after t_b, s (> 0).
    pub blend: f64,
}

/// `[reference]`: what `taut converge` and `taut verify` measure this
/// scene's errors against (MODEL §8). A scene with `[manufactured]` has the
/// manufactured solution as its reference and needs no `[reference]`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ReferenceSpec {
    /// The reference.
    pub kind: ReferenceKind,
    /// Galerkin modes J of a `riding_mass_galerkin` reference (default
    /// clamp(4N, 800, 3200) for the finest mesh N of a study).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
}

/// `reference.kind`.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ReferenceKind {
    /// The modal series of a constant force moving at constant speed over a
    /// pinned–pinned string or tensioned beam (MODEL §8).
    MovingForceSeries,
    /// A mass without spring riding bilaterally at constant speed over a
    /// pinned–pinned tensioned beam: the Galerkin solution in the exact
    /// modes with the convective terms (MODEL §9.2).
    RidingMassGalerkin,
    /// The exact time history of the *discretized* beam under standing
    /// forces switched on at t = 0: Σ φⱼφⱼᵀF(1 − cos ωⱼt)/ωⱼ² over the
    /// model's own eigenpairs. No space error: a pure Δt reference.
    StandingForceModes,
    /// Richardson extrapolation of the study's own finest levels (the default).
    Richardson,
}

impl ReferenceKind {
    /// The scene's name of this kind.
    pub fn name(self) -> &'static str {
        match self {
            ReferenceKind::MovingForceSeries => "moving_force_series",
            ReferenceKind::RidingMassGalerkin => "riding_mass_galerkin",
            ReferenceKind::StandingForceModes => "standing_force_modes",
            ReferenceKind::Richardson => "richardson",
        }
    }
}

fn finite(field: &str, v: f64, what: &str) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::invalid(
            field,
            v,
            format!("must be a finite number ({what})"),
        ))
    }
}

fn within(field: &str, v: f64, max: f64, what: &str) -> Result<f64> {
    finite(field, v, what)?;
    if v.abs() <= max {
        Ok(v)
    } else {
        Err(Error::invalid(
            field,
            v,
            format!("must be in [−{max}, {max}] ({what})"),
        ))
    }
}

fn coefficients(field: &str, c: &[f64], unit: &str) -> Result<()> {
    if c.is_empty() || c.len() > MAX_COEFFICIENTS {
        return Err(Error::invalid(
            field,
            format!("{} coefficients", c.len()),
            format!("must have 1 ..= {MAX_COEFFICIENTS} (degree ≤ 8)"),
        ));
    }
    for (k, v) in c.iter().enumerate() {
        finite(&format!("{field}.{k}"), *v, unit)?;
    }
    Ok(())
}

/// The range checks of one line's terms (`prefix`: `manufactured` or
/// `manufactured.messenger`).
fn check_terms(terms: &[TermSpec], prefix: &str, t_end: f64) -> Result<()> {
    if terms.is_empty() || terms.len() > MAX_TERMS {
        return Err(Error::invalid(
            format!("{prefix}.term"),
            format!("{} terms", terms.len()),
            format!("must have 1 ..= {MAX_TERMS} [[{prefix}.term]] tables"),
        ));
    }
    for (i, term) in terms.iter().enumerate() {
        let f = |k: &str| format!("{prefix}.term.{i}.{k}");
        finite(&f("amplitude"), term.amplitude, "m")?;
        if term.amplitude == 0.0 {
            return Err(Error::invalid(
                f("amplitude"),
                0,
                "must be ≠ 0 (m): a zero term adds nothing",
            ));
        }
        for (k, x) in term.x.iter().enumerate() {
            let g = |key: &str| f(&format!("x.{k}.{key}"));
            match x {
                XFactor::Polynomial { coefficients: c } => {
                    coefficients(&g("coefficients"), c, "dimensionless")?
                }
                XFactor::Sine { half_waves, phase } => {
                    within(
                        &g("half_waves"),
                        *half_waves,
                        MAX_HALF_WAVES,
                        "half-waves over L",
                    )?;
                    if *half_waves == 0.0 {
                        return Err(Error::invalid(
                            g("half_waves"),
                            0,
                            "makes sin(0·πξ + φ) = sin φ a constant, which the supports' correction removes (or 0): must be ≠ 0 (half-waves over L, |n| ≤ 100)",
                        ));
                    }
                    finite(&g("phase"), *phase, "rad")?;
                }
                XFactor::Exponential { rate } => {
                    within(&g("rate"), *rate, MAX_X_RATE, "e^{rate·x/L}")?;
                }
            }
        }
        if term.t.is_empty() {
            return Err(Error::invalid(
                f("t"),
                "[]",
                "needs at least one factor: a constant time part is removed with its value at t = 0, leaving nothing",
            ));
        }
        for (k, t) in term.t.iter().enumerate() {
            let g = |key: &str| f(&format!("t.{k}.{key}"));
            match t {
                TFactor::Polynomial { coefficients: c } => {
                    coefficients(&g("coefficients"), c, "s⁻ᵏ")?
                }
                TFactor::Sine { frequency, phase } => {
                    finite(&g("frequency"), *frequency, "Hz")?;
                    if !(0.0..=MAX_FREQUENCY).contains(frequency) {
                        return Err(Error::invalid(
                            g("frequency"),
                            frequency,
                            format!("must be in [0, {MAX_FREQUENCY}] Hz"),
                        ));
                    }
                    finite(&g("phase"), *phase, "rad")?;
                }
                TFactor::Exponential { rate } => {
                    finite(&g("rate"), *rate, "1/s")?;
                    if rate.abs() * t_end > MAX_T_EXPONENT {
                        return Err(Error::invalid(
                            g("rate"),
                            rate,
                            format!(
                                "must have |rate|·time.end ≤ {MAX_T_EXPONENT} (here time.end = {t_end} s): |rate| ≤ {:.4e} 1/s",
                                MAX_T_EXPONENT / t_end
                            ),
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

impl ManufacturedSpec {
    /// The range checks of the table alone (`t_end`: the run's end, s).
    pub fn check(&self, t_end: f64) -> Result<()> {
        check_terms(&self.terms, "manufactured", t_end)?;
        if let Some(m) = &self.messenger {
            check_terms(&m.terms, "manufactured.messenger", t_end)?;
        }
        self.check_loss(t_end)
    }

    fn check_loss(&self, t_end: f64) -> Result<()> {
        if let Some(l) = &self.loss {
            for (k, v, unit) in [
                ("start", l.start, "s"),
                ("end", l.end, "s"),
                ("gap", l.gap, "m"),
                ("blend", l.blend, "s"),
            ] {
                let field = format!("manufactured.loss.{k}");
                finite(&field, v, unit)?;
                if v <= 0.0 {
                    return Err(Error::invalid(field, v, format!("must be > 0 ({unit})")));
                }
            }
            if l.start <= l.blend {
                return Err(Error::invalid(
                    "manufactured.loss.start",
                    l.start,
                    format!(
                        "must be > manufactured.loss.blend = {} s: the contact force falls to 0 over the blend before the loss, after t = 0",
                        l.blend
                    ),
                ));
            }
            if l.end <= l.start {
                return Err(Error::invalid(
                    "manufactured.loss.end",
                    l.end,
                    format!("must be > manufactured.loss.start = {} s", l.start),
                ));
            }
            if l.end + l.blend > t_end {
                return Err(Error::invalid(
                    "manufactured.loss.end",
                    l.end,
                    format!(
                        "must leave the blend ({} s) before the run's end {t_end} s: ≤ {} s",
                        l.blend,
                        t_end - l.blend
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// The reference a validated scene declares ([`crate::resolve::Resolved::reference`]),
/// its assumptions checked against the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Declared {
    /// `[manufactured]`: the manufactured solution (MODEL §11).
    Manufactured,
    /// [`ReferenceKind::MovingForceSeries`].
    MovingForceSeries,
    /// [`ReferenceKind::RidingMassGalerkin`], with its J when given.
    RidingMassGalerkin {
        /// `reference.modes`.
        modes: Option<usize>,
    },
    /// [`ReferenceKind::StandingForceModes`].
    StandingForceModes,
    /// Richardson extrapolation (no `[reference]`, or `kind = "richardson"`).
    Richardson,
}

impl Declared {
    /// The name in tables (`reference` column): the scene's kind, or
    /// `manufactured`.
    pub fn name(self) -> &'static str {
        match self {
            Declared::Manufactured => "manufactured",
            Declared::MovingForceSeries => ReferenceKind::MovingForceSeries.name(),
            Declared::RidingMassGalerkin { .. } => ReferenceKind::RidingMassGalerkin.name(),
            Declared::StandingForceModes => ReferenceKind::StandingForceModes.name(),
            Declared::Richardson => ReferenceKind::Richardson.name(),
        }
    }

    /// True for a reference that is an exact solution (not extrapolated
    /// from the study's own runs).
    pub fn is_exact(self) -> bool {
        self != Declared::Richardson
    }
}
