//! The report: the findings and the tables of `out/xtask/stability.md`
//! (explained in `docs/stability.md`).

use super::{cases::*, score::*};
// ---------------------------------------------------------------------------
// The page
// ---------------------------------------------------------------------------

pub(super) fn outcome_cell(o: &Outcome) -> String {
    match o {
        Outcome::Rejected(_) => "rejected as invalid input".into(),
        Outcome::Stopped(_) => "stopped with a diagnosis".into(),
        Outcome::Ran(f) if f.warnings.is_empty() => "ran".into(),
        Outcome::Ran(f) => format!(
            "ran with {} warning{}",
            f.warnings.len(),
            if f.warnings.len() == 1 { "" } else { "s" }
        ),
    }
}

/// Rows of one case in the findings: section, label, (row index, case, row).
pub(super) type Group<'a> = (usize, &'a str, Vec<(usize, &'a Case, &'a Row)>);

/// List the rows with `verdict`, grouped by case (formulations together),
/// numbered from `first`; returns how many groups were listed.
pub(super) fn findings(
    w: &mut String,
    sections: &[Section],
    results: &[Vec<Row>],
    verdict: Verdict,
    first: usize,
) -> usize {
    let mut groups: Vec<Group> = Vec::new();
    for (i, (s, rows)) in sections.iter().zip(results).enumerate() {
        for (j, (case, row)) in s.cases.iter().zip(rows).enumerate() {
            if row.verdict != verdict {
                continue;
            }
            match groups
                .iter_mut()
                .find(|(gi, label, _)| *gi == i && *label == case.label)
            {
                Some(g) => g.2.push((j, case, row)),
                None => groups.push((i, case.label.as_str(), vec![(j, case, row)])),
            }
        }
    }
    for (n, (i, label, members)) in groups.iter().enumerate() {
        let (_, case, row) = members[0];
        let rows: Vec<String> = members
            .iter()
            .map(|(j, c, _)| match c.form {
                "—" => format!("{i}.{}", j + 1),
                form => format!("{i}.{} {form}", j + 1),
            })
            .collect();
        let _ = writeln!(
            w,
            "{}. **{label}** ({}; rows {}). {}: {}.\n\n   ```sh\n   {}\n   ```",
            first + n,
            sections[*i].title,
            rows.join(", "),
            row.what,
            case.why,
            command(case.scene, &case.sets)
        );
        if let Check::Run { scene, sets, .. } = &case.check {
            let _ = writeln!(
                w,
                "\n   Reference:\n\n   ```sh\n   {}\n   ```",
                command(scene, sets)
            );
        }
        let _ = writeln!(w);
    }
    groups.len()
}

