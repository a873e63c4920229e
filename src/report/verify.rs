//! `verify.csv`, `verify.json` and the terminal order table of `taut verify`.

use std::path::Path;

use serde::Serialize;

use super::table::{Column, Table};
use crate::error::{Error, Result};
use crate::study::verify::{DOMINANCE_LIMIT, Status, VerifyRow};

/// Column order of `verify.csv`.
pub(crate) const VERIFY_COLUMNS: [&str; 29] = [
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
    "allowed_low",
    "allowed_high",
    "error_bound",
    "range_coarse",
    "range_fine",
    "finest_error",
    "relative_error",
    "other_share",
    "penalty_share",
    "start_share",
    "loss_share",
    "omega_max_dt",
    "status",
    "note",
    "levels",
    "errors",
    "loss_intervals",
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
pub(crate) fn verify_rows(rows: &[VerifyRow]) -> Table {
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
        real(&|r| r.allowed.0),
        real(&|r| r.allowed.1),
        real(&|r| r.error_bound),
        real(&|r| r.range.0),
        real(&|r| r.range.1),
        real(&|r| r.errors.last().copied().unwrap_or(f64::NAN)),
        real(&|r| r.relative_error),
        real(&|r| r.other_share),
        real(&|r| r.penalty_share.unwrap_or(f64::NAN)),
        real(&|r| r.start_share),
        real(&|r| r.loss_share),
        real(&|r| r.omega_max_dt),
        label(&|r| r.status.name().to_string()),
        Column::Text(
            rows.iter()
                .map(|r| (!r.note.is_empty()).then(|| r.note.clone()))
                .collect(),
        ),
        label(&|r| joined(&r.levels)),
        label(&|r| joined(&r.errors)),
        label(&|r| {
            r.loss_intervals
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(";")
        }),
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
pub(crate) struct Counts {
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
    /// Declared to diverge, and diverging.
    pub diverges: usize,
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
                Status::Diverges => c.diverges += 1,
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

/// Write `verify.csv`, `verify.json` and `verify.md` (the order table,
/// [`verify_markdown`]) into `dir`.
pub(crate) fn write_verify(dir: &Path, rows: &[VerifyRow], wall_seconds: f64) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    verify_rows(rows).write_csv(&dir.join("verify.csv"))?;
    let md = dir.join("verify.md");
    std::fs::write(&md, verify_markdown(rows)).map_err(|e| Error::io(&md, e))?;
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
        "{} rows: {} pass, {} fail, {} known, {} cannot, {} reported, {} diverges\n",
        rows.len(),
        c.pass,
        c.fail,
        c.known,
        c.cannot,
        c.reported,
        c.diverges
    ));
    s
}

/// The order table as markdown (`verify.md`): one line per case, refined
/// variable, quantity, method and discretization, one column per
/// formulation; each cell the expected order, the observed ladder orders
/// over the support pairs (least–largest) and the status (✓ pass, ✗ fail,
/// `known`, `cannot`, `reported`; a cell with mixed statuses lists each).
pub(crate) fn verify_markdown(rows: &[VerifyRow]) -> String {
    let mut forms: Vec<&str> = Vec::new();
    for r in rows {
        if !forms.contains(&r.formulation.as_str()) {
            forms.push(&r.formulation);
        }
    }
    let mut keys: Vec<(&str, &str, &str, &str, &str)> = Vec::new();
    for r in rows {
        let k = (
            r.case.as_str(),
            r.variable.as_str(),
            r.quantity.as_str(),
            r.method.as_str(),
            r.discretization.as_str(),
        );
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    let mut s = String::from("| case | var | quantity | method | space |");
    for f in &forms {
        s.push_str(&format!(" {f} |"));
    }
    s.push_str("\n|---|---|---|---|---|");
    for _ in &forms {
        s.push_str("---|");
    }
    s.push('\n');
    for k in keys {
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} |",
            k.0, k.1, k.2, k.3, k.4
        ));
        for f in &forms {
            let cell: Vec<&VerifyRow> = rows
                .iter()
                .filter(|r| {
                    (
                        r.case.as_str(),
                        r.variable.as_str(),
                        r.quantity.as_str(),
                        r.method.as_str(),
                        r.discretization.as_str(),
                    ) == k
                        && r.formulation == *f
                })
                .collect();
            s.push_str(&format!(" {} |", cell_text(&cell)));
        }
        s.push('\n');
    }
    s
}

/// One cell of [`verify_markdown`].
fn cell_text(rows: &[&VerifyRow]) -> String {
    if rows.is_empty() {
        return String::new();
    }
    let mut parts = Vec::new();
    for (status, mark) in [
        (Status::Pass, "✓"),
        (Status::Fail, "✗"),
        (Status::Known, "known"),
        (Status::Reported, "reported"),
        (Status::Diverges, "diverges"),
    ] {
        let obs: Vec<f64> = rows
            .iter()
            .filter(|r| r.status == status)
            .map(|r| r.observed)
            .filter(|o| o.is_finite())
            .collect();
        let n = rows.iter().filter(|r| r.status == status).count();
        if n == 0 {
            continue;
        }
        let (lo, hi) = obs
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &o| {
                (a.min(o), b.max(o))
            });
        let range = if obs.is_empty() {
            "—".to_string()
        } else if (hi - lo) < 0.005 {
            format!("{lo:.2}")
        } else {
            format!("{lo:.2}–{hi:.2}")
        };
        let expected = rows
            .iter()
            .find(|r| r.status == status && r.expected.is_finite())
            .map_or(String::new(), |r| format!("{:.1}: ", r.expected));
        let expected = if status == Status::Pass || status == Status::Fail {
            expected
        } else {
            String::new()
        };
        parts.push(format!("{expected}{range} {mark}"));
    }
    let cannot = rows.iter().filter(|r| r.status == Status::Cannot).count();
    if cannot > 0 {
        parts.push(if cannot == rows.len() {
            "cannot".to_string()
        } else {
            format!("cannot ×{cannot}")
        });
    }
    parts.join("; ")
}
