//! `taut compare`: the same scene under several contact formulations, time
//! integrators and space discretizations, with agreement on contact loss as the headline measure:
//! formulations side by side, methods side by side.
//!
//! Every combination runs on the same scene text with the same overrides
//! plus the method's `[integrator]` ([`MethodFactory::integrator`]), with
//! its formulation and discretization set as a typed
//! `RunVariant`, so meshes, steps and settings are identical
//! and histories can be compared step by step. A combination that means
//! nothing (a scene error naming both keys, e.g. `moreau_jean` with
//! `penalty`, or an explicit method above its stability limit) is skipped
//! with its reason; a run that stops (divergence, failed contact solve) is
//! listed as failed; the others are tabulated.

use serde::Serialize;

use super::space::SpaceChoice;
use super::variant::{RunVariant, base_scene};
use crate::error::{Error, Result};
use crate::integrate::MethodFactory;
use crate::resolve::{Resolved, resolve_scene};
use crate::run::RunOutput;
use crate::scene::{Formulation, Scene};

/// One combination's row of the comparison (columns of `compare.csv`).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CompareRow {
    /// Time integrator (`integrator.method`, or a custom method's name).
    pub method: String,
    /// Space discretization (`mesh.kind`, with J for the modal kinds:
    /// `modal J=40`).
    pub discretization: String,
    /// Formulation name.
    pub formulation: String,
    /// Measure of the symmetric difference between this formulation's loss
    /// set and the reference's, in x_m/L (t/t_end for stationary carriers),
    /// summed over carriers.
    pub loss_set_difference: f64,
    /// max over steps and carriers of |λ − λ_ref|, N.
    pub max_force_difference: f64,
    /// RMS over steps and carriers of λ − λ_ref, N.
    pub rms_force_difference: f64,
    /// Largest penetration max(0, −g) over steps and carriers, m.
    pub max_penetration_all_carriers: f64,
    /// Smallest gap over steps and carriers, m.
    pub min_gap_all_carriers: f64,
    /// Smallest contact force over steps and carriers, N.
    pub force_min_all_carriers: f64,
    /// Largest |g·λ| over steps and carriers, N·m.
    pub max_gap_force_product_all_carriers: f64,
    /// Carrier 0's values of the quantities the tables with one row per
    /// run offer ([`crate::quantity::Offer::RUN_TABLES`]), by name.
    #[serde(flatten)]
    pub quantities: crate::quantity::Values,
    /// Wall-clock seconds of the run.
    pub wall_seconds: f64,
    /// The run's warnings (e.g. contact chatter); empty when none.
    pub warnings: Vec<String>,
    /// Each dropper's slack (`[[dropper]]`, scene order); empty, and absent
    /// from compare.json, without droppers.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub droppers: Vec<DropperSlack>,
}

/// A dropper's slack in one run of a comparison.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct DropperSlack {
    /// The dropper's name.
    pub name: String,
    /// Steps slack over all steps.
    pub slack_fraction: f64,
    /// Slack intervals.
    pub slack_interval_count: usize,
    /// Start time of the first slack interval, s (null if never slack).
    pub first_slack_time: Option<f64>,
}

/// A combination that did not give a row, and why.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct NotRun {
    /// Time integrator.
    pub method: String,
    /// Space discretization (empty when the study has one).
    #[serde(skip_serializing_if = "String::is_empty")]
    pub discretization: String,
    /// Formulation.
    pub formulation: String,
    /// Why: the error, typed (written as the CLI prints it).
    pub reason: Reason,
}

/// Why a combination gave no row: the error its run (or its scene) raised,
/// and where on the study's grid, if the study has one. Shared, since one
/// scene error is the reason of every grid point built on that scene.
#[derive(Debug, Clone)]
pub struct Reason {
    /// The grid point: level i of the mesh and the step Δt, s (`taut precision`).
    pub at: Option<(usize, f64)>,
    /// The error.
    pub error: std::sync::Arc<Error>,
}

impl Reason {
    /// The error `e`, at no grid point.
    pub fn new(e: Error) -> Reason {
        Reason {
            at: None,
            error: std::sync::Arc::new(e),
        }
    }

    /// How the run ended.
    pub fn end(&self) -> crate::run::RunEnd {
        crate::run::RunEnd::of_error(&self.error)
    }
}

impl std::fmt::Display for Reason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.at {
            Some((i, dt)) => write!(f, "level {i}, Δt = {dt:e} s: {}", self.error),
            None => write!(f, "{}", self.error),
        }
    }
}

