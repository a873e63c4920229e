//! `compare.csv`, `compare.json` and `compare.svg` of `taut compare`.

use std::path::Path;

use serde::Serialize;

use super::plot::{
    Panel, abscissa_label, filtered_label, force_series, panels_plot, support_marks,
};
use super::table::{Column, Table};
use crate::error::{Error, Result};
use crate::study::compare::{CompareRow, Comparison, NotRun};

/// The columns of `compare.csv` that are the comparison's own (documented
/// in `docs/output.md`): who ran, how far each run is from the reference,
/// and the contact's extremes over every carrier. After them come the
/// registry's quantities of carrier 0 offered to the tables with one row
/// per run ([`crate::quantity::Offer::RUN_TABLES`]), then `wall_seconds`.
pub const COMPARE_COLUMNS: [&str; 10] = [
    "method",
    "discretization",
    "formulation",
    "loss_set_difference",
    "max_force_difference",
    "rms_force_difference",
    "max_penetration_all_carriers",
    "min_gap_all_carriers",
    "force_min_all_carriers",
    "max_gap_force_product_all_carriers",
];

/// `compare.csv` as a table ([`COMPARE_COLUMNS`], the quantities, then
/// `wall_seconds`): one row per run.
pub fn compare_rows(c: &Comparison) -> Table {
    let rows = &c.rows;
    let label =
        |f: fn(&CompareRow) -> &str| Column::Label(rows.iter().map(|r| f(r).to_string()).collect());
    let real = |f: fn(&CompareRow) -> f64| Column::Real(rows.iter().map(f).collect());
    let columns = [
        label(|r| &r.method),
        label(|r| &r.discretization),
        label(|r| &r.formulation),
        real(|r| r.loss_set_difference),
        real(|r| r.max_force_difference),
        real(|r| r.rms_force_difference),
        real(|r| r.max_penetration_all_carriers),
        real(|r| r.min_gap_all_carriers),
        real(|r| r.force_min_all_carriers),
        real(|r| r.max_gap_force_product_all_carriers),
    ];
    let mut t = Table::new();
    for (name, column) in COMPARE_COLUMNS.into_iter().zip(columns) {
        t.push(name, column);
    }
    t.push_quantities(rows.iter().map(|r| &r.quantities));
    t.push("wall_seconds", real(|r| r.wall_seconds));
    // with droppers: each one's slack fraction (every run has the same droppers)
    if let Some(first) = rows.first() {
        for (i, d) in first.droppers.iter().enumerate() {
            let col = rows
                .iter()
                .map(|r| r.droppers.get(i).map_or(f64::NAN, |x| x.slack_fraction))
                .collect();
            t.push(
                format!("dropper_{}_slack_fraction", d.name),
                Column::Real(col),
            );
        }
    }
    t
}

#[derive(Serialize)]
struct CompareJson<'a> {
    taut_version: &'static str,
    reference_method: &'a str,
    reference: &'static str,
    scene: Option<&'a crate::scene::Scene>,
    rows: &'a [CompareRow],
    skipped: &'a [NotRun],
    failed: &'a [NotRun],
    /// Where runs chattered, which did not and the parameters measured not
    /// to ([`chatter_note`]); absent when none chattered.
    #[serde(skip_serializing_if = "Option::is_none")]
    chatter_note: Option<String>,
}

