//! Worker threads of the parallel studies (`taut sweep --threads N`): a
//! bounded count, and a pool that either starts or says why not.

use crate::error::{Error, Result};

/// Most worker threads per available core. Each sweep point is one
/// CPU-bound run, so threads beyond the cores add no speed, only memory (a
/// stack and a run's buffers each) and switching; a few per core still
/// allows for cores the process does not see (a container's CPU quota) or
/// runs that wait on the disk.
pub(crate) const MAX_THREADS_PER_CORE: usize = 4;

/// Most worker threads on any machine, however many cores it reports:
/// starting a thread costs a stack mapping and a kernel task, and 10⁵ of
/// them took minutes to start and exhausted a memory limit.
pub(crate) const MAX_THREADS: usize = 1024;

/// The largest `--threads` allowed here: `MAX_THREADS_PER_CORE` × the
/// cores available to the process (1 if unknown), at most `MAX_THREADS`.
pub fn max_threads() -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    cores.saturating_mul(MAX_THREADS_PER_CORE).min(MAX_THREADS)
}

fn allowed(max: usize) -> String {
    format!(
        "must be in 1 ..= {max} ({MAX_THREADS_PER_CORE} × the {} cores available, at most {MAX_THREADS}): each run is CPU-bound, so more threads add memory, not speed",
        std::thread::available_parallelism().map_or(1, |n| n.get())
    )
}

/// Check a `--threads` value: 1 ..= [`max_threads`].
pub(crate) fn check_threads(n: usize) -> Result<usize> {
    let max = max_threads();
    if (1..=max).contains(&n) {
        Ok(n)
    } else {
        Err(Error::invalid("--threads", n, allowed(max)))
    }
}

/// A pool of `n` workers (`None`: rayon's default, one per core).
fn pool_builder(n: Option<usize>) -> rayon::ThreadPoolBuilder {
    rayon::ThreadPoolBuilder::new().num_threads(n.unwrap_or(0))
}

/// A pool the system would not start, as an error naming `--threads`.
fn pool_error(n: Option<usize>, e: rayon::ThreadPoolBuildError) -> Error {
    Error::invalid(
        "--threads",
        n.map_or_else(|| "default (one per core)".to_string(), |n| n.to_string()),
        format!(
            "the worker pool could not start ({e}): give fewer threads, or raise the process's thread or memory limit"
        ),
    )
}

/// Run `work` in a worker pool of its own with `threads` workers (default:
/// one per core), for a caller that makes several studies in one process
/// with different thread counts (the Python module's `threads=`): rayon's
/// process-wide pool can be started only once. A value outside
/// [`check_threads`]'s range, or a pool the system cannot start, is an
/// error naming `--threads`, never a panic in the first parallel loop.
pub(crate) fn in_pool<R: Send>(
    threads: Option<usize>,
    work: impl FnOnce() -> R + Send,
) -> Result<R> {
    let n = threads.map(check_threads).transpose()?;
    let pool = pool_builder(n).build().map_err(|e| pool_error(n, e))?;
    Ok(pool.install(work))
}

/// `f` of every item, in parallel on the current worker pool, the costliest
/// first (`cost`), returned in the items' order; `progress(done, total)`
/// is called on the calling thread as each finishes (so a front end's
/// progress need not be shared across threads).
pub fn map_with_progress<T: Sync, R: Send>(
    items: &[T],
    cost: impl Fn(&T) -> f64,
    f: impl Fn(&T) -> R + Sync,
    progress: &mut dyn FnMut(usize, usize),
) -> Vec<R> {
    use rayon::prelude::*;
    let n = items.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| cost(&items[b]).total_cmp(&cost(&items[a])));
    let (tx, rx) = std::sync::mpsc::channel::<()>();
    let pool = rayon::current_num_threads();
    let mut done: Vec<(usize, R)> = std::thread::scope(|s| {
        let worker = s.spawn(|| {
            // the calling thread's pool, not the global one
            let run = || {
                order
                    .par_iter()
                    .with_max_len(1)
                    .map_with(tx, |tx, &i| {
                        let r = f(&items[i]);
                        // the receiver outlives the workers
                        let _ = tx.send(());
                        (i, r)
                    })
                    .collect::<Vec<_>>()
            };
            match rayon::ThreadPoolBuilder::new().num_threads(pool).build() {
                Ok(p) => p.install(run),
                Err(_) => run(),
            }
        });
        let mut finished = 0;
        for () in rx {
            finished += 1;
            progress(finished, n);
        }
        worker
            .join()
            .unwrap_or_else(|payload| std::panic::resume_unwind(payload))
    });
    done.sort_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, r)| r).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parallel_maps_keep_the_order_and_report_each_item() {
        let items: Vec<u64> = (0..20).collect();
        let mut seen = Vec::new();
        let out = map_with_progress(&items, |&x| x as f64, |&x| x * x, &mut |d, t| {
            seen.push((d, t))
        });
        assert_eq!(out, items.iter().map(|x| x * x).collect::<Vec<_>>());
        assert_eq!(seen.len(), 20);
        assert_eq!(seen.last(), Some(&(20, 20)));
    }

    #[test]
    fn thread_counts_outside_one_to_the_cap_are_refused() {
        let max = max_threads();
        assert!((MAX_THREADS_PER_CORE..=MAX_THREADS).contains(&max));
        assert_eq!(check_threads(1).unwrap(), 1);
        assert_eq!(check_threads(max).unwrap(), max);
        for bad in [0, max + 1, 100_000, usize::MAX] {
            let e = check_threads(bad).unwrap_err().to_string();
            assert!(
                e.contains(&format!("`--threads` = {bad}:")) && e.contains(&format!("1 ..= {max}")),
                "{e}"
            );
        }
    }
}
