//! What `report.html` shows of each file a command writes, and how a table
//! reads on a page: [`FILES`] names every output of every command
//! ([`Outputs::files`]) with the way the page shows it (a table, a plot, a
//! summary, or named as not shown with the reason), [`grid_html`] lays a
//! table out without horizontal scrolling (a wide table split into parts
//! that repeat its identifying columns, a short wide one transposed) and
//! classes each verdict cell ([`verdict_class`]), and [`Tally`] counts the
//! verdicts for the page's first section.

use std::fmt::Write as _;

use super::html::{esc, short};
use super::outputs::{Outputs, Show};

/// Every file a command writes, by the command's kind, in page order.
pub(crate) const FILES: &[(&str, Outputs, Show)] = &[
    ("summary.json", Outputs::Run, Show::Summary),
    (
        "standard.csv",
        Outputs::Run,
        Show::Table("the standards' statistics over the analysis section", &[]),
    ),
    (
        "accuracy.csv",
        Outputs::Run,
        Show::Table("accuracy-targeted run: pilots and the chosen run", &[]),
    ),
    (
        "spans.csv",
        Outputs::Run,
        Show::Table("contact force per span", &[]),
    ),
    (
        "supports.csv",
        Outputs::Run,
        Show::Table("uplift at the supports", &[]),
    ),
    (
        "static_heights.csv",
        Outputs::Run,
        Show::Table(
            "form-finding: each dropper's design and static contact-wire height",
            &[],
        ),
    ),
    (
        "droppers_static.csv",
        Outputs::Run,
        Show::Table(
            "form-finding: each dropper's found length and static force",
            &[],
        ),
    ),
    (
        "force.svg",
        Outputs::Run,
        Show::Plot("contact force (light), filtered force (bold), contact loss"),
    ),
    (
        "line.svg",
        Outputs::Run,
        Show::Plot("the line: both wires, droppers and the uplift envelope"),
    ),
    (
        "history.csv",
        Outputs::Run,
        Show::Named("the time series, a row per step: drawn in force.svg"),
    ),
    (
        "standard.json",
        Outputs::Run,
        Show::Named("the statistics of standard.csv, in JSON"),
    ),
    (
        "envelope.csv",
        Outputs::Run,
        Show::Named("the uplift envelope, a row per mesh node: drawn in line.svg"),
    ),
    (
        "snapshots.csv",
        Outputs::Run,
        Show::Named(
            "the wire's displacement at the requested times, a row per (time, point): data for a plot",
        ),
    ),
    (
        "field.csv",
        Outputs::Run,
        Show::Named("the wire's displacement field, a row per (time, point): data for a plot"),
    ),
    ("compare.json", Outputs::Compare, Show::Json),
    (
        "compare.csv",
        Outputs::Compare,
        Show::Table(
            "formulations, methods and discretizations compared (verdict: chatter, unresolved losses or other warnings, from compare.json)",
            &["verdict"],
        ),
    ),
    (
        "compare.svg",
        Outputs::Compare,
        Show::Plot("contact force of each compared run"),
    ),
    ("converge.json", Outputs::Converge, Show::Json),
    (
        "converge.csv",
        Outputs::Converge,
        Show::Table("convergence: errors, orders and regimes", &["regime"]),
    ),
    (
        "converge.svg",
        Outputs::Converge,
        Show::Plot("errors against refinement"),
    ),
    (
        "precision.csv",
        Outputs::Precision,
        Show::Table("work–precision", &["pareto"]),
    ),
    (
        "precision.svg",
        Outputs::Precision,
        Show::Plot("error against cost"),
    ),
    ("uncertainty.json", Outputs::Uncertainty, Show::Json),
    (
        "uncertainty.csv",
        Outputs::Uncertainty,
        Show::Table(
            "numerical uncertainty u_num of each quantity",
            &["behaviour", "asymptotic"],
        ),
    ),
    (
        "uncertainty.svg",
        Outputs::Uncertainty,
        Show::Plot("each quantity over the family, with its extrapolation"),
    ),
    (
        "modes.csv",
        Outputs::Modes,
        Show::Table("natural frequencies (the string's beside them)", &[]),
    ),
    (
        "mode_shapes.csv",
        Outputs::Modes,
        Show::Named("the mode shapes, a row per point: data for a plot"),
    ),
    (
        "verify.csv",
        Outputs::Verify,
        Show::Table(
            "verification: observed against expected orders",
            &["status"],
        ),
    ),
    (
        "verify.json",
        Outputs::Verify,
        Show::Named("the rows of verify.csv, in JSON"),
    ),
    (
        "verify.md",
        Outputs::Verify,
        Show::Named("the rows of verify.csv, as Markdown"),
    ),
    ("gate.json", Outputs::Gate, Show::Json),
    (
        "junit.xml",
        Outputs::Gate,
        Show::Named("the checks of gate.json, as JUnit XML for CI"),
    ),
    (
        "sweep.csv",
        Outputs::Sweep,
        Show::Table(
            "the sweep's points",
            &["loss_fraction_span_converged", "tolerance_met", "error"],
        ),
    ),
    (
        "merge.csv",
        Outputs::Sweep,
        Show::Table("the shard folders this merge joined", &[]),
    ),
    (
        "timing.csv",
        Outputs::Sweep,
        Show::Table("wall time of each point", &[]),
    ),
    (
        "sweep.svg",
        Outputs::Sweep,
        Show::Plot("the sweep's results against its axis"),
    ),
    (
        "force_map.svg",
        Outputs::Sweep,
        Show::Plot("mean contact force over the sweep"),
    ),
    (
        "loss_map.svg",
        Outputs::Sweep,
        Show::Plot("where contact is lost over the sweep"),
    ),
    (
        "refinement.svg",
        Outputs::Sweep,
        Show::Plot("the in-span P_l under refinement"),
    ),
    (
        "loss_fraction_map.svg",
        Outputs::Sweep,
        Show::Plot("P_l over the sweep's grid"),
    ),
    (
        "loss_fraction_span_map.svg",
        Outputs::Sweep,
        Show::Plot("in-span P_l over the sweep's grid"),
    ),
    (
        "refinement_map.svg",
        Outputs::Sweep,
        Show::Plot("where the loss map is converged"),
    ),
    (
        "tolerance.svg",
        Outputs::Sweep,
        Show::Plot("accuracy-targeted sweep: u_num of each point against the tolerance"),
    ),
    (
        "u_num_map.svg",
        Outputs::Sweep,
        Show::Plot("accuracy-targeted sweep: u_num over the grid"),
    ),
    (
        "sweep_force.csv",
        Outputs::Sweep,
        Show::Named("the grid of mean contact force along the span, drawn in force_map.svg"),
    ),
    (
        "sweep_loss.csv",
        Outputs::Sweep,
        Show::Named("the grid of contact loss along the span, drawn in loss_map.svg"),
    ),
];

