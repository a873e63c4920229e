//! `taut gate`: re-run a suite of golden cases and compare each stored
//! quantity with its reference, within per-quantity absolute and relative
//! tolerances that carry their reasons.
//!
//! A suite is a folder of case files `*.json`:
//!
//! ```json
//! {
//!   "description": "the study's reference moving case",
//!   "scene": "../scenes/reference.toml",
//!   "set": ["mesh.elements=400"],
//!   "quantities": {
//!     "steps": { "value": 6000, "abs": 0, "rel": 0, "reason": "integer count" },
//!     "force_mean": { "value": 46.3375, "abs": 0, "rel": 1e-6, "reason": "…" }
//!   }
//! }
//! ```
//!
//! `scene` is relative to the case file. A quantity passes when
//! |value − reference| ≤ abs + rel·|reference|. [`quantity_names`] lists what
//! can be gated.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::resolve::load_scene;
use crate::run::{RunOutput, run};

/// One gated quantity: reference value, tolerances and why.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Tolerance {
    /// Reference value.
    pub value: f64,
    /// Absolute tolerance (≥ 0), in the quantity's unit.
    pub abs: f64,
    /// Relative tolerance (≥ 0).
    pub rel: f64,
    /// Why this tolerance.
    pub reason: String,
}

/// A case file.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct GateCase {
    /// What the case is.
    pub description: String,
    /// Scene path, relative to the case file.
    pub scene: String,
    /// `--set` overrides.
    #[serde(default)]
    pub set: Vec<String>,
    /// Gated quantities by name.
    pub quantities: BTreeMap<String, Tolerance>,
}

/// What a case may gate: every quantity of the registry
/// ([`crate::quantity::all`]), of carrier 0, or of carrier N with the
/// suffix `_N` (`force_mean_1`); and `final_probe_N`, probe N's last value.
pub fn quantity_names() -> Vec<&'static str> {
    crate::quantity::all()
        .into_iter()
        .map(|q| q.name)
        .chain(["final_probe"])
        .collect()
}

/// Extract a quantity from a run; `None` if the run does not have it (an
/// unknown name, a carrier or probe it does not have, the first loss of a
/// contact never lost): such a check fails.
pub fn quantity(out: &RunOutput, name: &str) -> Option<f64> {
    // `final_probe_N` is probe N; any other `NAME_N` is NAME of carrier N
    if let Some(p) = name.strip_prefix("final_probe_") {
        let p: usize = p.parse().ok()?;
        return out.history.probes.get(p)?.1.last().copied();
    }
    let (base, carrier) = match name.rsplit_once('_') {
        Some((b, c)) if !c.is_empty() && c.chars().all(|ch| ch.is_ascii_digit()) => {
            (b, c.parse::<usize>().ok()?)
        }
        _ => (name, 0),
    };
    crate::quantity::by_name(base)?.of(out, carrier)
}

/// The result for one quantity.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Check {
    /// Case name (file stem).
    pub case: String,
    /// Quantity name.
    pub quantity: String,
    /// Value of this run.
    pub value: f64,
    /// Reference value.
    pub reference: f64,
    /// Allowed |value − reference|.
    pub tolerance: f64,
    /// |value − reference|.
    pub difference: f64,
    /// Passed.
    pub pass: bool,
    /// The tolerance's reason.
    pub reason: String,
}

/// A case that could not run (bad file, failed run).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CaseError {
    /// Case name.
    pub case: String,
    /// What went wrong.
    pub error: String,
}

/// The whole gate.
#[derive(Debug, Clone, Serialize)]
pub struct GateReport {
    /// Every check, case by case.
    pub checks: Vec<Check>,
    /// Cases that did not run.
    pub errors: Vec<CaseError>,
    /// Wall seconds per case.
    pub wall_seconds: BTreeMap<String, f64>,
}

impl GateReport {
    /// True when every case ran, at least one quantity was checked and
    /// every check passed: a gate that checked nothing does not pass.
    pub fn passed(&self) -> bool {
        self.errors.is_empty() && !self.checks.is_empty() && self.checks.iter().all(|c| c.pass)
    }
}

