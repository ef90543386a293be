//! The numbers of coordinates the type-erased layer is built for.
//!
//! The engine's dimensions are const generics (every dual number and matrix of a step lives on the
//! stack), so each number of coordinates a spec can choose at run time is a separate copy of the
//! engine behind [`crate::Erased`]. Text systems ([`crate::expression::ExpressionSpec::into_dyn`]) and
//! the built-in chain of pendula take their sizes from this one list, [`SIZES`]: every count up to 16,
//! then 20, 24, 32, 40 and 50; and both are erased as one system type, [`RuntimeSized`], so that each
//! size is one copy of the engine, not one per system type.
//!
//! A text system whose count lies between two sizes runs in the next one up, with padding
//! coordinates that it hides ([`crate::padding`]). Above 50 both run in a dimension chosen at run
//! time ([`crate::dim::Dynamic`]), which is faster there than the fixed arrays were (at 64 and 100
//! links the dynamic chain took 0.54–0.68 of the fixed chain's time per step, `ddirac bench --only
//! dimension` before 64, 80 and 100 left this list; BENCHMARKS.md).

use crate::expression::ExpressionSystem;
use crate::systems::PendulumChain;
use crate::{Chart, Coordinate, CoordinateKind, Scalar, System};

/// Calls `$callback!(1 2 … 16 20 24 32 40 50)`: the sizes of [`SIZES`] as literals, for the
/// dispatches that instantiate the engine for each.
#[cfg(not(test))]
macro_rules! with_sizes {
    ($callback:ident) => {
        $callback! { 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 20 24 32 40 50 }
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
/// assert_eq!(ddirac::SIZES.len(), 21);
/// assert!(ddirac::SIZES.contains(&16) && ddirac::SIZES.contains(&50));
/// assert!(!ddirac::SIZES.contains(&64));
/// assert!(!ddirac::SIZES.contains(&17));
/// ```
pub const SIZES: &[usize] = with_sizes!(list);

/// The smallest engine size of [`SIZES`] that holds `n` coordinates, if any.
pub(crate) fn engine_size(n: usize) -> Option<usize> {
    SIZES.iter().copied().find(|&m| m >= n.max(1))
}

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

/// The systems whose number of coordinates is chosen at run time, as one type: the engine is
/// instantiated once per size for all of them. Every method is the inner system's.
// One value per erased system (and per chart stepper of it): the variants' sizes do not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
pub(crate) enum RuntimeSized<const N: usize> {
    /// A text system.
    Text(ExpressionSystem<N>),
    /// The built-in chain of pendula.
    Chain(PendulumChain<N>),
}

/// `$self.method(args)` on the inner system.
macro_rules! inner {
    ($self:ident . $method:ident ( $($arg:expr),* )) => {
        match $self {
            RuntimeSized::Text(system) => system.$method($($arg),*),
            RuntimeSized::Chain(system) => system.$method($($arg),*),
        }
    };
}

impl<const N: usize> System<N> for RuntimeSized<N> {
    fn coordinates(&self) -> [Coordinate; N] {
        inner!(self.coordinates())
    }

    #[inline(always)]
    fn lagrangian<D: Scalar>(&self, q: &[D; N], v: &[D; N]) -> D {
        inner!(self.lagrangian(q, v))
    }

    fn exact_solution(&self, q0: &[f64; N], p0: &[f64; N], t: f64) -> Option<[Option<f64>; N]> {
        inner!(self.exact_solution(q0, p0, t))
    }

    fn charts(&self) -> Vec<Chart<N>> {
        inner!(self.charts())
    }

    fn chart_to_main<D: Scalar>(&self, chart: usize, q: &[D; N]) -> [D; N] {
        inner!(self.chart_to_main(chart, q))
    }

    fn main_to_chart<D: Scalar>(&self, chart: usize, q: &[D; N]) -> [D; N] {
        inner!(self.main_to_chart(chart, q))
    }

    fn chart_lagrangian<D: Scalar>(&self, chart: usize, q: &[D; N], v: &[D; N]) -> Option<D> {
        inner!(self.chart_lagrangian(chart, q, v))
    }

    fn chart_quality(&self, chart: usize, q: &[f64; N]) -> f64 {
        inner!(self.chart_quality(chart, q))
    }

    fn nearest_in_main(&self, q: [f64; N], near: &[f64; N], kinds: &[CoordinateKind; N]) -> [f64; N] {
        inner!(self.nearest_in_main(q, near, kinds))
    }
}
