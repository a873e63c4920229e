//! A method's parameters, typed (MODEL §5, §9.1): what `[integrator]`
//! resolves to, checked where it is parsed (`method_choice.rs`), and what
//! a stepper is built from. The generalized-α family shares one parameter
//! set ([`GenAlphaParams`]: Newmark, HHT and WBZ are named members of
//! it); Bathe and Moreau–Jean have one parameter each; a method
//! registered by name gets the values of the keys it declares
//! ([`ParameterValues`]).

use super::integrator::Key;

/// Default HHT α: the damping most often quoted for HHT (Hilber, Hughes &
/// Taylor 1977 recommend α ∈ [0, 1/3]; 0.05 damps the highest modes mildly).
pub(crate) const DEFAULT_HHT_ALPHA: f64 = 0.05;

/// Default Bathe splitting γ_B = 1/2 (Bathe & Baig 2005: equal sub-steps).
pub(crate) const DEFAULT_BATHE_GAMMA: f64 = 0.5;

/// Default Moreau–Jean θ = 1/2: the trapezoidal rule in velocity, which
/// conserves the energy of a linear system between impacts.
pub(crate) const DEFAULT_THETA: f64 = 0.5;

/// The parameters of the generalized-α family (MODEL §5):
/// `A = (1 − α_m)M + (1 − α_f)βΔt²K`, balance at t_{n+1−α_f} and t_{n+1−α_m}.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GenAlphaParams {
    /// α_m.
    pub alpha_m: f64,
    /// α_f.
    pub alpha_f: f64,
    /// β.
    pub beta: f64,
    /// γ.
    pub gamma: f64,
}

impl GenAlphaParams {
    /// Generalized-α from ρ∞ ∈ [0, 1] (Chung & Hulbert 1993):
    /// α_m = (2ρ∞ − 1)/(ρ∞ + 1), α_f = ρ∞/(ρ∞ + 1), γ = ½ − α_m + α_f,
    /// β = (1 − α_m + α_f)²/4.
    pub fn from_rho_inf(rho: f64) -> Self {
        let alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
        let alpha_f = rho / (rho + 1.0);
        let gamma = 0.5 - alpha_m + alpha_f;
        let beta = 0.25 * (1.0 - alpha_m + alpha_f).powi(2);
        GenAlphaParams {
            alpha_m,
            alpha_f,
            beta,
            gamma,
        }
    }

    /// Newmark's average acceleration: α_m = α_f = 0, β = ¼, γ = ½.
    pub fn newmark() -> Self {
        GenAlphaParams {
            alpha_m: 0.0,
            alpha_f: 0.0,
            beta: 0.25,
            gamma: 0.5,
        }
    }

    /// HHT-α, α ∈ [0, 1/3]: α_m = 0, α_f = α, γ = ½ + α, β = (1 + α)²/4.
    pub fn hht(alpha: f64) -> Self {
        GenAlphaParams {
            alpha_m: 0.0,
            alpha_f: alpha,
            beta: 0.25 * (1.0 + alpha).powi(2),
            gamma: 0.5 + alpha,
        }
    }

    /// WBZ-α from ρ∞: α_f = 0, α_m = (ρ∞ − 1)/(ρ∞ + 1), γ = ½ − α_m,
    /// β = (1 − α_m)²/4.
    pub fn wbz(rho: f64) -> Self {
        let alpha_m = (rho - 1.0) / (rho + 1.0);
        GenAlphaParams {
            alpha_m,
            alpha_f: 0.0,
            beta: 0.25 * (1.0 - alpha_m).powi(2),
            gamma: 0.5 - alpha_m,
        }
    }
}

/// A method's parameters resolved: what a stepper is built from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scheme {
    /// The generalized-α family (`generalized_alpha`, `newmark`, `hht`, `wbz`).
    GenAlpha(GenAlphaParams),
    /// Bathe's composite scheme with splitting γ_B ∈ (0, 1).
    Bathe {
        /// γ_B: the first sub-step ends at t + γ_B Δt.
        gamma: f64,
    },
    /// Explicit central difference with the consistent mass.
    CentralDifference,
    /// Moreau–Jean θ-scheme, θ ∈ [½, 1].
    MoreauJean {
        /// θ.
        theta: f64,
    },
    /// Exact modal propagation (MODEL §9.3); no parameters.
    ModalExact,
    /// A method registered by name (`integrate::register`): the values of
    /// the parameters it declares; its stepper is its own factory's.
    Registered(ParameterValues),
}

/// The values of the `[integrator]` keys a registered method declares
/// (`MethodInfo::parameters`), each in its range, its default where the
/// scene gives none; `None` for a key it does not declare.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ParameterValues {
    values: [Option<f64>; Key::ALL.len()],
}

impl ParameterValues {
    /// The value of `key`, if the method declares it.
    pub fn get(&self, key: Key) -> Option<f64> {
        self.values[key as usize]
    }

    /// Set the value of `key`.
    pub(crate) fn set(&mut self, key: Key, value: f64) {
        self.values[key as usize] = Some(value);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rho_one_is_the_study_s_parameter_set() {
        let ga = GenAlphaParams::from_rho_inf(1.0);
        assert_eq!(
            (ga.alpha_m, ga.alpha_f, ga.beta, ga.gamma),
            (0.5, 0.5, 0.25, 0.5)
        );
    }

    #[test]
    fn rho_zero_is_asymptotically_annihilating() {
        let ga = GenAlphaParams::from_rho_inf(0.0);
        assert_eq!((ga.alpha_m, ga.alpha_f), (-1.0, 0.0));
        assert_eq!(ga.gamma, 1.5);
        assert_eq!(ga.beta, 1.0);
    }

    #[test]
    fn named_sets_are_members_of_the_family() {
        // HHT with α = 0 and WBZ with ρ∞ = 1 are Newmark's average acceleration
        assert_eq!(GenAlphaParams::hht(0.0), GenAlphaParams::newmark());
        assert_eq!(GenAlphaParams::wbz(1.0), GenAlphaParams::newmark());
        // second order: γ = ½ − α_m + α_f for every member
        for p in [
            GenAlphaParams::hht(0.3),
            GenAlphaParams::wbz(0.4),
            GenAlphaParams::from_rho_inf(0.6),
        ] {
            assert!((p.gamma - (0.5 - p.alpha_m + p.alpha_f)).abs() < 1e-15);
        }
    }

    #[test]
    fn keys_index_their_own_values() {
        let mut v = ParameterValues::default();
        v.set(Key::Theta, 0.7);
        assert_eq!(v.get(Key::Theta), Some(0.7));
        assert!(
            Key::ALL
                .iter()
                .filter(|&&k| k != Key::Theta)
                .all(|&k| v.get(k).is_none())
        );
    }
}
