//! What a stepper hands out and takes back: the [`State`] of a step, the [`OwnedRow`] of the
//! trajectory and the [`StepReport`] of a step.

use super::progress::Progress;
use crate::diagnostics::Row;
use crate::dim::{Dim, Fixed};
use crate::{newton, Method};

/// A state of a run at step k: the configuration, the momenta and, when it was taken from a
/// [`Stepper`], all that the stepper needs to continue bit for bit ([`Stepper::restart`]).
///
/// A state taken from a stepper holds the configuration in its chart (each angle's re-centred base
/// in (−π, π] and its full turns), the momenta of the scheme, the predictor's last unknowns and
/// their count, the Newton Jacobian kept across steps, the energy watch and the run's record (the
/// statistics and warnings of the steps before). A cold state ([`State::new`], [`State::cold`])
/// holds only k, q and p: a stepper starts from it as on a first step.
///
/// ```
/// use ddirac::State;
/// let cold = State::new(0, [0.0; 4], [1.0, 0.0, 1.0, 1.0]);
/// assert!(!cold.is_warm());
/// assert_eq!(cold.p(), &[1.0, 0.0, 1.0, 1.0]);
/// ```
///
/// [`Stepper`]: crate::Stepper
/// [`Stepper::restart`]: crate::Stepper::restart
#[derive(Debug, Clone)]
pub struct StateIn<Dm: Dim> {
    pub(super) k: usize,
    pub(super) q: Dm::Array<f64>,
    pub(super) p: Dm::Array<f64>,
    pub(super) memory: Option<Box<Memory<Dm>>>,
}

/// The state of a run of a system of `N` coordinates ([`StateIn`] in a fixed dimension).
pub type State<const N: usize> = StateIn<Fixed<N>>;

/// The part of a state only a stepper reads, with the method and step it belongs to.
#[derive(Debug, Clone)]
pub(super) struct Memory<Dm: Dim> {
    pub(super) method: Method,
    pub(super) h: f64,
    pub(super) progress: Progress<Dm>,
    /// The chart the progress is in, and the last point in the main chart.
    pub(super) chart: usize,
    pub(super) near: Dm::Array<f64>,
}

impl<Dm: Dim> StateIn<Dm> {
    /// A cold state at step `k` from a configuration `q` (angles may be unwrapped) and canonical
    /// momenta `p`.
    pub fn new(k: usize, q: Dm::Array<f64>, p: Dm::Array<f64>) -> Self {
        Self { k, q, p, memory: None }
    }

    /// This state without the stepper's memory: a stepper restarted from it starts from (q, p) as
    /// on a first step, and a new record (the summary then covers the steps from k on).
    pub fn cold(&self) -> Self {
        Self::new(self.k, self.q.clone(), self.p.clone())
    }

    /// The step index k.
    pub fn k(&self) -> usize {
        self.k
    }

    /// The configuration q_k, angles unwrapped.
    pub fn q(&self) -> &Dm::Array<f64> {
        &self.q
    }

    /// The canonical momenta p_k.
    pub fn p(&self) -> &Dm::Array<f64> {
        &self.p
    }

    /// Whether the state holds a stepper's memory (it was taken by
    /// [`Stepper::state`](crate::Stepper::state)).
    pub fn is_warm(&self) -> bool {
        self.memory.is_some()
    }
}

/// A row of the trajectory by value ([`crate::Stepper::row`]); [`OwnedRow::as_row`] gives the
/// [`Row`] that [`crate::integrate`] hands to its observer.
#[derive(Debug, Clone, PartialEq)]
pub struct OwnedRowIn<Dm: Dim> {
    /// Step index k.
    pub k: usize,
    /// Time t_k = k h.
    pub t: f64,
    /// Configuration q_k (angles unwrapped unless asked otherwise).
    pub q: Dm::Array<f64>,
    /// Canonical momenta p_k.
    pub p: Dm::Array<f64>,
    /// The Hamiltonian H(q_k, p_k).
    pub energy: f64,
    /// L_d(q_k, q_{k+1}), once step k is taken (the stepper's row of step k is taken before).
    pub discrete_energy: Option<f64>,
    /// The chart of the atlas the step was in (0: the main chart, in which q and p are reported).
    pub chart: usize,
    pub(super) momentum_map: Dm::Array<f64>,
    pub(super) n_g: usize,
}

/// A row of a run of a system of `N` coordinates ([`OwnedRowIn`] in a fixed dimension).
pub type OwnedRow<const N: usize> = OwnedRowIn<Fixed<N>>;

impl<const N: usize> Copy for OwnedRow<N> {}

impl<Dm: Dim> OwnedRowIn<Dm> {
    /// The momentum map J(q_k, p_k) = p_g, one entry per group coordinate.
    pub fn momentum_map(&self) -> &[f64] {
        &self.momentum_map.as_ref()[..self.n_g]
    }

    /// The row as [`crate::integrate`] reports it.
    pub fn as_row(&self) -> Row<'_> {
        Row {
            k: self.k,
            t: self.t,
            q: self.q.as_ref(),
            p: self.p.as_ref(),
            energy: self.energy,
            discrete_energy: self.discrete_energy,
            momentum_map: self.momentum_map(),
            chart: self.chart,
        }
    }
}

/// What a step reports: its discrete energy and how its Newton solve went.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepReport {
    /// The step taken, k (the stepper is now at k + 1).
    pub k: usize,
    /// L_d(q_k, q_{k+1}), the paper's discrete energy of the step.
    pub discrete_energy: f64,
    /// Newton corrections, residual and Jacobians of the step (one correction for a closed-form step).
    pub newton: newton::NewtonStats,
}
