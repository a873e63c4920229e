//! `[integrator]` as the scene gives it (MODEL §5, §9.1): the method's name
//! and the four parameter keys, each a typed field ([`Key`] names them).
//! Plain data: which method the name selects, and which keys that method
//! reads, is resolved once, by [`IntegratorSpec::resolve`]
//! (`method_choice.rs`).

use serde::{Deserialize, Serialize};

/// `integrator.method` when the scene gives none: `generalized_alpha`,
/// the study's method (`Method::default`).
pub(crate) const DEFAULT_METHOD: &str = "generalized_alpha";

/// `[integrator]` as the scene gives it.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct IntegratorSpec {
    /// The method's name (default `generalized_alpha`): a built-in
    /// `Method` or one registered by name (`integrate::register`), found
    /// once, when the scene is resolved.
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
    DEFAULT_METHOD.to_string()
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

/// A parameter key of `[integrator]`: which typed field of
/// [`IntegratorSpec`] a method reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Key {
    /// `rho_inf`: ρ∞ of `generalized_alpha` and `wbz`.
    RhoInf,
    /// `alpha`: HHT's α.
    Alpha,
    /// `gamma`: Bathe's γ_B.
    Gamma,
    /// `theta`: Moreau–Jean's θ.
    Theta,
}

impl Key {
    /// Every key, in the order of the table (docs/scene.md).
    pub const ALL: [Key; 4] = [Key::RhoInf, Key::Alpha, Key::Gamma, Key::Theta];

    /// The key as written in `[integrator]`.
    pub fn name(self) -> &'static str {
        match self {
            Key::RhoInf => "rho_inf",
            Key::Alpha => "alpha",
            Key::Gamma => "gamma",
            Key::Theta => "theta",
        }
    }

    /// The value `spec` gives for this key.
    pub fn of(self, spec: &IntegratorSpec) -> Option<f64> {
        match self {
            Key::RhoInf => spec.rho_inf,
            Key::Alpha => spec.alpha,
            Key::Gamma => spec.gamma,
            Key::Theta => spec.theta,
        }
    }

    /// Set this key of `spec` to `value`.
    pub fn set(self, spec: &mut IntegratorSpec, value: Option<f64>) {
        match self {
            Key::RhoInf => spec.rho_inf = value,
            Key::Alpha => spec.alpha = value,
            Key::Gamma => spec.gamma = value,
            Key::Theta => spec.theta = value,
        }
    }
}
