//! What a stepper hands out and takes back: the [`State`] of a step, to save and to restart from.

use super::progress::Progress;
use crate::dim::{Dim, Fixed};
use crate::Method;

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
    /// Whether the progress is that of the chart's glued steps ([`crate::blend`]).
    pub(super) glued: bool,
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
