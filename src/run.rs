//! One run: scene → integrator → history and statistics.

use std::time::Instant;

use crate::error::Result;
use crate::integrate::{Integrator, MethodFactory};
use crate::record::{ContactStats, History};
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
    let mut h = History::with_capacity(sc.steps + 1, nc, &sc.probes);
    let record = |it: &Integrator, h: &mut History| -> Result<()> {
        h.t.push(it.time());
        for c in 0..nc {
            let s = it.sample(c);
            it.check(&s, c)?;
            h.carriers[c].push(&s);
        }
        for (pv, (_, col)) in probes.iter().zip(h.probes.iter_mut()) {
            col.push(it.displacement_at(pv));
        }
        Ok(())
    };
    record(&it, &mut h)?;
    let every = (sc.steps / 200).max(1);
    for n in 1..=sc.steps {
        it.step()?;
        record(&it, &mut h)?;
        if n % every == 0 || n == sc.steps {
            progress(n, sc.steps);
        }
    }
    let wall_seconds = start.elapsed().as_secs_f64();
    let stats = h
        .carriers
        .iter()
        .map(|tr| ContactStats::from_trace(&h.t, tr, sc.beam.length))
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
    warnings.extend(crate::warnings::resolution_warnings(sc, &h, &stats));
    for (c, tr) in h.carriers.iter().enumerate() {
        let peak = (1..h.len())
            .filter(|&i| it.near_support(tr.x[i]))
            .map(|i| tr.force[i].abs())
            .fold(0.0, f64::max);
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
