//! The built-in time integrators (`integrator.method`, MODEL §5 and §9.1)
//! and what scene validation asks of any method ([`MethodInfo`]).
//!
//! [`Method`] is the one place each built-in method is described: its
//! name, the parameters of `[integrator]` it reads with their ranges, its
//! typed parameters ([`Method::scheme`]), its formal order, the contact
//! settings and bases it accepts and its diagnosis. Each parameter key
//! belongs to some methods only (`rho_inf` to `generalized_alpha` and
//! `wbz`, `alpha` to `hht`, `gamma` to `bathe`, `theta` to
//! `moreau_jean`); a key given for a method that does not use it is an
//! error naming both keys (`method_choice.rs`), not silently ignored.

use serde::{Deserialize, Serialize};

use super::contact::{ContactSpec, Formulation, Placement};
use super::discretization::Discretization;
use super::integrator::{IntegratorSpec, Key};
use super::scheme::{
    DEFAULT_BATHE_GAMMA, DEFAULT_HHT_ALPHA, DEFAULT_THETA, GenAlphaParams, Scheme,
};
use crate::error::{Error, Result};

/// The built-in time integrators (`integrator.method`, MODEL §9.1): the
/// one place each is described (name, parameters with their ranges, formal
/// order in Δt, which contact settings and bases it accepts, its typed
/// parameters and its diagnosis). Its stepper is built from its
/// [`Scheme`] by `integrate::stepper_for`.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq, Default, Hash)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Generalized-α (Chung & Hulbert 1993) with spectral radius ρ∞ (MODEL §5).
    #[default]
    GeneralizedAlpha,
    /// Newmark's average acceleration: α_m = α_f = 0, β = 1/4, γ = 1/2.
    Newmark,
    /// Hilber–Hughes–Taylor α: α_m = 0, α_f = α, γ = 1/2 + α, β = (1 + α)²/4.
    Hht,
    /// Wood–Bossak–Zienkiewicz: α_f = 0, α_m = (ρ∞ − 1)/(ρ∞ + 1).
    Wbz,
    /// Bathe's composite scheme (Bathe & Baig 2005): trapezoidal, then
    /// three-point backward Euler.
    Bathe,
    /// Central difference, explicit in K, with forward-increment Lagrange contact.
    CentralDifference,
    /// Moreau–Jean's velocity-level θ-scheme with impulses (Jean 1999).
    MoreauJean,
    /// Exact propagation of each mode of a diagonal basis over the step
    /// (Duhamel; MODEL §9.3): `mesh.kind = "galerkin"` or `"modal"` only.
    ModalExact,
}

/// ρ∞ ∈ [0, 1] of `generalized_alpha` and `wbz` (default 1: no dissipation).
const RHO_INF: Parameter = Parameter {
    key: Key::RhoInf,
    default: 1.0,
    range: "[0, 1]",
    contains: |v| (0.0..=1.0).contains(&v),
};

/// HHT α ∈ [0, 1/3].
const HHT_ALPHA: Parameter = Parameter {
    key: Key::Alpha,
    default: DEFAULT_HHT_ALPHA,
    range: "[0, 1/3] (HHT is unconditionally stable and second order there)",
    contains: |v| (0.0..=1.0 / 3.0).contains(&v),
};

/// Bathe's splitting γ_B ∈ (0, 1).
const BATHE_GAMMA: Parameter = Parameter {
    key: Key::Gamma,
    default: DEFAULT_BATHE_GAMMA,
    range: "(0, 1) (the first sub-step ends inside the step)",
    contains: |v| v > 0.0 && v < 1.0,
};

/// Moreau–Jean θ ∈ [½, 1].
const THETA: Parameter = Parameter {
    key: Key::Theta,
    default: DEFAULT_THETA,
    range: "[0.5, 1] (below 1/2 the θ-scheme is unstable)",
    contains: |v| (0.5..=1.0).contains(&v),
};

impl Method {
    /// Every built-in method, in the order `taut compare --methods` lists them.
    pub const ALL: [Method; 8] = [
        Method::GeneralizedAlpha,
        Method::Newmark,
        Method::Hht,
        Method::Wbz,
        Method::Bathe,
        Method::CentralDifference,
        Method::MoreauJean,
        Method::ModalExact,
    ];

