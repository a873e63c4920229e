//! The method seam: what a time integrator is to a run, and the registry
//! of methods by name.
//!
//! A method is a [`MethodFactory`]: its description ([`MethodInfo`]: name,
//! parameters, the contact settings and bases it accepts) and the
//! [`Stepper`] it builds for a run. The built-in ones are the values of
//! [`Method`], described in `scene/method.rs` and stepped by
//! [`stepper_for`]; a method of one's own is registered by name
//! ([`register`]) and is then reached as the built-in ones are: from a
//! scene (`integrator.method = "<name>"`), from `--methods <name>`
//! ([`parse_methods`]) and from Rust ([`method_named`],
//! [`crate::run_with`]). `examples/custom_method.rs` does it end to end.

use std::sync::RwLock;

use super::{
    Bathe, CentralDifference, GenAlpha, Initial, ModalExact, MoreauJean, Multipliers, State,
    Stepper, System,
};
use crate::error::{Error, Result};
use crate::resolve::Resolved;
use crate::scene::{IntegratorSpec, Method, MethodInfo, Scheme, method_names};

/// Builds a [`Stepper`] for a run: a built-in [`Method`], or a method of
/// one's own (describe it with [`MethodInfo`], build it here, and
/// [`register`] it to reach it by name).
pub trait MethodFactory: MethodInfo {
    /// Build the stepper for a validated scene, given its system and the
    /// consistent initial state (the accelerations in `init`; a method may
    /// adjust `st`, e.g. to a half-step velocity). A method that works with
    /// impulses says so with [`System::set_multipliers`]. The driver has
    /// checked [`MethodInfo::accepts`] for the scene.
    fn build(
        &self,
        sc: &Resolved,
        sys: &mut System,
        st: &mut State,
        init: Initial,
    ) -> Result<Box<dyn Stepper>>;

    /// The `[integrator]` that selects this method in a scene whose own is
    /// `base`, as typed data (a built-in method: its name with the
    /// parameters of `base` it reads). `None` (the default): the method
    /// runs on the scene as it is, through [`crate::run_with`].
    fn integrator(&self, _base: &IntegratorSpec) -> Option<IntegratorSpec> {
        None
    }

    /// True when this factory builds what the scene's own `[integrator]`
    /// builds for `sc` (a built-in method named there), so the run may step
    /// in a batch with others (`integrate::batch`); a method of one's own
    /// steps alone.
    fn is_scene_method(&self, _sc: &Resolved) -> bool {
        false
    }

    /// The method's formal order in Δt for the scene `sc` (the order of its
    /// local truncation error minus one, for smooth solutions), which
    /// `taut converge` and `taut verify` hold observed orders against;
    /// `None` when not declared.
    fn time_order(&self, _sc: &Resolved) -> Option<f64> {
        None
    }

    /// What a diagnosis names as this method's likely cause when a run of
    /// `sc` with a moving contact goes unstable or chatters (a built-in
    /// generalized-α member: its undamped constraint mode); `None` by
    /// default.
    fn constraint_note(&self, _sc: &Resolved) -> Option<String> {
        None
    }
}

impl Method {
    /// This method's scheme for the scene `sc`: its parameters read from
    /// the scene's `[integrator]` (keys of other methods ignored), its
    /// contact settings and basis checked, whatever method the scene names.
    pub fn scheme_for(self, sc: &Resolved) -> Result<Scheme> {
        self.scheme(&sc.integrator, &sc.contact, sc.discretization)
    }
}

impl MethodFactory for Method {
    /// Builds this method (not the scene's): `run_with(&sc, &Method::Newmark)`
    /// steps Newmark whatever `sc`'s `[integrator]` names.
    fn build(
        &self,
        sc: &Resolved,
        sys: &mut System,
        st: &mut State,
        init: Initial,
    ) -> Result<Box<dyn Stepper>> {
        let scheme = self.scheme_for(sc)?;
        stepper_for(scheme, sc, sys, st, init)
    }

    fn integrator(&self, base: &IntegratorSpec) -> Option<IntegratorSpec> {
        Some(Method::integrator(*self, base))
    }

    fn is_scene_method(&self, sc: &Resolved) -> bool {
        sc.integrator.method == self.name()
    }

    fn time_order(&self, sc: &Resolved) -> Option<f64> {
        let scheme = self.scheme_for(sc).ok()?;
        Some(Method::time_order(*self, &scheme))
    }

    fn constraint_note(&self, sc: &Resolved) -> Option<String> {
        let scheme = self.scheme_for(sc).ok()?;
        Method::constraint_note(*self, &scheme)
    }
}

