//! `[integrator]`: which time integrator a run uses, and its parameters
//! (MODEL §5 and §9.1).
//!
//! [`Method`] is the scene's data enum (`integrator.method`); [`Scheme`] is
//! the method with its parameters resolved into the numbers the stepper
//! uses. Each parameter key belongs to some methods only (`rho_inf` to
//! `generalized_alpha` and `wbz`, `alpha` to `hht`, `gamma` to `bathe`,
//! `theta` to `moreau_jean`); a key given for a method that does not use it
//! is an error naming both keys, not silently ignored.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// The time integrator (`integrator.method`, MODEL §9.1).
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

impl Method {
    /// Every method, in the order `taut compare --methods` lists them.
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

    /// True when the method needs a diagonal basis (`mesh.kind =
    /// "galerkin"` or `"modal"`): it propagates each mode on its own.
    pub fn needs_modal_basis(self) -> bool {
        self == Method::ModalExact
    }

    /// The method named `name`, if any.
    pub fn from_name(name: &str) -> Option<Method> {
        Method::ALL.into_iter().find(|m| m.name() == name)
    }

    /// The parameter keys of `[integrator]` this method reads.
    pub fn parameters(self) -> &'static [&'static str] {
        match self {
            Method::GeneralizedAlpha | Method::Wbz => &["rho_inf"],
            Method::Hht => &["alpha"],
            Method::Bathe => &["gamma"],
            Method::MoreauJean => &["theta"],
            Method::Newmark | Method::CentralDifference | Method::ModalExact => &[],
        }
    }
}

/// Default HHT α: the damping most often quoted for HHT (Hilber, Hughes &
/// Taylor 1977 recommend α ∈ [0, 1/3]; 0.05 damps the highest modes mildly).
pub const DEFAULT_HHT_ALPHA: f64 = 0.05;

/// Default Bathe splitting γ_B = 1/2 (Bathe & Baig 2005: equal sub-steps).
pub const DEFAULT_BATHE_GAMMA: f64 = 0.5;

/// Default Moreau–Jean θ = 1/2: the trapezoidal rule in velocity, which
/// conserves the energy of a linear system between impacts.
pub const DEFAULT_THETA: f64 = 0.5;

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

/// A method with its parameters resolved: what a stepper is built from.
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
}

/// `[integrator]` as the scene gives it.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct IntegratorSpec {
    /// The method (default `generalized_alpha`).
    #[serde(default)]
    pub method: Method,
    /// Spectral radius at infinite frequency ρ∞ ∈ [0, 1] for
    /// `generalized_alpha` and `wbz` (default 1: no dissipation).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rho_inf: Option<f64>,
    /// HHT α ∈ [0, 1/3] (default 0.05).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub alpha: Option<f64>,
    /// Bathe's splitting γ_B ∈ (0, 1) (default 0.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gamma: Option<f64>,
    /// Moreau–Jean θ ∈ [0.5, 1] (default 0.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub theta: Option<f64>,
}

