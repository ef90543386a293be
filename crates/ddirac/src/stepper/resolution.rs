//! What a run's steps resolve, measured as it goes: the size of the increments q_{k+1} − q_k and how
//! much they change from one step to the next, relative to their size (about h ω for a motion of
//! frequency ω). A step of a method of order p then errs by about |Δq| (h ω)^p, its truncation error;
//! a Newton tolerance that lets each step's increment be off by more than that (an iteration
//! accepted at the tolerance leaves an error up to it) spoils the accuracy the order promises, and
//! the run says so ([`WarningKind::LooseTolerance`](crate::WarningKind::LooseTolerance)).

use crate::dim::Dim;

/// How many times a step's estimated truncation error the error a Newton tolerance allows must
/// exceed for a `loose_tolerance` warning.
pub const LOOSE_TOLERANCE_MARGIN: f64 = 10.0;

/// Tolerances at or below this are never loose: the Newton iterates stop at round-off near it.
const ROUND_OFF: f64 = 1e-10;

/// The increments of a run so far: the last one, the sums of the sizes ‖Δq_k‖∞ and of the changes
/// ‖Δq_k − Δq_{k−1}‖∞ (from the second step on), and the number of steps.
#[derive(Debug, Clone)]
pub(super) struct Resolution<Dm: Dim> {
    last: Dm::Array<f64>,
    sizes: f64,
    changes: f64,
    steps: usize,
}

impl<Dm: Dim> Resolution<Dm> {
    pub(super) fn new(dim: Dm) -> Self {
        Self { last: dim.array(|_| 0.0), sizes: 0.0, changes: 0.0, steps: 0 }
    }

    /// Whether a run with the Newton `tolerance` needs the increments: a tolerance at round-off is
    /// never loose.
    #[inline(always)]
    pub(super) fn watches(tolerance: f64) -> bool {
        tolerance > ROUND_OFF
    }

    /// Takes the increment `dq` of a step.
    #[inline(always)]
    pub(super) fn push(&mut self, dq: &Dm::Array<f64>) {
        let (mut size, mut change) = (0.0f64, 0.0f64);
        for (d, last) in dq.as_ref().iter().zip(self.last.as_mut()) {
            size = size.max(d.abs());
            change = change.max((d - *last).abs());
            *last = *d;
        }
        if self.steps > 0 {
            self.sizes += size;
            self.changes += change;
        }
        self.steps += 1;
    }

    /// What a `loose_tolerance` warning says when the Newton `tolerance` lets a step of a method of
    /// order `order` err by more than [`LOOSE_TOLERANCE_MARGIN`] times its estimated truncation error.
    pub(super) fn loose(&self, tolerance: f64, order: u8) -> Option<String> {
        if !Self::watches(tolerance) || self.steps < 3 || self.sizes <= 0.0 {
            return None;
        }
        let size = self.sizes / (self.steps - 1) as f64;
        let relative_change = self.changes / self.sizes;
        let truncation = size * relative_change.powi(i32::from(order));
        let allowed = tolerance * (1.0 + size);
        if !truncation.is_finite() || allowed <= LOOSE_TOLERANCE_MARGIN * truncation {
            return None;
        }
        let suggested = 10f64.powf(truncation.max(ROUND_OFF).log10().floor());
        Some(format!(
            "the Newton tolerance {tolerance:e} lets each step's increment be off by up to about {allowed:.1e}, more \
             than {LOOSE_TOLERANCE_MARGIN} times the step's own truncation error (about {truncation:.1e}: increments \
             of typical size {size:.1e}, changing by {relative_change:.1e} of it from step to step, to the order \
             {order} of the method); the result may be no more accurate than the tolerance allows: use \
             `method.tolerance` ≤ {suggested:.0e}"
        ))
    }
}
