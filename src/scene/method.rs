//! `[integrator]`: which time integrator a run uses, and its parameters
//! (MODEL §5 and §9.1).
//!
//! [`Method`] is the scene's data enum (`integrator.method`); [`Scheme`] is
//! the method with its parameters resolved into the numbers the stepper
//! uses. Each parameter key belongs to some methods only (`rho_inf` to
//! `generalized_alpha` and `wbz`, `alpha` to `hht`, `gamma` to `bathe`,
//! `theta` to `moreau_jean`); a key given for a method that does not use it
//! is an error naming both keys, not silently ignored.

use std::sync::RwLock;

use serde::{Deserialize, Serialize};

use super::{ContactSpec, Discretization, Formulation, Placement};
use crate::error::{Error, Result};

/// The built-in time integrators (`integrator.method`, MODEL §9.1): the
/// one place each is described (name, parameters with their ranges, formal
/// order in Δt, which contact settings and bases it accepts, its scheme and
/// its diagnosis). Its stepper is built from its [`Scheme`] by
/// `integrate::stepper_for`.
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
    key: "rho_inf",
    default: 1.0,
    range: "[0, 1]",
    contains: |v| (0.0..=1.0).contains(&v),
};

/// HHT α ∈ [0, 1/3].
const HHT_ALPHA: Parameter = Parameter {
    key: "alpha",
    default: DEFAULT_HHT_ALPHA,
    range: "[0, 1/3] (HHT is unconditionally stable and second order there)",
    contains: |v| (0.0..=1.0 / 3.0).contains(&v),
};

/// Bathe's splitting γ_B ∈ (0, 1).
const BATHE_GAMMA: Parameter = Parameter {
    key: "gamma",
    default: DEFAULT_BATHE_GAMMA,
    range: "(0, 1) (the first sub-step ends inside the step)",
    contains: |v| v > 0.0 && v < 1.0,
};

/// Moreau–Jean θ ∈ [½, 1].
const THETA: Parameter = Parameter {
    key: "theta",
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

    /// The scheme with the parameter values `v` (in the order of
    /// [`Method::parameters`], each in its range).
    fn scheme_of(self, v: &[f64]) -> Scheme {
        match self {
            Method::GeneralizedAlpha => Scheme::GenAlpha(GenAlphaParams::from_rho_inf(v[0])),
            Method::Wbz => Scheme::GenAlpha(GenAlphaParams::wbz(v[0])),
            Method::Newmark => Scheme::GenAlpha(GenAlphaParams::newmark()),
            Method::Hht => Scheme::GenAlpha(GenAlphaParams::hht(v[0])),
            Method::Bathe => Scheme::Bathe { gamma: v[0] },
            Method::CentralDifference => Scheme::CentralDifference,
            Method::MoreauJean => Scheme::MoreauJean { theta: v[0] },
            Method::ModalExact => Scheme::ModalExact,
        }
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
        if self == Method::ModalExact && c.formulation == Formulation::Impact {
            return Err(Error::invalid(
                "contact.formulation",
                "\"impact\"",
                "integrator.method = modal_exact holds the contact force over each step and imposes the gap itself at the step's end (MODEL §9.3); an impact law acts by impulses on the gap rate, which that representation has no place for, and a velocity-level condition would replace the position gap it propagates exactly: use lagrange, penalty or complementarity (or integrator.method = moreau_jean for an impact law)",
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
            spec.set(p.key, base.get(p.key));
        }
        spec
    }

    /// This method's scheme for a scene whose `[integrator]` is `base` (its
    /// parameters read from `base`, keys of other methods ignored) and whose
    /// contact and basis are `c`, `d`: what a run of this method steps with.
    pub fn scheme(
        self,
        base: &IntegratorSpec,
        c: &ContactSpec,
        d: Discretization,
    ) -> Result<Scheme> {
        let scheme = self.integrator(base).scheme()?;
        self.accepts(c, d)?;
        Ok(scheme)
    }
}

/// One parameter of `[integrator]` a method reads.
#[derive(Debug, Clone, Copy)]
pub struct Parameter {
    /// The key in `[integrator]` (one of [`IntegratorSpec::KEYS`]).
    pub key: &'static str,
    /// Its value when the scene gives none.
    pub default: f64,
    /// The allowed range as the error message states it.
    pub range: &'static str,
    /// True when a value lies in the range (false for NaN).
    pub contains: fn(f64) -> bool,
}

/// A method's description as scene validation reads it: the built-in
/// [`Method`]s, and every method registered by name
/// (`integrate::register`), whose `MethodFactory` builds on it.
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

/// The methods registered by name besides the built-in ones, in the order
/// of registration (`integrate::register` adds to it).
static REGISTERED: RwLock<Vec<&'static dyn MethodInfo>> = RwLock::new(Vec::new());

/// The method named `name`: a built-in one, or one registered.
pub fn method_info(name: &str) -> Option<&'static dyn MethodInfo> {
    static BUILT_IN: [Method; Method::ALL.len()] = Method::ALL;
    if let Some(m) = BUILT_IN.iter().find(|m| m.name() == name) {
        return Some(m);
    }
    registered().into_iter().find(|m| m.name() == name)
}

/// The methods registered besides the built-in ones.
fn registered() -> Vec<&'static dyn MethodInfo> {
    REGISTERED
        .read()
        .map_or_else(|e| e.into_inner().clone(), |r| r.clone())
}

/// Every method's name: the built-in ones, then those registered.
pub fn method_names() -> Vec<String> {
    let mut names: Vec<String> = Method::ALL.iter().map(|m| m.name().to_string()).collect();
    names.extend(registered().iter().map(|m| m.name()));
    names
}

