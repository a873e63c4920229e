//! The held-out set: families of scenes the stored pairs
//! ([`super::replay::STORED`]) do not contain, each held against a truth,
//! and never used to choose or tune an estimator. The estimators and the
//! rule that picks among them ([`super::replay::choose`]) are fixed on the
//! stored pairs; the held-out pairs only check them.
//!
//! `cargo xtask uncertainty heldout` runs every case (one `taut
//! uncertainty` family of K = 4 levels per starting resolution, every
//! quantity of the family at once, and one truth run per case and support
//! zone with its check at half the resolution) and writes
//! [`HELD_OUT`]; `cargo xtask uncertainty replay golden/uncertainty_heldout.jsonl`
//! assesses them again, and a default test replays the file.

use std::io::Write;

use taut::error::Result;
use taut::record::zone::support_zone_of;
use taut::resolve::resolve_scene;
use taut::run::run;
use taut::study::uncertainty::{DEFAULT_LEVELS, Role, quantity, uncertainty};

use super::cases::Truth;
use super::{Row, truth};

/// The held-out pairs as stored with the repository.
pub const HELD_OUT: &str = "golden/uncertainty_heldout.jsonl";

/// Where a held-out case's true value comes from.
#[derive(Debug, Clone, Copy)]
pub enum HeldTruth {
    /// The exact moving-force series (MODEL §8).
    Series,
    /// The same scene and discretization run finer than every family's
    /// finest level (`fine`: its overrides, ×4 or more in the level
    /// parameter and in 1/Δt), and checked against the same at half that
    /// resolution (`half`).
    Finer {
        /// Overrides of the truth run.
        fine: &'static [&'static str],
        /// Overrides of its check at half the resolution.
        half: &'static [&'static str],
    },
}

/// One held-out case.
#[derive(Debug, Clone)]
pub struct HeldOut {
    /// Its name in the tables.
    pub name: &'static str,
    /// The scene file, relative to the repository.
    pub scene: &'static str,
    /// Fixed overrides.
    pub set: &'static [&'static str],
    /// The key the starting level is set by (`mesh.elements`, or
    /// `line.element_length` for a generated line).
    pub start_key: &'static str,
    /// Starting levels (the key's value) and Δt₀ (s).
    pub starts: &'static [(&'static str, f64)],
    /// The quantities held against the truth.
    pub quantities: &'static [&'static str],
    /// The truth.
    pub truth: HeldTruth,
}

/// Quantities of a case with a contact force: smooth (the force's mean,
/// its 0–20 Hz standard deviation, the displacement's RMS and maximum)
/// and not (the raw force's standard deviation and maximum, which carry
/// the contact's step-to-step spikes).
const FORCE_AND_DISPLACEMENT: &[&str] = &[
    "force_mean",
    "filtered_force_std",
    "displacement_rms",
    "displacement_max",
    "force_std",
    "force_max",
];

/// [`FORCE_AND_DISPLACEMENT`] and the share of time in loss in the span
/// (not smooth), for a case whose contact is lost at every level.
const WITH_LOSS: &[&str] = &[
    "force_mean",
    "filtered_force_std",
    "displacement_rms",
    "displacement_max",
    "force_std",
    "force_max",
    "loss_fraction_span",
];

/// A Hermite case's starts: N₀ = 25, 50 with Δt₀ = 4e-4, 2e-4 s (finest
/// family level: N = 400, Δt = 2.5e-5 s).
const HERMITE_STARTS: &[(&str, f64)] = &[("25", 4e-4), ("25", 2e-4), ("50", 4e-4), ("50", 2e-4)];

/// The truth of a Hermite case: N = 1600, Δt = 6.25e-6 s, four times
/// finer in both than the finest family level of [`HERMITE_STARTS`].
const HERMITE_TRUTH: HeldTruth = HeldTruth::Finer {
    fine: &["mesh.elements=1600", "time.step=6.25e-6"],
    half: &["mesh.elements=800", "time.step=1.25e-5"],
};