/// Written as the text the CLI prints (compare.json, converge.json).
impl Serialize for Reason {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// Two reasons are the same when they say the same.
impl PartialEq for Reason {
    fn eq(&self, other: &Reason) -> bool {
        self.to_string() == other.to_string()
    }
}

/// One run of a comparison.
pub struct CompareRun {
    /// Time integrator name.
    pub method: String,
    /// Space discretization label (`hermite`, `modal J=40`).
    pub discretization: String,
    /// Formulation.
    pub formulation: Formulation,
    /// The resolved scene.
    pub scene: Resolved,
    /// What it produced.
    pub output: RunOutput,
}

impl CompareRun {
    /// `method/formulation`, the label of plots (with the discretization
    /// when `space` is true: `method/modal J=40/formulation`).
    pub fn label(&self, space: bool) -> String {
        if space {
            format!(
                "{}/{}/{}",
                self.method,
                self.discretization,
                self.formulation.name()
            )
        } else {
            format!("{}/{}", self.method, self.formulation.name())
        }
    }
}

/// A finished comparison.
pub struct Comparison {
    /// The reference method.
    pub reference_method: String,
    /// The reference formulation.
    pub reference: Formulation,
    /// The reference discretization's label.
    pub reference_discretization: String,
    /// True when several discretizations are compared.
    pub several_discretizations: bool,
    /// The runs in the order asked for (methods outer, discretizations,
    /// formulations inner).
    pub runs: Vec<CompareRun>,
    /// One row per run, same order.
    pub rows: Vec<CompareRow>,
    /// Combinations that mean nothing for this scene (scene errors naming
    /// both keys, an explicit method above its limit).
    pub skipped: Vec<NotRun>,
    /// Combinations whose run stopped (divergence, failed contact solve).
    pub failed: Vec<NotRun>,
}

/// What to compare.
pub struct CompareSpec<'a> {
    /// Time integrators; empty for the scene's own.
    pub methods: Vec<&'a dyn MethodFactory>,
    /// Contact formulations.
    pub formulations: Vec<Formulation>,
    /// Space discretizations; empty for the scene's own.
    pub discretizations: Vec<SpaceChoice>,
    /// The reference method, an index into `methods` (the first by default).
    pub reference_method: usize,
    /// The reference discretization, an index into `discretizations` (the
    /// first by default).
    pub reference_discretization: usize,
    /// The reference formulation (run too if not listed).
    pub reference: Formulation,
    /// Runs stepped together when they share their effective matrix
    /// (`--batch`; 1: every run alone). The rows are the same whatever it is.
    pub batch: usize,
}

/// Parse `lagrange,penalty,…` into formulations.
pub(crate) fn parse_formulations(list: &str) -> Result<Vec<Formulation>> {
    let mut out = Vec::new();
    for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let f = Formulation::ALL
            .into_iter()
            .find(|f| f.name() == name)
            .ok_or_else(|| {
                let all: Vec<&str> = Formulation::ALL.iter().map(|f| f.name()).collect();
                Error::invalid(
                    "--formulations",
                    name,
                    format!("must be among {}", all.join(", ")),
                )
            })?;
        if out.contains(&f) {
            return Err(Error::invalid("--formulations", name, "is listed twice"));
        }
        out.push(f);
    }
    if out.is_empty() {
        return Err(Error::invalid(
            "--formulations",
            list,
            "name at least one formulation",
        ));
    }
    Ok(out)
}

