//! Manufactured solutions for the whole problem (MODEL §11): a smooth beam
//! motion v*(x, t) chosen from a small family, and for each carrier the
//! contact force λ*(t) and mass motion q*(t) consistent with it, with the
//! source that makes them the exact solution of the model.
//!
//! **The motion.** `v*(x, t) = Σᵢ aᵢ Xᵢ(x) T̂ᵢ(t)`: each x-shape a product of
//! polynomials, sines and exponentials in ξ = x/L corrected to meet the
//! supports ([`supports`]), each time part a product of the same kinds in t
//! with its value and rate at t = 0 removed, `T̂ = T − T(0) − T'(0)t`, so
//! the beam starts straight and at rest, as every run does (MODEL §5).
//!
//! **The source.** `p*(x, t) = ρA v*_tt + EI v*_xxxx − T v*_xx − Σ_c P_c(t)
//! δ(x − x_c(t))`: a smooth part, separable as `Σᵢ aᵢ[T̂ᵢ''(t) ρA Xᵢ(x) +
//! T̂ᵢ(t) (EI Xᵢ'''' − T Xᵢ'')(x)]` ([`Manufactured::source_shapes`],
//! [`Manufactured::source_coefficients`]), whose x-parts a discretization
//! projects once per run (`model::source`); and a point load at each
//! carrier that cancels the carrier's own ([`Manufactured::point_load`]):
//! `−s F` for a moving force, `−s λ*(t)` for a mass–spring, whose contact
//! then has to deliver λ* for the beam to follow v* — the contact coupling
//! is verified, not bypassed.
//!
//! **A mass–spring carrier** (MODEL §2). In contact its mass follows the
//! beam, `q* = w* = s v*(x_m(t), t)`, whose second derivative carries the
//! convective terms, `ẅ* = s(v_tt + 2V v_xt + V² v_xx + V̇ v_x)` at x_m;
//! the consistent force is the mass equation's,
//! `λ_c = kδ0 − s m g − m ẅ* − c_s ẇ* − k w*`. Without a loss interval
//! λ* = λ_c and the mass needs no source. With `[manufactured.loss]`
//! (t_a, t_b, gap G, blend τ): λ* = χ(t) λ_c, χ a C³ step from 1 to 0 over
//! [t_a − τ, t_a] and back over [t_b, t_b + τ]; the gap opens as
//! g* = G (4u(1 − u))⁴, u = (t − t_a)/(t_b − t_a), on [t_a, t_b] (zero with
//! three derivatives at both ends), q* = w* − g*, and the mass equation gets
//! the source `f_q = m q̈* + c_s q̇* + k q* − (kδ0 − s m g) + λ*`, zero
//! wherever χ = 1. Signorini holds exactly: λ* = 0 while g* > 0, g* = 0
//! while λ* > 0. A unilateral contact must keep λ* > 0 outside the loss:
//! [`Manufactured::new`] checks it on a fine time grid and refuses the scene
//! otherwise, naming the time and the value.

pub mod factor;
pub mod jet;
pub mod supports;

use factor::{Factor, Product};
use jet::Jet;
use supports::{Ends, Shape};

use crate::error::{Error, Result};
use crate::scene::manufactured::{LossSpec, ManufacturedSpec, TFactor, XFactor};
use crate::scene::{BeamProps, CarrierKind, CarrierProps, ContactKind, Motion};

/// Time samples of the consistency checks per step of the run (at least
/// [`MIN_CHECK_SAMPLES`], at most [`MAX_CHECK_SAMPLES`]): λ* of a smooth
/// motion cannot change sign between samples a quarter step apart without
/// the run itself missing it.
pub const CHECK_SAMPLES_PER_STEP: usize = 4;
/// Fewest samples of the consistency checks.
pub const MIN_CHECK_SAMPLES: usize = 2001;
/// Most samples of the consistency checks (bounds validation's cost).
pub const MAX_CHECK_SAMPLES: usize = 400_001;

/// A shape whose largest value on the span, sampled at
/// [`SHAPE_SAMPLES`] points, is below this fraction of its raw shape's is
/// taken as removed by the support correction (the raw shape was a
/// polynomial of the correction's own powers).
const VANISHED: f64 = 1e-10;
const SHAPE_SAMPLES: usize = 257;

