//! A request to stop every run of the process between two steps, as a signal handler (Ctrl-C) or
//! another thread makes it. A run that sees it returns [`crate::Error::Interrupted`] with the step it
//! stopped at; the request stays until [`clear`]ed. The check is one relaxed atomic load per step.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Asks every run of the process to stop before its next step. Safe to call from a signal handler.
///
/// ```
/// ddirac::interrupt::request();
/// assert!(ddirac::interrupt::requested());
/// ddirac::interrupt::clear();
/// assert!(!ddirac::interrupt::requested());
/// ```
pub fn request() {
    REQUESTED.store(true, Ordering::Relaxed);
}

/// Withdraws the request, so that runs started afterwards go on.
pub fn clear() {
    REQUESTED.store(false, Ordering::Relaxed);
}

/// Whether a stop has been requested.
#[inline]
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}