    /// The scene name (`"generalized_alpha"`, …).
    pub fn name(self) -> &'static str {
        match self {
            Method::GeneralizedAlpha => "generalized_alpha",
            Method::Newmark => "newmark",
            Method::Hht => "hht",
            Method::Wbz => "wbz",
            Method::Bathe => "bathe",
            Method::CentralDifference => "central_difference",
            Method::MoreauJean => "moreau_jean",
            Method::ModalExact => "modal_exact",
        }
    }

    /// The built-in method named `name`, if any.
    pub fn from_name(name: &str) -> Option<Method> {
        Method::ALL.into_iter().find(|m| m.name() == name)
    }

    /// The parameters of `[integrator]` this method reads, with their
    /// defaults and ranges.
    pub fn parameters(self) -> &'static [Parameter] {
        match self {
            Method::GeneralizedAlpha | Method::Wbz => &[RHO_INF],
            Method::Hht => &[HHT_ALPHA],
            Method::Bathe => &[BATHE_GAMMA],
            Method::MoreauJean => &[THETA],
            Method::Newmark | Method::CentralDifference | Method::ModalExact => &[],
        }
    }

    /// This method's typed parameters from `spec` (keys of other methods
    /// ignored), each checked against its range where it is read: what a
    /// run of this method steps with.
    pub fn scheme(self, spec: &IntegratorSpec) -> Result<Scheme> {
        let value = |p: &Parameter| p.value(spec);
        Ok(match self {
            Method::GeneralizedAlpha => {
                Scheme::GenAlpha(GenAlphaParams::from_rho_inf(value(&RHO_INF)?))
            }
            Method::Wbz => Scheme::GenAlpha(GenAlphaParams::wbz(value(&RHO_INF)?)),
            Method::Newmark => Scheme::GenAlpha(GenAlphaParams::newmark()),
            Method::Hht => Scheme::GenAlpha(GenAlphaParams::hht(value(&HHT_ALPHA)?)),
            Method::Bathe => Scheme::Bathe {
                gamma: value(&BATHE_GAMMA)?,
            },
            Method::CentralDifference => Scheme::CentralDifference,
            Method::MoreauJean => Scheme::MoreauJean {
                theta: value(&THETA)?,
            },
            Method::ModalExact => Scheme::ModalExact,
        })
    }

    /// The formal order in Δt of this method's `scheme` (the order of its
    /// local truncation error minus one, for smooth solutions): 2 for the
    /// generalized-α family, Bathe, central difference and modal_exact; for
    /// Moreau–Jean 2 at θ = ½ (the trapezoidal rule) and 1 otherwise
    /// (MODEL §9.1).
    pub fn time_order(self, scheme: &Scheme) -> f64 {
        match scheme {
            Scheme::MoreauJean { theta } if *theta != 0.5 => 1.0,
            _ => 2.0,
        }
    }

    /// Refuse a contact setting or basis this method does not go with (the
    /// table in `docs/methods.md`), naming both keys.
    pub fn accepts(self, c: &ContactSpec, d: Discretization) -> Result<()> {
        let alpha_level = matches!(
            self,
            Method::GeneralizedAlpha | Method::Newmark | Method::Hht | Method::Wbz
        );
        if c.placement == Placement::Alpha && !alpha_level {
            return Err(Error::invalid(
                "contact.placement",
                "\"alpha\"",
                format!(
                    "imposes the gap at the generalized-α level t_{{n+1−α_f}}, which integrator.method = {} does not have: use contact.placement = \"end\" (or a generalized-α method)",
                    self.name()
                ),
            ));
        }
        if self == Method::MoreauJean {
            let why = match c.formulation {
                Formulation::Penalty => Some(
                    "penalty regularizes a position gap with a stiffness, while integrator.method = moreau_jean solves for impulses on gap rates: use lagrange or complementarity",
                ),
                Formulation::Impact => Some(
                    "integrator.method = moreau_jean is itself the velocity-level impact scheme (restitution from contact.impact.restitution): use lagrange (exact active set) or complementarity (clarabel) to solve its impulse problem",
                ),
                _ => None,
            };
            if let Some(why) = why {
                return Err(Error::invalid(
                    "contact.formulation",
                    format!("\"{}\"", c.formulation.name()),
                    why,
                ));
            }
        }
        // modal_exact propagates each mode on its own (MODEL §9.3)
        if self == Method::ModalExact && d == Discretization::Hermite {
            return Err(Error::invalid(
                "integrator.method",
                format!("\"{}\"", self.name()),
                "propagates each mode of a diagonal basis exactly, and mesh.kind = \"hermite\" (or string elements) couples its unknowns through banded M and K: use mesh.kind = \"galerkin\" (the exact modes of the continuous beam) or mesh.kind = \"modal\" (the lowest FE modes), with mesh.modes = J",
            ));
        }
        Ok(())
    }

    /// Why this method, with `scheme`, may leave a moving contact's
    /// constraint undamped — the cause a diagnosis names when such a run
    /// goes unstable or chatters; `None` for a method without that mode.
    ///
    /// A generalized-α-family method imposes the gap at t_{n+1} but
    /// balances forces at t_{n+1−α_f}: the constraint direction keeps a
    /// step-to-step (Nyquist) mode that only some parameter sets damp, and
    /// a moving contact point drives it (MODEL §5, as `contact.placement =
    /// "alpha"` does). Measured on the reference case at Δt = 1e-4 s
    /// (`cargo xtask methods`, docs/methods.md): with a bilateral
    /// mass Newmark, HHT α ≤ 0.1, WBZ ρ∞ = 0.8 and generalized-α ρ∞ = 0.9
    /// diverge, while ρ∞ = 1 or 0.5, HHT α ≥ 0.2, WBZ ρ∞ ≤ 0.5 and Bathe run.
    pub fn constraint_note(self, scheme: &Scheme) -> Option<String> {
        let Scheme::GenAlpha(p) = scheme else {
            return None;
        };
        Some(format!(
            "the contact constraint's step-to-step mode, which integrator.method = {} (α_m = {:.3}, α_f = {:.3}) may leave undamped: a moving contact point drives it (MODEL §5; measured on the reference case, newmark, hht with alpha ≤ 0.1, wbz with rho_inf = 0.8 and generalized_alpha with rho_inf = 0.9 go unstable, while rho_inf = 1 or 0.5, hht with alpha ≥ 0.2, wbz with rho_inf ≤ 0.5 and bathe run: docs/methods.md)",
            self.name(),
            p.alpha_m,
            p.alpha_f
        ))
    }

    /// The `[integrator]` that selects this method in a scene whose own is
    /// `base`: this method's name with the parameters of `base` it reads (a
    /// `rho_inf` of generalized-α is dropped for Bathe), as typed data.
    pub fn integrator(self, base: &IntegratorSpec) -> IntegratorSpec {
        let mut spec = IntegratorSpec {
            method: self.name().to_string(),
            ..IntegratorSpec::default()
        };
        for p in self.parameters() {
            p.key.set(&mut spec, p.key.of(base));
        }
        spec
    }
}

