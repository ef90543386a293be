//! Native code shared between runs.
//!
//! Compiling a program to native code costs far more than tracing and differentiating it (about
//! 6 ms for the double spherical pendulum, a second for a chain of fifty pendula), and runs that
//! differ only in their step size, their parameters (when they are runtime inputs, see
//! [`crate::Scalar`]) or their initial data trace the same programs. The process keeps the native
//! code of the last [`CAPACITY`] distinct programs, keyed by the program itself, so that such runs —
//! the step sizes of a convergence study, the members of an ensemble — compile once.

use std::collections::{HashMap, VecDeque};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use super::{JitError, NativeProgram, Program};

/// How many distinct programs keep their native code.
pub const CAPACITY: usize = 32;

#[derive(Default)]
struct Cache {
    native: HashMap<Program, Arc<NativeProgram>>,
    /// Programs in the order they were compiled, oldest first.
    order: VecDeque<Program>,
}

static CACHE: Mutex<Option<Cache>> = Mutex::new(None);
static COMPILATIONS: AtomicUsize = AtomicUsize::new(0);

/// The native code of `program`: compiled now, or shared with an earlier run that compiled the same
/// program. Compiling holds the cache, so that threads asking for one program at once compile it once.
///
/// ```
/// use ddirac::compiled::{native, native_compilations, Binary, Instruction, Program};
/// let program = Program {
///     inputs: 2,
///     instructions: vec![Instruction::Input(0), Instruction::Input(1), Instruction::Binary(Binary::Atan2, 0, 1)],
///     outputs: vec![2],
/// };
/// let before = native_compilations();
/// let (first, second) = (native(&program)?, native(&program)?);
/// assert_eq!(native_compilations(), before + 1);
/// assert!(std::sync::Arc::ptr_eq(&first, &second));
/// # Ok::<(), ddirac::compiled::JitError>(())
/// ```
pub fn native(program: &Program) -> Result<Arc<NativeProgram>, JitError> {
    let mut guard = CACHE.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let cache = guard.get_or_insert_with(Cache::default);
    if let Some(native) = cache.native.get(program) {
        return Ok(Arc::clone(native));
    }
    let native = Arc::new(NativeProgram::compile(program)?);
    COMPILATIONS.fetch_add(1, Ordering::Relaxed);
    if cache.order.len() == CAPACITY {
        if let Some(oldest) = cache.order.pop_front() {
            cache.native.remove(&oldest);
        }
    }
    cache.order.push_back(program.clone());
    cache.native.insert(program.clone(), Arc::clone(&native));
    Ok(native)
}

/// How many programs this process has compiled to native code through [`native`].
pub fn native_compilations() -> usize {
    COMPILATIONS.load(Ordering::Relaxed)
}
