//! The coverage study without its runs: every pair's family values and
//! true value written once (`cargo xtask uncertainty --dump FILE`), then
//! assessed again by the library's current estimators (`cargo xtask
//! uncertainty replay FILE`), so a change to an estimator is measured on
//! the whole grid in seconds. The tables it prints are the study's; only
//! the final `cargo xtask uncertainty` run goes into the docs. It also
//! compares taut's estimator with Roache's GCI, Eça & Hoekstra's and Xing
//! & Stern's per kind of quantity, and checks the one chosen on the stored
//! pairs ([`choose`]) on the file replayed (the held-out pairs).

use std::io::Write;

use serde_json::{Value, json};
use taut::study::uncertainty::{FS_ASYMPTOTIC, FS_CAUTIOUS, Inputs, RATIO, assess, least_squares};

use super::{COVERAGE_TARGET, Row, summary, table_rows};

/// Write `rows`, one JSON object a line ([`row_json`]).
pub fn write(path: &str, rows: &[Row]) -> std::io::Result<()> {
    write_lines(path, rows, row_json)
}

/// One stored pair as its JSON line: the family, its truth and how to
/// assess it again ([`read`]).
pub fn row_json(r: &Row) -> Value {
    json!({
            "case": r.case,
            "quantity": r.quantity,
            "start": [r.start.0, r.start.1],
            "finest": [r.finest.0, r.finest.1],
            "truth": r.truth,
            "truth_spread": r.truth_spread,
            "support_zone": r.support_zone,
            "diagonal": r.diagonal,
            "space": r.space,
            "formal": [r.formal.0, r.formal.1],
            "smooth": r.smooth,
    })
}

/// `line(r)` of every row of `rows` to `path`, one JSON object a line.
fn write_lines(path: &str, rows: &[Row], line: impl Fn(&Row) -> Value) -> std::io::Result<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    for r in rows {
        writeln!(f, "{}", line(r))?;
    }
    f.flush()
}

/// The rows of `path` ([`write`]), each assessed again.
pub fn read(path: &str) -> Result<Vec<Row>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            serde_json::from_str(l)
                .map(|v| reassess(&v))
                .map_err(|e| format!("{path}: {e}"))
        })
        .collect()
}

/// Read the rows of `path`, assess each again, and print the tables and
/// the frontier; with `pairs`, also write each pair's u_num, estimated
/// error and true error there, one JSON line a pair in the same order
/// (what `scripts/sibling_spread.py` reads).
pub fn main(path: &str, pairs: Option<&str>) {
    let rows = read(path).unwrap_or_else(|e| panic!("{e}"));
    if let Some(out) = pairs {
        write_pairs(out, &rows).unwrap_or_else(|e| panic!("{out}: {e}"));
    }
    let mut cases: Vec<(&str, &str)> = Vec::new();
    for r in &rows {
        if !cases.contains(&(r.case, r.quantity)) {
            cases.push((r.case, r.quantity));
        }
    }
    for (c, q) in cases {
        let of: Vec<Row> = rows
            .iter()
            .filter(|r| r.case == c && r.quantity == q)
            .cloned()
            .collect();
        print!("\n**{c}**, `{q}`\n{}", table_rows(&of));
    }
    print!("{}", summary(&rows));
    print!("{}", kinds(&rows));
    print!("{}", frontier(&rows));
    let left_out: Vec<&Row> = rows.iter().filter(|r| !truth_converges(r)).collect();
    if !left_out.is_empty() {
        let covered = left_out.iter().filter(|r| r.covered()).count();
        println!(
            "\n{} pairs left out of the coverage figures below, their truth not converged ({}); taut's bar covers {covered} of them",
            left_out.len(),
            TRUTH_NOT_CONVERGED.join(", ")
        );
    }
    print!("{}", estimator_table(&rows));
    let stored = read(&format!("{}/{STORED}", crate::ROOT)).unwrap_or_else(|e| panic!("{e}"));
    print!("{}", selection(&stored, &rows));
}

/// The estimators compared on the same runs, per kind of quantity:
/// taut's (`assess`), Roache's GCI, Eça & Hoekstra's least squares and
/// Xing & Stern's factor of safety.
pub const ESTIMATORS: [&str; 4] = ["taut's", "Roache's GCI", "Eça & Hoekstra", "Xing & Stern"];

