//! `sweep.csv`, `sweep_force.csv`, `sweep_loss.csv` and `timing.csv` of
//! `taut sweep` / `taut merge`, and a merge's `merge.csv` (maps: see
//! `report::sweep_maps`).

use std::io::Write;
use std::path::Path;

use super::fmt_f64;
use super::table::{Column, Table};
use crate::error::{Error, Result};
use crate::study::sweep::{PROFILE_BINS, Refined, SweepRecord, SweepSpec, refinement_converged};

fn opt(v: Option<f64>) -> String {
    v.filter(|x| x.is_finite()).map(fmt_f64).unwrap_or_default()
}

fn write(path: &Path, text: &str) -> Result<()> {
    let mut f = std::fs::File::create(path).map_err(|e| Error::io(path, e))?;
    f.write_all(text.as_bytes()).map_err(|e| Error::io(path, e))
}

/// `sweep.csv` as a table: the swept values, `speed_ratio` (unless swept),
/// the point's results, and with `--check-refinement` the refined run's
/// N, Δt, P_l and in-span P_l, their changes and whether the in-span part
/// is converged. A stopped point has empty results and its `error`.
pub fn sweep_table(spec: &SweepSpec, records: &[SweepRecord]) -> Table {
    let mut t = Table::new();
    for (k, a) in spec.axes.iter().enumerate() {
        t.push(
            a.key.clone(),
            Column::Real(records.iter().map(|r| r.values[k]).collect()),
        );
    }
    let real = |f: fn(&SweepRecord) -> f64| Column::RealOrNone(records.iter().map(f).collect());
    if !spec.axes.iter().any(|a| a.key == "speed_ratio") {
        t.push("speed_ratio", real(|r| r.speed_ratio.unwrap_or(f64::NAN)));
    }
    t.push_quantities(records.iter().map(|r| &r.quantities));
    t.push(
        "warnings",
        Column::Count(records.iter().map(|r| r.warnings.len() as u64).collect()),
    );
    t.push(
        "error",
        Column::Text(records.iter().map(|r| r.error.clone()).collect()),
    );
    // the point's work, every run made for it: where a map's time went, the
    // same on any machine (its CPU seconds are in timing.csv)
    t.push(
        "dof_steps_used",
        Column::RealOrNone(
            records
                .iter()
                .map(|r| r.dof_steps.unwrap_or(f64::NAN))
                .collect(),
        ),
    );
    if spec.tolerance.is_some() {
        tolerance_columns(&mut t, records);
    }
    if !spec.check_refinement {
        return t;
    }
    let refined = |f: fn(&Refined) -> f64| {
        Column::RealOrNone(
            records
                .iter()
                .map(|r| r.refined.as_ref().map_or(f64::NAN, f))
                .collect(),
        )
    };
    let change = |f: fn(&Refined, &SweepRecord) -> f64| {
        Column::RealOrNone(
            records
                .iter()
                .map(|r| r.refined.as_ref().map_or(f64::NAN, |x| f(x, r)))
                .collect(),
        )
    };
    t.push(
        "refined_elements",
        Column::CountOrNone(
            records
                .iter()
                .map(|r| r.refined.as_ref().map(|f| f.elements as u64))
                .collect(),
        ),
    );
    t.push(
        "refined_modes",
        Column::CountOrNone(
            records
                .iter()
                .map(|r| r.refined.as_ref().and_then(|f| f.modes.map(|j| j as u64)))
                .collect(),
        ),
    );
    t.push("refined_dt", refined(|f| f.dt));
    t.push("refined_loss_fraction", refined(|f| f.loss_fraction));
    t.push(
        "refined_loss_fraction_span",
        refined(|f| f.loss_fraction_span),
    );
    t.push(
        "loss_fraction_change",
        change(|f, r| f.loss_fraction - r.loss_fraction()),
    );
    t.push(
        "loss_fraction_span_change",
        change(|f, r| f.loss_fraction_span - r.loss_fraction_span()),
    );
    t.push(
        "loss_fraction_span_converged",
        Column::Label(
            records
                .iter()
                .map(|r| {
                    r.refined
                        .as_ref()
                        .and_then(|f| {
                            refinement_converged(r.loss_fraction_span(), f.loss_fraction_span)
                        })
                        .map_or("", |c| if c { "yes" } else { "no" })
                        .to_string()
                })
                .collect(),
        ),
    );
    t.push(
        "refined_error",
        Column::Text(
            records
                .iter()
                .map(|r| r.refined.as_ref().and_then(|f| f.error.clone()))
                .collect(),
        ),
    );
    t
}

