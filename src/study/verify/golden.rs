//! The golden error constants: each `pass` row's finest error of the
//! quick matrix, stored in `golden/verify/quick_errors.json` and bundled in
//! the binary, and a `pass` row whose finest error grows beyond
//! [`GOLDEN_FACTOR`] times its constant failed by `taut verify` itself. An
//! order alone misses a defect that keeps it (`modal_exact`'s hold with its
//! two coefficients swapped keeps order 2 while its force errors grow
//! 1.6–2.2×); the constant catches it.
//!
//! A row with no constant (a case, method or set of one's own, or a row
//! that was not `pass` when the file was written) is not judged on one: its
//! note says so and [`GoldenOutcome::missing`] counts it.
//! `taut verify --update-golden` accepts a deliberate change: the rows that
//! ran replace their constants (the others are kept), the file is
//! rewritten and every constant that moved is listed ([`update`]).

use std::collections::BTreeMap;
use std::sync::OnceLock;

use super::ROUND_OFF_FLOOR;
use super::row::{Status, VerifyRow};
use crate::error::{Error, Result};

/// How much a pass row's finest error may grow over its golden constant:
/// the run-to-run spread is nil (two runs of the quick matrix gave
/// bit-identical finest errors in all 1592 rows: the harness is
/// deterministic), so this is the room left for another platform's
/// floating point and for deliberate changes small enough not to need
/// an update; `modal_exact`'s swapped hold grows force errors 1.6–2.2×.
pub(crate) const GOLDEN_FACTOR: f64 = 1.5;

/// The golden file, from the repository's root (the crate's: `taut verify
/// --update-golden` writes it there).
pub const GOLDEN_FILE: &str = "golden/verify/quick_errors.json";

/// The golden file as built into the binary, so that `taut verify` judges
/// the same constants from any directory.
const BUNDLED: &str = include_str!("../../../golden/verify/quick_errors.json");

/// A constant moved by more than this (relative) is listed in an update's
/// diff: below it the change is another platform's last digits.
const DIFF_SHOWN: f64 = 0.01;

/// What the golden check did to a matrix's rows.
#[derive(Debug, Clone, Default)]
pub struct GoldenOutcome {
    /// `pass` rows failed: finest error above `GOLDEN_FACTOR` (1.5) × constant.
    pub failed: usize,
    /// `pass` rows with no constant in the file (not judged on one).
    pub missing: usize,
    /// An update's diff, one line a constant: `~ key: old → new (ratio×)`,
    /// `+ key: new`, `- key: old`; empty without an update.
    pub diff: Vec<String>,
    /// An update's new file text (to write to [`GOLDEN_FILE`]).
    pub updated: Option<String>,
}

/// A row's identity: case, method, discretization, formulation,
/// supports, variable, quantity.
pub(crate) fn key(r: &VerifyRow) -> String {
    format!(
        "{} {} {} {} {} {} {}",
        r.case, r.method, r.discretization, r.formulation, r.supports, r.variable, r.quantity
    )
}

/// Each pass row's finest error, by [`key`].
pub(crate) fn constants(rows: &[VerifyRow]) -> BTreeMap<String, f64> {
    rows.iter()
        .filter(|r| r.status == Status::Pass)
        .filter_map(|r| r.errors.last().map(|e| (key(r), *e)))
        .filter(|(_, e)| e.is_finite())
        .collect()
}

/// Parse a golden file's text: an object of row keys to finite errors.
fn parse(text: &str) -> std::result::Result<BTreeMap<String, f64>, String> {
    let map: BTreeMap<String, f64> = serde_json::from_str(text).map_err(|e| e.to_string())?;
    match map.iter().find(|(_, e)| !(e.is_finite() && **e >= 0.0)) {
        Some((k, e)) => Err(format!("`{k}` = {e} is not a finite error ≥ 0")),
        None => Ok(map),
    }
}

/// The bundled constants ([`BUNDLED`]), parsed once.
pub(crate) fn bundled() -> Result<&'static BTreeMap<String, f64>> {
    static PARSED: OnceLock<std::result::Result<BTreeMap<String, f64>, String>> = OnceLock::new();
    PARSED.get_or_init(|| parse(BUNDLED)).as_ref().map_err(|e| {
        Error::invalid(
            GOLDEN_FILE,
            "the file built into taut",
            format!("must be a JSON object of row keys to finite errors: {e}"),
        )
    })
}