/// The kinds of quantity the figures are given for: smooth in the
/// resolution, and not (MODEL §12).
pub const KINDS: [(&str, bool); 2] = [("smooth", true), ("not smooth", false)];

/// u_num of estimator `ESTIMATORS[e]` for `r` (NaN where it gives none).
pub fn u_of(e: usize, r: &Row) -> f64 {
    match e {
        0 => r.u_num,
        1 => roache_gci(r),
        2 => eca_hoekstra(r),
        _ => xing_stern(r),
    }
}

/// Coverage and sharpness of one estimator on one kind of pairs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Figures {
    /// Pairs of the kind.
    pub pairs: usize,
    /// Share whose u_num covers the true error (no u_num: not covered).
    pub covered: f64,
    /// The median of u_num/|error|, a pair without u_num counted as ∞ (no
    /// bound) and an exact pair (u_num = error = 0) left out.
    pub median: f64,
    /// Pairs given a u_num (the rest are refused: diverging data, or no
    /// monotone triple for a three-level estimator).
    pub given: usize,
    /// Share of those covered.
    pub covered_given: f64,
}

/// Quantities whose truth does not converge where contact is lost and
/// made again, left out of every coverage figure in both sets by name
/// (never by a bar): the registry defines `force_max` as the largest λ
/// over the steps, "a re-contact spike" that "grows as Δt falls"
/// (`taut::quantity`), and on the held-out reference case at V0/c = 0.85
/// its levels grow 2.5–4× a level and its refined truth still moves 16 %
/// between its last two resolutions. A bar for it is checked by nothing.
/// The raw force's std is kept: its refined truth moves 2 %.
pub const TRUTH_NOT_CONVERGED: [&str; 1] = ["force_max"];

/// The pair's truth converges ([`TRUTH_NOT_CONVERGED`]).
pub fn truth_converges(r: &Row) -> bool {
    !TRUTH_NOT_CONVERGED.contains(&r.quantity)
}

/// [`Figures`] of estimator `e` over the pairs of `rows` that are
/// `smooth` (or not) and whose truth converges ([`truth_converges`]).
pub fn figures(rows: &[Row], e: usize, smooth: bool) -> Figures {
    let of: Vec<&Row> = rows
        .iter()
        .filter(|r| r.smooth == smooth && truth_converges(r))
        .collect();
    let u: Vec<(f64, f64)> = of.iter().map(|r| (u_of(e, r), r.error())).collect();
    let covered = u.iter().filter(|(u, err)| *u >= *err).count();
    let ratios = u
        .iter()
        .filter(|(u, err)| !(*u == 0.0 && *err == 0.0))
        .map(|(u, err)| if u.is_nan() { f64::INFINITY } else { u / err })
        .collect();
    let given = u.iter().filter(|(u, _)| !u.is_nan()).count();
    Figures {
        pairs: of.len(),
        covered: covered as f64 / of.len().max(1) as f64,
        median: median(ratios),
        given,
        covered_given: covered as f64 / given.max(1) as f64,
    }
}

/// Every estimator's [`Figures`] per kind of quantity in `rows`.
fn estimator_table(rows: &[Row]) -> String {
    let mut s = String::from(
        "\n| estimator | kind | pairs | covered | median u_num / error | given a u_num | of those covered |\n|---|---|---|---|---|---|---|\n",
    );
    for (e, name) in ESTIMATORS.iter().enumerate() {
        for (kind, smooth) in KINDS {
            let f = figures(rows, e, smooth);
            s.push_str(&format!(
                "| {name} | {kind} | {} | {:.1} % | {:.2} | {} | {:.1} % |\n",
                f.pairs,
                100.0 * f.covered,
                f.median,
                f.given,
                100.0 * f.covered_given
            ));
        }
    }
    s
}

