//! Programs shared between runs.
//!
//! Compiling a program to native code costs far more than tracing and differentiating it (about
//! 6 ms for the double spherical pendulum, a second for a chain of fifty pendula), and runs that
//! differ only in their step size, their parameters (when they are runtime inputs, see
//! [`crate::Scalar`]) or their initial data trace the same programs. The process keeps the prepared
//! programs (native code with the `jit` feature) of the last [`CAPACITY`] distinct programs, keyed by
//! the program itself, so that such runs — the step sizes of a convergence study, the members of an
//! ensemble — compile once.

use std::collections::VecDeque;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use super::executable::Executable;
use super::{CompileError, Program};
use rustc_hash::FxHashMap;

/// How many distinct programs keep their native code.
pub const CAPACITY: usize = 32;

#[derive(Default)]
struct Cache {
    prepared: FxHashMap<Program, Arc<Executable>>,
    /// Programs in the order they were compiled, oldest first.
    order: VecDeque<Program>,
}

static CACHE: Mutex<Option<Cache>> = Mutex::new(None);
static COMPILATIONS: AtomicUsize = AtomicUsize::new(0);

/// `program` ready to run: prepared now, or shared with an earlier run that prepared the same program.
/// Preparing holds the cache, so that threads asking for one program at once compile it once.
pub(crate) fn shared(program: &Program) -> Result<Arc<Executable>, CompileError> {
    let mut guard = CACHE.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let cache = guard.get_or_insert_with(Cache::default);
    if let Some(prepared) = cache.prepared.get(program) {
        return Ok(Arc::clone(prepared));
    }
    let prepared = Arc::new(Executable::new(program)?);
    COMPILATIONS.fetch_add(1, Ordering::Relaxed);
    if cache.order.len() == CAPACITY {
        if let Some(oldest) = cache.order.pop_front() {
            cache.prepared.remove(&oldest);
        }
    }
    cache.order.push_back(program.clone());
    cache.prepared.insert(program.clone(), Arc::clone(&prepared));
    Ok(prepared)
}

/// How many programs this process has prepared to run (compiled to native code, with the `jit`
/// feature) for compiled derivatives; programs shared between runs count once.
///
/// ```
/// use ddirac::compiled::native_compilations;
/// use ddirac::{solve, Differentiation, InitialMomentum, Method, OutputOptions, Problem, systems::Kepler};
/// let method = Method { differentiation: Differentiation::Compiled, ..Method::default() };
/// let run = |h: f64| {
///     let problem = Problem::new(h, 10, vec![1.0, 0.0], InitialMomentum::Momentum(vec![0.0, 1.1]));
///     solve(&Kepler::default(), &problem, &method, &OutputOptions::default()).unwrap();
/// };
/// run(0.01);
/// let before = native_compilations();
/// run(0.02); // the same programs: the step size is an input of them
/// assert_eq!(native_compilations(), before);
/// ```
pub fn native_compilations() -> usize {
    COMPILATIONS.load(Ordering::Relaxed)
}
