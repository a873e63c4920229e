//! `standard.csv` and `standard.json`: each carrier's statistics over the
//! analysis section as the railway standards ask for them
//! (docs/output.md#the-standards-statistics; `record::standard`).

use std::path::Path;

use serde::Serialize;

use super::table::{Column, Table};
use crate::error::Result;
use crate::record::{StandardStats, SupportUplift};
use crate::resolve::Resolved;

/// What taut computes, in one sentence a reader of `standard.json` sees
/// beside the numbers (docs/output.md#the-standards-statistics says how it
/// relates to EN 50317, EN 50318 and EN 50367).
pub(crate) const STANDARD_BASIS: &str = "the contact force low-pass filtered to 0–band Hz (2nd-order Butterworth, forward and backward: zero phase); over the steps whose contact point lies in the section: mean F_m, population standard deviation σ, statistical max/min F_m ± 3σ, actual max/min of the filtered force, percentage of steps with the contact open; uplift at each support in the section = largest v(x_s, t) minus the support's static position (the wire under its own loads, no carrier)";

/// Millimetres in a metre (the uplift of `standard.csv`).
const MM_PER_M: f64 = 1e3;

/// `standard.csv`: a row per carrier: `carrier`, `x_start`, `x_end` (m),
/// `band_hz`, `speed` (m/s), `speed_kmh`, `samples`, `mean`, `std`,
/// `statistical_max`, `statistical_min`, `max`, `min` (N, the filtered
/// force), `loss_percent` (%), `uplift_max_mm` (mm, as the terminal
/// shows it; `uplift_max` in m in standard.json), `uplift_x` (m); an
/// empty cell where a value is not defined.
pub fn standard_table(rows: &[StandardStats]) -> Table {
    let mut t = Table::new();
    let real = |f: fn(&StandardStats) -> f64| Column::Real(rows.iter().map(f).collect());
    let opt = |f: fn(&StandardStats) -> Option<f64>| {
        Column::RealOrNone(rows.iter().map(|r| f(r).unwrap_or(f64::NAN)).collect())
    };
    t.push(
        "carrier",
        Column::Count(rows.iter().map(|r| r.carrier as u64).collect()),
    );
    t.push("x_start", real(|r| r.x_start));
    t.push("x_end", real(|r| r.x_end));
    t.push("band_hz", real(|r| r.band_hz));
    t.push("speed", real(|r| r.speed));
    t.push("speed_kmh", real(|r| r.speed_kmh));
    t.push(
        "samples",
        Column::Count(rows.iter().map(|r| r.samples as u64).collect()),
    );
    t.push("mean", opt(|r| r.mean));
    t.push("std", opt(|r| r.std));
    t.push("statistical_max", opt(|r| r.statistical_max));
    t.push("statistical_min", opt(|r| r.statistical_min));
    t.push("max", opt(|r| r.max));
    t.push("min", opt(|r| r.min));
    t.push("loss_percent", opt(|r| r.loss_percent));
    // in mm, as the terminal prints it, the unit in the name
    t.push("uplift_max_mm", opt(|r| r.uplift_max.map(|u| u * MM_PER_M)));
    t.push("uplift_x", opt(|r| r.uplift_x));
    t
}

/// `standard.json`.
#[derive(Debug, Serialize)]
struct StandardJson<'a> {
    taut_version: &'static str,
    /// What is computed ([`STANDARD_BASIS`]).
    basis: &'static str,
    /// The filtered force's band, Hz.
    band_hz: f64,
    /// The section, m, and the spans it was given as.
    section: Section,
    /// A row per carrier.
    carriers: &'a [StandardStats],
    /// The supports in the section, with their static position and uplift.
    supports: Vec<&'a SupportUplift>,
}

#[derive(Debug, Serialize)]
struct Section {
    x_start: f64,
    x_end: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    spans: Option<[usize; 2]>,
}

/// Write `standard.csv` and `standard.json` into `dir`.
pub(crate) fn write_standard(
    dir: &Path,
    sc: &Resolved,
    rows: &[StandardStats],
    supports: &[SupportUplift],
) -> Result<()> {
    standard_table(rows).write_csv(&dir.join("standard.csv"))?;
    let a = &sc.analysis;
    super::write_json(
        &dir.join("standard.json"),
        &StandardJson {
            taut_version: env!("CARGO_PKG_VERSION"),
            basis: STANDARD_BASIS,
            band_hz: a.band_hz,
            section: Section {
                x_start: a.x[0],
                x_end: a.x[1],
                spans: a.spans,
            },
            carriers: rows,
            supports: supports.iter().filter(|s| a.contains(s.x)).collect(),
        },
    )
}
