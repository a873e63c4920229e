//! The process's memory budget: runs in flight together stay within it.
//!
//! Validation refuses a run whose own estimate is above
//! [`crate::resolve::MEMORY_BUDGET_BYTES`], but a study runs several at once:
//! a modal sweep at N = 3200 on `--threads 4` put four 1.3 GB eigenproblems
//! in flight and aborted on a failed allocation. So every run
//! ([`crate::run`], [`crate::run_batch`]) reserves its estimate
//! ([`crate::Resolved::memory_estimate`]) here before it allocates, and
//! gives it back when it ends. A reservation waits while the runs in flight
//! hold too much for it to fit in [`PROCESS_BUDGET_BYTES`]: the study then
//! runs fewer at once (its worker threads wait), with the same results, since
//! each run is a pure function of its scene. A reservation larger than the
//! whole budget (one batch of several runs) goes ahead when nothing else is
//! held, and a reservation on a thread that already holds one (a batch that
//! falls back to running its members alone) goes ahead at once, so nothing
//! waits for ever.

use std::sync::{Condvar, Mutex};

/// Memory all runs in flight in one process may plan to use together,
/// bytes: the per-run budget (2 GiB), so that a study never plans more than
/// one largest run, whatever its thread count.
pub const PROCESS_BUDGET_BYTES: u64 = crate::resolve::MEMORY_BUDGET_BYTES;

/// Bytes reserved by the runs in flight.
static HELD: Mutex<u64> = Mutex::new(0);
static FREED: Condvar = Condvar::new();

thread_local! {
    /// Reservations this thread holds: a nested one must not wait for the
    /// outer one, which only this thread can give back.
    static HELD_HERE: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// A reservation; dropping it gives the bytes back.
#[derive(Debug)]
pub struct Reservation {
    bytes: u64,
}

impl Drop for Reservation {
    fn drop(&mut self) {
        HELD_HERE.with(|h| h.set(h.get().saturating_sub(1)));
        let mut held = HELD.lock().unwrap_or_else(|p| p.into_inner());
        *held = held.saturating_sub(self.bytes);
        FREED.notify_all();
    }
}

/// Reserve `bytes`, waiting until they fit beside the reservations held
/// (or nothing else is held, or this thread already holds one).
pub fn reserve(bytes: u64) -> Reservation {
    let nested = HELD_HERE.with(|h| {
        h.set(h.get() + 1);
        h.get() > 1
    });
    let mut held = HELD.lock().unwrap_or_else(|p| p.into_inner());
    while !nested && *held > 0 && held.saturating_add(bytes) > PROCESS_BUDGET_BYTES {
        held = FREED.wait(held).unwrap_or_else(|p| p.into_inner());
    }
    *held = held.saturating_add(bytes);
    Reservation { bytes }
}

/// Bytes reserved now (the tests' view of the budget).
#[cfg(test)]
fn held() -> u64 {
    *HELD.lock().unwrap_or_else(|p| p.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicU64, Ordering};

    #[test]
    fn reservations_in_flight_stay_within_the_budget() {
        // eight threads each reserving 40 % of the budget: at most two at once
        let most = AtomicU64::new(0);
        let part = PROCESS_BUDGET_BYTES * 2 / 5;
        std::thread::scope(|s| {
            for _ in 0..8 {
                s.spawn(|| {
                    let _r = reserve(part);
                    most.fetch_max(held(), Ordering::SeqCst);
                    std::thread::sleep(std::time::Duration::from_millis(20));
                });
            }
        });
        let m = most.load(Ordering::SeqCst);
        assert!(m <= PROCESS_BUDGET_BYTES && m >= part, "{m}");
        // larger than the whole budget: goes ahead alone
        let big = reserve(3 * PROCESS_BUDGET_BYTES);
        // and a nested reservation on the same thread goes ahead too (a
        // batch falling back to its runs alone): it would wait for ever
        let nested = reserve(PROCESS_BUDGET_BYTES);
        drop(nested);
        drop(big);
    }
}