/// The stepper of a built-in `scheme`.
pub fn stepper_for(
    scheme: Scheme,
    sc: &Resolved,
    sys: &mut System,
    st: &mut State,
    init: Initial,
) -> Result<Box<dyn Stepper>> {
    // a multi-mass pantograph: modal_exact does not carry it (`chain.rs`)
    // and refuses before any check of its own
    if sys.has_chains() && scheme == Scheme::ModalExact {
        return Err(super::chain::refusal(method_name(scheme)));
    }
    Ok(match scheme {
        Scheme::GenAlpha(p) => {
            // a deliberate defect of the test build (`crate::defects`)
            let p = if crate::defects::on(crate::defects::Defect::StepGamma) {
                crate::scene::GenAlphaParams {
                    gamma: p.gamma + 0.01,
                    ..p
                }
            } else {
                p
            };
            Box::new(GenAlpha::new(p, sys, st, init)?)
        }
        Scheme::Bathe { gamma } => Box::new(Bathe::new(gamma, sys, st, init)?),
        Scheme::CentralDifference => Box::new(CentralDifference::new(sc, sys, st, init)?),
        Scheme::MoreauJean { theta } => {
            sys.set_multipliers(Multipliers::Impulses);
            Box::new(MoreauJean::new(theta, sys, st)?)
        }
        Scheme::ModalExact => Box::new(ModalExact::new(sys)?),
        Scheme::Registered => {
            return Err(Error::invalid(
                "integrator.method",
                format!("\"{}\"", sc.integrator.method),
                "is a registered method, built by its own factory (integrate::method_named)",
            ));
        }
    })
}

/// The methods registered by name besides the built-in ones.
static REGISTERED: RwLock<Vec<&'static dyn MethodFactory>> = RwLock::new(Vec::new());

/// Register `method` by its name, so that a scene (`integrator.method =
/// "<name>"`), `--methods <name>` and [`method_named`] reach it as they
/// reach a built-in method. Refused when the name is malformed or taken (a
/// built-in name, or one registered before).
pub fn register(method: &'static dyn MethodFactory) -> Result<()> {
    let mut list = REGISTERED.write().unwrap_or_else(|e| e.into_inner());
    crate::scene::register_info(method)?;
    list.push(method);
    Ok(())
}

/// The method named `name`: a built-in [`Method`], or one [`register`]ed.
pub fn method_named(name: &str) -> Option<&'static dyn MethodFactory> {
    static BUILT_IN: [Method; Method::ALL.len()] = Method::ALL;
    if let Some(m) = BUILT_IN.iter().find(|m| m.name() == name) {
        return Some(m);
    }
    let list = REGISTERED.read().unwrap_or_else(|e| e.into_inner());
    list.iter().copied().find(|m| m.name() == name)
}

/// The method a validated scene names (`integrator.method`).
pub fn scene_method(sc: &Resolved) -> Result<&'static dyn MethodFactory> {
    method_named(&sc.integrator.method).ok_or_else(|| {
        Error::invalid(
            "integrator.method",
            format!("\"{}\"", sc.integrator.method),
            format!("must be among {}", method_names().join(", ")),
        )
    })
}

/// Parse a comma-separated list of method names (`--methods`): built-in
/// ones and those [`register`]ed.
pub fn parse_methods(list: &str) -> Result<Vec<&'static dyn MethodFactory>> {
    let mut out: Vec<&'static dyn MethodFactory> = Vec::new();
    for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let m = method_named(name).ok_or_else(|| {
            Error::invalid(
                "--methods",
                name,
                format!("must be among {}", method_names().join(", ")),
            )
        })?;
        if out.iter().any(|x| x.name() == name) {
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

/// The scene name of a built-in scheme, for messages.
fn method_name(scheme: Scheme) -> &'static str {
    match scheme {
        Scheme::GenAlpha(_) => "generalized_alpha",
        Scheme::Bathe { .. } => "bathe",
        Scheme::CentralDifference => "central_difference",
        Scheme::MoreauJean { .. } => "moreau_jean",
        Scheme::ModalExact => "modal_exact",
        Scheme::Registered => "registered",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn method_lists_are_checked() {
        let names = |l: &str| -> Vec<String> {
            match parse_methods(l) {
                Ok(list) => list.iter().map(|m| m.name()).collect(),
                Err(e) => panic!("a valid list: {e}"),
            }
        };
        assert_eq!(names("bathe, newmark"), ["bathe", "newmark"]);
        let e = parse_methods("bathe,magic")
            .err()
            .expect("magic is refused")
            .to_string();
        assert!(e.contains("magic") && e.contains("moreau_jean"), "{e}");
        assert!(parse_methods("hht,hht").is_err());
        assert!(parse_methods(",").is_err());
    }

    /// A name is registered once, and no built-in name is taken over.
    #[test]
    fn names_are_unique_and_well_formed() {
        struct Named(&'static str);
        impl MethodInfo for Named {
            fn name(&self) -> String {
                self.0.to_string()
            }
        }
        impl MethodFactory for Named {
            fn build(
                &self,
                _: &Resolved,
                _: &mut System,
                _: &mut State,
                _: Initial,
            ) -> Result<Box<dyn Stepper>> {
                unreachable!("never run")
            }
        }
        static BATHE: Named = Named("bathe");
        static MINE: Named = Named("unit_test_method");
        static BAD: Named = Named("Not a name");
        assert!(register(&BATHE).is_err());
        assert!(register(&BAD).is_err());
        register(&MINE).unwrap();
        let e = register(&MINE).unwrap_err().to_string();
        assert!(e.contains("unit_test_method") && e.contains("taken"), "{e}");
        assert_eq!(
            method_named("unit_test_method").map(|m| m.name()),
            Some("unit_test_method".to_string())
        );
        assert!(crate::scene::method_names().contains(&"unit_test_method".to_string()));
    }
}
