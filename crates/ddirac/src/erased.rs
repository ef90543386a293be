//! A type-erased layer over [`System`] for the command line and bindings: one object-safe trait,
//! so that callers need not know a system's type or its number of coordinates.

use crate::diagnostics::{Row, Summary};
use crate::integrator::OutputError;
use crate::{CheckReport, Coordinate, Error, Method, OutputOptions, Problem, System};

/// A system whose type and dimension are erased.
pub trait DynSystem: Send + Sync {
    /// The coordinates, in order.
    fn coordinates(&self) -> Vec<Coordinate>;

    /// Runs a problem; see [`crate::integrate`].
    fn integrate(
        &self,
        problem: &Problem,
        method: &Method,
        output: &OutputOptions,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
    ) -> Result<Summary, Error>;

    /// Checks a problem without integrating; see [`crate::check`].
    fn check(&self, problem: &Problem, method: &Method) -> Result<CheckReport, Error>;
}

/// Wraps a system with `N` coordinates as a [`DynSystem`].
///
/// ```
/// use ddirac::{DynSystem, Erased, systems::ChargedParticle};
/// let system: Box<dyn DynSystem> = Box::new(Erased(ChargedParticle::default()));
/// assert_eq!(system.coordinates()[3].name, "theta");
/// ```
#[derive(Debug, Clone)]
pub struct Erased<S, const N: usize>(pub S);

impl<S: System<N> + Send + Sync, const N: usize> DynSystem for Erased<S, N> {
    fn coordinates(&self) -> Vec<Coordinate> {
        self.0.coordinates().to_vec()
    }

    fn integrate(
        &self,
        problem: &Problem,
        method: &Method,
        output: &OutputOptions,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
    ) -> Result<Summary, Error> {
        crate::integrate(&self.0, problem, method, output, observer)
    }

    fn check(&self, problem: &Problem, method: &Method) -> Result<CheckReport, Error> {
        crate::check(&self.0, problem, method)
    }
}
