//! A type-erased layer over [`System`] for the command line and bindings: object-safe traits, so
//! that callers need not know a system's type or its number of coordinates.

use std::any::Any;
use std::sync::Arc;

use crate::diagnostics::OutputError;
use crate::diagnostics::{Row, Summary};
use crate::dim::{Dim, Dynamic, Fixed};
use crate::mechanics::lagrangian::{Borrowed, SystemIn};
use crate::{
    CheckReport, Coordinate, Error, Input, Method, OutputOptions, OwnedRowIn, Problem, StateIn, StepReport, StepperIn,
    System,
};

/// A system whose type and dimension are erased.
pub trait DynSystem: Send + Sync {
    /// The coordinates, in order.
    fn coordinates(&self) -> Vec<Coordinate>;

    /// The names of the other charts of the system's atlas; see [`System::charts`].
    fn charts(&self) -> Vec<String>;

    /// Runs a problem; see [`crate::integrate`].
    fn integrate(
        &self,
        problem: &Problem,
        method: &Method,
        output: &OutputOptions,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
    ) -> Result<Summary, Error>;

    /// Runs a problem, calling `watch` every [`crate::WATCH_STEPS`] steps; see
    /// [`crate::integrate_watched`].
    fn integrate_watched(
        &self,
        problem: &Problem,
        method: &Method,
        output: &OutputOptions,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
        watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
    ) -> Result<Summary, Error>;

    /// Checks a problem without integrating; see [`crate::check`].
    fn check(&self, problem: &Problem, method: &Method) -> Result<CheckReport, Error>;

    /// A stepper for a problem; see [`Stepper::new`](crate::StepperIn::new).
    fn stepper<'a>(&'a self, problem: &Problem, method: &Method) -> Result<Box<dyn DynStepper + 'a>, Error>;

    /// The exact motion from (q0, p0) at time t on the coordinates it is known for; see
    /// [`System::exact_solution`]. `None` for a system without one, or for vectors of another size.
    fn exact_solution(&self, q0: &[f64], p0: &[f64], t: f64) -> Option<Vec<Option<f64>>>;
}

/// Wraps a system with `N` coordinates as a [`DynSystem`].
///
/// ```
/// use ddirac::{DynSystem, Erased, systems::ChargedParticle};
/// let system: Box<dyn DynSystem> = Box::new(Erased(ChargedParticle::default()));
/// assert_eq!(system.coordinates()[3].name, "theta");
/// // The paper's exact gyration (§7.1), known for q1, q2, q3 (not for θ): q(t) = (sin t, cos t − 1, t).
/// let exact = system.exact_solution(&[0.0; 4], &[1.0, 0.0, 1.0, 1.0], 0.5).unwrap();
/// assert_eq!(exact[3], None);
/// let expected = [0.5f64.sin(), 0.5f64.cos() - 1.0, 0.5];
/// assert!((0..3).all(|i| (exact[i].unwrap() - expected[i]).abs() < 1e-15));
/// assert_eq!(system.exact_solution(&[0.0; 3], &[1.0, 0.0, 1.0], 0.0), None);
/// ```
#[derive(Debug, Clone)]
pub struct Erased<S, const N: usize>(pub S);

/// Wraps a system whose number of coordinates is chosen at run time (a system in [`Dynamic`], such
/// as [`crate::expression::ExpressionLagrangian`]) as a [`DynSystem`].
#[derive(Debug, Clone)]
pub struct ErasedDynamic<S>(pub S);

/// A wrapper that holds a system in a dimension: what [`DynSystem`] is implemented for.
pub trait Holds: Send + Sync {
    /// The dimension.
    type Dm: Dim;
    /// The system.
    type System: SystemIn<Self::Dm> + Send + Sync;

    /// The system held.
    fn held(&self) -> &Self::System;
}

impl<S: System<N> + Send + Sync, const N: usize> Holds for Erased<S, N> {
    type Dm = Fixed<N>;
    type System = S;

    fn held(&self) -> &S {
        &self.0
    }
}

impl<S: SystemIn<Dynamic> + Send + Sync> Holds for ErasedDynamic<S> {
    type Dm = Dynamic;
    type System = S;

    fn held(&self) -> &S {
        &self.0
    }
}

impl<H: Holds> DynSystem for H {
    fn coordinates(&self) -> Vec<Coordinate> {
        self.held().coordinates().as_ref().to_vec()
    }

    fn charts(&self) -> Vec<String> {
        self.held().charts().into_iter().map(|(name, _)| name).collect()
    }

    fn integrate(
        &self,
        problem: &Problem,
        method: &Method,
        output: &OutputOptions,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
    ) -> Result<Summary, Error> {
        crate::integrate(self.held(), problem, method, output, observer)
    }