/// One parameter of `[integrator]` a method reads.
#[derive(Debug, Clone, Copy)]
pub struct Parameter {
    /// Its key in `[integrator]`.
    pub key: Key,
    /// Its value when the scene gives none.
    pub default: f64,
    /// The allowed range as the error message states it.
    pub range: &'static str,
    /// True when a value lies in the range (false for NaN).
    pub contains: fn(f64) -> bool,
}

impl Parameter {
    /// Its value in `spec`, the default filled, checked against its range
    /// (a range check is false for NaN, so this also rejects non-finite
    /// values).
    pub fn value(&self, spec: &IntegratorSpec) -> Result<f64> {
        let v = self.key.of(spec).unwrap_or(self.default);
        if (self.contains)(v) {
            Ok(v)
        } else {
            Err(Error::invalid(
                format!("integrator.{}", self.key.name()),
                v,
                format!("must be in {}", self.range),
            ))
        }
    }
}

/// A method's description as scene validation reads it: the built-in
/// [`Method`]s, and every method registered by name
/// (`integrate::register`), whose `MethodFactory` builds on it. The
/// registry (`method_registry.rs`) keeps it with the method's name.
pub trait MethodInfo: Sync {
    /// The name in `integrator.method`, `--methods`, tables and plots.
    fn name(&self) -> String;

    /// The parameters of `[integrator]` it reads (none by default): a key
    /// given for a method that does not read it is refused.
    fn parameters(&self) -> &[Parameter] {
        &[]
    }

