//! The matrix's parameter sets: a built-in method with one `[integrator]`
//! parameter fixed (ρ∞ of `generalized_alpha` and `wbz`, α of `hht`, γ of
//! `bathe`, θ of `moreau_jean`), so that every parameter a user may set is
//! verified away from its default, not only at it (a coefficient that is
//! right at the default alone — Bathe's c₁ at γ = ½ — shows nowhere else).
//! The quick matrix runs the set marked `quick` of each method beside the
//! default.
//!
//! | method | values (beside the scene's own) | quick |
//! |---|---|---|
//! | `generalized_alpha` | ρ∞ = 0.8, 0.5, 0 (the scene's: 1) | 0.5 |
//! | `hht` | α = 1/9, 1/3 (ρ∞ = 0.8, 0.5; the scene's: 0.05; α = 0 is Newmark) | 1/3 |
//! | `wbz` | ρ∞ = 0.8, 0.5, 0 (at ρ∞ = 1 it is Newmark's parameter set, α_m = α_f = 0: the matrix does not run it twice) | 0.5 |
//! | `bathe` | γ = 0.6 (the scene's: ½) | 0.6 |
//! | `moreau_jean` | θ = 1 (the scene's: ½; first order) | 1 |

use crate::error::Result;
use crate::integrate::{Initial, MethodFactory, State, Stepper, System};
use crate::resolve::Resolved;
use crate::scene::{
    ContactSpec, Discretization, IntegratorSpec, Key, Method, MethodInfo, Parameter,
};

/// A built-in method with one parameter fixed (module docs).
#[derive(Debug, Clone, Copy)]
pub struct Tuned {
    /// The built-in method.
    pub method: Method,
    /// Its `[integrator]` key.
    pub key: Key,
    /// The value.
    pub value: f64,
    /// The `method` column: `wbz(rho_inf=0.5)`.
    pub label: &'static str,
    /// The quick matrix runs it (one non-default value of each method).
    pub quick: bool,
}

/// HHT's α for ρ∞ = 0.8: α = (1 − ρ∞)/(1 + ρ∞) = 1/9.
const HHT_ALPHA_08: f64 = 1.0 / 9.0;

/// HHT's α for ρ∞ = 0.5: 1/3, the end of its range.
const HHT_ALPHA_05: f64 = 1.0 / 3.0;

/// Bathe's γ away from ½: 0.6, where c₁ = (1 − γ)/(γΔt) and its
/// reciprocal-looking misprint γ/((1 − γ)Δt) differ by 2.25×.
const BATHE_GAMMA: f64 = 0.6;

/// Every parameter set the full matrix adds (module docs).
pub static TUNED: [Tuned; 10] = [
    Tuned {
        method: Method::GeneralizedAlpha,
        key: Key::RhoInf,
        value: 0.8,
        label: "generalized_alpha(rho_inf=0.8)",
        quick: false,
    },
    Tuned {
        method: Method::GeneralizedAlpha,
        key: Key::RhoInf,
        value: 0.5,
        label: "generalized_alpha(rho_inf=0.5)",
        quick: true,
    },
    Tuned {
        method: Method::GeneralizedAlpha,
        key: Key::RhoInf,
        value: 0.0,
        label: "generalized_alpha(rho_inf=0)",
        quick: false,
    },
    Tuned {
        method: Method::Hht,
        key: Key::Alpha,
        value: HHT_ALPHA_08,
        label: "hht(alpha=1/9)",
        quick: false,
    },
    Tuned {
        method: Method::Hht,
        key: Key::Alpha,
        value: HHT_ALPHA_05,
        label: "hht(alpha=1/3)",
        quick: true,
    },
    Tuned {
        method: Method::Wbz,
        key: Key::RhoInf,
        value: 0.8,
        label: "wbz(rho_inf=0.8)",
        quick: false,
    },
    Tuned {
        method: Method::Wbz,
        key: Key::RhoInf,
        value: 0.5,
        label: "wbz(rho_inf=0.5)",
        quick: true,
    },
    Tuned {
        method: Method::Wbz,
        key: Key::RhoInf,
        value: 0.0,
        label: "wbz(rho_inf=0)",
        quick: false,
    },
    Tuned {
        method: Method::Bathe,
        key: Key::Gamma,
        value: BATHE_GAMMA,
        label: "bathe(gamma=0.6)",
        quick: true,
    },
    Tuned {
        method: Method::MoreauJean,
        key: Key::Theta,
        value: 1.0,
        label: "moreau_jean(theta=1)",
        quick: true,
    },
];

/// The parameter sets of `method` in [`TUNED`].
pub fn tuned_of(method: Method) -> impl Iterator<Item = &'static Tuned> {
    TUNED.iter().filter(move |t| t.method == method)
}

impl MethodInfo for Tuned {
    fn name(&self) -> String {
        self.label.to_string()
    }

    fn parameters(&self) -> &[Parameter] {
        self.method.parameters()
    }

    fn accepts(&self, c: &ContactSpec, d: Discretization) -> Result<()> {
        self.method.accepts(c, d)
    }
}

impl MethodFactory for Tuned {
    fn build(
        &self,
        sc: &Resolved,
        sys: &mut System,
        st: &mut State,
        init: Initial,
    ) -> Result<Box<dyn Stepper>> {
        self.method.build(sc, sys, st, init)
    }

    /// The method's `[integrator]` with this parameter set.
    fn integrator(&self, base: &IntegratorSpec) -> Option<IntegratorSpec> {
        let mut spec = self.method.integrator(base);
        self.key.set(&mut spec, Some(self.value));
        Some(spec)
    }

    fn is_scene_method(&self, sc: &Resolved) -> bool {
        sc.method.built_in_method() == Some(self.method)
            && self.key.of(&sc.scene.integrator) == Some(self.value)
    }

    fn time_order(&self, sc: &Resolved) -> Option<f64> {
        MethodFactory::time_order(&self.method, sc)
    }

    fn constraint_note(&self, sc: &Resolved) -> Option<String> {
        MethodFactory::constraint_note(&self.method, sc)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{GenAlphaParams, Scheme};

    /// WBZ at ρ∞ = 1 is Newmark's parameter set, so the matrix runs WBZ at
    /// the other values only; each tuned set is the scheme its name says.
    #[test]
    fn the_tuned_sets_are_the_schemes_they_name() {
        assert_eq!(GenAlphaParams::wbz(1.0), GenAlphaParams::newmark());
        for t in &TUNED {
            let spec = t.integrator(&IntegratorSpec::default()).unwrap();
            let scheme = spec.resolve().unwrap().scheme;
            let expected = match t.method {
                Method::GeneralizedAlpha => Scheme::GenAlpha(GenAlphaParams::from_rho_inf(t.value)),
                Method::Hht => Scheme::GenAlpha(GenAlphaParams::hht(t.value)),
                Method::Wbz => Scheme::GenAlpha(GenAlphaParams::wbz(t.value)),
                Method::Bathe => Scheme::Bathe { gamma: t.value },
                Method::MoreauJean => Scheme::MoreauJean { theta: t.value },
                m => panic!("{}: no parameter set expected for {m:?}", t.label),
            };
            assert_eq!(scheme, expected, "{}", t.label);
        }
        // every user-settable key has a non-default value in the quick matrix
        for key in Key::ALL {
            assert!(
                TUNED.iter().any(|t| t.quick && t.key == key),
                "{key:?}: no quick parameter set"
            );
        }
    }
}
