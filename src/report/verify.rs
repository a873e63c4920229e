//! `verify.csv`, `verify.json` and the terminal order table of `taut verify`.

use std::path::Path;

use serde::Serialize;

use super::table::{Column, Table};
use crate::error::{Error, Result};
use crate::study::verify::{DOMINANCE_LIMIT, Status, VerifyRow};

/// Column order of `verify.csv`.
pub const VERIFY_COLUMNS: [&str; 22] = [
    "case",
    "method",
    "discretization",
    "formulation",
    "supports",
    "variable",
    "quantity",
    "expected",
    "tolerance",
    "observed",
    "finest_order",
    "range_coarse",
    "range_fine",
    "finest_error",
    "relative_error",
    "other_share",
    "omega_max_dt",
    "status",
    "note",
    "levels",
    "errors",
    "wall_seconds",
];

/// Values joined by `;` (shortest round-trip form; empty for NaN).
fn joined(v: &[f64]) -> String {
    v.iter()
        .map(|x| {
            if x.is_finite() {
                super::fmt_f64(*x)
            } else {
                String::new()
            }
        })
        .collect::<Vec<_>>()
        .join(";")
}

/// `verify.csv` as a table ([`VERIFY_COLUMNS`]).
pub fn verify_rows(rows: &[VerifyRow]) -> Table {
    let label = |f: &dyn Fn(&VerifyRow) -> String| Column::Label(rows.iter().map(f).collect());
    let real = |f: &dyn Fn(&VerifyRow) -> f64| Column::RealOrNone(rows.iter().map(f).collect());
    let columns = [
        label(&|r| r.case.clone()),
        label(&|r| r.method.clone()),
        label(&|r| r.discretization.clone()),
        label(&|r| r.formulation.clone()),
        label(&|r| r.supports.clone()),
        label(&|r| r.variable.clone()),
        label(&|r| r.quantity.clone()),
        real(&|r| r.expected),
        real(&|r| r.tolerance),
        real(&|r| r.observed),
        real(&|r| r.orders.last().copied().unwrap_or(f64::NAN)),
        real(&|r| r.range.0),
        real(&|r| r.range.1),
        real(&|r| r.errors.last().copied().unwrap_or(f64::NAN)),
        real(&|r| r.relative_error),
        real(&|r| r.other_share),
        real(&|r| r.omega_max_dt),
        label(&|r| r.status.name().to_string()),
        Column::Text(
            rows.iter()
                .map(|r| (!r.note.is_empty()).then(|| r.note.clone()))
                .collect(),
        ),
        label(&|r| joined(&r.levels)),
        label(&|r| joined(&r.errors)),
        Column::Real(rows.iter().map(|r| r.wall_seconds).collect()),
    ];
    let mut t = Table::new();
    for (name, column) in VERIFY_COLUMNS.into_iter().zip(columns) {
        t.push(name, column);
    }
    t
}

/// Counts of each status.
#[derive(Debug, Clone, Copy, Default, Serialize, PartialEq, Eq)]
pub struct Counts {
    /// Rows that passed.
    pub pass: usize,
    /// Rows that failed.
    pub fail: usize,
    /// Known deviations.
    pub known: usize,
    /// Combinations that cannot show an order (with the reason).
    pub cannot: usize,
    /// Reported without an expectation.
    pub reported: usize,
}

impl Counts {
    /// Count the rows' statuses.
    pub fn of(rows: &[VerifyRow]) -> Self {
        let mut c = Counts::default();
        for r in rows {
            match r.status {
                Status::Pass => c.pass += 1,
                Status::Fail => c.fail += 1,
                Status::Known => c.known += 1,
                Status::Cannot => c.cannot += 1,
                Status::Reported => c.reported += 1,
            }
        }
        c
    }
}

#[derive(Serialize)]
struct VerifyJson<'a> {
    taut_version: &'static str,
    dominance_limit: f64,
    counts: Counts,
    wall_seconds: f64,
    rows: &'a [VerifyRow],
}

/// Write `verify.csv` and `verify.json` into `dir`.
pub fn write_verify(dir: &Path, rows: &[VerifyRow], wall_seconds: f64) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    verify_rows(rows).write_csv(&dir.join("verify.csv"))?;
    super::write_json(
        &dir.join("verify.json"),
        &VerifyJson {
            taut_version: env!("CARGO_PKG_VERSION"),
            dominance_limit: DOMINANCE_LIMIT,
            counts: Counts::of(rows),
            wall_seconds,
            rows,
        },
    )
}

/// The terminal table: one line per row, observed beside expected.
pub fn verify_table(rows: &[VerifyRow]) -> String {
    let mut s = format!(
        "{:<14} {:<18} {:<9} {:<15} {:<15} {:>3} {:<12} {:>8} {:>8} {:>7}  {}\n",
        "case",
        "method",
        "space",
        "formulation",
        "supports",
        "var",
        "quantity",
        "expected",
        "observed",
        "share",
        "status"
    );
    let f = |v: f64, w: usize, p: usize| {
        if v.is_finite() {
            format!("{v:>w$.p$}")
        } else {
            format!("{:>w$}", "—")
        }
    };
    for r in rows {
        s.push_str(&format!(
            "{:<14} {:<18} {:<9} {:<15} {:<15} {:>3} {:<12} {} {} {}  {}{}\n",
            r.case,
            r.method,
            r.discretization,
            r.formulation,
            r.supports,
            r.variable,
            r.quantity,
            f(r.expected, 8, 1),
            f(r.observed, 8, 2),
            f(r.other_share, 7, 3),
            r.status.name(),
            if r.status == Status::Pass || r.note.is_empty() {
                String::new()
            } else {
                format!(": {}", r.note)
            }
        ));
    }
    let c = Counts::of(rows);
    s.push_str(&format!(
        "{} rows: {} pass, {} fail, {} known, {} cannot, {} reported\n",
        rows.len(),
        c.pass,
        c.fail,
        c.known,
        c.cannot,
        c.reported
    ));
    s
}