    /// Refuse a contact setting or basis the method does not go with, with
    /// an error naming both keys (everything by default: a method stepping
    /// through `integrate::System` works with every contact law).
    fn accepts(&self, _contact: &ContactSpec, _d: Discretization) -> Result<()> {
        Ok(())
    }
}

impl MethodInfo for Method {
    fn name(&self) -> String {
        Method::name(*self).to_string()
    }

    fn parameters(&self) -> &[Parameter] {
        Method::parameters(*self)
    }

    fn accepts(&self, c: &ContactSpec, d: Discretization) -> Result<()> {
        Method::accepts(*self, c, d)
    }
}

/// Why a scene cannot take the impact law with `modal_exact`, or `None`
/// when it can: `carriers` carriers with `contacts` contacts in all, a
/// manufactured source on a unilateral contact (`source`), damped modes
/// (`damped`). Checked when the scene resolves and when a run is built.
pub(crate) fn impact_refusal(
    carriers: usize,
    contacts: usize,
    source: bool,
    damped: bool,
) -> Option<String> {
    if contacts != 1 || carriers != 1 {
        Some(format!(
            "with integrator.method = modal_exact locates each re-contact of one mass–spring carrier within its step; this scene has {carriers} carriers and {contacts} contacts: use one carrier, or integrator.method = moreau_jean for an impact law on several"
        ))
    } else if source {
        Some("with integrator.method = modal_exact propagates the free motion back from t_{n+1} to a re-contact instant, which a manufactured source's time-dependent load does not allow on a unilateral contact: use contact.formulation = \"lagrange\" for a manufactured solution, or integrator.method = moreau_jean".to_string())
    } else if damped {
        Some("with integrator.method = modal_exact propagates each mode back to a re-contact instant by its undamped map, and the modes are damped (beam.damping): remove beam.damping, or use integrator.method = moreau_jean".to_string())
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scene_the_located_impact_cannot_carry_is_named() {
        let two = impact_refusal(2, 2, false, false).unwrap();
        assert!(
            two.contains("2 carriers") && two.contains("moreau_jean"),
            "{two}"
        );
        let src = impact_refusal(1, 1, true, false).unwrap();
        assert!(
            src.contains("manufactured") && src.contains("lagrange"),
            "{src}"
        );
        let damped = impact_refusal(1, 1, false, true).unwrap();
        assert!(damped.contains("beam.damping"), "{damped}");
        assert!(impact_refusal(1, 1, false, false).is_none());
    }

    #[test]
    fn the_default_method_is_the_study_s() {
        assert_eq!(
            Method::default().name(),
            crate::scene::integrator::DEFAULT_METHOD
        );
    }

    #[test]
    fn a_method_selected_keeps_the_parameters_it_reads() {
        let base = IntegratorSpec {
            method: "generalized_alpha".into(),
            rho_inf: Some(0.8),
            ..IntegratorSpec::default()
        };
        assert_eq!(Method::Wbz.integrator(&base).rho_inf, Some(0.8));
        assert_eq!(Method::Bathe.integrator(&base).rho_inf, None);
        let wbz = Method::Wbz.integrator(&base);
        assert_eq!(
            Method::Wbz.scheme(&wbz).unwrap(),
            Scheme::GenAlpha(GenAlphaParams::wbz(0.8))
        );
    }

    #[test]
    fn ranges_are_checked_where_the_parameters_are_read() {
        let bad = [
            (Method::Hht, Key::Alpha, 0.5),
            (Method::Bathe, Key::Gamma, 1.0),
            (Method::MoreauJean, Key::Theta, 0.4),
            (Method::Wbz, Key::RhoInf, f64::NAN),
        ];
        for (method, key, value) in bad {
            let mut spec = IntegratorSpec {
                method: method.name().to_string(),
                ..IntegratorSpec::default()
            };
            key.set(&mut spec, Some(value));
            let e = method.scheme(&spec).unwrap_err().to_string();
            assert!(e.contains(&format!("integrator.{}", key.name())), "{e}");
        }
    }

    /// `Method as usize` indexes `Method::ALL` (the registry's built-in
    /// entries rely on it).
    #[test]
    fn every_method_sits_at_its_own_index() {
        for (i, m) in Method::ALL.iter().enumerate() {
            assert_eq!(*m as usize, i);
        }
    }
}