/// One term a·X(x)·T̂(t).
#[derive(Debug, Clone, PartialEq)]
struct Term {
    amplitude: f64,
    shape: Shape,
    time: Product,
    /// T(0) and T'(0).
    start: (f64, f64),
}

impl Term {
    /// T̂ and its derivatives at t.
    fn time_jet(&self, t: f64) -> Jet {
        let mut j = self.time.jet(t);
        j.0[0] -= self.start.0 + self.start.1 * t;
        j.0[1] -= self.start.1;
        j
    }
}

/// A carrier of a manufactured scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CarrierRole {
    /// A moving force F, N.
    Force(f64),
    /// A mass–spring (MODEL §2).
    Mass {
        /// m, kg.
        m: f64,
        /// k, N/m.
        k: f64,
        /// c_s, N·s/m.
        c: f64,
        /// kδ0 − s m g, N.
        f0: f64,
    },
}

/// One carrier's part.
#[derive(Debug, Clone, PartialEq)]
struct Carrier {
    s: f64,
    motion: Motion,
    role: CarrierRole,
}

/// The prescribed loss (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Loss {
    start: f64,
    end: f64,
    gap: f64,
    blend: f64,
}

/// The C³ step 35u⁴ − 84u⁵ + 70u⁶ − 20u⁷ on [0, 1] (0 → 1, three
/// derivatives zero at both ends).
fn smoothstep(u: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    u * u * u * u * (35.0 + u * (-84.0 + u * (70.0 - 20.0 * u)))
}

impl Loss {
    /// χ(t): 1 in contact, 0 in the loss, a C³ step over each blend.
    fn chi(&self, t: f64) -> f64 {
        if t <= self.start {
            smoothstep((self.start - t) / self.blend)
        } else if t >= self.end {
            smoothstep((t - self.end) / self.blend)
        } else {
            0.0
        }
    }

    /// g*, ġ*, g̈* at t.
    fn gap(&self, t: f64) -> [f64; 3] {
        if t <= self.start || t >= self.end {
            return [0.0; 3];
        }
        // G (4u(1 − u))⁴ = G 256 p⁴, p = u(1 − u)
        let d = self.end - self.start;
        let u = (t - self.start) / d;
        let p = u * (1.0 - u);
        let (dp, ddp) = (1.0 - 2.0 * u, -2.0);
        let g = 256.0 * self.gap;
        [
            g * p.powi(4),
            g * 4.0 * p.powi(3) * dp / d,
            g * (12.0 * p * p * dp * dp + 4.0 * p.powi(3) * ddp) / (d * d),
        ]
    }
}

/// v* and the derivatives a carrier's motion needs, at one (x, t).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Fields {
    /// v, m.
    pub v: f64,
    /// v_x.
    pub v_x: f64,
    /// v_xx, 1/m.
    pub v_xx: f64,
    /// v_t, m/s.
    pub v_t: f64,
    /// v_tt, m/s².
    pub v_tt: f64,
    /// v_xt, 1/s.
    pub v_xt: f64,
}

/// The manufactured solution of a scene (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Manufactured {
    terms: Vec<Term>,
    length: f64,
    rho_a: f64,
    ei: f64,
    tension: f64,
    carriers: Vec<Carrier>,
    loss: Option<Loss>,
}

fn x_factor(f: &XFactor) -> Factor {
    match f {
        XFactor::Polynomial { coefficients } => Factor::Polynomial(coefficients.clone()),
        XFactor::Sine { half_waves, phase } => Factor::Sine {
            rate: half_waves * std::f64::consts::PI,
            phase: *phase,
        },
        XFactor::Exponential { rate } => Factor::Exponential { rate: *rate },
    }
}

fn t_factor(f: &TFactor) -> Factor {
    match f {
        TFactor::Polynomial { coefficients } => Factor::Polynomial(coefficients.clone()),
        TFactor::Sine { frequency, phase } => Factor::Sine {
            rate: 2.0 * std::f64::consts::PI * frequency,
            phase: *phase,
        },
        TFactor::Exponential { rate } => Factor::Exponential { rate: *rate },
    }
}