/// Every file of [`FILES`] and of the studies that declare theirs
/// (`declared`: [`Outputs::Declared`]), in page order.
pub(crate) fn files(declared: &[Outputs]) -> Vec<(&'static str, Outputs, Show)> {
    let mut all = FILES.to_vec();
    for &kind in declared {
        if let Outputs::Declared(d) = kind {
            all.extend(d.files.iter().map(|&(f, show)| (f, kind, show)));
        }
    }
    all
}

/// The command that writes a kind of folder, as the page names it.
pub(crate) fn command(kind: Outputs, present: &dyn Fn(&str) -> bool) -> String {
    let s = match kind {
        Outputs::Run => {
            let mut s = String::from("taut run");
            if present("accuracy.csv") {
                s.push_str(" --tolerance");
            }
            if present("static_heights.csv") || present("droppers_static.csv") {
                s.push_str(" (line, form-finding)");
            } else if present("spans.csv") || present("line.svg") {
                s.push_str(" (line)");
            }
            return s;
        }
        Outputs::Compare => "taut compare",
        Outputs::Converge => "taut converge",
        Outputs::Precision => "taut precision",
        Outputs::Gate => "taut gate",
        Outputs::Modes => "taut modes",
        Outputs::Uncertainty => "taut uncertainty",
        Outputs::Verify => "taut verify",
        Outputs::Declared(d) => d.command,
        Outputs::Sweep => {
            // a merge's tables and maps are a sweep's; its merge.csv is not
            let tolerance = present("tolerance.svg") || present("u_num_map.svg");
            return match (present("merge.csv"), tolerance) {
                (true, true) => "taut merge (of a sweep --tolerance)",
                (true, false) => "taut merge",
                (false, true) => "taut sweep --tolerance",
                (false, false) => "taut sweep",
            }
            .into();
        }
    };
    s.into()
}

