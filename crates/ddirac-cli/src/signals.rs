//! SIGINT, SIGTERM and SIGHUP: a run stops, removes what it had not finished writing, says so and
//! exits with 128 + the signal's number (130, 143, 129).
//!
//! [`install`] starts a thread that receives the signals and asks the library to stop its runs
//! ([`ddirac::interrupt::request`]). The run notices a signal before its next step
//! ([`ddirac::Error::Interrupted`]) or at its next row ([`check`], called by the row observer) and
//! unwinds: its temporary files and its lock are removed
//! on drop, and `main` prints the message and exits. When no row comes within [`GRACE`] (a run that
//! writes a row every million steps, the compilation of the derivatives, the drawing of figures), or
//! at a second signal, the signal thread does the same itself: it removes everything registered with
//! [`register`] and exits the process. Whoever of the two goes first [`claim`]s the signal, so that
//! exactly one of them reports it.
//!
//! A [`critical`] section (the renaming of a finished run's files into place) is never cut: the
//! signal thread waits for it to end before it removes anything.

use std::path::PathBuf;
use std::sync::atomic::{AtomicI32, AtomicU64, AtomicU8, Ordering};
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// How long the signal thread waits for the run to notice a signal before it cleans up itself.
pub const GRACE: Duration = Duration::from_millis(300);

/// The signal received, 0 before any.
static RECEIVED: AtomicI32 = AtomicI32::new(0);
/// Who reports the signal: nobody yet, the run's thread, or the signal thread.
static CLAIMED: AtomicU8 = AtomicU8::new(NOBODY);
const NOBODY: u8 = 0;
const RUN: u8 = 1;
const SIGNAL_THREAD: u8 = 2;

/// What to remove when the process is stopped, by registration id.
static REGISTRY: Mutex<Vec<(u64, Cleanup)>> = Mutex::new(Vec::new());
static NEXT_ID: AtomicU64 = AtomicU64::new(0);

/// The numbers of the signals handled, the same on every Unix.
const SIGHUP: i32 = 1;
const SIGINT: i32 = 2;
const SIGTERM: i32 = 15;

/// A signal that stops a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Signal(i32);

impl Signal {
    /// The signal's name, `SIGINT`, `SIGTERM` or `SIGHUP`.
    pub fn name(self) -> String {
        match self.0 {
            SIGINT => "SIGINT".into(),
            SIGTERM => "SIGTERM".into(),
            SIGHUP => "SIGHUP".into(),
            other => format!("signal {other}"),
        }
    }

    /// The exit status of a process stopped by the signal: 128 + its number.
    pub fn exit_code(self) -> u8 {
        u8::try_from(128 + self.0).unwrap_or(u8::MAX)
    }
}

/// A run stopped by a signal.
#[derive(Debug, thiserror::Error)]
#[error("interrupted by {}{}: no output written (the run's temporary files are removed)", signal.name(),
        step.map_or(String::new(), |k| format!(" at step {k}")))]
pub struct Interrupted {
    /// The signal.
    pub signal: Signal,
    /// The step the run had reached, if known.
    pub step: Option<usize>,
}

/// Paths to remove if the process is stopped, in this order: trees, files, then directories that
/// are empty by then.
#[derive(Debug, Default, Clone)]
pub struct Cleanup {
    /// Directories removed with their content (a run's staging directory).
    pub trees: Vec<PathBuf>,
    /// Files (a lock).
    pub files: Vec<PathBuf>,
    /// Directories removed if empty (an output directory made for the run).
    pub empty_dirs: Vec<PathBuf>,
}

/// A [`Cleanup`] in the registry; unregistered on drop.
#[derive(Debug)]
pub struct Registration(u64);

impl Drop for Registration {
    fn drop(&mut self) {
        registry().retain(|(id, _)| *id != self.0);
    }
}

/// Registers paths to remove if a signal stops the process.
pub fn register(cleanup: Cleanup) -> Registration {
    let id = NEXT_ID.fetch_add(1, Ordering::Relaxed);
    registry().push((id, cleanup));
    Registration(id)
}

