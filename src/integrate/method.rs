//! The method seam: what a time integrator is to a run, and how a method
//! found by name reaches its factory.
//!
//! A method is a [`MethodFactory`]: its description ([`MethodInfo`]: name,
//! parameters, the contact settings and bases it accepts) and the
//! [`Stepper`] it builds for a run. The built-in ones are the values of
//! [`Method`], described in `scene/method.rs` and stepped by
//! [`stepper_for`] from their typed parameters; a method of one's own is
//! registered by name ([`register`]) and is then reached as the built-in
//! ones are: from a scene (`integrator.method = "<name>"`), from
//! `--methods <name>` ([`parse_methods`]) and from Rust ([`method_named`],
//! [`crate::run_with`]). `examples/custom_method.rs` does it end to end.
//!
//! There is one registry, the scene layer's (`scene/method_registry.rs`):
//! [`register`] adds the factory's description and a type-erased handle
//! to the factory itself ([`FactoryHandle`]), and [`factory_of`] reads a
//! [`MethodRef`] back into its factory, a downcast to this file's own
//! type: a resolved scene's method ([`crate::scene::ResolvedMethod`]) is
//! built without a lookup by name.

use super::bathe::Bathe;
use super::central_difference::CentralDifference;
use super::gen_alpha::GenAlpha;
use super::modal_exact::ModalExact;
use super::moreau_jean::MoreauJean;
use super::state::State;
use super::step_map::Multipliers;
use super::stepper::Stepper;
use super::system::{Initial, System};
use crate::error::{Error, Result};
use crate::resolve::Resolved;
use crate::scene::{
    IntegratorSpec, Method, MethodInfo, MethodRef, Scheme, method_names, method_ref,
};

/// Builds a [`Stepper`] for a run: a built-in [`Method`], or a method of
/// one's own (describe it with [`MethodInfo`], build it here, and
/// [`register`] it to reach it by name).
pub trait MethodFactory: MethodInfo {
    /// Build the stepper for a validated scene, given its system and the
    /// consistent initial state (the accelerations in `init`; a method may
    /// adjust `st`, e.g. to a half-step velocity). A method that works with
    /// impulses says so with `System::set_multipliers`. The driver has
    /// checked [`MethodInfo::accepts`] for the scene. A method registered
    /// by name that declares parameters ([`MethodInfo::parameters`]) finds
    /// their checked values in `sc.method.scheme`
    /// ([`Scheme::Registered`]) when the scene names it.
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
    /// This method's typed parameters for the scene `sc`: the scene's own,
    /// resolved once, when the scene names this method; otherwise read
    /// from the scene's `[integrator]` (keys of other methods ignored)
    /// with its contact settings and basis checked.
    pub fn scheme_for(self, sc: &Resolved) -> Result<Scheme> {
        if sc.method.built_in_method() == Some(self) {
            return Ok(sc.method.scheme);
        }
        let scheme = self.scheme(&sc.scene.integrator)?;
        self.accepts(&sc.contact, sc.discretization)?;
        Ok(scheme)
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
        sc.method.built_in_method() == Some(*self)
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
pub(crate) fn stepper_for(
    scheme: Scheme,
    sc: &Resolved,
    sys: &mut System,
    st: &mut State,
    init: Initial,
) -> Result<Box<dyn Stepper>> {
    // a multi-mass pantograph: modal_exact does not carry it (`chain.rs`)
    // and refuses before any check of its own
    if sys.has_chains() && scheme == Scheme::ModalExact {
        return Err(super::chain::refusal(Method::ModalExact.name()));
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
        Scheme::Registered(_) => {
            return Err(Error::invalid(
                "integrator.method",
                format!("\"{}\"", sc.method.name()),
                "is a registered method, built by its own factory (integrate::method_named)",
            ));
        }
    })
}

/// The type-erased handle a registry entry keeps of a registered
/// factory (module docs): only [`register`] makes one, only
/// [`factory_of`] reads one.
struct FactoryHandle(&'static dyn MethodFactory);

/// The built-in methods as factories.
static BUILT_IN: [Method; Method::ALL.len()] = Method::ALL;

/// Register `method` by its name, so that a scene (`integrator.method =
/// "<name>"`), `--methods <name>` and `method_named` reach it as they
/// reach a built-in method. Refused when the name is malformed or taken (a
/// built-in name, or one registered before).
pub fn register(method: &'static dyn MethodFactory) -> Result<()> {
    crate::scene::register_method(method, Box::new(FactoryHandle(method)))?;
    Ok(())
}

/// The factory of a method of the registry: a built-in [`Method`], or the
/// factory [`register`] put behind the entry's handle.
pub(crate) fn factory_of(method: MethodRef) -> &'static dyn MethodFactory {
    if let Some(m) = method.built_in_method() {
        return &BUILT_IN[m as usize];
    }
    let handle = method
        .factory()
        .and_then(|f| f.downcast_ref::<FactoryHandle>());
    match handle {
        Some(h) => h.0,
        None => unreachable!("a registered entry holds the handle integrate::register made"),
    }
}

/// The method named `name`: a built-in [`Method`], or one [`register`]ed.
pub(crate) fn method_named(name: &str) -> Option<&'static dyn MethodFactory> {
    method_ref(name).map(factory_of)
}

/// The method a validated scene names (`integrator.method`), as it was
/// resolved: no lookup by name.
pub(crate) fn scene_method(sc: &Resolved) -> &'static dyn MethodFactory {
    factory_of(sc.method.handle)
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

    /// A scene naming a registered method resolves to its entry once; the
    /// entry gives back the very factory registered (no lookup by name),
    /// with the values of the parameters it declares, checked.
    #[test]
    fn a_registered_method_resolves_to_its_own_factory() {
        use crate::scene::{IntegratorSpec, Key, Parameter};
        struct Declares;
        const THETA: Parameter = Parameter {
            key: Key::Theta,
            default: 0.75,
            range: "[0.5, 1]",
            contains: |v| (0.5..=1.0).contains(&v),
        };
        impl MethodInfo for Declares {
            fn name(&self) -> String {
                "unit_test_declares".to_string()
            }
            fn parameters(&self) -> &[Parameter] {
                &[THETA]
            }
        }
        impl MethodFactory for Declares {
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
        static DECLARES: Declares = Declares;
        register(&DECLARES).unwrap();
        let mut spec = IntegratorSpec {
            method: "unit_test_declares".into(),
            ..IntegratorSpec::default()
        };
        let m = spec.resolve().unwrap();
        assert!(std::ptr::addr_eq(factory_of(m.handle), &DECLARES));
        let Scheme::Registered(values) = m.scheme else {
            panic!("a registered method's scheme: {:?}", m.scheme)
        };
        assert_eq!(values.get(Key::Theta), Some(0.75));
        assert_eq!(values.get(Key::RhoInf), None);
        spec.theta = Some(0.4);
        let e = spec.resolve().unwrap_err().to_string();
        assert!(
            e.contains("integrator.theta") && e.contains("[0.5, 1]"),
            "{e}"
        );
        spec.theta = None;
        spec.rho_inf = Some(0.5);
        let e = spec.resolve().unwrap_err().to_string();
        assert!(
            e.contains("integrator.rho_inf") && e.contains("unit_test_declares"),
            "{e}"
        );
    }
}
