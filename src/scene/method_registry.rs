//! The one registry of time integrators by name: the built-in [`Method`]s
//! and the methods registered from outside the crate
//! (`integrate::register`), each found by its name once — when a scene is
//! resolved, or a front end's `--methods` is read — and held from then on
//! as a [`MethodRef`].
//!
//! **The seam.** A method registered by name is a factory of steppers
//! (`integrate::MethodFactory`), a type of the integrate layer, four
//! floors above this one: scene validation must find the method and check
//! its keys and contact settings without importing the integrators. So an
//! entry holds the method's description ([`MethodInfo`], a scene-layer
//! trait its factory extends) and its factory behind a type-erased handle
//! (`dyn Any`), which only `integrate::register` puts there and only the
//! integrate layer reads back (a downcast to its own type, no lookup by
//! name). A built-in method needs no handle: its entry is the [`Method`]
//! itself, and the integrate layer builds its stepper from its typed
//! parameters.

use std::any::Any;
use std::sync::RwLock;

use super::method::{Method, MethodInfo};
use crate::error::{Error, Result};

/// A method registered by name: its name, its description and its
/// factory's type-erased handle.
struct Entry {
    name: &'static str,
    info: &'static dyn MethodInfo,
    factory: Box<dyn Any + Send + Sync>,
}

/// A method of the registry, found once by name: a built-in [`Method`],
/// or a registered one. Copy, compared by identity, no lookup by name
/// behind it.
#[derive(Clone, Copy)]
pub struct MethodRef(Which);

#[derive(Clone, Copy)]
enum Which {
    BuiltIn(Method),
    Registered(&'static Entry),
}

/// The built-in methods as descriptions (`MethodRef::info` lends them).
static BUILT_IN: [Method; Method::ALL.len()] = Method::ALL;

/// The methods registered besides the built-in ones, in the order of
/// registration; each entry lives as long as the process.
static REGISTERED: RwLock<Vec<&'static Entry>> = RwLock::new(Vec::new());

impl MethodRef {
    /// The built-in method `m`.
    pub fn built_in(m: Method) -> Self {
        MethodRef(Which::BuiltIn(m))
    }

    /// The name in `integrator.method`, `--methods`, tables and plots.
    pub fn name(self) -> &'static str {
        match self.0 {
            Which::BuiltIn(m) => m.name(),
            Which::Registered(e) => e.name,
        }
    }

    /// Its description: parameters, the contact settings it accepts.
    pub fn info(self) -> &'static dyn MethodInfo {
        match self.0 {
            Which::BuiltIn(m) => &BUILT_IN[m as usize],
            Which::Registered(e) => e.info,
        }
    }

    /// The built-in method it is, if it is one.
    pub fn built_in_method(self) -> Option<Method> {
        match self.0 {
            Which::BuiltIn(m) => Some(m),
            Which::Registered(_) => None,
        }
    }

    /// A registered method's factory, type-erased (module docs: the
    /// integrate layer reads it back); `None` for a built-in one.
    pub(crate) fn factory(self) -> Option<&'static (dyn Any + Send + Sync)> {
        match self.0 {
            Which::BuiltIn(_) => None,
            Which::Registered(e) => Some(e.factory.as_ref()),
        }
    }
}

impl PartialEq for MethodRef {
    fn eq(&self, other: &Self) -> bool {
        match (self.0, other.0) {
            (Which::BuiltIn(a), Which::BuiltIn(b)) => a == b,
            (Which::Registered(a), Which::Registered(b)) => std::ptr::eq(a, b),
            _ => false,
        }
    }
}

impl Eq for MethodRef {}

impl std::fmt::Debug for MethodRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_tuple("MethodRef").field(&self.name()).finish()
    }
}

/// The methods registered besides the built-in ones.
fn registered() -> Vec<&'static Entry> {
    REGISTERED
        .read()
        .map_or_else(|e| e.into_inner().clone(), |r| r.clone())
}

/// The method named `name`: a built-in one, or one registered; the one
/// lookup by name (a scene's `integrator.method` as it is resolved, a
/// front end's `--methods`).
pub(crate) fn method_ref(name: &str) -> Option<MethodRef> {
    if let Some(m) = Method::ALL.into_iter().find(|m| m.name() == name) {
        return Some(MethodRef::built_in(m));
    }
    registered()
        .into_iter()
        .find(|e| e.name == name)
        .map(|e| MethodRef(Which::Registered(e)))
}

/// Every method's name: the built-in ones, then those registered.
pub(crate) fn method_names() -> Vec<String> {
    let mut names: Vec<String> = Method::ALL.iter().map(|m| m.name().to_string()).collect();
    names.extend(registered().iter().map(|e| e.name.to_string()));
    names
}

/// Add a method by the name `info` gives, with its factory's type-erased
/// handle (`integrate::register` is the one caller). Refused when the
/// name is malformed or taken.
pub(crate) fn register_method(
    info: &'static dyn MethodInfo,
    factory: Box<dyn Any + Send + Sync>,
) -> Result<MethodRef> {
    let name = info.name();
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
    if Method::ALL.iter().any(|m| m.name() == name) || list.iter().any(|e| e.name == name) {
        return Err(Error::invalid(
            "method name",
            format!("\"{name}\""),
            "is taken by another method (each name selects one method)",
        ));
    }
    // one entry per method for the life of the process
    let entry: &'static Entry = Box::leak(Box::new(Entry {
        name: name.leak(),
        info,
        factory,
    }));
    list.push(entry);
    Ok(MethodRef(Which::Registered(entry)))
}