/// The finest error a row is held to against constant `g`: a row whose
/// finest level is at the round-off floor ([`ROUND_OFF_FLOOR`] of the exact
/// solution's largest value) has an error that is round-off, not a constant
/// of the method, so the floor stands in for a smaller constant.
fn held_to(r: &VerifyRow, g: f64) -> f64 {
    let e = r.errors.last().copied().unwrap_or(f64::NAN);
    let floor = ROUND_OFF_FLOOR * e / r.relative_error;
    if floor.is_finite() { g.max(floor) } else { g }
}

/// Judge the `pass` rows against `golden`: a row above [`GOLDEN_FACTOR`]
/// times its constant fails, its note naming the error, the constant, the
/// factor and the file; a row with no constant keeps its status, its note
/// saying so.
pub(crate) fn judge(rows: &mut [VerifyRow], golden: &BTreeMap<String, f64>) -> GoldenOutcome {
    let mut out = GoldenOutcome::default();
    for r in rows.iter_mut().filter(|r| r.status == Status::Pass) {
        let e = r.errors.last().copied().unwrap_or(f64::NAN);
        match golden.get(&key(r)) {
            None => {
                out.missing += 1;
                let sep = if r.note.is_empty() { "" } else { " " };
                r.note.push_str(&format!(
                    "{sep}[no golden error in {GOLDEN_FILE}: not judged on one; `taut verify --update-golden` adds it]"
                ));
            }
            Some(&g) if e.is_nan() || e > GOLDEN_FACTOR * held_to(r, g) => {
                out.failed += 1;
                r.status = Status::Fail;
                let prior = if r.note.is_empty() {
                    String::new()
                } else {
                    format!("; {}", r.note)
                };
                r.note = format!(
                    "above its golden error: the finest error {e:.3e} is {:.2}× the golden {g:.3e} of {GOLDEN_FILE}, above GOLDEN_FACTOR = {GOLDEN_FACTOR} (orders within their bands; a deliberate change is accepted with `taut verify --update-golden`){prior}",
                    e / g
                );
            }
            Some(_) => {}
        }
    }
    out
}

/// Accept `rows` as the new constants: each row that ran drops its old
/// constant and, where it passes, stores its finest error; rows that did
/// not run keep theirs. Returns the new constants and the diff (constants
/// moved by more than [`DIFF_SHOWN`], added or removed).
pub(crate) fn update(
    rows: &[VerifyRow],
    before: &BTreeMap<String, f64>,
) -> (BTreeMap<String, f64>, Vec<String>) {
    let mut now = before.clone();
    for r in rows {
        now.remove(&key(r));
    }
    now.extend(constants(rows));
    let mut diff = Vec::new();
    for (k, e) in &now {
        match before.get(k) {
            Some(g) if (e / g - 1.0).abs() <= DIFF_SHOWN => {}
            Some(g) => diff.push(format!("~ {k}: {g:.4e} → {e:.4e} ({:.2}×)", e / g)),
            None => diff.push(format!("+ {k}: {e:.4e}")),
        }
    }
    for (k, g) in before.iter().filter(|(k, _)| !now.contains_key(*k)) {
        diff.push(format!("- {k}: {g:.4e}"));
    }
    (now, diff)
}

