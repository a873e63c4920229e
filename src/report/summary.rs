//! `summary.json`: the resolved scene, derived figures and contact statistics.

use std::path::Path;

use serde::Serialize;

use crate::error::Result;
use crate::record::{
    CarrierTrace, ContactStats, DropperStats, Filtered, SpanStats, StandardStats, SupportUplift,
    span_of,
};
use crate::resolve::Resolved;
use crate::run::RunOutput;
use crate::scene::{Discretization, Scene};

/// Figures derived from the scene and the run.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Derived {
    /// Mass per length ρA, kg/m.
    pub mass_per_length: f64,
    /// Bending stiffness EI, N·m².
    pub bending_stiffness: f64,
    /// Axial stiffness EA, N (null unless `youngs_modulus` and `area` are given).
    pub axial_stiffness: Option<f64>,
    /// String wave speed c = sqrt(T/ρA), m/s.
    pub wave_speed: f64,
    /// V0/c for carrier 0 (its cruise speed; null when T = 0).
    pub speed_ratio: Option<f64>,
    /// T/EA (null unless EA is known).
    pub tension_ratio: Option<f64>,
    /// Beam mass M = ρA L, kg.
    pub beam_mass: f64,
    /// The length the discretization resolves, m: the element length
    /// h = L/N on a uniform mesh, the longest element of a graded one, L/J
    /// for `galerkin`, the larger of the two for `modal`
    /// ([`Resolved::resolution`]).
    pub element_length: f64,
    /// Unknowns (beam dofs + mass dofs).
    pub dofs: usize,
    /// Steps taken.
    pub steps: usize,
    /// Time step, s.
    pub dt: f64,
    /// End time, s.
    pub end_time: f64,
    /// The discretization: "hermite" or "string" elements, or the modal
    /// bases "galerkin" and "modal" (`mesh.kind`, MODEL §9.2).
    pub elements: &'static str,
    /// Number of modes J of a modal basis (absent for elements).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// The mesh grading and its h_max/h_min (absent when uniform).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grading: Option<(&'static str, f64)>,
}

/// The whole `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// taut's version.
    pub taut_version: &'static str,
    /// The scene after overrides; defaults of `[contact]`, `[integrator]` and
    /// `[gravity]` are written out, optional carrier keys only when given.
    pub scene: Scene,
    /// Derived figures.
    pub derived: Derived,
    /// Contact statistics of carrier 0.
    pub contact: ContactStats,
    /// Contact statistics of every carrier, in scene order.
    pub carriers: Vec<ContactStats>,
    /// Every quantity of the registry ([`crate::quantity::all`]) for every
    /// carrier, in scene order: one object of `name: value` (`null` where
    /// undefined) a carrier. The names are those of every table and of
    /// `taut gate`.
    pub quantities: Vec<crate::quantity::Values>,
    /// Statistics of every dropper (`[[dropper]]`), in scene order: force
    /// range and slack intervals. Absent without droppers.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub droppers: Vec<DropperStats>,
    /// Contact force statistics of every carrier in every span between
    /// the line's supports (`[output] supports`; docs/output.md#spans),
    /// carrier by carrier, span by span. Absent without supports.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub spans: Vec<SpanStats>,
    /// The wire's displacement range at each support, with the time of its
    /// largest value (docs/output.md#supports). Absent without supports.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub supports: Vec<SupportUplift>,
    /// Each carrier's standard statistics over the analysis section
    /// (`[analysis]`; `standard.csv`, docs/output.md#the-standards-statistics).
    pub standard: Vec<StandardStats>,
    /// Wall-clock seconds of the run: model assembly, factorization, initial
    /// accelerations and the time loop with recording.
    pub wall_seconds: f64,
    /// Findings that make the numbers suspect (empty when none).
    pub warnings: Vec<String>,
    /// Form-finding's result (`docs/lines.md` eq. F1–F5): absent without a
    /// dropper `design_height`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub form_finding: Option<FormSummary>,
}

/// `summary.json`'s `form_finding`: how close the line at rest came to its
/// design heights (docs/output.md#form-finding).
#[derive(Debug, Clone, Serialize)]
pub struct FormSummary {
    /// ε_F, m ([`crate::integrate::FORM_TOLERANCE`]).
    pub tolerance: f64,
    /// max |v_c(x_d) − V_d| with the lengths as given, m.
    pub start_error: f64,
    /// max |v_c(x_d) − V_d| after form-finding, m.
    pub error: f64,
    /// Newton steps taken.
    pub steps: usize,
}

impl Summary {
    /// Collect the summary of a run.
    pub fn new(sc: &Resolved, out: &RunOutput) -> Self {
        let b = &sc.beam;
        let c = b.wave_speed();
        let v0 = sc.carriers[0].motion.profile.cruise_speed();
        let carriers: Vec<ContactStats> = out
            .stats
            .iter()
            .zip(&out.history.carriers)
            .map(|(st, tr)| ContactStats {
                force_filtered: filtered(out, tr),
                ..st.clone()
            })
            .collect();
        Summary {
            taut_version: env!("CARGO_PKG_VERSION"),
            scene: with_found_lengths(sc, out),
            derived: Derived {
                mass_per_length: b.rho_a,
                bending_stiffness: b.ei,
                axial_stiffness: b.ea,
                wave_speed: c,
                speed_ratio: (c > 0.0).then(|| v0 / c),
                tension_ratio: b.ea.map(|ea| b.tension / ea),
                beam_mass: b.total_mass(),
                element_length: sc.resolution(),
                dofs: out.dofs,
                steps: out.steps,
                dt: out.dt,
                end_time: out.history.t.last().copied().unwrap_or(0.0),
                elements: match sc.discretization {
                    Discretization::Hermite if b.is_string() => "string",
                    d => d.name(),
                },
                modes: sc.discretization.modes(),
                grading: sc.grading.ratio().map(|r| (sc.grading.name(), r)),
            },
            contact: carriers[0].clone(),
            quantities: (0..carriers.len())
                .map(|c| crate::quantity::Values::of_all(out, c))
                .collect(),
            carriers,
            droppers: out.droppers.clone(),
            spans: spans_filtered(sc, out),
            supports: out.history.supports.clone(),
            standard: out.standard.clone(),
            wall_seconds: out.wall_seconds,
            warnings: out.warnings.clone(),
            form_finding: out.form.as_ref().map(|f| FormSummary {
                tolerance: crate::integrate::FORM_TOLERANCE,
                start_error: f.start_error,
                error: f.error,
                steps: f.steps,
            }),
        }
    }
}

