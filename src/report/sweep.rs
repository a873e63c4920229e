//! `sweep.csv`, `sweep_force.csv`, `sweep_loss.csv` and `timing.csv` of
//! `taut sweep` / `taut merge` (maps: see `report::sweep_maps`).

use std::io::Write;
use std::path::Path;

use super::fmt_f64;
use crate::error::{Error, Result};
use crate::study::sweep::{PROFILE_BINS, SweepRecord, SweepSpec, refinement_converged};

fn opt(v: Option<f64>) -> String {
    v.filter(|x| x.is_finite()).map(fmt_f64).unwrap_or_default()
}

fn num(v: f64) -> String {
    if v.is_finite() {
        fmt_f64(v)
    } else {
        String::new()
    }
}

fn write(path: &Path, text: &str) -> Result<()> {
    let mut f = std::fs::File::create(path).map_err(|e| Error::io(path, e))?;
    f.write_all(text.as_bytes()).map_err(|e| Error::io(path, e))
}

/// The `--check-refinement` columns of a row: the refined run's N, Δt, P_l
/// and in-span P_l, the changes, whether the in-span part is converged.
fn refined_cells(r: &SweepRecord) -> String {
    let Some(f) = &r.refined else {
        return ",,,,,,,,".into();
    };
    let converged = refinement_converged(r.loss_fraction_span, f.loss_fraction_span)
        .map_or("", |c| if c { "yes" } else { "no" });
    format!(
        ",{},{},{},{},{},{},{converged},{}",
        f.elements,
        num(f.dt),
        num(f.loss_fraction),
        num(f.loss_fraction_span),
        num(f.loss_fraction - r.loss_fraction),
        num(f.loss_fraction_span - r.loss_fraction_span),
        f.error
            .as_deref()
            .map(|e| format!("\"{}\"", e.replace('"', "'")))
            .unwrap_or_default()
    )
}

/// Write the CSV outputs of a sweep into `dir`. Wall times go to
/// `timing.csv` only, so the other files are the same bytes on any machine
/// and thread count.
pub fn write_sweep(dir: &Path, spec: &SweepSpec, records: &[SweepRecord]) -> Result<()> {
    let names: Vec<&str> = spec.axes.iter().map(|a| a.key.as_str()).collect();
    let has_ratio = names.contains(&"speed_ratio");
    let mut s = names.join(",");
    if !has_ratio {
        s.push_str(",speed_ratio");
    }
    s.push_str(",loss_fraction,loss_fraction_span,loss_fraction_support,force_mean,force_std,force_min,force_max,first_loss_position,contact_switches,warnings,error");
    if spec.check_refinement {
        s.push_str(",refined_elements,refined_dt,refined_loss_fraction,refined_loss_fraction_span,loss_fraction_change,loss_fraction_span_change,loss_fraction_span_converged,refined_error");
    }
    s.push('\n');
    for r in records {
        let vals: Vec<String> = r.values.iter().map(|v| fmt_f64(*v)).collect();
        s.push_str(&vals.join(","));
        if !has_ratio {
            s.push(',');
            s.push_str(&opt(r.speed_ratio));
        }
        s.push_str(&format!(
            ",{},{},{},{},{},{},{},{},{},{},{}",
            num(r.loss_fraction),
            num(r.loss_fraction_span),
            num(r.loss_fraction_support),
            num(r.force_mean),
            num(r.force_std),
            num(r.force_min),
            num(r.force_max),
            opt(r.first_loss_position),
            r.contact_switches,
            r.warnings.len(),
            r.error
                .as_deref()
                .map(|e| format!("\"{}\"", e.replace('"', "'")))
                .unwrap_or_default()
        ));
        if spec.check_refinement {
            s.push_str(&refined_cells(r));
        }
        s.push('\n');
    }
    write(&dir.join("sweep.csv"), &s)?;

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

    let mut t = String::from("index,wall_seconds\n");
    for r in records {
        t.push_str(&format!("{},{}\n", r.index, opt(r.wall_seconds)));
    }
    write(&dir.join("timing.csv"), &t)
}