/// Write the three files into `dir`.
pub fn write_compare(dir: &Path, c: &Comparison) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    compare_rows(c).write_csv(&dir.join("compare.csv"))?;

    let json = dir.join("compare.json");
    let doc = CompareJson {
        taut_version: env!("CARGO_PKG_VERSION"),
        reference_method: &c.reference_method,
        reference: c.reference.name(),
        scene: c.runs.first().map(|r| &r.scene.scene),
        rows: &c.rows,
        skipped: &c.skipped,
        failed: &c.failed,
        chatter_note: chatter_note(c),
    };
    super::write_json(&json, &doc)?;

    let Some(first) = c.runs.first() else {
        return Ok(());
    };
    let x_desc = abscissa_label(&first.scene);
    let several_methods = c.runs.iter().any(|r| r.method != first.method);
    let space = c.several_discretizations;
    // small multiples: a panel per run on common axes, its raw force light
    // and its filtered force bold, so that runs that agree to a pixel can
    // still be told apart, each titled with its difference to the reference
    let panels: Vec<Panel> = c
        .runs
        .iter()
        .zip(&c.rows)
        .map(|(r, row)| {
            let label = if several_methods || space {
                r.label(space)
            } else {
                r.formulation.name().to_string()
            };
            Panel {
                title: format!(
                    "{label}: P_l = {:.4} ({:.4} in span), RMS Δλ vs reference {} N",
                    row.quantities.real(&crate::quantity::LOSS_FRACTION),
                    row.quantities.real(&crate::quantity::LOSS_FRACTION_SPAN),
                    short(row.rms_force_difference)
                ),
                series: force_series(&r.scene, &r.output, "λ"),
                marks: support_marks(&r.scene),
            }
        })
        .collect();
    let title = format!(
        "contact force by {}: {}, dt = {} s; reference {}/{}",
        match (several_methods, space) {
            (true, true) => "method, discretization and formulation",
            (false, true) => "discretization and formulation",
            (true, false) => "method and formulation",
            (false, false) => "formulation",
        },
        if space {
            "discretizations as labelled".to_string()
        } else {
            format!("{} elements", first.scene.elements)
        },
        first.scene.dt,
        c.reference_method,
        c.reference.name()
    );
    panels_plot(
        &dir.join("compare.svg"),
        &title,
        (x_desc, "contact force λ (N)"),
        &panels,
        super::plot::LOSS_SHADING,
        &filtered_label(first.output.history.band_hz()),
    )
}

/// A difference in a panel's title: 0, three decimals, or two digits with
/// an exponent below 0.01 (round-off against the reference).
fn short(v: f64) -> String {
    match v.abs() {
        0.0 => "0".into(),
        a if a >= 0.01 => format!("{v:.3}"),
        _ => format!("{v:.1e}"),
    }
}

/// The parameters measured not to chatter on the reference case at
/// Δt = 1e-4 s (docs/methods.md "The undamped constraint mode: ringing and
/// chatter"), the advice a comparison that finds chatter gives.
pub const NO_CHATTER: &str = "measured without chatter on the reference case at Δt = 1e-4 s (docs/methods.md): generalized_alpha with integrator.rho_inf = 1 or 0.5, hht with integrator.alpha ≥ 0.2, wbz with integrator.rho_inf ≤ 0.5, bathe; or contact.formulation = \"impact\", which does not impose the gap and avoids the mode";

/// Where a comparison finds chatter, what to use instead: the runs that
/// chattered, those of this comparison that did not, and [`NO_CHATTER`];
/// None when no run chattered.
pub fn chatter_note(c: &Comparison) -> Option<String> {
    let space = c.several_discretizations;
    let runs: Vec<(String, &[String])> = c
        .rows
        .iter()
        .map(|r| {
            let who = if space {
                format!("{}/{}/{}", r.method, r.discretization, r.formulation)
            } else {
                format!("{}/{}", r.method, r.formulation)
            };
            (who, r.warnings.as_slice())
        })
        .collect();
    chatter_note_of(&runs)
}