/// The estimator used for a kind of quantity, chosen on the stored pairs
/// alone (never on the held-out ones): of those covering at least
/// [`COVERAGE_TARGET`] of the stored pairs of that kind, the one with the
/// smallest median u_num/|error|; if none does, the one covering most.
/// Returns its index in [`ESTIMATORS`] and whether it reached the target.
pub fn choose(stored: &[Row], smooth: bool) -> (usize, bool) {
    let f: Vec<Figures> = (0..ESTIMATORS.len())
        .map(|e| figures(stored, e, smooth))
        .collect();
    let met = (0..f.len())
        .filter(|&e| f[e].covered >= COVERAGE_TARGET)
        .min_by(|&a, &b| f[a].median.total_cmp(&f[b].median));
    match met {
        Some(e) => (e, true),
        None => (
            (0..f.len())
                .max_by(|&a, &b| f[a].covered.total_cmp(&f[b].covered))
                .expect("estimators"),
            false,
        ),
    }
}

/// The choice made on `stored` ([`choose`]) and its figures on `rows`.
fn selection(stored: &[Row], rows: &[Row]) -> String {
    let mut s = String::from(
        "\n| kind | chosen on the stored pairs | stored: covered, median | these pairs: covered, median |\n|---|---|---|---|\n",
    );
    for (kind, smooth) in KINDS {
        let (e, met) = choose(stored, smooth);
        let (a, b) = (figures(stored, e, smooth), figures(rows, e, smooth));
        s.push_str(&format!(
            "| {kind} | {}{} | {:.1} %, {:.2} | {:.1} %, {:.2} |\n",
            ESTIMATORS[e],
            if met {
                ""
            } else {
                " (none reaches the target)"
            },
            100.0 * a.covered,
            a.median,
            100.0 * b.covered,
            b.median
        ));
    }
    s
}

/// The finest three diagonal values, coarsest first, when all are given.
fn finest_three(r: &Row) -> Option<(f64, f64, f64)> {
    let k = r.diagonal.len();
    if k < 3 {
        return None;
    }
    Some((r.diagonal[k - 3]?, r.diagonal[k - 2]?, r.diagonal[k - 1]?))
}

/// The finest three diagonal levels' observed order p and Richardson
/// error |ε₂₁|/(r^p − 1), where they converge monotonically (0 < R < 1);
/// what Roache's GCI and Xing & Stern's estimator scale by their F_s.
fn richardson_finest(r: &Row) -> Option<(f64, f64)> {
    let (s3, s2, s1) = finest_three(r)?;
    let (e32, e21) = (s2 - s3, s1 - s2);
    let ratio = e21 / e32;
    if !(ratio > 0.0 && ratio < 1.0) {
        return None;
    }
    let rr = RATIO as f64;
    let p = (1.0 / ratio).ln() / rr.ln();
    Some((p, (e21 / (rr.powf(p) - 1.0)).abs()))
}

/// Roache's GCI of the finest three diagonal levels as published (no
/// carrying down of a fast finest difference, which taut adds): F_s
/// [`FS_ASYMPTOTIC`] when the observed order is within 0.5 of the formal
/// one (the smaller of space and time: the diagonal refines both), else
/// [`FS_CAUTIOUS`]; NaN where the three do not converge monotonically.
fn roache_gci(r: &Row) -> f64 {
    let Some((p, delta)) = richardson_finest(r) else {
        return f64::NAN;
    };
    let formal = r.formal.0.min(r.formal.1);
    let fs = if (p - formal).abs() <= 0.5 {
        FS_ASYMPTOTIC
    } else {
        FS_CAUTIOUS
    };
    fs * delta
}

/// Eça & Hoekstra's least-squares estimator (the library's
/// `least_squares::estimate`) on the whole diagonal, h_i = r^−i, at the
/// smaller formal order; NaN where a level is missing or no fit is made.
fn eca_hoekstra(r: &Row) -> f64 {
    let Some(phi) = r.diagonal.iter().copied().collect::<Option<Vec<f64>>>() else {
        return f64::NAN;
    };
    let h: Vec<f64> = (0..phi.len())
        .map(|i| (RATIO as f64).powi(-(i as i32)))
        .collect();
    least_squares::estimate(&h, &phi, r.formal.0.min(r.formal.1), r.smooth)
        .and_then(|ls| ls.u.last().copied())
        .unwrap_or(f64::NAN)
}

/// The median of `x` (NaN when empty).
fn median(mut x: Vec<f64>) -> f64 {
    if x.is_empty() {
        return f64::NAN;
    }
    x.sort_by(f64::total_cmp);
    let n = x.len();
    if n % 2 == 1 {
        x[n / 2]
    } else {
        0.5 * (x[n / 2 - 1] + x[n / 2])
    }
}

