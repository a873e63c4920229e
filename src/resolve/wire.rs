//! `[output] snapshots`, `snapshot_points` and `field` resolved: which
//! steps record the wire's displacement v(x) along the span, and where
//! (docs/output.md#snapshots).
//!
//! A snapshot asked for at time t is taken at the step nearest to it,
//! n = round(t/Δt) (at most the last step): no interpolation in time, so
//! every recorded value is the state of a step, the same number a probe at
//! that x and that step records. `snapshots.csv` gives both the time asked
//! for and the step's time.

use crate::error::{Error, Result};
use crate::model::mesh::Mesh;
use crate::scene::{Discretization, Grading, OutputSpec};

/// Most points of a snapshot or of the field: far more than any mesh
/// resolves; the memory estimate bounds their product with the rows.
pub(crate) const MAX_POINTS: u64 = 1_000_000;

/// What a run records of the wire beyond its history.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct WirePlan {
    /// (step, requested time in s) of each snapshot, in the scene's order.
    pub snapshots: Vec<(usize, f64)>,
    /// Snapshot points, m (empty without snapshots).
    pub snapshot_x: Vec<f64>,
    /// Record the field every this many steps (0: no field).
    pub field_every: usize,
    /// Field points, m (empty without a field).
    pub field_x: Vec<f64>,
    /// The line's supports, m, strictly increasing in [0, L]: consecutive
    /// pairs are spans (`spans.csv`), and the uplift is recorded at each
    /// (`supports.csv`). `[output] supports`; empty: none. The one list
    /// every source of supports fills: the `[messenger]` supports when the
    /// scene gives none here (`Scene::validate`).
    pub supports: Vec<f64>,
    /// The envelope's points, m: the mesh nodes with `[output] envelope =
    /// true`, else empty (none recorded).
    pub envelope_x: Vec<f64>,
}

impl WirePlan {
    /// Rows of the field over `steps` steps: steps 0, K, 2K, … ≤ steps.
    pub fn field_rows(&self, steps: usize) -> usize {
        steps
            .checked_div(self.field_every)
            .map_or(0, |rows| rows + 1)
    }

    /// Values recorded over a run of `steps` steps (snapshots, field, and
    /// the envelope's x, v_min, v_max and the supports' x, v_max, v_min,
    /// t_max).
    pub fn values(&self, steps: usize) -> u64 {
        let snap = (self.snapshots.len() as u64).saturating_mul(self.snapshot_x.len() as u64);
        let field = (self.field_rows(steps) as u64).saturating_mul(self.field_x.len() as u64);
        let envelope = 3 * self.envelope_x.len() as u64 + 4 * self.supports.len() as u64;
        snap.saturating_add(field).saturating_add(envelope)
    }

    /// Points the recorder evaluates at (one point vector each).
    pub fn points(&self) -> u64 {
        (self.snapshot_x.len() + self.field_x.len() + self.envelope_x.len() + self.supports.len())
            as u64
    }
}

/// The run's mesh as the discretization sees it.
pub(crate) struct Grid {
    /// Span L, m.
    pub length: f64,
    /// `mesh.elements`.
    pub elements: usize,
    /// `mesh.grading`.
    pub grading: Grading,
    /// `mesh.kind`.
    pub discretization: Discretization,
    /// Δt, s.
    pub dt: f64,
    /// Steps of the run.
    pub steps: usize,
    /// The run's end, s.
    pub t_end: f64,
}

/// The mesh nodes, m: the FE mesh's, or for `galerkin` (no mesh) those of
/// the uniform mesh of `mesh.elements` elements.
pub(crate) fn nodes(g: &Grid) -> Result<Vec<f64>> {
    let mesh = match g.discretization {
        Discretization::Galerkin { .. } => Mesh::uniform(g.length, g.elements),
        _ => Mesh::new(g.length, g.elements, g.grading)?,
    };
    Ok((0..=mesh.elements()).map(|i| mesh.node(i)).collect())
}

/// `n` points (≥ 2) equally spaced over [0, L], both ends included, or the
/// mesh nodes when `n` is absent.
fn points(field: &str, n: Option<u64>, g: &Grid) -> Result<Vec<f64>> {
    let Some(n) = n else { return nodes(g) };
    if !(2..=MAX_POINTS).contains(&n) {
        return Err(Error::invalid(
            field,
            n,
            format!(
                "must be in 2 ..= {MAX_POINTS} (equally spaced points over [0, L], both ends included)"
            ),
        ));
    }
    let last = (n - 1) as f64;
    Ok((0..n)
        .map(|i| {
            if i + 1 == n {
                g.length
            } else {
                g.length * i as f64 / last
            }
        })
        .collect())
}

/// Check and resolve `[output]`'s wire keys.
pub(crate) fn resolve_wire(o: &OutputSpec, g: &Grid) -> Result<WirePlan> {
    let mut plan = WirePlan::default();
    for (i, &t) in o.snapshots.iter().enumerate() {
        if !(t.is_finite() && (0.0..=g.t_end).contains(&t)) {
            return Err(Error::invalid(
                format!("output.snapshots.{i}"),
                t,
                format!("must be a time in [0, {}] s (the run's end)", g.t_end),
            ));
        }
        let n = ((t / g.dt).round() as usize).min(g.steps);
        plan.snapshots.push((n, t));
    }
    match (plan.snapshots.is_empty(), o.snapshot_points) {
        (false, n) => plan.snapshot_x = points("output.snapshot_points", n, g)?,
        (true, Some(n)) => {
            return Err(Error::invalid(
                "output.snapshot_points",
                n,
                "must come with output.snapshots (the times to record): give them or remove it",
            ));
        }
        (true, None) => {}
    }
    if let Some(f) = &o.field {
        if f.every == 0 {
            return Err(Error::invalid(
                "output.field.every",
                0,
                "must be an integer ≥ 1 (record the field every K-th step)",
            ));
        }
        plan.field_every = usize::try_from(f.every).unwrap_or(usize::MAX);
        plan.field_x = points("output.field.points", f.points, g)?;
    }
    plan.supports = resolve_supports(&o.supports, g.length)?;
    if o.envelope {
        plan.envelope_x = nodes(g)?;
    }
    Ok(plan)
}

/// Check `[output] supports` on a span of `length` m: each finite in
/// [0, L], strictly increasing.
pub(crate) fn resolve_supports(supports: &[f64], length: f64) -> Result<Vec<f64>> {
    for (i, &x) in supports.iter().enumerate() {
        let field = format!("output.supports.{i}");
        if !(x.is_finite() && (0.0..=length).contains(&x)) {
            return Err(Error::invalid(
                field,
                x,
                format!("must be a position in [0, {length}] m (the beam's span)"),
            ));
        }
        if let Some(&prev) = i.checked_sub(1).and_then(|j| supports.get(j))
            && x <= prev
        {
            return Err(Error::invalid(
                field,
                x,
                format!(
                    "must be greater than output.supports.{} = {prev} m (supports strictly increasing)",
                    i - 1
                ),
            ));
        }
    }
    Ok(supports.to_vec())
}
