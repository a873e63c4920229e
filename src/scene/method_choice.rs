//! The method a scene's `[integrator]` chooses, resolved once (MODEL
//! §9.1): its name found in the registry, its keys checked (a key of
//! another method is refused naming both), its parameters typed and each
//! in its range. A [`ResolvedMethod`] is what `Resolved` keeps and what
//! the integrators build a run's stepper from; nothing after it looks a
//! method up by name.

use super::contact::ContactSpec;
use super::discretization::Discretization;
use super::integrator::{IntegratorSpec, Key};
use super::method::{Method, MethodInfo};
use super::method_registry::{MethodRef, method_names, method_ref};
use super::scheme::{ParameterValues, Scheme};
use crate::error::{Error, Result};

/// A scene's method, resolved: its registry entry and its typed
/// parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ResolvedMethod {
    /// The method (a built-in one, or one registered by name).
    pub handle: MethodRef,
    /// Its parameters, typed and checked ([`Scheme`]; a registered
    /// method's: the values of the keys it declares).
    pub scheme: Scheme,
}

impl ResolvedMethod {
    /// The built-in `method` with its typed parameters from `spec` (keys
    /// of other methods ignored).
    pub fn built_in(method: Method, spec: &IntegratorSpec) -> Result<Self> {
        Ok(ResolvedMethod {
            handle: MethodRef::built_in(method),
            scheme: method.scheme(spec)?,
        })
    }

    /// The method's name.
    pub fn name(&self) -> &'static str {
        self.handle.name()
    }

    /// The built-in method it is, if it is one.
    pub fn built_in_method(&self) -> Option<Method> {
        self.handle.built_in_method()
    }

    /// Refuse a contact setting or basis the method does not go with
    /// ([`MethodInfo::accepts`]).
    pub fn accepts(&self, c: &ContactSpec, d: Discretization) -> Result<()> {
        self.handle.info().accepts(c, d)
    }
}

impl IntegratorSpec {
    /// The method this `[integrator]` names: a built-in one or one
    /// registered by name; an error naming the known ones otherwise.
    pub fn method_ref(&self) -> Result<MethodRef> {
        method_ref(&self.method).ok_or_else(|| {
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

    /// Resolve the method once: its name, its keys (a key of another
    /// method is an error naming both) and their ranges, into its typed
    /// parameters. The contact settings and basis are checked apart
    /// ([`ResolvedMethod::accepts`]).
    pub fn resolve(&self) -> Result<ResolvedMethod> {
        let handle = self.method_ref()?;
        let reads =
            |info: &dyn MethodInfo, key: Key| info.parameters().iter().any(|p| p.key == key);
        for key in Key::ALL {
            let Some(value) = key.of(self) else {
                continue;
            };
            if reads(handle.info(), key) {
                continue;
            }
            let users: Vec<String> = method_names()
                .into_iter()
                .filter(|n| method_ref(n).is_some_and(|m| reads(m.info(), key)))
                .collect();
            return Err(Error::invalid(
                format!("integrator.{}", key.name()),
                value.to_string(),
                format!(
                    "is a parameter of integrator.method = {}; integrator.method = {} does not use it (remove it or change the method)",
                    users.join(" or "),
                    handle.name()
                ),
            ));
        }
        let scheme = match handle.built_in_method() {
            Some(m) => m.scheme(self)?,
            None => {
                let mut values = ParameterValues::default();
                for p in handle.info().parameters() {
                    values.set(p.key, p.value(self)?);
                }
                Scheme::Registered(values)
            }
        };
        Ok(ResolvedMethod { handle, scheme })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::scheme::GenAlphaParams;

    #[test]
    fn a_key_of_another_method_is_refused_naming_both() {
        let spec = IntegratorSpec {
            method: "bathe".into(),
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
                method: method.name().to_string(),
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
    fn an_unknown_method_is_refused_naming_the_known_ones() {
        let spec = IntegratorSpec {
            method: "magic".into(),
            ..IntegratorSpec::default()
        };
        let e = spec.resolve().unwrap_err().to_string();
        assert!(
            e.contains("integrator.method") && e.contains("magic") && e.contains("moreau_jean"),
            "{e}"
        );
    }

    #[test]
    fn a_built_in_method_resolves_to_itself_with_typed_parameters() {
        let spec = IntegratorSpec {
            method: "wbz".into(),
            rho_inf: Some(0.5),
            ..IntegratorSpec::default()
        };
        let m = spec.resolve().unwrap();
        assert_eq!(m.built_in_method(), Some(Method::Wbz));
        assert_eq!(m.handle, MethodRef::built_in(Method::Wbz));
        assert_eq!(m.scheme, Scheme::GenAlpha(GenAlphaParams::wbz(0.5)));
        assert_eq!(m.name(), "wbz");
    }
}