/// The held-out cases: the riding mass at three speeds (V/c = 0.3, 0.6,
/// 0.9; each ending with the mass at x = 40 m of 50), a string under a
/// moving force (exact series), a two-span line with droppers and its
/// messenger (five droppers a span, on the nodes of every level), the
/// reference case at V0/c = 0.85 (a speed the stored pairs do not have;
/// contact is lost at every level) and the three-mass pantograph on the
/// clamped–pinned wire.
pub fn held_out() -> Vec<HeldOut> {
    vec![
        HeldOut {
            name: "riding mass V/c = 0.3",
            scene: "scenes/riding_mass_pinned.toml",
            set: &["carrier.speed.value=44.97", "time.end=0.8895"],
            start_key: "mesh.elements",
            starts: HERMITE_STARTS,
            quantities: FORCE_AND_DISPLACEMENT,
            truth: HERMITE_TRUTH,
        },
        HeldOut {
            name: "riding mass V/c = 0.6",
            scene: "scenes/riding_mass_pinned.toml",
            set: &["carrier.speed.value=89.94", "time.end=0.4447"],
            start_key: "mesh.elements",
            starts: HERMITE_STARTS,
            quantities: FORCE_AND_DISPLACEMENT,
            truth: HERMITE_TRUTH,
        },
        HeldOut {
            name: "riding mass V/c = 0.9",
            scene: "scenes/riding_mass_pinned.toml",
            set: &["carrier.speed.value=134.92", "time.end=0.2965"],
            start_key: "mesh.elements",
            starts: HERMITE_STARTS,
            quantities: FORCE_AND_DISPLACEMENT,
            truth: HERMITE_TRUTH,
        },
        HeldOut {
            name: "string, moving force",
            scene: "scenes/moving_force_string.toml",
            set: &[],
            start_key: "mesh.elements",
            starts: HERMITE_STARTS,
            quantities: &["displacement_rms", "displacement_max"],
            truth: HeldTruth::Series,
        },
        HeldOut {
            name: "two-span line with droppers",
            scene: "scenes/line_10_spans.toml",
            set: &[
                "line.spans=2",
                "line.droppers={ count = 5, end_distance = 7.5 }",
                "time.end=1.2",
            ],
            start_key: "line.element_length",
            starts: &[("2.5", 4e-4), ("2.5", 2e-4)],
            quantities: FORCE_AND_DISPLACEMENT,
            // finest family level: h = 0.3125 m, Δt = 2.5e-5 s
            truth: HeldTruth::Finer {
                fine: &["line.element_length=0.078125", "time.step=6.25e-6"],
                half: &["line.element_length=0.15625", "time.step=1.25e-5"],
            },
        },
        HeldOut {
            name: "reference case V0/c = 0.85, Hermite",
            scene: "scenes/reference.toml",
            set: &["carrier.speed.cruise=127.4"],
            start_key: "mesh.elements",
            starts: &[("100", 4e-4), ("100", 2e-4), ("200", 4e-4), ("200", 2e-4)],
            quantities: WITH_LOSS,
            // finest family level: N = 1600, Δt = 2.5e-5 s
            truth: HeldTruth::Finer {
                fine: &["mesh.elements=6400", "time.step=6.25e-6"],
                half: &["mesh.elements=3200", "time.step=1.25e-5"],
            },
        },
        HeldOut {
            name: "three-mass pantograph",
            scene: "scenes/pantograph_3mass.toml",
            set: &[],
            start_key: "mesh.elements",
            starts: HERMITE_STARTS,
            quantities: FORCE_AND_DISPLACEMENT,
            truth: HERMITE_TRUTH,
        },
    ]
}

/// How a case's truth was computed, in words (stored with each pair).
fn truth_source(case: &HeldOut) -> String {
    match case.truth {
        HeldTruth::Series => "the exact moving-force series (MODEL §8)".into(),
        HeldTruth::Finer { fine, half } => format!(
            "the same scene run finer: {}; its own accuracy from {}",
            fine.join(", "),
            half.join(", ")
        ),
    }
}

/// The values of `names` in a run of `text` with overrides `set`.
fn run_values(text: &str, set: &[String], names: &[&str]) -> Result<Vec<f64>> {
    let out = run(&resolve_scene(text, set)?, &mut |_, _| {})?;
    Ok(names
        .iter()
        .map(|n| quantity(n).and_then(|q| q.of(&out, 0)).unwrap_or(f64::NAN))
        .collect())
}