/// Run `text` (with `overrides`) once per formulation under the scene's own
/// method and compare each with `reference` (run too if not listed).
/// `progress(done, total)` after each run.
pub fn compare(
    text: &str,
    overrides: &[String],
    formulations: &[Formulation],
    reference: Formulation,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Comparison> {
    let spec = CompareSpec {
        methods: Vec::new(),
        formulations: formulations.to_vec(),
        discretizations: Vec::new(),
        reference_method: 0,
        reference_discretization: 0,
        reference,
        batch: crate::study::sweep::AUTO_BATCH_LANES,
    };
    compare_methods(text, overrides, &spec, progress)
}

/// Run every method × formulation of `spec` and compare each with the
/// reference combination. `progress(done, total)` after each run.
pub fn compare_methods(
    text: &str,
    overrides: &[String],
    spec: &CompareSpec,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Comparison> {
    let base = resolve_scene(text, overrides)?;
    base.require_every_step("taut compare")?;
    let own = crate::integrate::scene_method(&base);
    let methods: Vec<&dyn MethodFactory> = if spec.methods.is_empty() {
        vec![own]
    } else {
        spec.methods.clone()
    };
    if spec.reference_method >= methods.len() {
        return Err(Error::invalid(
            "--reference-method",
            spec.reference_method,
            format!("must name one of the {} methods compared", methods.len()),
        ));
    }
    let spaces: Vec<Option<SpaceChoice>> = if spec.discretizations.is_empty() {
        vec![None]
    } else {
        spec.discretizations.iter().copied().map(Some).collect()
    };
    if spec.reference_discretization >= spaces.len() {
        return Err(Error::invalid(
            "--reference-discretization",
            spec.reference_discretization,
            format!(
                "must name one of the {} discretizations compared",
                spaces.len()
            ),
        ));
    }
    // (method index, discretization index, formulation, shown in the table)
    let mut order: Vec<(usize, usize, Formulation, bool)> = Vec::new();
    for m in 0..methods.len() {
        for d in 0..spaces.len() {
            for &f in &spec.formulations {
                order.push((m, d, f, true));
            }
        }
    }
    let reference = (
        spec.reference_method,
        spec.reference_discretization,
        spec.reference,
    );
    if !order.iter().any(|&(m, d, f, _)| (m, d, f) == reference) {
        order.push((reference.0, reference.1, reference.2, false));
    }
    let total = order.len();
    let (mut runs, mut skipped, mut failed) = (Vec::new(), Vec::new(), Vec::new());
    let mut shown = Vec::new();
    let space_label = |d: usize, sc: Option<&Resolved>| match (spaces[d], sc) {
        (_, Some(sc)) => sc.discretization.label(),
        (Some(c), None) => c.name().to_string(),
        (None, None) => base.discretization.label(),
    };
    let mut keys = Vec::new();
    // each method's scene, parsed once
    let method_scenes: Vec<Result<Scene>> = methods
        .iter()
        .map(|&m| base_scene(text, overrides, Some(m)))
        .collect();
    // every combination's scene first, then the runs together: those that
    // share a matrix step in batches (`--batch`), each bit-identical alone
    let resolved: Vec<Result<Resolved>> = order
        .iter()
        .map(|&(m, d, f, _)| {
            let variant = RunVariant {
                formulation: Some(f),
                space: spaces[d].map(|c| (c, 1.0)),
                ..RunVariant::default()
            };
            match &method_scenes[m] {
                Ok(scene) => variant.apply_to(scene),
                // parsed again only to hand this combination its own error
                Err(_) => base_scene(text, overrides, Some(methods[m]))
                    .and_then(|scene| variant.apply_to(&scene)),
            }
        })
        .collect();
    let jobs: Vec<(Resolved, &dyn MethodFactory)> = order
        .iter()
        .zip(&resolved)
        .filter_map(|(&(m, ..), sc)| sc.as_ref().ok().map(|sc| (sc.clone(), methods[m])))
        .collect();
    let mut finished = 0;
    let mut outputs = crate::run::run_many(&jobs, spec.batch, &mut |_| {
        finished += 1;
        progress(finished, total);
    })
    .into_iter();
    for (&(m, d, f, show), sc) in order.iter().zip(resolved) {
        let factory = methods[m];
        let name = factory.name();
        let not_run = |e: Error| NotRun {
            method: name.clone(),
            discretization: if spaces.len() > 1 {
                space_label(d, None)
            } else {
                String::new()
            },
            formulation: f.name().to_string(),
            reason: Reason::new(e),
        };
        let outcome = sc.and_then(|sc| {
            let out = outputs.next().expect("one output per resolved scene");
            out.map(|out| (sc, out))
        });
        match outcome {
            Ok((scene, output)) => {
                runs.push(CompareRun {
                    method: name,
                    discretization: space_label(d, Some(&scene)),
                    formulation: f,
                    scene,
                    output,
                });
                keys.push((m, d, f));
                shown.push(show);
            }
            // stopped on request: not this combination's failure
            Err(Error::Interrupted) => return Err(Error::Interrupted),
            // the combination means nothing for this scene: a scene error
            // (both keys named) or a step the method cannot take
            Err(e @ (Error::Invalid { .. } | Error::Parse { .. } | Error::Override { .. })) => {
                skipped.push(not_run(e))
            }
            Err(e) => failed.push(not_run(e.in_run(&format!("{name}/{}", f.name())))),
        }
    }
    progress(total, total);
    let ref_name = methods[reference.0].name();
    let ref_idx = keys.iter().position(|&k| k == reference).ok_or_else(|| {
        let why = skipped
            .iter()
            .chain(&failed)
            .find(|n| n.method == ref_name && n.formulation == reference.2.name())
            .map_or(String::new(), |n| format!(": {}", n.reason));
        Error::invalid(
            "--reference",
            format!("{ref_name}/{}", reference.2.name()),
            format!("the reference combination must run{why}"),
        )
    })?;
    let reference_discretization = runs[ref_idx].discretization.clone();
    let rows: Vec<CompareRow> = runs.iter().map(|r| row(r, &runs[ref_idx].output)).collect();
    // keep only the combinations asked for (the reference, if added, is last)
    let (runs, rows): (Vec<_>, Vec<_>) = runs
        .into_iter()
        .zip(rows)
        .zip(shown)
        .filter_map(|(rr, show)| show.then_some(rr))
        .unzip();
    Ok(Comparison {
        reference_method: ref_name,
        reference: reference.2,
        reference_discretization,
        several_discretizations: spaces.len() > 1,
        runs,
        rows,
        skipped,
        failed,
    })
}

/// Measure of a lost-step set on the abscissa: a lost step i covers
/// [s_{i−1}, s_i]; `a XOR b` gives the symmetric difference.
fn loss_set_difference(sc: &Resolved, a: &RunOutput, b: &RunOutput) -> f64 {
    let stationary = sc.carriers.iter().all(|c| c.motion.is_stationary());
    let t = &a.history.t;
    let t_end = *t.last().unwrap_or(&1.0);
    let mut total = 0.0;
    for (ta, tb) in a.history.carriers.iter().zip(&b.history.carriers) {
        for i in 1..ta.in_contact.len() {
            if ta.in_contact[i] != tb.in_contact[i] {
                total += if stationary {
                    (t[i] - t[i - 1]) / t_end
                } else {
                    (ta.x[i] - ta.x[i - 1]).abs() / sc.beam.length
                };
            }
        }
    }
    total
}

fn row(r: &CompareRun, reference: &RunOutput) -> CompareRow {
    let (sc, out) = (&r.scene, &r.output);
    let (mut max_d, mut sum2, mut count) = (0.0f64, 0.0, 0usize);
    for (ta, tb) in out.history.carriers.iter().zip(&reference.history.carriers) {
        for (x, y) in ta.force.iter().zip(&tb.force).skip(1) {
            let d = x - y;
            max_d = max_d.max(d.abs());
            sum2 += d * d;
            count += 1;
        }
    }
    CompareRow {
        method: r.method.clone(),
        discretization: r.discretization.clone(),
        formulation: r.formulation.name().to_string(),
        loss_set_difference: loss_set_difference(sc, out, reference),
        max_force_difference: max_d,
        rms_force_difference: (sum2 / count.max(1) as f64).sqrt(),
        max_penetration_all_carriers: out
            .stats
            .iter()
            .map(|s| s.max_penetration)
            .fold(0.0, f64::max),
        min_gap_all_carriers: out
            .stats
            .iter()
            .map(|s| s.min_gap)
            .fold(f64::INFINITY, f64::min),
        force_min_all_carriers: out
            .stats
            .iter()
            .map(|s| s.force.min)
            .fold(f64::INFINITY, f64::min),
        max_gap_force_product_all_carriers: out
            .stats
            .iter()
            .map(|s| s.max_gap_force_product)
            .fold(0.0, f64::max),
        quantities: crate::quantity::Values::of(out, 0, crate::quantity::Offer::RUN_TABLES),
        wall_seconds: out.wall_seconds,
        warnings: out.warnings.clone(),
        droppers: out
            .droppers
            .iter()
            .map(|d| DropperSlack {
                name: d.name.clone(),
                slack_fraction: d.slack_fraction,
                slack_interval_count: d.slack_interval_count,
                first_slack_time: d.slack_intervals_time.first().map(|i| i[0]),
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formulation_lists_are_checked() {
        assert_eq!(
            parse_formulations("lagrange, penalty").unwrap(),
            vec![Formulation::Lagrange, Formulation::Penalty]
        );
        let e = parse_formulations("lagrange,magic")
            .unwrap_err()
            .to_string();
        assert!(e.contains("magic") && e.contains("complementarity"), "{e}");
        assert!(parse_formulations("penalty,penalty").is_err());
        assert!(parse_formulations(" , ").is_err());
    }
}

#[cfg(test)]
mod reason_tests {
    use super::*;
    use crate::run::RunEnd;

    #[test]
    fn a_reason_keeps_the_typed_error_and_prints_the_old_text() {
        let diverged = Error::Diverged {
            step: 3,
            time: 0.3,
            quantity: "λ".into(),
            value: 1e9,
            cause: "too large a step".into(),
        };
        let text = diverged.to_string();
        let r = Reason::new(diverged);
        assert_eq!(r.end(), RunEnd::Diverged);
        assert_eq!(r.to_string(), text, "printed as the error itself");
        assert_eq!(
            serde_json::to_string(&r).unwrap(),
            serde_json::to_string(&text).unwrap(),
            "written as the same text"
        );
        let at = Reason {
            at: Some((2, 2.5e-5)),
            error: std::sync::Arc::new(Error::invalid("time.step", 1, "too large")),
        };
        assert_eq!(at.end(), RunEnd::Refused);
        assert!(
            at.to_string().starts_with("level 2, Δt = 2.5e-5 s: "),
            "{at}"
        );
        assert_eq!(RunEnd::of_error(&Error::Interrupted), RunEnd::Interrupted);
        assert_eq!(RunEnd::of::<()>(&Ok(())), RunEnd::Completed);
    }
}
