//! `[messenger]` against the rest of the scene (`docs/lines.md` eq.
//! W1–W6): its supports on the mesh's nodes, the bases that carry it, and
//! the linear messenger droppers' springs it gains.
//!
//! * Each support must fall on a node of the mesh (a pinned support
//!   removes that node's messenger w, as an end support removes the
//!   contact wire's; an elastic one, `docs/lines.md` E1, keeps it and adds
//!   its spring, dashpot and mass there); a support between nodes would
//!   need a constraint, not a removed unknown. The error names the support
//!   and the nearest node.
//! * Every implicit method steps it: the generalized-α family
//!   (`generalized_alpha`, `newmark`, `hht`, `wbz`), `bathe` and
//!   `moreau_jean` use the assembled two-line M, K (and C) like any
//!   other (verified on the two-wire manufactured solution, second order
//!   in Δt on both wires), and so does `central_difference`, held below
//!   2/ω_max of the two-line model (its element bound covers both lines
//!   and the droppers, `BeamModel::omega_bound`). Tension-only messenger
//!   droppers still need the generalized-α family (`integrate::dropper`).
//! * `mesh.kind = "hermite"` (the element model, uniform or graded) or
//!   `"modal"`: the J lowest modes of that two-line model (ties and
//!   attachments in it before the eigen-solve, so M = I, K = diag ω²; a
//!   point on either line is Φᵀ of its FE point vector). A `galerkin`
//!   basis is the bare contact wire's exact modes: refused.
//! * The closed-form references are of the bare contact wire, and
//!   `standing_force_modes` reads the one-line model: refused. A
//!   manufactured solution covers both lines (`crate::manufactured`).
//! * A linear messenger dropper's spring k_d r_d r_dᵀ (r_d = r_c − r_m,
//!   eq. W4) couples the two lines, so it goes into the messenger's `ties`,
//!   not into the contact wire's attachments.

use crate::error::{Error, Result};
use crate::model::mesh::Mesh;
use crate::scene::{
    Discretization, Dropper, Grading, ReferenceKind, ResolvedMethod, Scene, Scheme,
};

/// The largest distance between a support and its node that counts as
/// "on the node", relative to the span: round-off in the node positions
/// (x_i = L·i/N or a graded mesh's sums, a few ε·L), far below any
/// element.
const ON_NODE_RELATIVE: f64 = 1e-9;

/// Check the messenger's supports against the mesh and the scene's other
/// choices (module docs); nothing to check without `[messenger]`.
pub(crate) fn check_messenger(
    scene: &Scene,
    beam: &crate::scene::BeamProps,
    elements: usize,
    grading: Grading,
    d: Discretization,
    method: &ResolvedMethod,
) -> Result<()> {
    let Some(m) = &beam.messenger else {
        return Ok(());
    };
    let why = match method.scheme {
        Scheme::GenAlpha(_)
        | Scheme::Bathe { .. }
        | Scheme::MoreauJean { .. }
        | Scheme::CentralDifference => None,
        Scheme::ModalExact => Some("it steps a diagonal basis of the contact wire alone"),
        Scheme::Registered(_) => Some("a registered method is not verified with two lines"),
    };
    if let Some(why) = why {
        return Err(Error::invalid(
            "integrator.method",
            format!("\"{}\"", method.name()),
            format!(
                "cannot carry a [messenger] ({why}): use a method verified with two lines, generalized_alpha, newmark, hht, wbz, bathe, moreau_jean or central_difference"
            ),
        ));
    }
    if let Discretization::Galerkin { .. } = d {
        return Err(Error::invalid(
            "mesh.kind",
            "\"galerkin\"",
            "cannot carry a [messenger] (its exact modes are of the bare contact wire): use mesh.kind = \"hermite\" (string elements when EI = 0), or \"modal\" (the modes of the two-line model)",
        ));
    }
    // a manufactured solution's source carries the messenger's motion
    super::attachment::closed_form_references(scene, "a [messenger]")?;
    if let Some(r) = &scene.reference
        && r.kind == ReferenceKind::StandingForceModes
    {
        return Err(Error::invalid(
            "reference.kind",
            "\"standing_force_modes\"",
            "reads the contact wire's own eigenpairs and does not include a [messenger]: use \"richardson\"",
        ));
    }
    let mesh = Mesh::new(beam.length, elements, grading)?;
    for (i, &x) in m.supports.iter().enumerate() {
        let (e, s) = mesh.locate(x);
        let node = if s < 0.5 { e } else { e + 1 };
        let xn = mesh.node(node);
        if (x - xn).abs() > ON_NODE_RELATIVE * beam.length {
            return Err(Error::invalid(
                format!("messenger.supports.{i}"),
                x,
                format!(
                    "must fall on a mesh node (the nearest is node {node} at x = {xn} m): move the support there, or choose mesh.elements so that a node falls on it"
                ),
            ));
        }
    }
    Ok(())
}

/// The springs (x_d, k_d) of the linear messenger droppers (module docs).
pub(crate) fn ties(droppers: &[Dropper]) -> Vec<(f64, f64)> {
    droppers
        .iter()
        .filter(|d| d.linear && d.on_messenger())
        .map(|d| (d.x, d.stiffness))
        .collect()
}

/// The dashpots (x_d, c_d) of the linear messenger droppers with damping:
/// c_d r_d r_dᵀ with r_d = r_c(x_d) − r_m(x_d) enters C (eq. D11).
pub(crate) fn tie_dashpots(droppers: &[Dropper]) -> Vec<(f64, f64)> {
    droppers
        .iter()
        .filter(|d| d.linear && d.on_messenger() && d.damping != 0.0)
        .map(|d| (d.x, d.damping))
        .collect()
}