/// Per kind of quantity (smooth, not): coverage and the median
/// u_num/|error| of the finest value, and the same of the scene's own
/// value (level 0) and its `u_scene`. Level 0's true value is the finest
/// pair's (the same quantity over the same window and zone).
fn kinds(rows: &[Row]) -> String {
    let mut s = String::from(
        "
| kind | pairs | u_num covers | median u_num / error | u_scene covers | median u_scene / error |\n|---|---|---|---|---|---|\n",
    );
    for (name, smooth) in [
        ("smooth", Some(true)),
        ("not smooth", Some(false)),
        ("all", None),
    ] {
        let of: Vec<&Row> = rows
            .iter()
            .filter(|r| smooth.is_none_or(|sm| r.smooth == sm))
            .collect();
        let n = of.len().max(1) as f64;
        let scene_error = |r: &Row| {
            r.diagonal
                .first()
                .copied()
                .flatten()
                .map_or(f64::NAN, |v| (v - r.truth).abs())
        };
        let covered = of.iter().filter(|r| r.covered()).count() as f64 / n;
        let scene_covered = of.iter().filter(|r| r.u_scene >= scene_error(r)).count() as f64 / n;
        s.push_str(&format!(
            "| {name} | {} | {:.1} % | {:.2} | {:.1} % | {:.2} |\n",
            of.len(),
            100.0 * covered,
            median(
                of.iter()
                    .map(|r| r.sharpness())
                    .filter(|x| !x.is_nan())
                    .collect()
            ),
            100.0 * scene_covered,
            median(
                of.iter()
                    .map(|r| r.u_scene / scene_error(r))
                    .filter(|x| !x.is_nan())
                    .collect()
            ),
        ));
    }
    s
}

/// The finest diagonal step's mesh and Δt parts added without their
/// signs, |Δ_h| + |Δ_Δt| (each the two-level Richardson error of its own
/// variable at order 1); NaN without a split.
fn split_sum(r: &Row) -> f64 {
    let k = r.diagonal.len();
    match (
        r.diagonal.get(k.wrapping_sub(2)).copied().flatten(),
        r.space.last().copied().flatten(),
        r.diagonal.last().copied().flatten(),
    ) {
        (Some(prev), Some(mid), Some(cur)) => (prev - mid).abs() + (mid - cur).abs(),
        _ => f64::NAN,
    }
}

/// Xing & Stern's factor-of-safety estimator (J. Fluids Eng. 132 (2010)
/// 061403) on the finest three diagonal levels: U = FS·|δ_RE|, δ_RE the
/// Richardson error ε₂₁/(r^p − 1) at the observed order p, and FS a
/// function of P = p/p_formal: 2.45 − 0.85P for 0 < P ≤ 1, 16.4P − 14.8
/// above (p_formal the smaller formal order: the diagonal refines both
/// variables, and the slower one rules). NaN where the three levels do not
/// converge monotonically (no p; the method gives no estimate there).
fn xing_stern(r: &Row) -> f64 {
    let Some((p, delta)) = richardson_finest(r) else {
        return f64::NAN;
    };
    let big_p = p / r.formal.0.min(r.formal.1);
    let fs = if big_p <= 1.0 {
        2.45 - 0.85 * big_p
    } else {
        16.4 * big_p - 14.8
    };
    fs * delta
}

/// Safety factors of the frontier's split estimators.
const FRONTIER_FACTORS: [f64; 5] = [1.0, 1.25, 1.5, 2.0, 3.0];