/// Files in a folder that are not outputs but a command's working state,
/// or the report itself: not named on the page.
pub(crate) const QUIET: [&str; 3] = ["report.html", super::INCOMPLETE_FILE, "sweep.lock"];

/// Most columns of one table part; a wider table is split into parts that
/// repeat its identifying columns (or transposed when short), so that no
/// table is wider than a 1400 px page or a printed one at 0.75 em.
pub(crate) const MAX_COLUMNS: usize = 12;

/// Most identifying (leading text) columns repeated in each part of a
/// split table.
const MAX_KEYS: usize = 4;

/// A table of at most this many rows and more than [`MAX_COLUMNS`]
/// columns is shown transposed (a row per column), not split.
const TRANSPOSE_ROWS: usize = 3;

/// A verdict's class: `good`, `bad` or `warn` (also for a verdict the
/// page does not know: a verdict is never shown uncoloured).
pub(crate) fn verdict_class(column: &str, v: &str) -> &'static str {
    let l = v.trim().to_ascii_lowercase();
    if column == "error" {
        return if l.is_empty() { "good" } else { "bad" };
    }
    match l.as_str() {
        "pass" | "yes" | "true" | "asymptotic" | "met" | "clean" | "converged" | "monotone"
        | "exact" | "passed" => "good",
        // not yet asymptotic is a caution, and a point off the Pareto
        // front a fact, not a failure
        "false" if column == "asymptotic" || column == "pareto" => "warn",
        "fail" | "failed" | "no" | "false" | "diverges" | "diverging" | "not converging"
        | "not met" | "chatter" | "skipped" => "bad",
        _ if l.starts_with("diverged") || l.starts_with("failed") => "bad",
        _ => "warn",
    }
}