/// Runs `f` without the signal thread removing anything meanwhile; `f` may unregister `done` (its
/// paths are then left alone by a signal that comes later).
pub fn critical<R>(done: Option<&Registration>, f: impl FnOnce() -> R) -> R {
    let mut registry = registry();
    let result = f();
    if let Some(done) = done {
        registry.retain(|(id, _)| *id != done.0);
    }
    result
}

fn registry() -> MutexGuard<'static, Vec<(u64, Cleanup)>> {
    REGISTRY.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Starts receiving SIGINT, SIGTERM and SIGHUP (without it, they end the process at once). Does
/// nothing elsewhere than on Unix.
#[cfg(not(unix))]
pub fn install() {}

/// Starts receiving SIGINT, SIGTERM and SIGHUP (without it, they end the process at once).
#[cfg(unix)]
pub fn install() {
    use signal_hook::iterator::Signals;
    let Ok(mut signals) = Signals::new([SIGINT, SIGTERM, SIGHUP]) else { return };
    std::thread::spawn(move || {
        let mut pending = None;
        loop {
            let signal = match pending.take() {
                Some(signal) => signal,
                None => match signals.forever().next() {
                    Some(signal) => signal,
                    None => return,
                },
            };
            // The first signal is the one reported.
            let _ = RECEIVED.compare_exchange(0, signal, Ordering::SeqCst, Ordering::SeqCst);
            // Runs stop before their next step, whether or not a row is due.
            ddirac::interrupt::request();
            let started = Instant::now();
            while started.elapsed() < GRACE && CLAIMED.load(Ordering::SeqCst) == NOBODY && pending.is_none() {
                std::thread::sleep(Duration::from_millis(10));
                pending = signals.pending().next();
            }
            if CLAIMED.compare_exchange(NOBODY, SIGNAL_THREAD, Ordering::SeqCst, Ordering::SeqCst).is_ok() {
                stop_now();
            }
        }
    });
}

/// The signal received, if any.
pub fn received() -> Option<Signal> {
    match RECEIVED.load(Ordering::SeqCst) {
        0 => None,
        signal => Some(Signal(signal)),
    }
}

/// Whether this thread may report the signal received: true for the first caller. A run that
/// cannot claim it must do nothing more: the signal thread is ending the process.
pub fn claim() -> bool {
    CLAIMED.compare_exchange(NOBODY, RUN, Ordering::SeqCst, Ordering::SeqCst).is_ok()
}

/// `Err` once a signal was received: the run stops at `step` and reports it. If the signal thread
/// already reports it, this never returns.
pub fn check(step: Option<usize>) -> Result<(), Interrupted> {
    let Some(signal) = received() else { return Ok(()) };
    if claim() {
        Err(Interrupted { signal, step })
    } else {
        loop {
            std::thread::park();
        }
    }
}

/// Removes everything registered (waiting for a critical section to end), reports the signal and
/// exits.
fn stop_now() -> ! {
    let signal = received().unwrap_or(Signal(SIGINT));
    let registry = registry();
    let cleanups: Vec<&Cleanup> = registry.iter().map(|(_, c)| c).collect();
    for tree in cleanups.iter().flat_map(|c| &c.trees) {
        remove_tree(tree);
    }
    for file in cleanups.iter().flat_map(|c| &c.files) {
        let _ = std::fs::remove_file(file);
    }
    for dir in cleanups.iter().flat_map(|c| &c.empty_dirs) {
        let _ = std::fs::remove_dir(dir);
    }
    let what = if cleanups.iter().any(|c| !c.trees.is_empty()) {
        ": no output written (the run's temporary files are removed)"
    } else {
        ""
    };
    // A progress bar may be drawn on the line: start a clean one.
    let clear = if std::io::IsTerminal::is_terminal(&std::io::stderr()) { "\r\x1b[2K" } else { "" };
    eprintln!("{clear}ddirac: interrupted by {}{what}", signal.name());
    std::process::exit(signal.exit_code().into())
}

/// Removes a directory and its content, retrying while another thread still creates files in it.
pub fn remove_tree(path: &std::path::Path) {
    for _ in 0..20 {
        match std::fs::remove_dir_all(path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => std::thread::sleep(Duration::from_millis(5)),
            _ => return,
        }
    }
}