/// Add `method` to the names a scene may use (`integrate::register` calls
/// this with its factory). Refused when the name is empty or taken.
pub(crate) fn register_info(method: &'static dyn MethodInfo) -> Result<()> {
    let name = method.name();
    let well_formed = !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
    if !well_formed {
        return Err(Error::invalid(
            "method name",
            format!("\"{name}\""),
            "must be non-empty lowercase ASCII letters, digits and '_' (it is written in integrator.method and --methods)",
        ));
    }
    let mut list = REGISTERED.write().unwrap_or_else(|e| e.into_inner());
    if Method::from_name(&name).is_some() || list.iter().any(|m| m.name() == name) {
        return Err(Error::invalid(
            "method name",
            format!("\"{name}\""),
            "is taken by another method (each name selects one method)",
        ));
    }
    list.push(method);
    Ok(())
}

/// The values of `params` in `spec`, defaults filled, each checked against
/// its range (a range check is false for NaN, so each also rejects
/// non-finite values).
fn values(params: &[Parameter], spec: &IntegratorSpec) -> Result<Vec<f64>> {
    params
        .iter()
        .map(|p| {
            let v = spec.get(p.key).unwrap_or(p.default);
            if (p.contains)(v) {
                Ok(v)
            } else {
                Err(Error::invalid(
                    format!("integrator.{}", p.key),
                    v,
                    format!("must be in {}", p.range),
                ))
            }
        })
        .collect()
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
    /// A method registered by name (`integrate::register`): its stepper is
    /// its own factory's, reading `[integrator]` itself.
    Registered,
}

/// `[integrator]` as the scene gives it.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct IntegratorSpec {
    /// The method's name (default `generalized_alpha`): a built-in
    /// [`Method`] or one registered by name (`integrate::register`).
    #[serde(default = "default_method")]
    pub method: String,
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

/// `integrator.method` when the scene gives none.
fn default_method() -> String {
    Method::default().name().to_string()
}

impl Default for IntegratorSpec {
    fn default() -> Self {
        IntegratorSpec {
            method: default_method(),
            rho_inf: None,
            alpha: None,
            gamma: None,
            theta: None,
        }
    }
}

impl IntegratorSpec {
    /// The parameter keys of `[integrator]`, in the order of the table.
    pub const KEYS: [&'static str; 4] = ["rho_inf", "alpha", "gamma", "theta"];

    /// The value given for parameter `key` (one of [`IntegratorSpec::KEYS`]).
    pub fn get(&self, key: &str) -> Option<f64> {
        match key {
            "rho_inf" => self.rho_inf,
            "alpha" => self.alpha,
            "gamma" => self.gamma,
            "theta" => self.theta,
            _ => None,
        }
    }

    /// Set parameter `key` (one of [`IntegratorSpec::KEYS`]; others are ignored).
    pub fn set(&mut self, key: &str, value: Option<f64>) {
        match key {
            "rho_inf" => self.rho_inf = value,
            "alpha" => self.alpha = value,
            "gamma" => self.gamma = value,
            "theta" => self.theta = value,
            _ => {}
        }
    }

    /// The method this `[integrator]` names: a built-in one or one
    /// registered by name; an error naming the known ones otherwise.
    pub fn method_info(&self) -> Result<&'static dyn MethodInfo> {
        method_info(&self.method).ok_or_else(|| {
            Error::invalid(
                "integrator.method",
                format!("\"{}\"", self.method),
                format!(
                    "must be among {} (a method of one's own is named after integrate::register)",
                    method_names().join(", ")
                ),
            )
        })
    }

    /// Check the method's name, its keys (a key of another method is an
    /// error naming both) and their ranges, and resolve its parameters.
    /// The contact settings and basis are checked apart
    /// ([`MethodInfo::accepts`]).
    pub fn scheme(&self) -> Result<Scheme> {
        let m = self.method_info()?;
        for key in IntegratorSpec::KEYS {
            let Some(value) = self.get(key) else {
                continue;
            };
            if m.parameters().iter().any(|p| p.key == key) {
                continue;
            }
            let users: Vec<String> = method_names()
                .into_iter()
                .filter(|n| {
                    method_info(n).is_some_and(|x| x.parameters().iter().any(|p| p.key == key))
                })
                .collect();
            return Err(Error::invalid(
                format!("integrator.{key}"),
                value.to_string(),
                format!(
                    "is a parameter of integrator.method = {}; integrator.method = {} does not use it (remove it or change the method)",
                    users.join(" or "),
                    m.name()
                ),
            ));
        }
        let v = values(m.parameters(), self)?;
        Ok(match Method::from_name(&self.method) {
            Some(builtin) => builtin.scheme_of(&v),
            None => Scheme::Registered,
        })
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
    fn a_key_of_another_method_is_refused_naming_both() {
        let spec = IntegratorSpec {
            method: "bathe".into(),
            theta: Some(0.6),
            ..IntegratorSpec::default()
        };
        let e = spec.scheme().unwrap_err().to_string();
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
                method: method.name().to_string(),
                rho_inf,
                alpha,
                gamma,
                theta,
            };
            let e = spec.scheme().unwrap_err().to_string();
            assert!(e.contains(field), "{e}");
        }
    }

    #[test]
    fn an_unknown_method_is_refused_naming_the_known_ones() {
        let spec = IntegratorSpec {
            method: "magic".into(),
            ..IntegratorSpec::default()
        };
        let e = spec.scheme().unwrap_err().to_string();
        assert!(
            e.contains("integrator.method") && e.contains("magic") && e.contains("moreau_jean"),
            "{e}"
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
        assert_eq!(
            Method::Wbz.integrator(&base).scheme().unwrap(),
            Scheme::GenAlpha(GenAlphaParams::wbz(0.8))
        );
    }
}