/// What a manufactured solution is built for: the beam, the carriers, the
/// contact kind, gravity and the run's time grid.
#[derive(Debug, Clone, Copy)]
pub struct Setting<'a> {
    /// The beam.
    pub beam: &'a BeamProps,
    /// The carriers, in scene order.
    pub carriers: &'a [CarrierProps],
    /// `contact.kind`.
    pub contact: ContactKind,
    /// Gravity on the carriers' masses, m/s².
    pub g: f64,
    /// The run's end, s.
    pub t_end: f64,
    /// Its steps.
    pub steps: usize,
}

impl Manufactured {
    /// Build the solution of `spec` for `at` and check that it is one: every
    /// shape meets the supports and is not removed by the correction, every
    /// time part is more than linear, and a unilateral contact keeps λ* > 0
    /// outside the prescribed loss (module docs).
    pub fn new(spec: &ManufacturedSpec, at: Setting) -> Result<Self> {
        spec.check(at.t_end)?;
        let b = at.beam;
        let ends = Ends {
            left: b.left,
            right: b.right,
            length: b.length,
            ei: b.ei,
            tension: b.tension,
        };
        let mut terms = Vec::with_capacity(spec.terms.len());
        for (i, t) in spec.terms.iter().enumerate() {
            let field = format!("manufactured.term.{i}.x");
            let raw = Product(t.x.iter().map(x_factor).collect());
            let shape = Shape::new(raw.clone(), &ends, &field)?;
            let (mut big, mut raw_big) = (0.0f64, 0.0f64);
            for k in 0..SHAPE_SAMPLES {
                let x = b.length * k as f64 / (SHAPE_SAMPLES - 1) as f64;
                big = big.max(shape.jet(x).d(0).abs());
                raw_big = raw_big.max(raw.jet(x / b.length).d(0).abs());
            }
            if big.is_nan() || big <= VANISHED * raw_big {
                return Err(Error::invalid(
                    field,
                    "a polynomial of degree ≤ 3",
                    "is removed entirely by the correction that makes a shape meet the supports (X = 0): multiply it by another factor or raise its degree",
                ));
            }
            let time = Product(t.t.iter().map(t_factor).collect());
            let j0 = time.jet(0.0);
            let term = Term {
                amplitude: t.amplitude,
                shape,
                time,
                start: (j0.d(0), j0.d(1)),
            };
            let moves = (0..=64).any(|k| term.time_jet(at.t_end * k as f64 / 64.0).d(2) != 0.0);
            if !moves {
                return Err(Error::invalid(
                    format!("manufactured.term.{i}.t"),
                    "a time part linear in t",
                    "leaves nothing once its value and rate at t = 0 are removed (T̂ = T − T(0) − T'(0)t = 0): use a factor curved in t",
                ));
            }
            terms.push(term);
        }
        let carriers: Vec<Carrier> = at
            .carriers
            .iter()
            .map(|c| {
                let s = c.side.sign();
                Carrier {
                    s,
                    motion: c.motion.clone(),
                    role: match c.kind {
                        CarrierKind::Force { force } => CarrierRole::Force(force),
                        CarrierKind::MassSpring {
                            mass,
                            stiffness,
                            damping,
                            preload,
                        } => CarrierRole::Mass {
                            m: mass,
                            k: stiffness,
                            c: damping,
                            f0: stiffness * preload - s * mass * at.g,
                        },
                    },
                }
            })
            .collect();
        let loss = spec.loss.as_ref().map(|l: &LossSpec| Loss {
            start: l.start,
            end: l.end,
            gap: l.gap,
            blend: l.blend,
        });
        let masses = carriers
            .iter()
            .filter(|c| matches!(c.role, CarrierRole::Mass { .. }))
            .count();
        if loss.is_some() {
            if masses == 0 {
                return Err(Error::invalid(
                    "manufactured.loss",
                    "a scene without a mass–spring carrier",
                    "prescribes a loss of contact, which needs a mass–spring carrier: remove [manufactured.loss] or add one",
                ));
            }
            if at.contact == ContactKind::Bilateral {
                return Err(Error::invalid(
                    "manufactured.loss",
                    "contact.kind = bilateral",
                    "a bilateral contact never opens: use contact.kind = \"unilateral\" or remove [manufactured.loss]",
                ));
            }
        }
        let m = Manufactured {
            terms,
            length: b.length,
            rho_a: b.rho_a,
            ei: b.ei,
            tension: b.tension,
            carriers,
            loss,
        };
        if at.contact == ContactKind::Unilateral {
            m.check_contact_kept(at.t_end, at.steps)?;
        }
        Ok(m)
    }