    fn integrate_watched(
        &self,
        problem: &Problem,
        method: &Method,
        output: &OutputOptions,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
        watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
    ) -> Result<Summary, Error> {
        crate::integrate_watched(self.held(), problem, method, output, observer, watch)
    }

    fn check(&self, problem: &Problem, method: &Method) -> Result<CheckReport, Error> {
        crate::check(self.held(), problem, method)
    }

    fn stepper<'a>(&'a self, problem: &Problem, method: &Method) -> Result<Box<dyn DynStepper + 'a>, Error> {
        Ok(Box::new(StepperIn::new(Borrowed(self.held()), problem, method)?))
    }

    fn exact_solution(&self, q0: &[f64], p0: &[f64], t: f64) -> Option<Vec<Option<f64>>> {
        let system = self.held();
        let dim = system.dim();
        if q0.len() != dim.n() || p0.len() != dim.n() {
            return None;
        }
        let (q0, p0) = (dim.array(|i| q0[i]), dim.array(|i| p0[i]));
        system.exact_solution(&q0, &p0, t).map(|exact| exact.as_ref().to_vec())
    }
}

/// A [`crate::Stepper`] whose system type and dimension are erased; vectors are `Vec`s.
///
/// ```
/// use ddirac::{DynState, DynSystem, Erased, Method, Rule, systems::ChargedParticle};
/// let system: Box<dyn DynSystem> = Box::new(Erased(ChargedParticle::default()));
/// let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
/// let mut stepper = system.stepper(&ChargedParticle::paper_problem(100), &method).unwrap();
/// stepper.step().unwrap();
/// let saved = stepper.state();
/// let second = stepper.step().unwrap();
/// stepper.restart(&saved).unwrap();
/// assert_eq!(stepper.step().unwrap(), second);
/// // A cold state from q and p only; the sizes are checked.
/// assert!(stepper.restart(&DynState::new(0, vec![0.0; 4], vec![1.0, 0.0, 1.0, 1.0])).is_ok());
/// assert!(stepper.restart(&DynState::new(0, vec![0.0; 3], vec![1.0, 0.0, 1.0])).is_err());
/// ```
pub trait DynStepper {
    /// The current step index k.
    fn k(&self) -> usize;

    /// The current time t_k.
    fn t(&self) -> f64;

    /// The number of steps N of the problem.
    fn steps(&self) -> usize;

    /// Whether all N steps are taken.
    fn is_finished(&self) -> bool;

    /// Report angles wrapped to (−π, π]; see [`Stepper::set_wrap_angles`](crate::StepperIn::set_wrap_angles).
    fn set_wrap_angles(&mut self, wrap: bool);

    /// Takes step k → k + 1; see [`Stepper::step`](crate::StepperIn::step).
    fn step(&mut self) -> Result<StepReport, Error>;

    /// Steps to the end, reporting every `every`-th row and the last to `observer` and calling
    /// `watch` every [`crate::WATCH_STEPS`] steps; see [`Stepper::run_to_end`](crate::StepperIn::run_to_end). After an error the
    /// stepper stays at the step that failed.
    fn run_to_end(
        &mut self,
        every: usize,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
        watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
    ) -> Result<(), Error>;

    /// The row of the current step; see [`Stepper::row`](crate::StepperIn::row).
    fn row(&mut self) -> DynRow;

    /// The state of the current step; see [`Stepper::state`](crate::StepperIn::state).
    fn state(&self) -> DynState;

    /// Continues from a state; see [`Stepper::restart`](crate::StepperIn::restart). An error for a state of another number of
    /// coordinates.
    fn restart(&mut self, state: &DynState) -> Result<(), Error>;

    /// The summary of the run; see [`Stepper::finish`](crate::StepperIn::finish).
    fn finish(self: Box<Self>) -> Result<Summary, Error>;

    /// The summary of the run, keeping the stepper; see [`Stepper::summary`](crate::StepperIn::summary).
    fn summary(&mut self) -> Result<Summary, Error>;

    /// Prepares the stepper for another problem, keeping its derivatives when they serve it
    /// unchanged; see [`Stepper::renew`](crate::StepperIn::renew).
    fn renew(&mut self, problem: &Problem) -> Result<bool, Error>;
}

impl<S: SystemIn<Dm> + Clone, Dm: Dim> DynStepper for StepperIn<S, Dm> {
    fn k(&self) -> usize {
        StepperIn::k(self)
    }

    fn t(&self) -> f64 {
        StepperIn::t(self)
    }

    fn steps(&self) -> usize {
        StepperIn::steps(self)
    }

    fn is_finished(&self) -> bool {
        StepperIn::is_finished(self)
    }

    fn set_wrap_angles(&mut self, wrap: bool) {
        StepperIn::set_wrap_angles(self, wrap);
    }

    fn step(&mut self) -> Result<StepReport, Error> {
        StepperIn::step(self)
    }