/// The filtered force's statistics of one carrier (its `force_filtered`,
/// [`crate::record::filter::stats_of_filtered`]); `null` when the history
/// does not hold every step.
fn filtered(out: &RunOutput, tr: &CarrierTrace) -> Filtered {
    if tr.force_filtered.is_empty() {
        Filtered::Unavailable
    } else {
        Filtered::Stats(crate::record::filter::stats_of_filtered(
            &out.history.t,
            &tr.force_filtered,
            out.window_end,
            out.history.band_hz(),
        ))
    }
}

/// The run's per-span statistics ([`RunOutput::spans`]) with the filtered
/// force's mean and σ over each span's steps: the carrier's
/// `force_filtered` (the whole run filtered at once, the filter of the
/// whole-run `force_filtered`), then its mean and population σ (two
/// passes) over the steps (rows 1…) whose x_m lies in the span
/// ([`span_of`]). Left `null` when the history does not hold every step.
fn spans_filtered(sc: &Resolved, out: &RunOutput) -> Vec<SpanStats> {
    let mut spans = out.spans.clone();
    let h = &out.history;
    if spans.is_empty() {
        return spans;
    }
    let supports = &sc.wire.supports;
    let per_carrier = supports.len().saturating_sub(1);
    for (c, tr) in h.carriers.iter().enumerate() {
        let f = &tr.force_filtered;
        if f.is_empty() {
            continue;
        }
        let Some(mine) = spans.get_mut(c * per_carrier..(c + 1) * per_carrier) else {
            continue;
        };
        // two passes over the steps: the sums, then the squared deviations
        let rows = 1..f.len().min(tr.x.len());
        let (mut n, mut sum, mut dev) = (
            vec![0usize; per_carrier],
            vec![0.0; per_carrier],
            vec![0.0; per_carrier],
        );
        for i in rows.clone() {
            if let Some(k) = span_of(supports, tr.x[i]) {
                n[k] += 1;
                sum[k] += f[i];
            }
        }
        let mean: Vec<f64> = sum.iter().zip(&n).map(|(s, &n)| s / n as f64).collect();
        for i in rows {
            if let Some(k) = span_of(supports, tr.x[i]) {
                dev[k] += (f[i] - mean[k]) * (f[i] - mean[k]);
            }
        }
        for (k, st) in mine.iter_mut().enumerate() {
            if n[k] > 0 {
                st.filtered_mean = Some(mean[k]);
                st.filtered_std = Some((dev[k] / n[k] as f64).sqrt());
            }
        }
    }
    spans
}

/// The terminal's description of a run's discretization, e.g.
/// `400 hermite elements (h = 0.1250 m)` or `modal: the J = 40 lowest modes
/// of 400 hermite elements (resolves 1.2500 m)`.
pub fn mesh_label(s: &Summary) -> String {
    let d = &s.derived;
    let n = s.scene.mesh.elements;
    let family = if s.derived.bending_stiffness == 0.0 {
        "string"
    } else {
        "hermite"
    };
    let graded = match d.grading {
        Some((name, r)) => format!(
            " graded toward {} (h_max/h_min = {r})",
            match name {
                "supports" => "both supports",
                "left" => "x = 0",
                "right" => "x = L",
                _ => "the point mesh.grading_at",
            }
        ),
        None => String::new(),
    };
    match (d.elements, d.modes) {
        ("galerkin", Some(j)) => format!(
            "galerkin: the J = {j} exact modes of the continuous beam (resolves L/J = {:.4} m)",
            d.element_length
        ),
        ("modal", Some(j)) => format!(
            "modal: the J = {j} lowest modes of {n} {family} elements{graded} (resolves {:.4} m)",
            d.element_length
        ),
        (_, _) if graded.is_empty() => {
            format!(
                "{n} {} elements (h = {:.4} m)",
                d.elements, d.element_length
            )
        }
        _ => format!(
            "{n} {} elements{graded} (h_max = {:.4} m)",
            d.elements, d.element_length
        ),
    }
}

/// Write `summary.json` (pretty-printed).
pub(crate) fn write_summary(path: &Path, s: &Summary) -> Result<()> {
    super::write_json(path, s)
}

/// The scene as it ran: a form-found dropper's `length` is the one found
/// (`docs/lines.md` eq. F1–F5), as `taut line expand` writes it.
fn with_found_lengths(sc: &Resolved, out: &RunOutput) -> Scene {
    let mut scene = sc.scene.clone();
    if let Some(form) = &out.form {
        for (spec, found) in scene.droppers.iter_mut().zip(&form.droppers) {
            spec.length = found.length;
        }
    }
    scene
}