/// The file text of `golden`: one row a line.
pub(crate) fn text(golden: &BTreeMap<String, f64>) -> String {
    serde_json::to_string_pretty(golden).unwrap_or_default() + "\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pass_row(errors: &[f64]) -> VerifyRow {
        let names = [
            "c",
            "m",
            "hermite",
            "lagrange",
            "pinned-pinned",
            "dt",
            "force",
        ];
        let mut r = VerifyRow::unmeasured(names.map(String::from), Status::Pass, String::new());
        r.errors = errors.to_vec();
        r.relative_error = errors.last().copied().unwrap_or(f64::NAN);
        r
    }

    /// The bundled file parses, and holds the constants of the quick
    /// matrix (its 937 pass rows when written).
    #[test]
    fn the_bundled_constants_parse() {
        let g = bundled().unwrap();
        assert!(g.len() > 900, "{} constants", g.len());
        assert!(parse("{\"a\": -1.0}").is_err());
        assert!(parse("[1]").is_err());
    }

    /// A row is flagged above the factor only, or without a finite error.
    #[test]
    fn a_row_is_flagged_above_the_factor() {
        let golden = constants(&[pass_row(&[4e-6, 1e-6])]);
        let failed = |finest: f64| judge(&mut [pass_row(&[4e-6, finest])], &golden).failed;
        assert_eq!(failed(1e-6), 0);
        assert_eq!(failed(1.49e-6), 0);
        assert_eq!(failed(1.51e-6), 1);
        assert_eq!(failed(f64::NAN), 1);
    }

    /// The judge fails a pass row above the factor with a note naming the
    /// error, the golden value, the factor and the file; leaves other
    /// statuses alone; and notes (does not fail) a row with no constant.
    #[test]
    fn the_judge_fails_a_row_above_its_golden_error_and_notes_a_missing_one() {
        let golden: BTreeMap<String, f64> = [(key(&pass_row(&[1.0])), 1e-6)].into();
        let mut rows = vec![pass_row(&[4e-6, 1.6e-6])];
        let o = judge(&mut rows, &golden);
        assert_eq!((o.failed, o.missing), (1, 0));
        assert_eq!(rows[0].status, Status::Fail);
        for part in [
            "1.600e-6",
            "1.000e-6",
            "1.60×",
            "GOLDEN_FACTOR = 1.5",
            GOLDEN_FILE,
        ] {
            assert!(rows[0].note.contains(part), "{part}: {}", rows[0].note);
        }
        // a row already not passing is not the golden check's
        let mut known = vec![pass_row(&[4e-6, 1.6e-6])];
        known[0].status = Status::Known;
        assert_eq!(judge(&mut known, &golden).failed, 0);
        assert_eq!(known[0].status, Status::Known);
        // no constant: noted, counted, still pass
        let mut other = vec![pass_row(&[4e-6, 1.6e-6])];
        other[0].case = "of one's own".into();
        let o = judge(&mut other, &golden);
        assert_eq!((o.failed, o.missing), (0, 1));
        assert_eq!(other[0].status, Status::Pass);
        assert!(
            other[0].note.contains("no golden error"),
            "{}",
            other[0].note
        );
    }

    /// At the round-off floor the floor stands in for a smaller constant:
    /// round-off noise above a tiny constant fails nothing.
    #[test]
    fn a_row_at_the_round_off_floor_is_held_to_the_floor() {
        let golden: BTreeMap<String, f64> = [(key(&pass_row(&[1.0])), 1e-12)].into();
        // finest error 5e-11 of a solution of size 1: below the floor
        let mut rows = vec![pass_row(&[4e-6, 5e-11])];
        assert_eq!(judge(&mut rows, &golden).failed, 0);
        // 4e-10 of a solution of size 1: above 1.5 × the floor
        let mut rows = vec![pass_row(&[4e-6, 4e-10])];
        assert_eq!(judge(&mut rows, &golden).failed, 1);
    }

    /// An update replaces the constants of the rows that ran, keeps the
    /// others, drops a row no longer passing, and lists what moved.
    #[test]
    fn an_update_lists_what_moved_and_keeps_what_did_not_run() {
        let mut a = pass_row(&[1e-3, 1e-6]);
        a.case = "a".into();
        let mut b = pass_row(&[1e-3, 1e-6]);
        b.case = "b".into();
        let mut c = pass_row(&[1e-3, 1e-6]);
        c.case = "c".into();
        let before: BTreeMap<String, f64> =
            [(key(&a), 1e-6), (key(&b), 1e-6), ("kept".to_string(), 3.0)].into();
        a.errors = vec![1e-3, 2e-6];
        b.status = Status::Fail;
        let (now, diff) = update(&[a.clone(), b.clone(), c.clone()], &before);
        assert_eq!(now.get(&key(&a)), Some(&2e-6));
        assert!(!now.contains_key(&key(&b)));
        assert_eq!(now.get(&key(&c)), Some(&1e-6));
        assert_eq!(now.get("kept"), Some(&3.0));
        assert_eq!(diff.len(), 3, "{diff:?}");
        assert!(
            diff.iter()
                .any(|d| d.starts_with("~ a ") && d.contains("2.00×"))
        );
        assert!(diff.iter().any(|d| d.starts_with("- b ")));
        assert!(diff.iter().any(|d| d.starts_with("+ c ")));
        assert_eq!(parse(&text(&now)).unwrap(), now);
    }
}
