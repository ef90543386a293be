//! What a stepper hands out after a step: the [`OwnedRow`] of the trajectory and the [`StepReport`]
//! of the step.

use crate::diagnostics::Row;
use crate::dim::{Dim, Fixed};
use crate::newton;

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