/// The case files of a suite, sorted by name.
pub(crate) fn case_files(suite: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(suite)
        .map_err(|e| Error::io(suite, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(Error::invalid(
            "SUITE_DIR",
            suite.display(),
            "must hold at least one case file (*.json)",
        ));
    }
    Ok(files)
}

/// Read and check a case file: no key repeated at any level (serde_json
/// would keep the last copy silently), at least one quantity, known
/// quantity names, finite non-negative tolerances with their reasons, and a
/// scene file (`*.toml`).
pub fn read_case(path: &Path) -> Result<GateCase> {
    let text = crate::input::read_text(path, "a gate case", crate::input::MAX_INPUT_BYTES)?;
    crate::json_keys::reject_duplicate_keys(&text, path)?;
    let case: GateCase = serde_json::from_str(&text)
        .map_err(|e| Error::parse(format!("{}: {e}", path.display())))?;
    if case.quantities.is_empty() {
        return Err(Error::invalid(
            format!("{}: quantities", path.display()),
            "{} (none)",
            format!(
                "must gate at least one quantity ({}): a case that checks nothing would pass whatever the run gives",
                quantity_names().join(", ")
            ),
        ));
    }
    let names = quantity_names();
    if Path::new(&case.scene)
        .extension()
        .is_none_or(|x| x != "toml")
    {
        return Err(Error::invalid(
            format!("{}: scene", path.display()),
            &case.scene,
            "must be a scene file (*.toml); a relative path is taken from the case file",
        ));
    }
    for (name, t) in &case.quantities {
        let field = format!("{}: quantities.{name}", path.display());
        if !names.iter().any(|q| {
            name == q
                || name
                    .strip_prefix(q)
                    .is_some_and(|r| r.starts_with('_') && r[1..].parse::<usize>().is_ok())
        }) {
            return Err(Error::invalid(
                field,
                name,
                format!("must be one of {}", names.join(", ")),
            ));
        }
        // abs + rel·|value| must be finite too: an infinite allowance passes
        // anything
        let allowance = t.abs + t.rel * t.value.abs();
        if !(t.abs >= 0.0 && t.rel >= 0.0 && allowance.is_finite()) {
            return Err(Error::invalid(
                field,
                format!("abs {} rel {} (value {})", t.abs, t.rel, t.value),
                "tolerances must be ≥ 0 and abs + rel·|value| finite",
            ));
        }
        if t.reason.trim().is_empty() {
            return Err(Error::invalid(
                field,
                "reason \"\"",
                "every tolerance needs its reason",
            ));
        }
    }
    Ok(case)
}

fn case_name(path: &Path) -> String {
    path.file_stem()
        .map_or_else(|| "case".into(), |s| s.to_string_lossy().into_owned())
}

/// Run one case.
pub fn run_case(path: &Path, case: &GateCase) -> Result<RunOutput> {
    let scene = path.parent().unwrap_or(Path::new(".")).join(&case.scene);
    let sc = load_scene(&scene, &case.set)?;
    run(&sc, &mut |_, _| {})
}

/// Check one run against its case.
pub(crate) fn check_case(name: &str, case: &GateCase, out: &RunOutput) -> Vec<Check> {
    case.quantities
        .iter()
        .map(|(q, t)| {
            let value = quantity(out, q).unwrap_or(f64::NAN);
            let tolerance = t.abs + t.rel * t.value.abs();
            let difference = (value - t.value).abs();
            Check {
                case: name.to_string(),
                quantity: q.clone(),
                value,
                reference: t.value,
                tolerance,
                difference,
                pass: difference <= tolerance,
                reason: t.reason.clone(),
            }
        })
        .collect()
}

/// Run a suite; `progress(done, total, case)` after each case. With
/// `update`, every case file's reference values are replaced by this run's
/// (tolerances and reasons kept) and the returned checks show what changed.
pub fn gate(
    suite: &Path,
    update: bool,
    progress: &mut dyn FnMut(usize, usize, &str),
) -> Result<GateReport> {
    gate_batched(
        suite,
        update,
        crate::study::sweep::AUTO_BATCH_LANES,
        progress,
    )
}

/// [`gate`] with the batch width given (`--batch`): cases whose runs share
/// their effective matrix (the same scene and mesh with other carriers, or
/// formulations) step together (`integrate::batch`); each case's numbers
/// are the same whatever the width.
pub(crate) fn gate_batched(
    suite: &Path,
    update: bool,
    batch: usize,
    progress: &mut dyn FnMut(usize, usize, &str),
) -> Result<GateReport> {
    let files = case_files(suite)?;
    let mut checks = Vec::new();
    let mut errors = Vec::new();
    let mut wall = BTreeMap::new();
    // every case's scene first, then the runs together
    let prepared: Vec<Result<(GateCase, crate::resolve::Resolved)>> = files
        .iter()
        .map(|path| {
            read_case(path).and_then(|case| {
                let scene = path.parent().unwrap_or(Path::new(".")).join(&case.scene);
                load_scene(&scene, &case.set).map(|sc| (case, sc))
            })
        })
        .collect();
    let scenes: Vec<crate::resolve::Resolved> = prepared
        .iter()
        .filter_map(|p| p.as_ref().ok().map(|(_, sc)| sc.clone()))
        .collect();
    let mut outputs = crate::run::run_batch(&scenes, batch, &mut |_| {}).into_iter();
    for (i, (path, prepared)) in files.iter().zip(prepared).enumerate() {
        let name = case_name(path);
        let outcome = prepared.and_then(|(case, _)| {
            let out = outputs.next().expect("one output per scene")?;
            Ok((case, out))
        });
        match outcome {
            Ok((mut case, out)) => {
                wall.insert(name.clone(), out.wall_seconds);
                let c = check_case(&name, &case, &out);
                if update {
                    for (q, t) in case.quantities.iter_mut() {
                        if let Some(v) = quantity(&out, q) {
                            t.value = v;
                        }
                    }
                    let text = serde_json::to_string_pretty(&case).map_err(|e| Error::Output {
                        path: path.clone(),
                        reason: e.to_string(),
                    })?;
                    std::fs::write(path, text + "\n").map_err(|e| Error::io(path, e))?;
                }
                checks.extend(c);
            }
            Err(e) => errors.push(CaseError {
                case: name.clone(),
                error: e.to_string(),
            }),
        }
        progress(i + 1, files.len(), &name);
    }
    Ok(GateReport {
        checks,
        errors,
        wall_seconds: wall,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_quantity_can_be_gated() {
        let names = quantity_names();
        for q in crate::quantity::all() {
            assert!(names.contains(&q.name), "{}", q.name);
        }
        assert_eq!(names.last(), Some(&"final_probe"));
    }

    #[test]
    fn tolerance_is_absolute_plus_relative() {
        let case = GateCase {
            description: "t".into(),
            scene: "x".into(),
            set: vec![],
            quantities: BTreeMap::from([(
                "steps".to_string(),
                Tolerance {
                    value: 100.0,
                    abs: 1.0,
                    rel: 0.01,
                    reason: "test".into(),
                },
            )]),
        };
        let mut out = crate::run::RunOutput {
            history: Default::default(),
            stats: vec![crate::record::ContactStats::from_trace(
                &[0.0],
                &Default::default(),
                crate::record::LossGeometry::span_only(1.0),
            )],
            droppers: vec![],
            spans: vec![],
            standard: vec![],
            dofs: 1,
            steps: 102,
            dt: 1.0,
            wall_seconds: 0.0,
            warnings: vec![],
            window_end: 1.0,
            force_lag: 0.0,
            form: None,
        };
        out.history.carriers.push(Default::default());
        assert!(check_case("c", &case, &out)[0].pass);
        out.steps = 103;
        assert!(!check_case("c", &case, &out)[0].pass);
    }
}
