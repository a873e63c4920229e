//! The level parameter a study refines in space: N of a Hermite mesh, J of
//! a modal basis (`taut uncertainty`'s family, the accuracy-targeted sweep
//! and so `run --tolerance`).

use crate::resolve::Resolved;
use crate::scene::{Discretization, MeshKind};
use crate::study::space::SpaceChoice;
use crate::study::variant::RunVariant;
/// The level parameter refined in space (module docs): the elements
/// N of a Hermite (or string) mesh, the modes J of a `galerkin` basis, and
/// the modes J of a `modal` basis with its FE mesh grown in proportion
/// (J may not exceed the FE unknowns). `h = L/level` either way.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Level {
    Elements(usize),
    Galerkin(usize),
    /// (J₀, N₀) of the scene.
    Modal(usize, usize),
}

impl Level {
    pub(crate) fn of(sc: &Resolved) -> Self {
        match sc.discretization {
            Discretization::Hermite => Level::Elements(sc.elements),
            Discretization::Galerkin { modes } => Level::Galerkin(modes),
            Discretization::Modal { modes } => Level::Modal(modes, sc.elements),
        }
    }

    /// The scene's own level (N₀ or J₀).
    pub(crate) fn start(&self) -> usize {
        match *self {
            Level::Elements(n) | Level::Galerkin(n) | Level::Modal(n, _) => n,
        }
    }

    /// `N` or `J`, for messages.
    pub(crate) fn symbol(&self) -> &'static str {
        match self {
            Level::Elements(_) => "N",
            _ => "J",
        }
    }

    /// The run at level `n` and step `dt`.
    pub(crate) fn variant(&self, n: usize, dt: f64) -> RunVariant {
        let mut v = RunVariant {
            dt: Some(dt),
            ..RunVariant::default()
        };
        match *self {
            Level::Elements(_) => v.elements = Some(n),
            Level::Galerkin(_) => {
                v.space = Some((
                    SpaceChoice {
                        kind: MeshKind::Galerkin,
                        modes: Some(n),
                    },
                    1.0,
                ))
            }
            Level::Modal(j0, n0) => {
                v.elements = Some((n0 * n).div_ceil(j0));
                v.space = Some((
                    SpaceChoice {
                        kind: MeshKind::Modal,
                        modes: Some(n),
                    },
                    1.0,
                ));
            }
        }
        v
    }
}