    fn run_to_end(
        &mut self,
        every: usize,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
        watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
    ) -> Result<(), Error> {
        StepperIn::run_to_end(self, every, observer, watch)
    }

    fn row(&mut self) -> DynRow {
        StepperIn::row(self).into()
    }

    fn state(&self) -> DynState {
        StepperIn::state(self).into()
    }

    fn restart(&mut self, state: &DynState) -> Result<(), Error> {
        if let Some(typed) = state.typed.as_ref().and_then(|t| t.downcast_ref::<StateIn<Dm>>()) {
            return StepperIn::restart(self, typed);
        }
        let dim = self.dim();
        let sized = |v: &[f64]| -> Result<Dm::Array<f64>, Error> {
            if v.len() != dim.n() {
                return Err(Error::Size { what: Input::State, expected: dim.n(), found: v.len() });
            }
            Ok(dim.array(|i| v[i]))
        };
        StepperIn::restart(self, &StateIn::new(state.k, sized(&state.q)?, sized(&state.p)?))
    }

    fn finish(self: Box<Self>) -> Result<Summary, Error> {
        StepperIn::finish(*self)
    }

    fn summary(&mut self) -> Result<Summary, Error> {
        StepperIn::summary(self)
    }

    fn renew(&mut self, problem: &Problem) -> Result<bool, Error> {
        StepperIn::renew(self, problem)
    }
}

/// A [`crate::State`] whose dimension is erased. A state taken from a stepper keeps the stepper's memory
/// for a bit-for-bit restart of a stepper of the same system, method and step.
#[derive(Clone)]
pub struct DynState {
    k: usize,
    q: Vec<f64>,
    p: Vec<f64>,
    /// The [`State`] of a stepper, when the state was taken from one.
    typed: Option<Arc<dyn Any + Send + Sync>>,
}

impl DynState {
    /// A cold state at step `k` from a configuration `q` and canonical momenta `p`; see [`State::new`](crate::StateIn::new).
    pub fn new(k: usize, q: Vec<f64>, p: Vec<f64>) -> Self {
        Self { k, q, p, typed: None }
    }

    /// This state without the stepper's memory; see [`State::cold`](crate::StateIn::cold).
    pub fn cold(&self) -> Self {
        Self::new(self.k, self.q.clone(), self.p.clone())
    }

    /// The step index k.
    pub fn k(&self) -> usize {
        self.k
    }

    /// The configuration q_k, angles unwrapped.
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// The canonical momenta p_k.
    pub fn p(&self) -> &[f64] {
        &self.p
    }

    /// This state with `q` and `p` cut or extended by zeros to `n` entries, keeping the stepper's
    /// memory (for a system run with padding coordinates, [`crate::padding`]).
    pub(crate) fn resized(mut self, n: usize) -> Self {
        self.q.resize(n, 0.0);
        self.p.resize(n, 0.0);
        self
    }

    /// Whether the state holds a stepper's memory.
    pub fn is_warm(&self) -> bool {
        self.typed.is_some()
    }
}

impl std::fmt::Debug for DynState {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DynState")
            .field("k", &self.k)
            .field("q", &self.q)
            .field("p", &self.p)
            .field("warm", &self.is_warm())
            .finish()
    }
}

impl<Dm: Dim> From<StateIn<Dm>> for DynState {
    fn from(state: StateIn<Dm>) -> Self {
        let (k, q, p) = (state.k(), state.q().as_ref().to_vec(), state.p().as_ref().to_vec());
        let typed: Option<Arc<dyn Any + Send + Sync>> = state.is_warm().then(|| Arc::new(state) as _);
        Self { k, q, p, typed }
    }
}

/// A row of the trajectory with its vectors as `Vec`s ([`DynStepper::row`]); see [`crate::OwnedRow`].
#[derive(Debug, Clone, PartialEq)]
pub struct DynRow {
    /// Step index k.
    pub k: usize,
    /// Time t_k = k h.
    pub t: f64,
    /// Configuration q_k.
    pub q: Vec<f64>,
    /// Canonical momenta p_k.
    pub p: Vec<f64>,
    /// The Hamiltonian H(q_k, p_k).
    pub energy: f64,
    /// L_d(q_k, q_{k+1}), once step k is taken.
    pub discrete_energy: Option<f64>,
    /// The momentum map J(q_k, p_k) = p_g.
    pub momentum_map: Vec<f64>,
    /// The chart of the atlas the step was in (0: the main chart).
    pub chart: usize,
}

impl<Dm: Dim> From<OwnedRowIn<Dm>> for DynRow {
    fn from(row: OwnedRowIn<Dm>) -> Self {
        Self {
            k: row.k,
            t: row.t,
            q: row.q.as_ref().to_vec(),
            p: row.p.as_ref().to_vec(),
            energy: row.energy,
            discrete_energy: row.discrete_energy,
            momentum_map: row.momentum_map().to_vec(),
            chart: row.chart,
        }
    }
}