/// Coverage against sharpness of simpler estimators made from the same
/// runs, beside the library's: U = c (|Δ_h| + |Δ_Δt|) of the finest
/// step, and its minimum and geometric mean with the library's u_num. It
/// shows where both targets can be met at once on this grid, if anywhere.
fn frontier(rows: &[Row]) -> String {
    let with = |u: &dyn Fn(&Row) -> f64| -> (f64, f64) {
        let r: Vec<Row> = rows
            .iter()
            .map(|r| Row {
                u_num: u(r),
                ..r.clone()
            })
            .collect();
        super::shares(&r)
    };
    let mut s =
        String::from("\n| estimator (same runs) | covered | u_num ≤ 10× error |\n|---|---|---|\n");
    let mut line = |name: String, (c, sh): (f64, f64)| {
        s.push_str(&format!(
            "| {name} | {:.1} % | {:.1} % |\n",
            100.0 * c,
            100.0 * sh
        ));
    };
    line(
        "taut's (GCI, least squares, split floor)".into(),
        with(&|r| r.u_num),
    );
    line(
        "Xing & Stern's factor of safety (finest three levels)".into(),
        with(&xing_stern),
    );
    line(
        "Xing & Stern's, else taut's where it gives none".into(),
        with(&|r| {
            let u = xing_stern(r);
            if u.is_finite() { u } else { r.u_num }
        }),
    );
    for c in FRONTIER_FACTORS {
        line(
            format!("{c} (\\|Δ_h\\| + \\|Δ_Δt\\|)"),
            with(&|r| c * split_sum(r)),
        );
    }
    // a factor for each kind of quantity: smooth, and not
    for (cs, cn) in [(1.25, 1.5), (1.25, 2.0), (1.0, 1.5)] {
        line(
            format!("{cs} (smooth) or {cn} (not smooth) × (\\|Δ_h\\| + \\|Δ_Δt\\|)"),
            with(&|r| if r.smooth { cs } else { cn } * split_sum(r)),
        );
    }
    for c in FRONTIER_FACTORS {
        line(
            format!("min(taut's, {c} (\\|Δ_h\\| + \\|Δ_Δt\\|))"),
            with(&|r| r.u_num.min(c * split_sum(r))),
        );
    }
    for c in FRONTIER_FACTORS {
        line(
            format!("sqrt(taut's · {c} (\\|Δ_h\\| + \\|Δ_Δt\\|))"),
            with(&|r| (r.u_num * c * split_sum(r)).sqrt()),
        );
    }
    s
}

/// Each row's u_num, estimated error and true error, one JSON line each.
fn write_pairs(path: &str, rows: &[Row]) -> std::io::Result<()> {
    write_lines(path, rows, |r| {
        json!({
            "case": r.case,
            "quantity": r.quantity,
            "start": [r.start.0, r.start.1],
            "u_num": r.u_num,
            "error_estimated": r.error_estimated,
            "error_true": r.error(),
        })
    })
}

/// A stored pair assessed by the current estimators.
fn reassess(v: &Value) -> Row {
    let num = |k: &str| v[k].as_f64().unwrap_or(f64::NAN);
    let list = |k: &str| -> Vec<Option<f64>> {
        v[k].as_array()
            .map(|a| a.iter().map(Value::as_f64).collect())
            .unwrap_or_default()
    };
    let pair = |k: &str| {
        (
            v[k][0].as_f64().unwrap_or(0.0),
            v[k][1].as_f64().unwrap_or(0.0),
        )
    };
    let leak = |k: &str| -> &'static str {
        Box::leak(v[k].as_str().unwrap_or("").to_string().into_boxed_str())
    };
    let (diagonal, space) = (list("diagonal"), list("space"));
    let formal = pair("formal");
    let smooth = v["smooth"].as_bool().unwrap_or(true);
    let a = assess(&Inputs {
        diagonal: &diagonal,
        space: &space,
        ratio: RATIO as f64,
        formal,
        smooth,
    });
    let (s0, s1) = pair("start");
    let (f0, f1) = pair("finest");
    Row {
        case: leak("case"),
        quantity: leak("quantity"),
        start: (s0 as usize, s1),
        finest: (f0 as usize, f1),
        value: a.value.unwrap_or(f64::NAN),
        u_num: a.u_num.unwrap_or(f64::NAN),
        u_scene: a.u_levels.first().copied().flatten().unwrap_or(f64::NAN),
        truth: num("truth"),
        estimator: a.estimator.name().to_string(),
        error_estimated: a.error.unwrap_or(f64::NAN),
        safety_factor: a.safety_factor.unwrap_or(f64::NAN),
        order: a.observed_order.unwrap_or(f64::NAN),
        behaviour: a.behaviour.name(),
        truth_spread: v["truth_spread"].as_f64(),
        support_zone: num("support_zone"),
        diagonal,
        space,
        formal,
        smooth,
    }
}

