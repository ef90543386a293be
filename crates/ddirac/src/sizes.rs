//! The numbers of coordinates the type-erased layer is built for.
//!
//! The engine's dimensions are const generics (every dual number and matrix of a step lives on the
//! stack), so each number of coordinates a spec can choose at run time is a separate copy of the
//! engine behind [`crate::Erased`]. Text systems ([`crate::expression::ExpressionSpec::into_dyn`]) and
//! the built-in chain of pendula take their sizes from this one list, [`SIZES`]: every count from 1
//! to 16; and both are erased as one system type, [`RuntimeSized`], so that each size is one copy of
//! the engine, not one per system type.
//!
//! Above 16 both run in a dimension chosen at run time ([`crate::dim::Dynamic`]), which costs no more
//! per step there: against the chain in its fixed dimension, the dynamic chain took 0.82 and 0.98 of
//! its time per step at 24 links (dual numbers, compiled), 0.73 and 0.90 at 32 and 0.84 and 0.71 at
//! 50; at 20, 1.02 and 1.06; at 16, 1.13 with compiled derivatives, which is why 16 stays (`ddirac
//! bench --only dimension` before 20, 24, 32, 40 and 50 left this list; BENCHMARKS.md). Each size
//! left is a copy of the engine fewer to compile, the larger the more.

/// Calls `$callback!(1 2 … 16)`: the sizes of [`SIZES`] as literals, for the
/// dispatches that instantiate the engine for each.
#[cfg(not(test))]
macro_rules! with_sizes {
    ($callback:ident) => {
        $callback! { 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 }
    };
}

/// The sizes of this crate's unit tests (`cargo test --lib`), which test the engine's parts and
/// not this list: each size is a copy of the engine, and the unit-test build is a second compile of
/// the whole crate. The integration tests, the doctests and everything else use the crate as it is
/// built for use, with every size above.
#[cfg(test)]
macro_rules! with_sizes {
    ($callback:ident) => {
        $callback! { 1 2 3 4 }
    };
}
pub(crate) use with_sizes;

macro_rules! list {
    ($($n:literal)*) => {
        &[$($n),*]
    };
}

/// The numbers of coordinates a type-erased system can have, ascending.
///
/// ```
/// assert_eq!(ddirac::SIZES, (1..=16).collect::<Vec<_>>());
/// assert!(!ddirac::SIZES.contains(&17) && !ddirac::SIZES.contains(&50));
/// ```
pub const SIZES: &[usize] = with_sizes!(list);

/// The smallest engine size of [`SIZES`] that holds `n` coordinates, if any.
pub(crate) fn engine_size(n: usize) -> Option<usize> {
    SIZES.iter().copied().find(|&m| m >= n.max(1))
}

/// The sizes as a reader would write them: `1–16`.
///
/// ```
/// assert_eq!(ddirac::sizes_text(), "1–16");
/// ```
pub fn sizes_text() -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut k = 0;
    while k < SIZES.len() {
        let mut end = k;
        while end + 1 < SIZES.len() && SIZES[end + 1] == SIZES[end] + 1 {
            end += 1;
        }
        parts.push(match end - k {
            0 => SIZES[k].to_string(),
            1 => format!("{}, {}", SIZES[k], SIZES[end]),
            _ => format!("{}–{}", SIZES[k], SIZES[end]),
        });
        k = end + 1;
    }
    parts.join(", ")
}
