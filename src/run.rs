//! One run: scene → integrator → history and statistics.

use std::time::Instant;

use crate::error::Result;
use crate::integrate::{Integrator, MethodFactory};
use crate::record::{ContactAccumulator, ContactStats, History, LossGeometry};
use crate::scene::Resolved;

/// What a run produces.
#[derive(Debug, Clone)]
pub struct RunOutput {
    /// Recorded histories (row 0 = t = 0).
    pub history: History,
    /// Contact statistics per carrier, in scene order.
    pub stats: Vec<ContactStats>,
    /// Number of unknowns (beam dofs + mass dofs).
    pub dofs: usize,
    /// Steps taken.
    pub steps: usize,
    /// Time step, s.
    pub dt: f64,
    /// Wall-clock time of the run (assembly, factorization, initial state,
    /// time loop and recording), s.
    pub wall_seconds: f64,
    /// Findings that make the numbers suspect (e.g. contact chatter).
    pub warnings: Vec<String>,
}

/// A contact that opens or closes on more than this fraction of the steps is
/// chattering: physical loss/reattachment events are separated by many steps,
/// a step-to-step on/off pattern is a numerical oscillation (MODEL §5).
pub const CHATTER_FRACTION: f64 = 0.05;

/// Run a validated scene with its own method (`[integrator]`).
/// `progress(done, total)` is called about 200 times.
pub fn run(sc: &Resolved, progress: &mut dyn FnMut(usize, usize)) -> Result<RunOutput> {
    drive(sc, &|sc| Integrator::new(sc), progress)
}

/// Run a validated scene with the method `factory` builds (a method of
/// one's own: `examples/custom_method.rs`).
pub fn run_with(
    sc: &Resolved,
    factory: &dyn MethodFactory,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunOutput> {
    drive(sc, &|sc| Integrator::with_method(sc, factory), progress)
}

/// Build the integrator, step it to the end, record and summarize.
fn drive(
    sc: &Resolved,
    build: &dyn Fn(&Resolved) -> Result<Integrator>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunOutput> {
    let start = Instant::now();
    let mut it = build(sc)?;
    let nc = it.carriers();
    let probes: Vec<_> = sc
        .probes
        .iter()
        .map(|(_, x)| it.beam().point_vector(*x))
        .collect();
    let every = sc.record_every.max(1);
    let mut h = History::with_capacity(sc.history_rows(), every, nc, &sc.probes);
    // statistics over every step, whatever rows the history keeps; the
    // near-support force peak (below) likewise
    let mut acc: Vec<ContactAccumulator> = (0..nc)
        .map(|c| ContactAccumulator::new(LossGeometry::of(sc, c)))
        .collect();
    let mut support_peak = vec![0.0f64; nc];
    let mut observe = |it: &Integrator, h: &mut History, keep: bool, first: bool| -> Result<()> {
        let t = it.time();
        if keep {
            h.t.push(t);
        }
        for c in 0..nc {
            let s = it.sample(c);
            it.check(&s, c)?;
            acc[c].push(t, &s);
            if !first && it.near_support(s.x) {
                support_peak[c] = support_peak[c].max(s.force.abs());
            }
            if keep {
                h.carriers[c].push(&s);
            }
        }
        if keep {
            for (pv, (_, col)) in probes.iter().zip(h.probes.iter_mut()) {
                col.push(it.displacement_at(pv));
            }
        }
        Ok(())
    };
    observe(&it, &mut h, true, true)?;
    let report_every = (sc.steps / 200).max(1);
    for n in 1..=sc.steps {
        it.step()?;
        observe(&it, &mut h, n % every == 0 || n == sc.steps, false)?;
        if n % report_every == 0 || n == sc.steps {
            progress(n, sc.steps);
        }
    }
    let wall_seconds = start.elapsed().as_secs_f64();
    let max_abs_w: Vec<f64> = acc.iter().map(ContactAccumulator::max_abs_w).collect();
    let stats = acc
        .into_iter()
        .map(ContactAccumulator::finish)
        .collect::<Vec<ContactStats>>();
    let warnings = stats
        .iter()
        .enumerate()
        .filter(|(_, st)| st.contact_switches as f64 > CHATTER_FRACTION * sc.steps as f64)
        .map(|(i, st)| {
            let cause = it.constraint_damping_note().map_or(String::new(), |w| {
                format!("; likely cause: {w}")
            });
            format!(
                "carrier {i}: contact switched {} times in {} steps: step-to-step chatter, a numerical oscillation (integrator.method = {}, contact.placement = {:?}; MODEL §5); these contact statistics are not a converged answer{cause}",
                st.contact_switches,
                sc.steps,
                sc.integrator.method.name(),
                sc.contact.placement
            )
        })
        .collect();
    // arrival at a support: forces beyond the divergence bound, allowed there
    let bound = it.force_bound();
    let mut warnings: Vec<String> = warnings;
    warnings.extend(crate::warnings::resolution_warnings(sc, &max_abs_w, &stats));
    for (c, &peak) in support_peak.iter().enumerate() {
        if peak > bound {
            warnings.push(format!(
                "carrier {c}: contact force {peak:.3e} N in the last element before a support (beyond the {bound:.1e} N bound applied elsewhere): the mass arrives with the beam under it deflected and is forced to w = 0 within one element, an impact the model has no law for; it grows as the step falls, and force_max includes it"
            ));
        }
    }
    Ok(RunOutput {
        warnings,
        dofs: it.dofs(),
        steps: it.steps_taken(),
        dt: sc.dt,
        history: h,
        stats,
        wall_seconds,
    })
}
