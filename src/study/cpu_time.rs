//! CPU seconds of the calling thread: what a sweep point's runs cost on
//! the thread that stepped them (`timing.csv`, the sweep's summary line).
//!
//! Wall time counts waiting for a shared core; CPU time does not, so a
//! map's cost per point stays comparable on a busy machine. The standard
//! library gives no thread CPU clock, and the one call needed is POSIX's
//! `clock_gettime(CLOCK_THREAD_CPUTIME_ID)` (through `libc`, already a
//! dependency on unix); elsewhere there is none and the figure is absent.

/// The calling thread's CPU time, s, from an arbitrary origin; `None` where
/// the platform gives no thread CPU clock.
pub fn thread_cpu_seconds() -> Option<f64> {
    #[cfg(unix)]
    {
        let mut ts = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `ts` is a valid, writable timespec for the call's duration.
        let r = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
        (r == 0).then_some(ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9)
    }
    #[cfg(not(unix))]
    {
        None
    }
}

/// The CPU seconds `f` took on the calling thread, with its result.
pub fn timed<R>(f: impl FnOnce() -> R) -> (R, Option<f64>) {
    let start = thread_cpu_seconds();
    let r = f();
    let spent = match (start, thread_cpu_seconds()) {
        (Some(a), Some(b)) => Some((b - a).max(0.0)),
        _ => None,
    };
    (r, spent)
}

/// `total` shared among members in proportion to their `weights` (a batch's
/// CPU time among its runs by their unknowns × steps: they step in turn or
/// as lanes of one sweep, each lane's share of the work its own).
pub fn shares(total: Option<f64>, weights: &[f64]) -> Vec<Option<f64>> {
    let sum: f64 = weights.iter().sum();
    weights
        .iter()
        .map(|w| {
            total.map(|t| {
                if sum > 0.0 {
                    t * w / sum
                } else {
                    t / weights.len() as f64
                }
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn busy_work_costs_cpu_time_and_sleep_does_not() {
        let (_, busy) = timed(|| {
            let mut x = 0.0f64;
            for i in 0..20_000_000u64 {
                x = std::hint::black_box(x + i as f64);
            }
            x
        });
        let (_, slept) = timed(|| std::thread::sleep(std::time::Duration::from_millis(200)));
        let (busy, slept) = (busy.unwrap(), slept.unwrap());
        assert!(busy > 0.0, "busy work measured {busy} s");
        // sleeping 0.2 s costs far less than that in CPU time (the
        // scheduler's bookkeeping only)
        assert!(slept < 0.05, "a sleep measured {slept} s of CPU");
    }

    #[test]
    fn shares_split_by_weight_and_sum_to_the_total() {
        let s = shares(Some(6.0), &[1.0, 2.0, 3.0]);
        assert_eq!(s, vec![Some(1.0), Some(2.0), Some(3.0)]);
        assert_eq!(shares(None, &[1.0]), vec![None]);
        assert_eq!(shares(Some(2.0), &[0.0, 0.0]), vec![Some(1.0), Some(1.0)]);
    }
}