/// The coverage study's pairs as stored with the repository
/// (`cargo xtask uncertainty --dump`, the run whose tables
/// docs/verification.md shows): a test replays them on every change of an
/// estimator.
pub const STORED: &str = "golden/uncertainty_pairs.jsonl";

#[cfg(test)]
mod tests {
    use super::*;
    use crate::uncertainty::{COVERAGE_TARGET, SHARPNESS_LIMIT, shares};

    /// Pairs the estimators are sharp at (u_num ≤ 10× the true error), of
    /// 129: 73 when the pairs were stored, 74 once a pre-asymptotic level
    /// 0 is left out, 75 once growing differences get Eça & Hoekstra's
    /// 3·Δ_M (a P_l family whose finer levels diverge: 2.0× its error
    /// where the whole family's least squares gave 25.5×). The estimators
    /// may not get wider than that without the docs' tables being made
    /// again.
    const SHARP_WHEN_STORED: usize = 75;

    #[test]
    fn the_stored_pairs_are_covered_at_the_target_and_no_wider_than_measured() {
        let rows = read(&format!("{}/{STORED}", crate::ROOT)).unwrap();
        assert_eq!(rows.len(), 129);
        let (covered, sharp) = shares(&rows);
        assert!(covered >= COVERAGE_TARGET, "covered {covered}");
        let n_sharp = (sharp * rows.len() as f64).round() as usize;
        assert!(n_sharp >= SHARP_WHEN_STORED, "sharp at {n_sharp} of 129");
    }

    /// The held-out pairs' coverage the estimator chosen on the stored
    /// pairs must reach for each kind of quantity: the stored pairs'
    /// target, since a bar's coverage is only known on pairs it was not
    /// chosen or tuned on.
    const HELD_OUT_COVERAGE: f64 = COVERAGE_TARGET;

    /// Held-out pairs (smooth, not smooth) covered by the estimator chosen
    /// on the stored pairs: 86 of 96 and 33 of 48 when the held-out set was
    /// stored (19 refused as diverging); 92 of 96 and 26 of 26 once
    /// growing differences get Eça & Hoekstra's 3·Δ_M and the 22
    /// `force_max` pairs are left out as not converged
    /// ([`TRUTH_NOT_CONVERGED`]; both rules were motivated by the held-out
    /// refusals, neither has a constant fitted to them). The estimators
    /// may not cover fewer without the docs' figures being made again.
    const HELD_OUT_COVERED_WHEN_STORED: [usize; 2] = [92, 26];

    /// The held-out pairs (smooth, not smooth), and the estimator chosen
    /// for each kind on the stored pairs.
    fn held_out_by_kind() -> Vec<(Vec<Row>, usize)> {
        use crate::uncertainty::heldout::HELD_OUT;
        let stored = read(&format!("{}/{STORED}", crate::ROOT)).unwrap();
        let held = read(&format!("{}/{HELD_OUT}", crate::ROOT)).unwrap();
        assert_eq!(held.len(), 144);
        KINDS
            .iter()
            .map(|&(_, smooth)| {
                let of: Vec<Row> = held
                    .iter()
                    .filter(|r| r.smooth == smooth)
                    .cloned()
                    .collect();
                (of, choose(&stored, smooth).0)
            })
            .collect()
    }

    #[test]
    fn the_estimator_is_chosen_on_the_stored_pairs_and_held_out_no_worse_than_measured() {
        for (k, (rows, e)) in held_out_by_kind().iter().enumerate() {
            let f = figures(rows, *e, KINDS[k].1);
            let covered = (f.covered * f.pairs as f64).round() as usize;
            assert!(
                covered >= HELD_OUT_COVERED_WHEN_STORED[k],
                "{}: {} covers {covered} of {}",
                KINDS[k].0,
                ESTIMATORS[*e],
                f.pairs
            );
            if KINDS[k].1 {
                assert!(f.median <= SHARPNESS_LIMIT, "smooth median {}", f.median);
            }
        }
    }

    #[test]
    fn the_held_out_pairs_are_covered_at_the_target() {
        for (k, (rows, e)) in held_out_by_kind().iter().enumerate() {
            let f = figures(rows, *e, KINDS[k].1);
            assert!(
                f.covered >= HELD_OUT_COVERAGE,
                "{}: {} covers {:.3}",
                KINDS[k].0,
                ESTIMATORS[*e],
                f.covered
            );
        }
    }

