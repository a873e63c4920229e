//! `taut compare`: the same scene under several contact formulations, with
//! agreement on contact loss as the headline measure (issue: formulations
//! side by side).
//!
//! Every formulation runs on the same scene text with the same overrides plus
//! `contact.formulation=<name>`, so meshes, steps and settings are identical
//! and histories can be compared step by step.

use serde::Serialize;

use crate::error::{Error, Result};
use crate::run::{RunOutput, run};
use crate::scene::{Formulation, Resolved, resolve_scene};

/// One formulation's row of the comparison (columns of `compare.csv`).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CompareRow {
    /// Formulation name.
    pub formulation: String,
    /// P_l (carrier 0).
    pub loss_fraction: f64,
    /// Measure of the symmetric difference between this formulation's loss
    /// set and the reference's, in x_m/L (t/t_end for stationary carriers),
    /// summed over carriers.
    pub loss_set_difference: f64,
    /// max over steps and carriers of |λ − λ_ref|, N.
    pub max_force_difference: f64,
    /// RMS over steps and carriers of λ − λ_ref, N.
    pub rms_force_difference: f64,
    /// Largest penetration max(0, −g) over steps and carriers, m.
    pub max_penetration: f64,
    /// Smallest gap, m.
    pub min_gap: f64,
    /// Smallest contact force, N.
    pub min_force: f64,
    /// Largest |g·λ|, N·m.
    pub max_gap_force_product: f64,
    /// Mean contact force (carrier 0), N.
    pub mean_force: f64,
    /// Largest contact force (carrier 0), N.
    pub max_force: f64,
    /// Contact switches (carrier 0).
    pub contact_switches: usize,
    /// Steps taken.
    pub steps: usize,
    /// Wall-clock seconds of the run.
    pub wall_seconds: f64,
    /// The run's warnings (e.g. contact chatter); empty when none.
    pub warnings: Vec<String>,
}

/// A finished comparison.
pub struct Comparison {
    /// The reference formulation.
    pub reference: Formulation,
    /// (formulation, resolved scene, run) in the order asked for.
    pub runs: Vec<(Formulation, Resolved, RunOutput)>,
    /// One row per formulation, same order.
    pub rows: Vec<CompareRow>,
}

/// Parse `lagrange,penalty,…` into formulations.
pub fn parse_formulations(list: &str) -> Result<Vec<Formulation>> {
    let mut out = Vec::new();
    for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let f = Formulation::ALL
            .into_iter()
            .find(|f| f.name() == name)
            .ok_or_else(|| {
                let all: Vec<&str> = Formulation::ALL.iter().map(|f| f.name()).collect();
                Error::invalid(
                    "--formulations",
                    name,
                    format!("must be among {}", all.join(", ")),
                )
            })?;
        if out.contains(&f) {
            return Err(Error::invalid("--formulations", name, "is listed twice"));
        }
        out.push(f);
    }
    if out.is_empty() {
        return Err(Error::invalid(
            "--formulations",
            list,
            "name at least one formulation",
        ));
    }
    Ok(out)
}

/// Run `text` (with `overrides`) once per formulation and compare each with
/// `reference` (run too if not listed). `progress(done, total)` after each run.
pub fn compare(
    text: &str,
    overrides: &[String],
    formulations: &[Formulation],
    reference: Formulation,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Comparison> {
    let mut order: Vec<Formulation> = formulations.to_vec();
    if !order.contains(&reference) {
        order.push(reference);
    }
    let mut runs = Vec::with_capacity(order.len());
    for (i, &f) in order.iter().enumerate() {
        let mut o = overrides.to_vec();
        o.push(format!("contact.formulation={}", f.name()));
        let sc = resolve_scene(text, &o)?;
        let out =
            run(&sc, &mut |_, _| {}).map_err(|e| e.in_run(&format!("formulation {}", f.name())))?;
        runs.push((f, sc, out));
        progress(i + 1, order.len());
    }
    let ref_idx = order
        .iter()
        .position(|&f| f == reference)
        .expect("pushed above");
    let mut rows: Vec<CompareRow> = runs
        .iter()
        .map(|(f, sc, out)| row(*f, sc, out, &runs[ref_idx].2))
        .collect();
    // keep only the formulations asked for (the reference, if added, is last)
    runs.truncate(formulations.len());
    rows.truncate(formulations.len());
    Ok(Comparison {
        reference,
        runs,
        rows,
    })
}

/// Measure of a lost-step set on the abscissa: a lost step i covers
/// [s_{i−1}, s_i]; `a XOR b` gives the symmetric difference.
fn loss_set_difference(sc: &Resolved, a: &RunOutput, b: &RunOutput) -> f64 {
    let stationary = sc.carriers.iter().all(|c| c.motion.is_stationary());
    let t = &a.history.t;
    let t_end = *t.last().unwrap_or(&1.0);
    let mut total = 0.0;
    for (ta, tb) in a.history.carriers.iter().zip(&b.history.carriers) {
        for i in 1..ta.in_contact.len() {
            if ta.in_contact[i] != tb.in_contact[i] {
                total += if stationary {
                    (t[i] - t[i - 1]) / t_end
                } else {
                    (ta.x[i] - ta.x[i - 1]).abs() / sc.beam.length
                };
            }
        }
    }
    total
}

fn row(f: Formulation, sc: &Resolved, out: &RunOutput, reference: &RunOutput) -> CompareRow {
    let (mut max_d, mut sum2, mut count) = (0.0f64, 0.0, 0usize);
    for (ta, tb) in out.history.carriers.iter().zip(&reference.history.carriers) {
        for (x, y) in ta.force.iter().zip(&tb.force).skip(1) {
            let d = x - y;
            max_d = max_d.max(d.abs());
            sum2 += d * d;
            count += 1;
        }
    }
    let s0 = &out.stats[0];
    CompareRow {
        formulation: f.name().to_string(),
        loss_fraction: s0.loss_fraction,
        loss_set_difference: loss_set_difference(sc, out, reference),
        max_force_difference: max_d,
        rms_force_difference: (sum2 / count.max(1) as f64).sqrt(),
        max_penetration: out
            .stats
            .iter()
            .map(|s| s.max_penetration)
            .fold(0.0, f64::max),
        min_gap: out
            .stats
            .iter()
            .map(|s| s.min_gap)
            .fold(f64::INFINITY, f64::min),
        min_force: out
            .stats
            .iter()
            .map(|s| s.force.min)
            .fold(f64::INFINITY, f64::min),
        max_gap_force_product: out
            .stats
            .iter()
            .map(|s| s.max_gap_force_product)
            .fold(0.0, f64::max),
        mean_force: s0.force.mean,
        max_force: s0.force.max,
        contact_switches: s0.contact_switches,
        steps: out.steps,
        wall_seconds: out.wall_seconds,
        warnings: out.warnings.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formulation_lists_are_checked() {
        assert_eq!(
            parse_formulations("lagrange, penalty").unwrap(),
            vec![Formulation::Lagrange, Formulation::Penalty]
        );
        let e = parse_formulations("lagrange,magic")
            .unwrap_err()
            .to_string();
        assert!(e.contains("magic") && e.contains("complementarity"), "{e}");
        assert!(parse_formulations("penalty,penalty").is_err());
        assert!(parse_formulations(" , ").is_err());
    }
}
