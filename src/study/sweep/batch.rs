//! Sweep points stepped together (`--batch`): the batch width, and the
//! work items of points that share their effective matrix.

use toml::Table;

use super::record::{SweepRecord, ended, record_guarded, record_of};
use super::spec::SweepSpec;
use crate::error::Result;
use crate::resolve::Resolved;

/// How many runs a sweep steps together (`--batch`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BatchWidth {
    /// `AUTO_BATCH_LANES`.
    Auto,
    /// At most this many (1: every run alone, the unbatched path).
    Fixed(usize),
}

/// The automatic batch width: four runs, one AVX2 vector of lanes.
/// Measured on the reference case (criterion group `batch`, N = 1600, and
/// `cargo run --release --example batch_profile -- B N` at N = 400, 800,
/// 1600), four lanes gave the best throughput at every size (2.2–2.6× the
/// runs alone), two little (0.94–1.35×: the half-width vectors barely pay
/// for the interleaving), eight less than four (the sweep's window of 3 × 16
/// columns no longer fits the sixteen vector registers).
pub(crate) const AUTO_BATCH_LANES: usize = 4;

/// The automatic batch width of a scene's runs: [`AUTO_BATCH_LANES`] for
/// generalized-α (SIMD lanes of one band sweep), the widest batch for
/// `modal_exact`, whose runs gain from sharing their basis and its tables
/// (built once per batch) and lose nothing by stepping in turn
/// (`integrate::modal_batch`).
pub(crate) fn auto_lanes(sc: &Resolved) -> usize {
    match sc.method.scheme {
        crate::scene::Scheme::ModalExact => crate::integrate::MAX_LANES,
        _ => AUTO_BATCH_LANES,
    }
}

/// The sweep's work items: points that share their effective matrix
/// ([`crate::integrate::batch_key`]), in grid order, grouped up to the
/// batch width; every other point alone.
pub(super) fn batches(
    spec: &SweepSpec,
    base: Option<&Table>,
    todo: &[usize],
    width: BatchWidth,
) -> Vec<Vec<usize>> {
    if width == BatchWidth::Fixed(1) {
        return todo.iter().map(|&i| vec![i]).collect();
    }
    let mut open: Vec<(crate::integrate::BatchKey, usize, Vec<usize>)> = Vec::new();
    let mut items: Vec<Vec<usize>> = Vec::new();
    for &i in todo {
        let key = spec.resolve_with(base, i).ok().and_then(|sc| {
            let key = crate::integrate::batch_key(&sc)?;
            let w = match width {
                BatchWidth::Fixed(b) => b,
                BatchWidth::Auto => auto_lanes(&sc),
            };
            Some((key, w))
        });
        let Some((key, w)) = key else {
            items.push(vec![i]);
            continue;
        };
        match open.iter_mut().position(|(k, ..)| *k == key) {
            Some(p) => {
                open[p].2.push(i);
                if open[p].2.len() >= open[p].1 {
                    items.push(open.remove(p).2);
                }
            }
            None => open.push((key, w, vec![i])),
        }
    }
    items.extend(open.into_iter().map(|(.., g)| g));
    items
}

/// The records of one work item, run together when it has several points
/// ([`crate::run::run_batch`]); a panic inside makes every point of the
/// item an error record (none of them is trusted), never the sweep's end.
pub(super) fn records_guarded(
    spec: &SweepSpec,
    base: Option<&Table>,
    id: &str,
    item: &[usize],
) -> Vec<SweepRecord> {
    if let [i] = item {
        return vec![record_guarded(spec, base, id, *i)];
    }
    let go = || {
        let scenes: Vec<Result<Resolved>> =
            item.iter().map(|&i| spec.resolve_with(base, i)).collect();
        let ok: Vec<Resolved> = scenes
            .iter()
            .filter_map(|s| s.as_ref().ok().cloned())
            .collect();
        let (outs, cpu) =
            crate::study::cpu_time::timed(|| crate::run::run_batch(&ok, item.len(), &mut |_| {}));
        // the batch's CPU time shared among its runs by their work
        let work: Vec<f64> = outs
            .iter()
            .map(|o| o.as_ref().map_or(0.0, |o| o.dofs as f64 * o.steps as f64))
            .collect();
        let mut cpu = crate::study::cpu_time::shares(cpu, &work).into_iter();
        let mut outs = outs.into_iter();
        item.iter()
            .zip(&scenes)
            .map(|(&i, sc)| {
                let ran = sc.as_ref().map(|_| {
                    (
                        outs.next().expect("one output per scene"),
                        cpu.next().expect("one share per output"),
                    )
                });
                let cpu = ran.as_ref().ok().and_then(|r| r.1);
                let ran = ran.map(|r| r.0);
                let mut r = record_of(spec, base, id, i, sc.as_ref().ok(), ended(&ran));
                r.add_cpu(cpu);
                r
            })
            .collect::<Vec<_>>()
    };
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(go)).unwrap_or_else(|payload| {
        let what = panic_message(payload.as_ref());
        item.iter()
            .map(|&i| SweepRecord {
                error: Some(format!(
                    "internal error (a panic in taut, please report it), in a batch of {} runs: {what}",
                    item.len()
                )),
                ..SweepRecord::stopped(id, i, spec.point(i))
            })
            .collect()
    })
}

/// A panic's message, for the error record of the runs it stopped.
pub(super) fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "no message".into())
}