impl IntegratorSpec {
    /// Check the keys against the method and resolve its parameters.
    pub fn resolve(&self) -> Result<Scheme> {
        let m = self.method;
        for (key, given) in [
            ("rho_inf", self.rho_inf.is_some()),
            ("alpha", self.alpha.is_some()),
            ("gamma", self.gamma.is_some()),
            ("theta", self.theta.is_some()),
        ] {
            if given && !m.parameters().contains(&key) {
                let users: Vec<&str> = Method::ALL
                    .iter()
                    .filter(|x| x.parameters().contains(&key))
                    .map(|x| x.name())
                    .collect();
                let value = match key {
                    "rho_inf" => self.rho_inf,
                    "alpha" => self.alpha,
                    "gamma" => self.gamma,
                    _ => self.theta,
                };
                return Err(Error::invalid(
                    format!("integrator.{key}"),
                    value.map_or(String::new(), |v| v.to_string()),
                    format!(
                        "is a parameter of integrator.method = {}; integrator.method = {} does not use it (remove it or change the method)",
                        users.join(" or "),
                        m.name()
                    ),
                ));
            }
        }
        // a range check is false for NaN, so each also rejects non-finite values
        let in_range = |key: &str, v: f64, ok: bool, range: &str| -> Result<f64> {
            if ok {
                Ok(v)
            } else {
                Err(Error::invalid(
                    format!("integrator.{key}"),
                    v,
                    format!("must be in {range}"),
                ))
            }
        };
        Ok(match m {
            Method::GeneralizedAlpha | Method::Wbz => {
                let rho = self.rho_inf.unwrap_or(1.0);
                let rho = in_range("rho_inf", rho, (0.0..=1.0).contains(&rho), "[0, 1]")?;
                Scheme::GenAlpha(if m == Method::Wbz {
                    GenAlphaParams::wbz(rho)
                } else {
                    GenAlphaParams::from_rho_inf(rho)
                })
            }
            Method::Newmark => Scheme::GenAlpha(GenAlphaParams::newmark()),
            Method::Hht => {
                let a = self.alpha.unwrap_or(DEFAULT_HHT_ALPHA);
                let a = in_range(
                    "alpha",
                    a,
                    (0.0..=1.0 / 3.0).contains(&a),
                    "[0, 1/3] (HHT is unconditionally stable and second order there)",
                )?;
                Scheme::GenAlpha(GenAlphaParams::hht(a))
            }
            Method::Bathe => {
                let g = self.gamma.unwrap_or(DEFAULT_BATHE_GAMMA);
                let g = in_range(
                    "gamma",
                    g,
                    g > 0.0 && g < 1.0,
                    "(0, 1) (the first sub-step ends inside the step)",
                )?;
                Scheme::Bathe { gamma: g }
            }
            Method::CentralDifference => Scheme::CentralDifference,
            Method::MoreauJean => {
                let t = self.theta.unwrap_or(DEFAULT_THETA);
                let t = in_range(
                    "theta",
                    t,
                    (0.5..=1.0).contains(&t),
                    "[0.5, 1] (below 1/2 the θ-scheme is unstable)",
                )?;
                Scheme::MoreauJean { theta: t }
            }
            Method::ModalExact => Scheme::ModalExact,
        })
    }
}

/// Parse a comma-separated list of method names (`--methods`).
pub fn parse_methods(list: &str) -> Result<Vec<Method>> {
    let mut out = Vec::new();
    for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let m = Method::from_name(name).ok_or_else(|| {
            let all: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
            Error::invalid(
                "--methods",
                name,
                format!("must be among {}", all.join(", ")),
            )
        })?;
        if out.contains(&m) {
            return Err(Error::invalid("--methods", name, "is listed twice"));
        }
        out.push(m);
    }
    if out.is_empty() {
        return Err(Error::invalid(
            "--methods",
            list,
            "name at least one method",
        ));
    }
    Ok(out)
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
    fn a_key_of_another_method_is_refused_naming_both() {
        let spec = IntegratorSpec {
            method: Method::Bathe,
            theta: Some(0.6),
            ..IntegratorSpec::default()
        };
        let e = spec.resolve().unwrap_err().to_string();
        assert!(
            e.contains("integrator.theta") && e.contains("moreau_jean") && e.contains("bathe"),
            "{e}"
        );
    }

    #[test]
    fn ranges_are_checked() {
        let bad = [
            (Method::Hht, None, Some(0.5), None, None, "integrator.alpha"),
            (
                Method::Bathe,
                None,
                None,
                Some(1.0),
                None,
                "integrator.gamma",
            ),
            (
                Method::MoreauJean,
                None,
                None,
                None,
                Some(0.4),
                "integrator.theta",
            ),
            (
                Method::Wbz,
                Some(f64::NAN),
                None,
                None,
                None,
                "integrator.rho_inf",
            ),
        ];
        for (method, rho_inf, alpha, gamma, theta, field) in bad {
            let spec = IntegratorSpec {
                method,
                rho_inf,
                alpha,
                gamma,
                theta,
            };
            let e = spec.resolve().unwrap_err().to_string();
            assert!(e.contains(field), "{e}");
        }
    }

    #[test]
    fn method_lists_are_checked() {
        assert_eq!(
            parse_methods("bathe, newmark").unwrap(),
            vec![Method::Bathe, Method::Newmark]
        );
        let e = parse_methods("bathe,magic").unwrap_err().to_string();
        assert!(e.contains("magic") && e.contains("moreau_jean"), "{e}");
        assert!(parse_methods("hht,hht").is_err());
        assert!(parse_methods(",").is_err());
    }
}