/// [`chatter_note`] of runs given as (label, warnings).
fn chatter_note_of(runs: &[(String, &[String])]) -> Option<String> {
    let chatters = |w: &[String]| w.iter().any(|w| w.contains(crate::run::CHATTER));
    let (bad, good): (Vec<_>, Vec<_>) = runs.iter().partition(|(_, w)| chatters(w));
    if bad.is_empty() {
        return None;
    }
    let list = |v: &[&(String, &[String])]| {
        v.iter()
            .map(|r| r.0.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let here = if good.is_empty() {
        String::new()
    } else {
        format!("; here without chatter: {}", list(&good))
    };
    Some(format!(
        "chatter in {} (its contact statistics are no answer){here}; {NO_CHATTER}",
        list(&bad)
    ))
}

/// The terminal table.
pub fn compare_table(c: &Comparison) -> String {
    let space = c.several_discretizations;
    let who = |m: &str, d: &str| {
        if space {
            format!("{m}/{d}")
        } else {
            m.to_string()
        }
    };
    let w = if space { 34 } else { 19 };
    let mut s = format!(
        "{:<w$} {:<16} {:>9} {:>9} {:>10} {:>11} {:>11} {:>11} {:>10} {:>9} {:>8}\n",
        if space {
            "method/discretization"
        } else {
            "method"
        },
        "formulation",
        "P_l",
        "in span",
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
            "{:<w$} {:<16} {:>9.5} {:>9.5} {:>10.5} {:>11.4e} {:>11.4e} {:>11.3e} {:>10.2} {:>9} {:>8.3}\n",
            who(&r.method, &r.discretization),
            r.formulation,
            r.quantities.real(&crate::quantity::LOSS_FRACTION),
            r.quantities.real(&crate::quantity::LOSS_FRACTION_SPAN),
            r.loss_set_difference,
            r.max_force_difference,
            r.rms_force_difference,
            r.max_penetration_all_carriers,
            r.quantities.real(&crate::quantity::FORCE_MAX),
            r.quantities.real(&crate::quantity::CONTACT_SWITCHES),
            r.wall_seconds
        ));
    }
    if c.rows.iter().any(|r| !r.droppers.is_empty()) {
        s.push_str("dropper slack fractions (intervals; first slack at t s):\n");
        for r in &c.rows {
            let list: Vec<String> = r
                .droppers
                .iter()
                .map(|d| {
                    let first = d
                        .first_slack_time
                        .map_or_else(|| "-".to_string(), |t| format!("{t:.4}"));
                    format!(
                        "{} {:.4} ({}; {first})",
                        d.name, d.slack_fraction, d.slack_interval_count
                    )
                })
                .collect();
            s.push_str(&format!(
                "  {:<w$} {:<16} {}\n",
                who(&r.method, &r.discretization),
                r.formulation,
                list.join(", ")
            ));
        }
    }
    s.push_str(&format!(
        "(differences against {}/{})\n",
        who(&c.reference_method, &c.reference_discretization),
        c.reference.name()
    ));
    for r in &c.rows {
        for w in &r.warnings {
            s.push_str(&format!(
                "  WARNING  {}/{}: {w}\n",
                who(&r.method, &r.discretization),
                r.formulation
            ));
        }
    }
    if let Some(note) = chatter_note(c) {
        s.push_str(&format!("  note     {note}\n"));
    }
    for n in &c.skipped {
        s.push_str(&format!(
            "  skipped  {}/{}: {}\n",
            who(&n.method, &n.discretization),
            n.formulation,
            n.reason
        ));
    }
    for n in &c.failed {
        s.push_str(&format!(
            "  FAILED   {}/{}: {}\n",
            who(&n.method, &n.discretization),
            n.formulation,
            n.reason
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A comparison with chatter names the runs that chattered, those that
    /// did not, and the parameters measured not to; without chatter, none.
    #[test]
    fn the_chatter_note_names_the_parameters_that_do_not_chatter() {
        let chatter = vec![format!(
            "carrier 0: contact switched 1419 times in 2000 steps: {}, a numerical oscillation",
            crate::run::CHATTER
        )];
        let none: Vec<String> = Vec::new();
        let runs = [
            ("newmark/lagrange".to_string(), chatter.as_slice()),
            ("generalized_alpha/lagrange".to_string(), none.as_slice()),
            ("hht/lagrange".to_string(), chatter.as_slice()),
        ];
        let note = chatter_note_of(&runs).expect("a note");
        assert!(
            note.contains("chatter in newmark/lagrange, hht/lagrange"),
            "{note}"
        );
        assert!(
            note.contains("here without chatter: generalized_alpha/lagrange"),
            "{note}"
        );
        for p in [
            "rho_inf = 1 or 0.5",
            "alpha ≥ 0.2",
            "rho_inf ≤ 0.5",
            "bathe",
            "\"impact\"",
        ] {
            assert!(note.contains(p), "{p} missing: {note}");
        }
        assert_eq!(chatter_note_of(&runs[1..2]), None);
    }
}