    /// A unilateral contact must press (λ* > 0) wherever it is closed.
    fn check_contact_kept(&self, t_end: f64, steps: usize) -> Result<()> {
        let n = (CHECK_SAMPLES_PER_STEP * steps).clamp(MIN_CHECK_SAMPLES, MAX_CHECK_SAMPLES);
        for (c, carrier) in self.carriers.iter().enumerate() {
            if !matches!(carrier.role, CarrierRole::Mass { .. }) {
                continue;
            }
            for k in 0..=n {
                let t = t_end * k as f64 / n as f64;
                if self.loss.is_some_and(|l| t >= l.start && t <= l.end) {
                    continue;
                }
                let lambda = self.lambda(c, t);
                if lambda.is_nan() || lambda <= 0.0 {
                    return Err(Error::invalid(
                        "manufactured.term",
                        format!(
                            "contact force λ* = {lambda:.6e} N of carrier {c} at t = {t:.6e} s"
                        ),
                        "must stay > 0 while a unilateral contact is closed (else the contact opens where the manufactured solution keeps it shut): lower the amplitudes, raise carrier.preload or the mass's weight, prescribe the opening with [manufactured.loss], or use contact.kind = \"bilateral\"",
                    ));
                }
            }
        }
        Ok(())
    }

    /// v*(x, t), m.
    pub fn v(&self, x: f64, t: f64) -> f64 {
        self.terms
            .iter()
            .map(|term| term.amplitude * term.shape.jet(x).d(0) * term.time_jet(t).d(0))
            .sum()
    }

    /// v* and its derivatives at (x, t).
    pub fn fields(&self, x: f64, t: f64) -> Fields {
        let mut f = Fields::default();
        for term in &self.terms {
            let (xs, ts) = (term.shape.jet(x), term.time_jet(t));
            let a = term.amplitude;
            f.v += a * xs.d(0) * ts.d(0);
            f.v_x += a * xs.d(1) * ts.d(0);
            f.v_xx += a * xs.d(2) * ts.d(0);
            f.v_t += a * xs.d(0) * ts.d(1);
            f.v_tt += a * xs.d(0) * ts.d(2);
            f.v_xt += a * xs.d(1) * ts.d(1);
        }
        f
    }

    /// The smooth source p_s(x, t) = ρA v_tt + EI v_xxxx − T v_xx, N/m.
    pub fn smooth_source(&self, x: f64, t: f64) -> f64 {
        self.terms
            .iter()
            .map(|term| {
                let (xs, ts) = (term.shape.jet(x), term.time_jet(t));
                term.amplitude
                    * (self.rho_a * xs.d(0) * ts.d(2)
                        + (self.ei * xs.d(4) - self.tension * xs.d(2)) * ts.d(0))
            })
            .sum()
    }

    /// The fastest rate of change of the x-shapes, 1/m: the largest |rate|
    /// of a sine or exponential factor, or a polynomial's degree, over L
    /// (at least the correction's degree 5 over L). A quadrature panel a
    /// fraction of 1/x_rate long resolves every shape.
    pub fn x_rate(&self) -> f64 {
        let per_xi = self
            .terms
            .iter()
            .flat_map(|t| t.shape.raw().0.iter())
            .map(|f| match f {
                Factor::Polynomial(c) => c.len().saturating_sub(1) as f64,
                Factor::Sine { rate, .. } | Factor::Exponential { rate } => rate.abs(),
            })
            .fold(5.0, f64::max);
        per_xi / self.length
    }

    /// Number of separable parts of the smooth source (two per term).
    pub fn source_count(&self) -> usize {
        2 * self.terms.len()
    }