/// The columns of an accuracy-targeted sweep (`--tolerance`): u_num of the
/// targeted quantity, whether it met the tolerance, and the resolution and
/// cost the point took.
fn tolerance_columns(t: &mut Table, records: &[SweepRecord]) {
    use crate::study::sweep::PointAccuracy;
    let acc = |f: fn(&PointAccuracy) -> f64| {
        Column::RealOrNone(
            records
                .iter()
                .map(|r| r.accuracy.as_ref().map_or(f64::NAN, f))
                .collect(),
        )
    };
    let count = |f: fn(&PointAccuracy) -> Option<u64>| {
        Column::CountOrNone(
            records
                .iter()
                .map(|r| r.accuracy.as_ref().and_then(f))
                .collect(),
        )
    };
    t.push("u_num", acc(|a| a.u_num));
    t.push(
        "tolerance_met",
        Column::Label(
            records
                .iter()
                .map(|r| match &r.accuracy {
                    Some(a) if a.met => "yes".into(),
                    Some(_) => "no".into(),
                    None => String::new(),
                })
                .collect(),
        ),
    );
    t.push("elements_used", count(|a| Some(a.elements as u64)));
    t.push("modes_used", count(|a| a.modes.map(|j| j as u64)));
    t.push("dt_used", acc(|a| a.dt));
    t.push("runs_used", count(|a| Some(a.runs as u64)));
    t.push(
        "predicted_cost",
        Column::RealOrNone(
            records
                .iter()
                .map(|r| {
                    r.accuracy
                        .as_ref()
                        .and_then(|a| a.predicted_cost)
                        .unwrap_or(f64::NAN)
                })
                .collect(),
        ),
    );
    t.push(
        "estimator",
        Column::Label(
            records
                .iter()
                .map(|r| {
                    r.accuracy
                        .as_ref()
                        .map_or(String::new(), |a| a.estimator.clone())
                })
                .collect(),
        ),
    );
    t.push(
        "not_met_because",
        Column::Text(
            records
                .iter()
                .map(|r| r.accuracy.as_ref().and_then(|a| a.not_met.clone()))
                .collect(),
        ),
    );
}

/// `merge.csv` of `taut merge`: the shard folders it joined, one a row, as
/// named on its command line. A merged folder's other files are the same
/// bytes as a sweep's; this one tells the report (and a reader) which
/// command wrote it.
pub(crate) fn write_merge(dir: &Path, shards: &[std::path::PathBuf]) -> Result<()> {
    let mut t = Table::new();
    t.push(
        "shard",
        Column::Text(
            shards
                .iter()
                .map(|s| Some(s.display().to_string()))
                .collect(),
        ),
    );
    t.write_csv(&dir.join("merge.csv"))
}

/// Write the CSV outputs of a sweep into `dir`. Wall and CPU times go to
/// `timing.csv` only, so the other files are the same bytes on any machine
/// and thread count.
pub fn write_sweep(dir: &Path, spec: &SweepSpec, records: &[SweepRecord]) -> Result<()> {
    let names: Vec<&str> = spec.axes.iter().map(|a| a.key.as_str()).collect();
    sweep_table(spec, records).write_csv(&dir.join("sweep.csv"))?;

    for (file, pick) in [
        (
            "sweep_force.csv",
            (|r: &SweepRecord| &r.force_profile) as fn(&SweepRecord) -> &Vec<Option<f64>>,
        ),
        ("sweep_loss.csv", |r: &SweepRecord| &r.loss_profile),
    ] {
        let mut s = names.join(",");
        for b in 0..PROFILE_BINS {
            s.push_str(&format!(
                ",x{}",
                fmt_f64((b as f64 + 0.5) / PROFILE_BINS as f64)
            ));
        }
        s.push('\n');
        for r in records {
            let vals: Vec<String> = r.values.iter().map(|v| fmt_f64(*v)).collect();
            s.push_str(&vals.join(","));
            let prof = pick(r);
            for b in 0..PROFILE_BINS {
                s.push(',');
                s.push_str(&opt(prof.get(b).copied().flatten()));
            }
            s.push('\n');
        }
        write(&dir.join(file), &s)?;
    }

    let mut t = String::from("index,wall_seconds,cpu_seconds,dof_steps_used\n");
    for r in records {
        t.push_str(&format!(
            "{},{},{},{}\n",
            r.index,
            opt(r.wall_seconds),
            opt(r.cpu_seconds),
            opt(r.dof_steps)
        ));
    }
    write(&dir.join("timing.csv"), &t)
}