/// Verdicts counted, in order of first appearance, with their class.
#[derive(Debug, Default, Clone)]
pub(crate) struct Tally(pub Vec<(String, &'static str, usize)>);

impl Tally {
    /// Count one verdict (a long one, such as `diverged: …`, by its head).
    pub fn add(&mut self, v: &str, class: &'static str) {
        let key = match v.split_once(':') {
            Some((head, _)) => head.trim().to_string(),
            None => v.trim().to_string(),
        };
        let key = if key.is_empty() { "—".into() } else { key };
        match self.0.iter_mut().find(|(k, c, _)| *k == key && *c == class) {
            Some((_, _, n)) => *n += 1,
            None => self.0.push((key, class, 1)),
        }
    }

    /// Add another tally's counts.
    pub fn extend(&mut self, other: &Tally) {
        for (k, c, n) in &other.0 {
            for _ in 0..*n {
                self.add(k, c);
            }
        }
    }

    /// The counts as coloured chips, `·`-separated; `—` when none.
    pub fn html(&self) -> String {
        if self.0.is_empty() {
            return "—".into();
        }
        self.0
            .iter()
            .map(|(k, c, n)| format!("<span class=\"{c}\">{} {n}</span>", esc(k)))
            .collect::<Vec<_>>()
            .join(" · ")
    }
}

/// A table read from a CSV (or made from JSON): column names, rows of
/// cells as text, and per row the notes shown under it (warnings).
#[derive(Debug, Default, Clone)]
pub(crate) struct Grid {
    pub names: Vec<String>,
    pub rows: Vec<Vec<String>>,
    pub notes: Vec<Vec<String>>,
}

impl Grid {
    /// A CSV's text as a grid (a quoted cell may hold commas).
    pub fn from_csv(text: &str) -> Grid {
        let mut lines = text.lines();
        let names = lines.next().map(split_csv).unwrap_or_default();
        let rows: Vec<Vec<String>> = lines.map(split_csv).collect();
        let notes = vec![Vec::new(); rows.len()];
        Grid { names, rows, notes }
    }

    /// The index of column `name`.
    pub fn col(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }

    /// Insert a column at `at`, a cell per row.
    pub fn insert(&mut self, at: usize, name: &str, cells: Vec<String>) {
        let at = at.min(self.names.len());
        self.names.insert(at, name.to_string());
        for (r, c) in self.rows.iter_mut().zip(cells) {
            let i = at.min(r.len());
            r.insert(i, c);
        }
    }
}

/// One CSV line's cells: commas separate, a quoted cell may hold commas
/// (taut writes no quote inside a quoted cell).
pub(crate) fn split_csv(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cell = String::new();
    let mut quoted = false;
    for ch in line.chars() {
        match ch {
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(std::mem::take(&mut cell)),
            c => cell.push(c),
        }
    }
    out.push(cell);
    out
}

/// Whether a cell reads as a number.
fn numeric(c: &str) -> bool {
    !c.is_empty() && c.parse::<f64>().is_ok()
}

/// A cell as shown: numbers to 6 significant digits, text escaped.
fn cell_text(c: &str) -> String {
    match c.parse::<f64>() {
        Ok(x) if !c.is_empty() => short(x),
        _ => esc(c),
    }
}

/// A grid as HTML tables (at most `max_rows` rows): the verdict columns
/// (`verdicts`, those present) moved beside the identifying ones and their
/// cells classed, their values counted into `tally`; each row's notes in a
/// row of their own under it. Wider than [`MAX_COLUMNS`]: split into parts
/// that repeat the identifying columns, or transposed when it has at most
/// [`TRANSPOSE_ROWS`] rows.
pub(crate) fn grid_html(g: &Grid, verdicts: &[&str], max_rows: usize, tally: &mut Tally) -> String {
    let mut h = String::new();
    if g.names.is_empty() || (g.names.len() == 1 && g.names[0].is_empty()) {
        return "<p class=\"note\">empty</p>\n".into();
    }
    let width = g.names.len();
    let cell = |r: &[String], i: usize| r.get(i).cloned().unwrap_or_default();
    let vcols: Vec<usize> = verdicts.iter().filter_map(|v| g.col(v)).collect();
    // the verdicts, counted and listed above the table
    let mut own = Tally::default();
    for &vi in &vcols {
        let column = &g.names[vi];
        for r in &g.rows {
            let v = cell(r, vi);
            // no verdict (a ladder's first level has no regime)
            if v.is_empty() {
                continue;
            }
            let class = verdict_class(column, &v);
            // a yes/no verdict is counted under its column's name
            let l = v.to_ascii_lowercase();
            if matches!(l.as_str(), "true" | "false" | "yes" | "no") {
                own.add(&format!("{column} {v}"), class);
            } else {
                own.add(&v, class);
            }
        }
    }
    if !own.0.is_empty() {
        let names: Vec<&str> = vcols.iter().map(|&i| g.names[i].as_str()).collect();
        let _ = writeln!(h, "<p>{}: {}</p>", esc(&names.join(", ")), own.html());
    }
    tally.extend(&own);
    let td = |h: &mut String, r: &[String], i: usize| {
        let c = cell(r, i);
        let mut classes: Vec<&str> = Vec::new();
        if !numeric(&c) {
            classes.push("text");
        }
        if vcols.contains(&i) && !c.is_empty() {
            classes.push(verdict_class(&g.names[i], &c));
        }
        if classes.is_empty() {
            let _ = write!(h, "<td>{}</td>", cell_text(&c));
        } else {
            let _ = write!(
                h,
                "<td class=\"{}\">{}</td>",
                classes.join(" "),
                cell_text(&c)
            );
        }
    };
    let shown = &g.rows[..g.rows.len().min(max_rows)];
    // identifying columns: the leading text columns of the first row; the
    // verdicts next, then the rest
    let first = g.rows.first();
    let mut keys = 0;
    while keys < width.min(MAX_KEYS)
        && !vcols.contains(&keys)
        && first.is_some_and(|r| !numeric(&cell(r, keys)))
    {
        keys += 1;
    }
    let keys = keys.max(1);
    let mut order: Vec<usize> = (0..keys).collect();
    order.extend(vcols.iter().copied().filter(|&i| i >= keys));
    order.extend((keys..width).filter(|i| !vcols.contains(i)));
    if width > MAX_COLUMNS && g.rows.len() <= TRANSPOSE_ROWS {
        // transposed: a row per column
        h.push_str("<table class=\"transposed\"><tbody>\n");
        for &i in &order {
            let _ = write!(h, "<tr><th>{}</th>", head(&g.names[i]));
            for r in shown {
                td(&mut h, r, i);
            }
            h.push_str("</tr>\n");
        }
        h.push_str("</tbody></table>\n");
        // each row's notes under the table, named by its identifying cells
        for (r, ns) in g.rows.iter().zip(&g.notes) {
            let who: Vec<String> = (0..keys).map(|i| cell(r, i)).collect();
            for n in ns {
                let _ = writeln!(
                    h,
                    "<p class=\"warning\">WARNING {}: {}</p>",
                    esc(&who.join("/")),
                    esc(n)
                );
            }
        }
    } else {
        let per = MAX_COLUMNS - keys;
        let rest = &order[keys..];
        let parts: Vec<&[usize]> = if rest.is_empty() {
            vec![&[]]
        } else {
            rest.chunks(per).collect()
        };
        for (p, part) in parts.iter().enumerate() {
            let cols: Vec<usize> = (0..keys).chain(part.iter().copied()).collect();
            if parts.len() > 1 {
                let _ = writeln!(
                    h,
                    "<p class=\"note\">part {} of {} (columns {}–{} of {}; the first {} repeated)</p>",
                    p + 1,
                    parts.len(),
                    esc(&g.names[part[0]]),
                    esc(&g.names[*part.last().unwrap_or(&part[0])]),
                    width,
                    keys
                );
            }
            h.push_str("<table><thead><tr>");
            for &i in &cols {
                let _ = write!(h, "<th>{}</th>", head(&g.names[i]));
            }
            h.push_str("</tr></thead><tbody>\n");
            for (k, r) in shown.iter().enumerate() {
                h.push_str("<tr>");
                for &i in &cols {
                    td(&mut h, r, i);
                }
                h.push_str("</tr>\n");
                // a row's warnings under it, in the first part
                if p == 0 {
                    for n in g.notes.get(k).into_iter().flatten() {
                        let _ = writeln!(
                            h,
                            "<tr class=\"row-note\"><td colspan=\"{}\">WARNING {}</td></tr>",
                            cols.len(),
                            esc(n)
                        );
                    }
                }
            }
            h.push_str("</tbody></table>\n");
        }
    }
    if g.rows.len() > max_rows {
        let _ = writeln!(
            h,
            "<p class=\"note\">{} of {} rows shown; the CSV beside the report has them all.</p>",
            max_rows,
            g.rows.len()
        );
    }
    h
}

/// A column's name as a header: escaped, free to wrap after each `_`
/// (`max_gap_force_product_all_carriers` wraps at its words, not inside
/// them).
fn head(name: &str) -> String {
    esc(name).replace('_', "_<wbr>")
}

/// A JSON array of objects as a grid of the given keys.
pub(crate) fn json_grid(rows: &[serde_json::Value], keys: &[&str]) -> Grid {
    let text = |v: &serde_json::Value| match v {
        serde_json::Value::String(s) => s.clone(),
        serde_json::Value::Null => String::new(),
        v => v.to_string(),
    };
    Grid {
        names: keys.iter().map(|k| k.to_string()).collect(),
        rows: rows
            .iter()
            .map(|r| keys.iter().map(|k| text(&r[*k])).collect())
            .collect(),
        notes: vec![Vec::new(); rows.len()],
    }
}

/// A compare run's verdict from its warnings: `chatter` (the contact
/// switched step to step: its statistics are no converged answer),
/// `unresolved` (losses shorter than the run resolves), `warning` (any
/// other), `clean` (none).
pub(crate) fn run_verdict(warnings: &[String]) -> &'static str {
    if warnings.iter().any(|w| w.contains("chatter")) {
        "chatter"
    } else if warnings.iter().any(|w| w.contains("not resolve")) {
        "unresolved"
    } else if warnings.is_empty() {
        "clean"
    } else {
        "warning"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_merged_folder_is_told_from_a_swept_one() {
        let with = |files: &'static [&'static str]| move |f: &str| files.contains(&f);
        let name = |files: &'static [&'static str]| command(Outputs::Sweep, &with(files));
        assert_eq!(name(&["sweep.csv"]), "taut sweep");
        assert_eq!(
            name(&["sweep.csv", "tolerance.svg"]),
            "taut sweep --tolerance"
        );
        assert_eq!(name(&["sweep.csv", "merge.csv"]), "taut merge");
        assert_eq!(
            name(&["sweep.csv", "merge.csv", "u_num_map.svg"]),
            "taut merge (of a sweep --tolerance)"
        );
    }

    #[test]
    fn csv_cells_keep_quoted_commas() {
        assert_eq!(split_csv("a,\"b, c\",,1"), ["a", "b, c", "", "1"]);
    }

    #[test]
    fn every_output_of_every_command_has_its_place() {
        use Outputs::*;
        for kind in [
            Run,
            Compare,
            Converge,
            Precision,
            Gate,
            Sweep,
            Modes,
            Uncertainty,
            Verify,
        ] {
            for f in kind.files() {
                assert!(
                    FILES.iter().any(|(n, k, _)| *n == f && *k == kind),
                    "{f} of {kind:?} has no place in the report"
                );
            }
        }
    }

    #[test]
    fn a_study_that_declares_its_files_has_them_placed() {
        // a study of one's own names its files and their place itself
        // (Outputs::Declared): no line of FILES or Outputs for it
        static MINE: super::super::outputs::Declared = super::super::outputs::Declared {
            command: "taut mine",
            files: &[("mine.csv", Show::Table("mine", &[]))],
        };
        let kind = Outputs::Declared(&MINE);
        assert_eq!(kind.files(), ["mine.csv"]);
        assert_eq!(command(kind, &|_| true), "taut mine");
        let all = files(&[kind, Outputs::Compare]);
        assert_eq!(all.len(), FILES.len() + 1);
        assert!(all.iter().any(|(n, k, _)| *n == "mine.csv" && *k == kind));
        assert!(!FILES.iter().any(|(n, _, _)| *n == "mine.csv"));
    }

    #[test]
    fn verdicts_are_classed() {
        for (c, v, want) in [
            ("status", "pass", "good"),
            ("status", "fail", "bad"),
            ("status", "known", "warn"),
            ("status", "cannot", "warn"),
            ("status", "diverges", "bad"),
            ("regime", "not converging", "bad"),
            ("regime", "diverged: error 3 as large", "bad"),
            ("regime", "pre-asymptotic", "warn"),
            ("tolerance_met", "yes", "good"),
            ("tolerance_met", "no", "bad"),
            ("asymptotic", "false", "warn"),
            ("error", "", "good"),
            ("error", "diverged", "bad"),
            ("verdict", "chatter", "bad"),
        ] {
            assert_eq!(verdict_class(c, v), want, "{c} = {v}");
        }
    }

    #[test]
    fn a_wide_table_is_split_and_a_short_one_transposed() {
        let names: Vec<String> = (0..30).map(|i| format!("c{i}")).collect();
        let row = |k: usize| -> Vec<String> {
            std::iter::once(format!("run{k}"))
                .chain((1..30).map(|i| (i * k).to_string()))
                .collect()
        };
        let mut g = Grid {
            names: names.clone(),
            rows: (0..5).map(row).collect(),
            notes: vec![Vec::new(); 5],
        };
        let h = grid_html(&g, &[], 200, &mut Tally::default());
        assert_eq!(h.matches("<table>").count(), 3, "{h}");
        assert!(h.contains("part 1 of 3"), "{h}");
        // every part repeats the identifying column
        assert_eq!(h.matches("<th>c0</th>").count(), 3);
        g.rows.truncate(1);
        g.notes.truncate(1);
        let h = grid_html(&g, &[], 200, &mut Tally::default());
        assert!(h.contains("class=\"transposed\""), "{h}");
        assert_eq!(h.matches("<tr>").count(), 30);
    }
}