    /// The x-parts of the smooth source at x into `out`
    /// ([`Manufactured::source_count`] long): ρA Xᵢ (N·s²/m² per m of
    /// amplitude·T̂'') and EI Xᵢ'''' − T Xᵢ'' (N/m²), term by term.
    pub fn source_shapes(&self, x: f64, out: &mut [f64]) {
        for (i, term) in self.terms.iter().enumerate() {
            let xs = term.shape.jet(x);
            out[2 * i] = self.rho_a * xs.d(0);
            out[2 * i + 1] = self.ei * xs.d(4) - self.tension * xs.d(2);
        }
    }

    /// The time parts of the smooth source at t into `out`: aᵢ T̂ᵢ''(t)
    /// and aᵢ T̂ᵢ(t), so that p_s = Σ out[k]·shape[k].
    pub fn source_coefficients(&self, t: f64, out: &mut [f64]) {
        for (i, term) in self.terms.iter().enumerate() {
            let ts = term.time_jet(t);
            out[2 * i] = term.amplitude * ts.d(2);
            out[2 * i + 1] = term.amplitude * ts.d(0);
        }
    }

    /// The carriers, in scene order.
    pub fn carriers(&self) -> usize {
        self.carriers.len()
    }

    /// What carrier c is.
    pub fn role(&self, c: usize) -> CarrierRole {
        self.carriers[c].role
    }

    /// Carrier c's position x_m(t), m.
    pub fn position(&self, c: usize, t: f64) -> f64 {
        self.carriers[c].motion.position(t)
    }

    /// w* = s v*(x_m(t), t) under carrier c and its first two total time
    /// derivatives (with the convective terms, module docs).
    pub fn w(&self, c: usize, t: f64) -> [f64; 3] {
        let car = &self.carriers[c];
        let (x, v, a) = (
            car.motion.position(t),
            car.motion.speed(t),
            car.motion.acceleration(t),
        );
        let f = self.fields(x, t);
        [
            car.s * f.v,
            car.s * (f.v_t + v * f.v_x),
            car.s * (f.v_tt + 2.0 * v * f.v_xt + v * v * f.v_xx + a * f.v_x),
        ]
    }

    /// The prescribed gap g* of a mass carrier and its rates (0 without a loss).
    fn gap(&self, t: f64) -> [f64; 3] {
        self.loss.map_or([0.0; 3], |l| l.gap(t))
    }

    /// q* of mass carrier c (m, positive into the beam): w* − g*. For a
    /// force carrier, w*.
    pub fn q(&self, c: usize, t: f64) -> f64 {
        let w = self.w(c, t)[0];
        match self.carriers[c].role {
            CarrierRole::Force(_) => w,
            CarrierRole::Mass { .. } => w - self.gap(t)[0],
        }
    }

    /// The gap g* of carrier c, m (0 for a force).
    pub fn gap_of(&self, c: usize, t: f64) -> f64 {
        match self.carriers[c].role {
            CarrierRole::Force(_) => 0.0,
            CarrierRole::Mass { .. } => self.gap(t)[0],
        }
    }

    /// λ* of carrier c, N: the applied F for a force, χ·λ_c for a mass.
    pub fn lambda(&self, c: usize, t: f64) -> f64 {
        match self.carriers[c].role {
            CarrierRole::Force(f) => f,
            CarrierRole::Mass { m, k, c: cs, f0 } => {
                let [w, wd, wdd] = self.w(c, t);
                let consistent = f0 - m * wdd - cs * wd - k * w;
                self.loss.map_or(consistent, |l| l.chi(t) * consistent)
            }
        }
    }

    /// The source on mass carrier c's equation, N (module docs; 0 without
    /// a loss, and for a force).
    pub fn mass_source(&self, c: usize, t: f64) -> f64 {
        let Some(loss) = self.loss else {
            return 0.0;
        };
        match self.carriers[c].role {
            CarrierRole::Force(_) => 0.0,
            CarrierRole::Mass { m, k, c: cs, f0 } => {
                // m q̈* + c q̇* + k q* − f0 = −λ_c − (m g̈* + c ġ* + k g*) with
                // q* = w* − g*, so f_q = (χ − 1)λ_c − (m g̈* + c ġ* + k g*):
                // exactly 0 where χ = 1 and g* = 0
                let [w, wd, wdd] = self.w(c, t);
                let [g, gd, gdd] = loss.gap(t);
                let consistent = f0 - m * wdd - cs * wd - k * w;
                (loss.chi(t) - 1.0) * consistent - (m * gdd + cs * gd + k * g)
            }
        }
    }