    /// The quantities left out as not converged are the ones the registry
    /// defines as growing as Δt falls, and no pair of the stored set is
    /// left out (its figures are unchanged by the rule).
    #[test]
    fn only_what_the_registry_says_grows_is_left_out() {
        for name in TRUTH_NOT_CONVERGED {
            let q = taut::quantity::by_name(name).expect("registered");
            assert!(q.definition.contains("grows as Δt falls"), "{name}");
        }
        let stored = read(&format!("{}/{STORED}", crate::ROOT)).unwrap();
        assert!(stored.iter().all(truth_converges));
        let held = read(&format!(
            "{}/{}",
            crate::ROOT,
            crate::uncertainty::heldout::HELD_OUT
        ))
        .unwrap();
        let out: Vec<&Row> = held.iter().filter(|r| !truth_converges(r)).collect();
        assert_eq!(out.len(), 22);
        assert!(out.iter().all(|r| r.quantity == "force_max"));
    }

    #[test]
    fn the_sharpest_estimator_at_the_target_is_chosen() {
        // a family converging at order 2 to 1.0 (finest 1.001), its true
        // error 1e-3 and 1e-3 + 1e-9: several estimators cover both, and
        // the choice is the sharpest of them
        let mut a = row(&[1.016, 1.004, 1.001], &[1.0041, 1.00102], 1.0);
        a.value = 1.001;
        a.u_num = 0.01;
        let mut b = a.clone();
        b.truth = 1.0 - 1e-9;
        let rows = [a, b];
        let f: Vec<Figures> = (0..ESTIMATORS.len())
            .map(|e| figures(&rows, e, true))
            .collect();
        let (e, met) = choose(&rows, true);
        assert!(met);
        assert!(f.iter().filter(|g| g.covered >= COVERAGE_TARGET).count() >= 2);
        assert!(f[e].covered >= COVERAGE_TARGET);
        for g in f.iter().filter(|g| g.covered >= COVERAGE_TARGET) {
            assert!(f[e].median <= g.median);
        }
    }

    fn row(diagonal: &[f64], space: &[f64], truth: f64) -> Row {
        Row {
            case: "c",
            quantity: "displacement_max",
            start: (25, 4e-4),
            finest: (200, 5e-5),
            value: f64::NAN,
            u_num: f64::NAN,
            u_scene: f64::NAN,
            truth,
            estimator: String::new(),
            error_estimated: f64::NAN,
            safety_factor: f64::NAN,
            order: f64::NAN,
            behaviour: "",
            truth_spread: Some(0.0),
            support_zone: 1.0,
            diagonal: diagonal.iter().map(|&v| Some(v)).collect(),
            space: space.iter().map(|&v| Some(v)).collect(),
            formal: (4.0, 2.0),
            smooth: true,
        }
    }

    #[test]
    fn a_replayed_pair_is_assessed_as_the_library_assesses_it() {
        // a monotone family near 1, and a scattered one
        let rows = [
            row(&[1.016, 1.004, 1.001], &[1.0041, 1.00102], 1.0),
            row(&[2.0, 2.3, 2.1, 2.2], &[2.25, 2.0, 2.15], 2.19),
        ];
        let path = std::env::temp_dir().join(format!("taut_replay_{}.jsonl", std::process::id()));
        let path = path.to_str().unwrap();
        write(path, &rows).unwrap();
        let back = read(path).unwrap();
        std::fs::remove_file(path).unwrap();
        assert_eq!(back.len(), 2);
        for (b, r) in back.iter().zip(&rows) {
            let a = assess(&Inputs {
                diagonal: &r.diagonal,
                space: &r.space,
                ratio: RATIO as f64,
                formal: r.formal,
                smooth: r.smooth,
            });
            assert_eq!(Some(b.u_num), a.u_num);
            assert_eq!(b.value, *r.diagonal.last().unwrap().as_ref().unwrap());
            assert_eq!(b.truth, r.truth);
            assert_eq!(b.estimator, a.estimator.name());
        }
        // the finest step 2.1 → 2.2 through the split run 2.15
        assert!((split_sum(&back[1]) - (0.05 + 0.05)).abs() < 1e-12);
    }
}
