//! The systems whose number of coordinates is chosen at run time, as one type ([`RuntimeSized`]): a
//! text system and the built-in chain of pendula share each size's copy of the engine
//! ([`crate::SIZES`]).

use crate::expression::ExpressionSystem;
use crate::systems::PendulumChain;
use crate::{Chart, Coordinate, CoordinateKind, Scalar, System};

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

    fn chart_quality<D: Scalar>(&self, chart: usize, q: &[D; N]) -> D {
        inner!(self.chart_quality(chart, q))
    }

    fn nearest_in_main(&self, q: [f64; N], near: &[f64; N], kinds: &[CoordinateKind; N]) -> [f64; N] {
        inner!(self.nearest_in_main(q, near, kinds))
    }
}