    /// The point part of p* at carrier c, N in +v (module docs): −s F for
    /// a force, −s λ*(t) for a mass.
    pub fn point_load(&self, c: usize, t: f64) -> f64 {
        -self.carriers[c].s * self.lambda(c, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::manufactured::TermSpec;
    use crate::scene::{Side, SpeedProfile, Support};

    fn beam(left: Support, right: Support) -> BeamProps {
        BeamProps {
            length: 2.0,
            rho_a: 1.5,
            ei: 4.0,
            ea: None,
            tension: 60.0,
            left,
            right,
            distributed_load: 0.0,
            attachments: Vec::new(),
            messenger: None,
        }
    }

    fn spec(loss: Option<LossSpec>) -> ManufacturedSpec {
        ManufacturedSpec {
            terms: vec![
                TermSpec {
                    amplitude: 2e-3,
                    x: vec![XFactor::Sine {
                        half_waves: 1.0,
                        phase: 0.0,
                    }],
                    t: vec![TFactor::Sine {
                        frequency: 3.0,
                        phase: 0.0,
                    }],
                },
                TermSpec {
                    amplitude: 1e-3,
                    x: vec![
                        XFactor::Polynomial {
                            coefficients: vec![0.0, 1.0, 0.5],
                        },
                        XFactor::Exponential { rate: 0.5 },
                    ],
                    t: vec![
                        TFactor::Polynomial {
                            coefficients: vec![1.0, 2.0],
                        },
                        TFactor::Exponential { rate: -1.0 },
                    ],
                },
            ],
            loss,
        }
    }

    fn mass_carrier(speed: SpeedProfile) -> CarrierProps {
        CarrierProps {
            kind: CarrierKind::MassSpring {
                mass: 0.5,
                stiffness: 200.0,
                damping: 0.3,
                preload: 0.05,
            },
            chain: None,
            side: Side::Above,
            motion: Motion::new(0.2, speed, 2.0),
        }
    }

    /// Central differences of step δ = 1e-4 s: truncation ≈ δ²·(fourth
    /// derivative) ~ 1e-8·(2π·3)⁴·|w| ≈ 1e-6 relative; 1e-5 separates a
    /// right formula from a wrong term.
    const FD_REL: f64 = 1e-5;

    #[test]
    fn the_carrier_s_motion_is_the_total_derivative_under_it() {
        let b = beam(Support::Clamped, Support::Pinned);
        let c = [mass_carrier(SpeedProfile::SmoothRamp { cruise: 4.0 })];
        let m = Manufactured::new(
            &spec(None),
            Setting {
                beam: &b,
                carriers: &c,
                contact: ContactKind::Bilateral,
                g: 9.81,
                t_end: 0.4,
                steps: 100,
            },
        )
        .unwrap();
        let d = 1e-4;
        for t in [0.05, 0.13, 0.3] {
            let w = |t: f64| m.w(0, t)[0];
            let [_, wd, wdd] = m.w(0, t);
            let fd1 = (w(t + d) - w(t - d)) / (2.0 * d);
            let fd2 = (w(t + d) - 2.0 * w(t) + w(t - d)) / (d * d);
            assert!(
                (fd1 - wd).abs() <= FD_REL * wd.abs().max(1e-3),
                "{t}: {wd} {fd1}"
            );
            assert!(
                (fd2 - wdd).abs() <= FD_REL * 10.0 * wdd.abs().max(1e-2),
                "{t}: {wdd} {fd2}"
            );
        }
        // starts straight and at rest
        assert_eq!(m.v(0.7, 0.0), 0.0);
        assert!(m.w(0, 0.0)[1].abs() < 1e-18);
    }

    #[test]
    fn the_source_is_the_operator_on_v() {
        let b = beam(Support::Pinned, Support::Pinned);
        let m = Manufactured::new(
            &spec(None),
            Setting {
                beam: &b,
                carriers: &[],
                contact: ContactKind::Unilateral,
                g: 0.0,
                t_end: 0.4,
                steps: 100,
            },
        )
        .unwrap();
        let (x, t, d) = (0.83, 0.21, 1e-3);
        let v = |x: f64, t: f64| m.v(x, t);
        let vtt = (v(x, t + d) - 2.0 * v(x, t) + v(x, t - d)) / (d * d);
        let vxx = (v(x + d, t) - 2.0 * v(x, t) + v(x - d, t)) / (d * d);
        let vxxxx = (v(x + 2.0 * d, t) - 4.0 * v(x + d, t) + 6.0 * v(x, t) - 4.0 * v(x - d, t)
            + v(x - 2.0 * d, t))
            / d.powi(4);
        let fd = b.rho_a * vtt + b.ei * vxxxx - b.tension * vxx;
        let p = m.smooth_source(x, t);
        // the fourth difference loses ε/δ⁴ ≈ 2e-4 of |v| ~ 1e-3: 1e-3 relative to p
        assert!((fd - p).abs() <= 1e-3 * p.abs(), "{p} {fd}");
        let mut shapes = vec![0.0; m.source_count()];
        let mut coef = vec![0.0; m.source_count()];
        m.source_shapes(x, &mut shapes);
        m.source_coefficients(t, &mut coef);
        let sum: f64 = shapes.iter().zip(&coef).map(|(a, b)| a * b).sum();
        assert!((sum - p).abs() <= 1e-12 * p.abs());
    }

    #[test]
    fn a_loss_keeps_signorini_and_the_mass_equation() {
        let b = beam(Support::Pinned, Support::Pinned);
        let c = [mass_carrier(SpeedProfile::Constant { value: 3.0 })];
        let loss = LossSpec {
            start: 0.15,
            end: 0.25,
            gap: 1e-4,
            blend: 0.05,
        };
        let m = Manufactured::new(
            &spec(Some(loss)),
            Setting {
                beam: &b,
                carriers: &c,
                contact: ContactKind::Unilateral,
                g: 9.81,
                t_end: 0.4,
                steps: 400,
            },
        )
        .unwrap();
        for k in 0..=400 {
            let t = 0.4 * k as f64 / 400.0;
            let (lambda, gap) = (m.lambda(0, t), m.gap_of(0, t));
            assert!(lambda >= 0.0 && gap >= 0.0 && lambda * gap == 0.0, "{t}");
            if !(0.1..=0.3).contains(&t) {
                assert_eq!(m.mass_source(0, t), 0.0);
            }
        }
        assert!(m.gap_of(0, 0.2) > 0.99e-4 && m.lambda(0, 0.2) == 0.0);
        assert!(m.lambda(0, 0.05) > 0.0 && m.lambda(0, 0.35) > 0.0);
        // the mass equation with its source, by differences of q*
        let d = 1e-5;
        let t = 0.18;
        let q = |t: f64| m.q(0, t);
        let (qd, qdd) = (
            (q(t + d) - q(t - d)) / (2.0 * d),
            (q(t + d) - 2.0 * q(t) + q(t - d)) / (d * d),
        );
        let CarrierRole::Mass {
            m: mm,
            k,
            c: cs,
            f0,
        } = m.role(0)
        else {
            panic!()
        };
        let residual = mm * qdd + cs * qd + k * q(t) - (f0 - m.lambda(0, t) + m.mass_source(0, t));
        assert!(residual.abs() < 1e-4 * f0.abs(), "{residual}");
    }

    #[test]
    fn a_unilateral_contact_that_would_open_is_refused() {
        let b = beam(Support::Pinned, Support::Pinned);
        let mut c = mass_carrier(SpeedProfile::Constant { value: 3.0 });
        c.kind = CarrierKind::MassSpring {
            mass: 0.5,
            stiffness: 200.0,
            damping: 0.0,
            preload: 0.0,
        };
        let mut s = spec(None);
        s.terms[0].amplitude = 0.5;
        let e = Manufactured::new(
            &s,
            Setting {
                beam: &b,
                carriers: &[c],
                contact: ContactKind::Unilateral,
                g: 9.81,
                t_end: 0.4,
                steps: 100,
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("manufactured.term") && e.contains("λ*"), "{e}");
    }
}
