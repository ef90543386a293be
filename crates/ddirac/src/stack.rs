//! The stack a step needs.
//!
//! The engine keeps every dual number, vector and matrix of a step on the stack (its dimensions are
//! const generics), so what a step needs grows with n²: about 3 MiB for 50 coordinates, more than
//! the 2 MiB of a thread that Rust spawns (rayon's workers, a test's thread). The stepper's entry
//! points run through `enough`, which continues on a stack taken from the heap when the thread has
//! less than that left, and costs nothing for systems of up to [`ON_ANY_THREAD`] coordinates.

use crate::dim::Dim;

/// Systems of up to this many coordinates run on the stack of any thread (tested with 2 MiB).
pub const ON_ANY_THREAD: usize = 16;

/// The stack kept free for an operation of a system of `n` coordinates: 256 KiB + 2 KiB · n²
/// (5.3 MiB for 50, where a step measured between 2 and 4 MiB).
pub const fn needed(n: usize) -> usize {
    (256 << 10) + n * n * (2 << 10)
}

/// Runs `f` for a system in `dim`, on a new stack of twice [`needed`]`(n)` when its arrays live on
/// the stack ([`Dim::ON_STACK`]) and less than that is left on this thread's.
#[inline(always)]
pub(crate) fn enough<Dm: Dim, R>(dim: Dm, f: impl FnOnce() -> R) -> R {
    let n = dim.n();
    if !Dm::ON_STACK || n <= ON_ANY_THREAD {
        f()
    } else {
        stacker::maybe_grow(needed(n), 2 * needed(n), f)
    }
}
