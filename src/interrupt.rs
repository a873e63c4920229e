//! Stopping work on request.
//!
//! A caller that cannot kill the process to stop a long study (the Python
//! module, on Ctrl-C: the interpreter lives on) calls [`request`]. Every run
//! then stops before its next step with [`Error::Interrupted`](crate::Error::Interrupted)
//! (`crate::error::Error`), a batch of runs stops all its lanes, and a sweep
//! saves no record of a run that stopped this way (the finished points it
//! saved stay, so the sweep resumes where it was).
//!
//! The request is process-wide: work is spread over worker threads (rayon)
//! that no per-call token reaches without threading one through every
//! study's signature, and a Ctrl-C is meant for all the work of the process
//! anyway. So a request stops every call that is running, and stays until
//! the last of them has returned: each call holds a [`Call`] while it works,
//! and the request is withdrawn when the last `Call` is dropped. Until then
//! every running call sees it, stops, and can tell its caller so (a call
//! that finished its work while the request stood reports the stop too,
//! rather than results some of whose runs may have been cut short). The CLI
//! never requests a stop (Ctrl-C ends the process; a sweep keeps what it
//! saved).

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Calls that hold a [`Call`]; the lock also orders a request's withdrawal
/// against a call's entry.
static ACTIVE: Mutex<usize> = Mutex::new(0);

/// A call at work. Dropping the last withdraws any stop request.
#[must_use = "the call is at work while this is held"]
pub struct Call(());

impl Call {
    /// Enter a call (the Python module, around each function). A request
    /// left standing by a hold that is over is withdrawn first.
    pub fn enter() -> Call {
        let mut n = ACTIVE.lock().unwrap_or_else(|p| p.into_inner());
        if *n == 0 && hold_over() {
            clear();
        }
        *n += 1;
        Call(())
    }
}

impl Drop for Call {
    fn drop(&mut self) {
        let mut n = ACTIVE.lock().unwrap_or_else(|p| p.into_inner());
        *n -= 1;
        if *n == 0 && hold_over() {
            clear();
        }
    }
}

/// Ask every run in the process to stop at its next step.
pub fn request() {
    REQUESTED.store(true, Ordering::SeqCst);
}

/// Ask every run in the process to stop, if a [`Call`] is at work, and
/// keep the request standing for `hold` even once the calls have
/// returned; returns whether one was at work. A Ctrl-C seen on a thread
/// that is not one of the calls' (Python's main thread while calls run in
/// a thread pool's workers, which never see a signal) stops them; the
/// calls the pool then starts from its queue (a pool that shuts down runs
/// what was queued) start within the hold and stop at once too. One seen
/// while nothing works requests nothing.
pub fn request_if_working(hold: Duration) -> bool {
    // the count's lock orders this against the last call's withdrawal
    let n = ACTIVE.lock().unwrap_or_else(|p| p.into_inner());
    if *n > 0 {
        request();
        *HOLD_UNTIL.lock().unwrap_or_else(|p| p.into_inner()) = Some(Instant::now() + hold);
    }
    *n > 0
}

/// Until when a stop request stands with no call at work
/// ([`request_if_working`]); `None`: withdrawn with the last call.
static HOLD_UNTIL: Mutex<Option<Instant>> = Mutex::new(None);

/// True when no hold keeps a request standing now.
fn hold_over() -> bool {
    let mut h = HOLD_UNTIL.lock().unwrap_or_else(|p| p.into_inner());
    match *h {
        Some(t) if Instant::now() < t => false,
        _ => {
            *h = None;
            true
        }
    }
}

/// Withdraw the request. [`Call`] does it when the last call returns; a
/// caller without calls (a test) may do it directly.
pub fn clear() {
    REQUESTED.store(false, Ordering::SeqCst);
}

/// Whether a stop was requested. One relaxed load: cheap enough to ask at
/// every step.
#[inline]
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}
