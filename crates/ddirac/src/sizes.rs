//! The numbers of coordinates the type-erased layer is built for.
//!
//! The engine's dimensions are const generics (every dual number and matrix of a step lives on the
//! stack), so each number of coordinates a spec can choose at run time is a separate copy of the
//! engine behind [`crate::Erased`]. Text systems ([`crate::expression::ExpressionSpec::into_dyn`]) and
//! the built-in chain of pendula take their sizes from this one list, [`SIZES`]: every count up to 16,
//! then 20, 24, 32, 40 and 50.

/// Calls `$callback!(1 2 … 16 20 24 32 40 50)`: the sizes of [`SIZES`] as literals, for the
/// dispatches that instantiate the engine for each.
macro_rules! with_sizes {
    ($callback:ident) => {
        $callback! { 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 20 24 32 40 50 }
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
/// assert_eq!(ddirac::SIZES.len(), 21);
/// assert!(ddirac::SIZES.contains(&16) && ddirac::SIZES.contains(&50));
/// assert!(!ddirac::SIZES.contains(&17));
/// ```
pub const SIZES: &[usize] = with_sizes!(list);

/// The sizes as a reader would write them: `1–16, 20, 24, 32, 40, 50`.
///
/// ```
/// assert_eq!(ddirac::sizes_text(), "1–16, 20, 24, 32, 40, 50");
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
