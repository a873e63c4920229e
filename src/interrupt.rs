//! Stopping work on request.
//!
//! A caller that cannot kill the process to stop a long study (the Python
//! module, on Ctrl-C: the interpreter lives on) calls [`request`]. Every run
//! then stops before its next step with [`Error::Interrupted`]
//! (`crate::error::Error`), a batch of runs stops all its lanes, and a sweep
//! saves no record of a run that stopped this way (the finished points it
//! saved stay, so the sweep resumes where it was). The caller [`clear`]s the
//! request once the interrupted call has returned.
//!
//! The flag is process-wide: work is spread over worker threads (rayon) that
//! no per-call token reaches without threading one through every study's
//! signature, and a Ctrl-C is meant for all the work of the process anyway.
//! The CLI never sets it (Ctrl-C ends the process; a sweep keeps what it
//! saved).

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Ask every run in the process to stop at its next step.
pub fn request() {
    REQUESTED.store(true, Ordering::SeqCst);
}

/// Withdraw the request (once the interrupted work has returned).
pub fn clear() {
    REQUESTED.store(false, Ordering::SeqCst);
}

/// Whether a stop was requested. One relaxed load: cheap enough to ask at
/// every step.
#[inline]
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}