pub(super) fn render(sections: &[Section], results: &[Vec<Row>], references: usize) -> String {
    let mut w = String::new();
    let rows_total: usize = results.iter().map(Vec::len).sum();
    let _ = writeln!(w, "# Stability at the extremes\n");
    let _ = writeln!(
        w,
        "*This report is generated, in full, by*\n\n\
         ```sh\ncargo xtask stability\n```\n\n\
         *(`xtask/src/stability/`; {rows_total} runs plus {references} reference runs, \
         one after another, a little over a minute on two cores), into \
         `out/xtask/stability.md`; `docs/stability.md` explains it.*\n"
    );
    let _ = writeln!(
        w,
        "Each row is one `taut run` of a bundled scene at an extreme parameter or resolution, \
         for each contact formulation where it makes sense (a moving force has no contact, \
         hence no formulation). The requirement: every run is either **accurate** or \
         **stopped with a diagnosis** (impossible input is **rejected**), never silently wrong. \
         The outcome is what the run returned: it ran, ran with warnings (quoted below the \
         table), stopped with a diagnosis (quoted), or was rejected as invalid input (quoted). \
         The verdict:\n"
    );
    let _ = writeln!(
        w,
        "| verdict | meaning |\n|---|---|\n\
         | accurate | ran without warning, and agrees with its reference within the tolerances |\n\
         | accurate, flagged | ran with a warning, yet agrees with its reference |\n\
         | inaccurate but flagged | ran with a warning, and the figures are indeed off |\n\
         | stopped | stopped with a diagnosis (`run diverged …` or `contact solve failed …`) |\n\
         | rejected | refused as invalid input, naming the field |\n\
         | marginal | ran without warning, outside the tolerance but not clearly wrong |\n\
         | *ill-determined* | ran without warning, but the case's P_l or mean is not determined to the tolerance even by its reference (it moves under refinement or a 1e-6 change of g) |\n\
         | **SILENTLY WRONG** | ran without warning, yet clearly off its reference (beyond the reference's own spread) |\n\
         | unchecked | ran without warning, with no reference to score it against |\n"
    );
    let _ = writeln!(
        w,
        "**References.** For an extreme of the physics (EI, T, V0) the reference is a Lagrange \
         run of the same physics two refinements finer (N = 1600, Δt = 2.5e-5 s); for m and k, \
         whose extremes put the carrier's own period at 0.2 ms, Lagrange at Δt = 1e-5 s; for an \
         extreme of the numerics (Δt, N, κ) the bundled reference case itself (Lagrange, \
         N = 400, Δt = 1e-4 s, same end time); for the `alpha` placement the same formulation \
         with placement `end`; for a moving force the analytic solution of MODEL §8.\n"
    );
    let _ = writeln!(
        w,
        "**Tolerances.** A run agrees when |ΔP_l| ≤ {PL_ABS} + {PL_REL}·P_l,ref and its mean \
         force is within {:.0} %; it is clearly wrong when |ΔP_l| exceeds twice that, when a \
         reference loss of at least {PL_ABS} is more than halved, or when the mean is off by more \
         than {:.0} % (both widened by the reference's own spread). The spread is how far the \
         reference's P_l and mean move under a 1e-6 change of g and, for the refined references, \
         one level coarser (N = 800, Δt = 5e-5 s; or Δt = 2e-5 s); a reference that moves \
         beyond the agreement tolerance makes its case *ill-determined*. A moving force agrees when max|w − w_a| under the force is within \
         {:.0} % of the deflection scale (the larger of max|w_a| and the static string \
         deflection F·L/(4T)), clearly wrong beyond {:.0} %. The peak force is shown but not \
         scored: re-contact peaks are not converged in Δt for any formulation even in the \
         bundled case ([formulations.md](formulations.md)), and the arrival at the far support \
         is an impact the model has no law for.\n",
        100.0 * MEAN_OK,
        100.0 * MEAN_BAD,
        100.0 * W_OK,
        100.0 * W_BAD
    );
    let _ = writeln!(
        w,
        "**Columns.** P_l: contact-loss fraction. λ mean, λ max: contact force, N, with the \
         x/L of the largest |λ|. pen.: largest penetration, m. sw.: contact switches. osc: \
         Σ|λ_{{n+1}} − λ_n| / Σ|λ_n|, the step-to-step change of the force relative to the \
         force. In the commands `taut` is `cargo run --release --`.\n"
    );

    // Findings
    let _ = writeln!(w, "## Findings\n");
    let wrong = findings(&mut w, sections, results, Verdict::SilentlyWrong, 1);
    if wrong == 0 {
        let _ = writeln!(
            w,
            "No run finished without warning while clearly off its reference.\n"
        );
    }
    let _ = writeln!(
        w,
        "**Not determined, and not flagged.** In these cases the Lagrange reference itself \
         moves beyond the tolerance under refinement or a 1e-6 change of g, so no single run \
         gives P_l or the mean force to the tolerance; the runs finish without a warning that \
         says so.\n"
    );
    let ill = findings(&mut w, sections, results, Verdict::IllDetermined, wrong + 1);
    if ill == 0 {
        let _ = writeln!(w, "None.\n");
    }
    let changed: Vec<String> = sections
        .iter()
        .zip(results)
        .enumerate()
        .flat_map(|(i, (s, rows))| {
            s.cases
                .iter()
                .zip(rows)
                .enumerate()
                .filter(|(_, (c, r))| c.expect != r.verdict)
                .map(move |(j, (c, r))| {
                    format!(
                        "- {i}.{} {}, {}: written for “{}”, now “{}”.",
                        j + 1,
                        c.label,
                        c.form,
                        c.expect.text(),
                        r.verdict.text()
                    )
                })
        })
        .collect();
    if !changed.is_empty() {
        let _ = writeln!(
            w,
            "**Changed since the explanations were written.** These rows' verdicts differ \
             from the ones their sentences explain; re-examine them:\n\n{}\n",
            changed.join("\n")
        );
    }

    // Summary
    let _ = writeln!(w, "## Summary\n");
    let order = [
        Accurate,
        AccurateFlagged,
        Flagged,
        Stopped,
        Rejected,
        Marginal,
        IllDetermined,
        SilentlyWrong,
        Unchecked,
    ];
    let _ = write!(w, "| extreme | rows |");
    for v in order {
        let _ = write!(w, " {} |", v.text());
    }
    let _ = writeln!(w);
    let _ = writeln!(w, "|---|---|{}", "---|".repeat(order.len()));
    let mut totals = [0usize; 9];
    for (i, (s, rows)) in sections.iter().zip(results).enumerate() {
        let _ = write!(w, "| {i}. {} | {} |", s.title, rows.len());
        for (k, v) in order.iter().enumerate() {
            let n = rows.iter().filter(|r| r.verdict == *v).count();
            totals[k] += n;
            if n == 0 {
                let _ = write!(w, " |");
            } else {
                let _ = write!(w, " {n} |");
            }
        }
        let _ = writeln!(w);
    }
    let _ = write!(w, "| all | {rows_total} |");
    for t in totals {
        let _ = write!(w, " {t} |");
    }
    let _ = writeln!(w, "\n");

    // Sections
    for (i, (s, rows)) in sections.iter().zip(results).enumerate() {
        let _ = writeln!(w, "## {i}. {}\n", s.title);
        if !s.intro.is_empty() {
            let _ = writeln!(w, "{}\n", s.intro);
        }
        let _ = writeln!(
            w,
            "| # | case | formulation | outcome | P_l | λ mean | λ max (x/L) | pen. | sw. | osc | accuracy | verdict |\n\
             |---|---|---|---|---|---|---|---|---|---|---|---|"
        );
        for (j, (case, row)) in s.cases.iter().zip(rows).enumerate() {
            let figs = match &row.outcome {
                Outcome::Ran(f) if f.mass_carrier => format!(
                    "{:.4} | {} | {} ({:.3}) | {:.1e} | {} | {:.3}",
                    f.loss,
                    fmt_g(f.mean),
                    fmt_g(f.max),
                    f.max_at,
                    f.penetration,
                    f.switches,
                    f.osc
                ),
                _ => "— | — | — | — | — | —".into(),
            };
            let _ = writeln!(
                w,
                "| {i}.{} | {} | {} | {} | {figs} | {} | {} |",
                j + 1,
                case.label,
                case.form,
                outcome_cell(&row.outcome),
                row.accuracy,
                row.verdict.text()
            );
        }
        let _ = writeln!(w);
        for (j, (case, row)) in s.cases.iter().zip(rows).enumerate() {
            let mut sentence = row.what.clone();
            if !case.why.is_empty() {
                let _ = write!(sentence, ": {}", case.why);
            }
            let _ = writeln!(
                w,
                "- **{i}.{}** {}, {}. {}.  \n  `{}`",
                j + 1,
                case.label,
                case.form,
                sentence,
                command(case.scene, &case.sets)
            );
            if let Outcome::Ran(f) = &row.outcome {
                for m in &f.warnings {
                    let _ = writeln!(w, "  > warning: {m}");
                }
            }
        }
        let _ = writeln!(w);
    }
    w
}
