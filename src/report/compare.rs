//! `compare.csv`, `compare.json` and `compare.svg` of `taut compare`.

use std::io::Write;
use std::path::Path;

use serde::Serialize;

use super::fmt_f64;
use super::plot::{abscissa, force_series, line_plot};
use crate::error::{Error, Result};
use crate::study::compare::{CompareRow, Comparison};

/// Column order of `compare.csv` (documented in `docs/output.md`).
pub const COMPARE_COLUMNS: [&str; 14] = [
    "formulation",
    "loss_fraction",
    "loss_set_difference",
    "max_force_difference",
    "rms_force_difference",
    "max_penetration",
    "min_gap",
    "min_force",
    "max_gap_force_product",
    "mean_force",
    "max_force",
    "contact_switches",
    "steps",
    "wall_seconds",
];

fn cells(r: &CompareRow) -> Vec<String> {
    vec![
        r.formulation.clone(),
        fmt_f64(r.loss_fraction),
        fmt_f64(r.loss_set_difference),
        fmt_f64(r.max_force_difference),
        fmt_f64(r.rms_force_difference),
        fmt_f64(r.max_penetration),
        fmt_f64(r.min_gap),
        fmt_f64(r.min_force),
        fmt_f64(r.max_gap_force_product),
        fmt_f64(r.mean_force),
        fmt_f64(r.max_force),
        r.contact_switches.to_string(),
        r.steps.to_string(),
        fmt_f64(r.wall_seconds),
    ]
}

#[derive(Serialize)]
struct CompareJson<'a> {
    taut_version: &'static str,
    reference: &'static str,
    scene: &'a crate::scene::Scene,
    rows: &'a [CompareRow],
}

/// Write the three files into `dir`.
pub fn write_compare(dir: &Path, c: &Comparison) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let csv = dir.join("compare.csv");
    let io = |e| Error::io(&csv, e);
    let mut w = std::io::BufWriter::new(std::fs::File::create(&csv).map_err(io)?);
    writeln!(w, "{}", COMPARE_COLUMNS.join(",")).map_err(io)?;
    for r in &c.rows {
        writeln!(w, "{}", cells(r).join(",")).map_err(io)?;
    }
    w.flush().map_err(io)?;

    let json = dir.join("compare.json");
    let doc = CompareJson {
        taut_version: env!("CARGO_PKG_VERSION"),
        reference: c.reference.name(),
        scene: &c.runs[0].1.scene,
        rows: &c.rows,
    };
    super::write_json(&json, &doc)?;

    let (_, sc, out) = &c.runs[0];
    let (_, x_desc) = abscissa(sc, out, 0);
    let series: Vec<_> = c
        .runs
        .iter()
        .flat_map(|(f, sc, out)| force_series(sc, out, f.name()))
        .collect();
    let title = format!(
        "contact force by formulation: {} elements, dt = {} s",
        sc.elements, sc.dt
    );
    line_plot(
        &dir.join("compare.svg"),
        &title,
        x_desc,
        "contact force λ (N)",
        &series,
    )
}

/// The terminal table.
pub fn compare_table(c: &Comparison) -> String {
    let mut s = format!(
        "{:<16} {:>9} {:>10} {:>11} {:>11} {:>11} {:>10} {:>9} {:>8}\n",
        "formulation",
        "P_l",
        "Δloss",
        "max|Δλ| N",
        "rms Δλ N",
        "max pen m",
        "max λ N",
        "switches",
        "wall s"
    );
    for r in &c.rows {
        s.push_str(&format!(
            "{:<16} {:>9.5} {:>10.5} {:>11.4e} {:>11.4e} {:>11.3e} {:>10.2} {:>9} {:>8.3}\n",
            r.formulation,
            r.loss_fraction,
            r.loss_set_difference,
            r.max_force_difference,
            r.rms_force_difference,
            r.max_penetration,
            r.max_force,
            r.contact_switches,
            r.wall_seconds
        ));
    }
    s.push_str(&format!("(differences against {})\n", c.reference.name()));
    for r in &c.rows {
        for w in &r.warnings {
            s.push_str(&format!("  WARNING  {}: {w}\n", r.formulation));
        }
    }
    s
}
