//! Stability at the extremes: runs the reference case (and other bundled
//! scenes where more apt) at extreme parameters and resolutions, for each
//! contact formulation where it makes sense, and writes the report
//! `out/xtask/stability.md` (every row, its command and verdict);
//! `docs/stability.md` explains it and quotes its summary.
//!
//! ```text
//! cargo xtask stability
//! ```
//!
//! Every row is one `taut run` (its command is written next to it). Its
//! outcome is one of: ran, ran with warnings, stopped with a diagnosis, or
//! rejected as invalid input. Where a reference exists (a better-resolved
//! Lagrange run of the same physics, the bundled reference case, or the
//! analytic solution of a moving-force scene), the row is scored for accuracy;
//! a run that finishes without warning yet is clearly off its reference is
//! listed under "Findings" as silently wrong. Runs are sequential and take
//! a little over a minute on an AMD EPYC, 2 vCPUs.
//!
//! One job a file: [`score`] (a case, its run and its score), [`cases`]
//! (the cases), [`page`] (findings and tables); this file runs them and
//! writes the page.

mod cases;
mod page;
mod score;

use cases::*;
use page::*;
use score::*;
/// The report: what `cargo xtask stability` runs (its
/// command-line arguments, if any, are read here).
pub fn main() {
    let started = Instant::now();
    let sections = sections();
    let mut cache: HashMap<String, Outcome> = HashMap::new();
    let total: usize = sections.iter().map(|s| s.cases.len()).sum();
    let mut results: Vec<Vec<Row>> = Vec::new();
    let mut done = 0;
    for s in &sections {
        let mut rows = Vec::new();
        for case in &s.cases {
            let t = Instant::now();
            let row = score(case, &mut cache);
            done += 1;
            eprintln!(
                "[{done:3}/{total}] {:6.2} s  {}, {}: {}",
                t.elapsed().as_secs_f64(),
                case.label,
                case.form,
                row.verdict.text()
            );
            rows.push(row);
        }
        results.push(rows);
    }
    let elapsed = started.elapsed().as_secs_f64();
    let page = render(&sections, &results, cache.len());
    let dir = format!("{}/out/xtask", crate::ROOT);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{dir}: {e}"));
    let path = format!("{dir}/stability.md");
    std::fs::write(&path, page).unwrap_or_else(|e| panic!("{path}: {e}"));
    eprintln!(
        "wrote {path}: {total} rows and {} reference runs in {elapsed:.1} s",
        cache.len()
    );
}