/// One case's pairs: each start's family, every listed quantity.
pub fn run_case(case: &HeldOut) -> Result<Vec<(Row, String)>> {
    let text = super::scene_text_of(case.scene);
    let base: Vec<String> = case.set.iter().map(|x| x.to_string()).collect();
    // truth and its spread per support zone (P_l is split at the start's
    // zone; nothing else depends on it)
    let mut known: Vec<(f64, Vec<f64>, Vec<f64>)> = Vec::new();
    let mut rows = Vec::new();
    for &(level, dt0) in case.starts {
        let mut set = base.clone();
        set.push(format!("{}={level}", case.start_key));
        set.push(format!("time.step={dt0:e}"));
        let sc = resolve_scene(&text, &set)?;
        let zone = support_zone_of(&sc);
        let u = uncertainty(&text, &set, DEFAULT_LEVELS, &mut |_, _| {})?;
        let (truths, spreads) = match known.iter().find(|(z, _, _)| *z == zone) {
            Some((_, t, s)) => (t.clone(), s.clone()),
            None => {
                let (t, s) = match case.truth {
                    HeldTruth::Series => {
                        let t = case
                            .quantities
                            .iter()
                            .map(|q| truth::true_value(Truth::Series, q, &sc, &text, &set, None))
                            .collect::<Result<Vec<f64>>>()?;
                        let n = t.len();
                        (t, vec![0.0; n])
                    }
                    HeldTruth::Finer { fine, half } => {
                        let with = |extra: &[&str]| {
                            let mut s = super::truth_set(&base, zone);
                            s.extend(extra.iter().map(|x| x.to_string()));
                            s
                        };
                        let t = run_values(&text, &with(fine), case.quantities)?;
                        let h = run_values(&text, &with(half), case.quantities)?;
                        let s = t.iter().zip(&h).map(|(a, b)| (a - b).abs()).collect();
                        (t, s)
                    }
                };
                known.push((zone, t.clone(), s.clone()));
                (t, s)
            }
        };
        let first = u.family.first().expect("a family");
        let fine = u
            .family
            .iter()
            .rfind(|m| m.role == Role::Diagonal)
            .expect("a diagonal");
        for (i, name) in case.quantities.iter().enumerate() {
            let Some(q) = u.quantities.iter().find(|q| q.quantity == *name) else {
                continue;
            };
            let a = &q.assessment;
            rows.push((
                Row {
                    case: case.name,
                    quantity: q.quantity,
                    start: (first.modes.unwrap_or(first.elements), first.dt),
                    finest: (fine.modes.unwrap_or(fine.elements), fine.dt),
                    value: a.value.unwrap_or(f64::NAN),
                    u_num: a.u_num.unwrap_or(f64::NAN),
                    u_scene: q.u_scene.unwrap_or(f64::NAN),
                    truth: truths[i],
                    estimator: a.estimator.name().to_string(),
                    error_estimated: a.error.unwrap_or(f64::NAN),
                    safety_factor: a.safety_factor.unwrap_or(f64::NAN),
                    order: a.observed_order.unwrap_or(f64::NAN),
                    behaviour: a.behaviour.name(),
                    truth_spread: Some(spreads[i]),
                    support_zone: zone,
                    diagonal: q.diagonal.clone(),
                    space: q.space.clone(),
                    formal: q.formal,
                    smooth: q.smooth,
                },
                truth_source(case),
            ));
        }
    }
    Ok(rows)
}

/// Write the held-out pairs to `path`: the stored pairs' fields
/// ([`super::replay::row_json`]) and how the truth was computed.
fn write(path: &str, rows: &[(Row, String)]) -> std::io::Result<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    for (r, how) in rows {
        let mut line = super::replay::row_json(r);
        line["truth_source"] = how.as_str().into();
        writeln!(f, "{line}")?;
    }
    f.flush()
}

/// `cargo xtask uncertainty heldout [OUT]`: run every held-out case and
/// write its pairs to `OUT` (default [`HELD_OUT`]), then replay them.
pub fn main(out: Option<&str>) {
    let path = out.map_or_else(|| format!("{}/{HELD_OUT}", crate::ROOT), str::to_string);
    let mut all = Vec::new();
    for case in held_out() {
        let clock = std::time::Instant::now();
        let rows = run_case(&case).unwrap_or_else(|e| panic!("{}: {e}", case.name));
        eprintln!(
            "{}: {} pairs in {:.1} s wall",
            case.name,
            rows.len(),
            clock.elapsed().as_secs_f64()
        );
        all.extend(rows);
    }
    write(&path, &all).unwrap_or_else(|e| panic!("{path}: {e}"));
    eprintln!("wrote {path}");
    super::replay::main(&path, None);
}
