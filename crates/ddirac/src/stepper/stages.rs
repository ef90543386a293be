//! The sub-steps of a step ([`crate::composition`]): the schemes of the distinct sub-step sizes γh,
//! each with its equations and derivatives, and the order in which a step takes them. A step of the
//! basic method is one sub-step of size h.

use std::sync::{Arc, Mutex, PoisonError};

use super::{Equipped, FirstStep};
use crate::diagnostics::DerivativePath;
use crate::dim::Dim;
use crate::scheme::Scheme;
use crate::{Differentiation, Error, Method};

/// Pivots below this fraction of the Jacobian's largest entry count as zero in the test that the
/// step equations determine the motion ([`Stages::first_step_rank`]).
const RANK_TOLERANCE: f64 = 1e-13;

/// A failed step is taken again as m = 2, 4, … equal sub-steps, up to this many.
pub const MAX_SUBDIVISION: usize = 64;

/// The schemes of a step's sub-steps.
pub(super) struct Stages<Sc, Dm: Dim> {
    /// One equipped scheme per distinct sub-step size γh, in the order of their first use.
    pub(super) distinct: Vec<Equipped<Sc, Dm>>,
    /// The sub-steps of a step, in order: the index of each one's scheme in `distinct`.
    pub(super) sequence: Vec<usize>,
    /// The fraction γ of each sub-step.
    pub(super) gammas: Vec<f64>,
    /// The step h.
    h: f64,
    /// The stages of a step taken as m equal steps of these stages, prepared when first needed.
    subdivided: Mutex<Vec<Subdivided<Sc, Dm>>>,
}

/// The stages of a step taken as m equal steps, with m.
type Subdivided<Sc, Dm> = (usize, Arc<Stages<Sc, Dm>>);

impl<Sc: Scheme<Dm>, Dm: Dim> Stages<Sc, Dm> {
    /// The stages of `method`'s composition for step `h` in a run of `steps` steps from `first`, and
    /// the derivative path of the first: `scheme(γh)` builds the scheme of a sub-step γh.
    pub(super) fn new(
        method: &Method,
        h: f64,
        steps: usize,
        first: &FirstStep<Dm>,
        scheme: impl FnMut(f64) -> Result<Sc, Error>,
    ) -> Result<(Self, DerivativePath), Error> {
        Self::with_fractions(method, h, method.composition.coefficients(), steps, first, scheme)
    }

    /// The stages of sub-steps γᵢh for the fractions `gammas`.
    fn with_fractions(
        method: &Method,
        h: f64,
        gammas: Vec<f64>,
        steps: usize,
        first: &FirstStep<Dm>,
        mut scheme: impl FnMut(f64) -> Result<Sc, Error>,
    ) -> Result<(Self, DerivativePath), Error> {
        let mut values: Vec<f64> = Vec::new();
        let sequence: Vec<usize> = gammas
            .iter()
            .map(|g| match values.iter().position(|v| v.to_bits() == g.to_bits()) {
                Some(i) => i,
                None => {
                    values.push(*g);
                    values.len() - 1
                }
            })
            .collect();
        let count = |i: usize| sequence.iter().filter(|&&j| j == i).count();
        let mut distinct: Vec<Equipped<Sc, Dm>> = Vec::with_capacity(values.len());
        let mut path = None;
        for (i, &g) in values.iter().enumerate() {
            // γ = 1 gives h itself, bit for bit.
            let (step, scheme) = (g * h, scheme(g * h)?);
            // The first sub-step's compiled programs serve the others with their own h, where
            // preparing them anew would choose compiled derivatives too (asked for, or at least as
            // many evaluations as the first's under `auto`): one trace for the whole composition.
            let shares = method.differentiation == Differentiation::Compiled || count(i) >= count(0);
            let shared = distinct.first().filter(|_| shares).and_then(|e| e.derivatives.for_step(step));
            let equipped = match shared {
                Some(derivatives) => Equipped::sharing(&distinct[0], scheme, derivatives, first, step),
                None => {
                    let (equipped, prepared) = Equipped::new(scheme, method, steps * count(i), first, g)?;
                    path.get_or_insert(prepared);
                    equipped
                }
            };
            distinct.push(equipped);
        }
        let path = path.expect("the first sub-step is prepared");
        Ok((Self { distinct, sequence, gammas, h, subdivided: Mutex::new(Vec::new()) }, path))
    }

    /// The stages of a step taken as `m` equal steps of these stages (sub-steps γᵢh/m), prepared at
    /// `first` the first time they are asked for (by dual numbers unless the method requires compiled
    /// derivatives: they serve the rare steps that need them).
    pub(super) fn subdivided(&self, m: usize, method: &Method, first: &FirstStep<Dm>) -> Result<Arc<Self>, Error> {
        let mut prepared = self.subdivided.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some((_, stages)) = prepared.iter().find(|(count, _)| *count == m) {
            return Ok(stages.clone());
        }
        let gammas: Vec<f64> = (0..m).flat_map(|_| self.gammas.iter().map(move |g| g / m as f64)).collect();
        let scheme = |step| Ok(self.first().scheme.resized(step));
        let (stages, _) = Self::with_fractions(method, self.h, gammas, 1, first, scheme)?;
        let stages = Arc::new(stages);
        prepared.push((m, stages.clone()));
        Ok(stages)
    }

    /// The scheme of the first sub-step (what does not depend on the sub-step size — bases, momenta,
    /// increments — is read from it).
    #[inline]
    pub(super) fn first(&self) -> &Equipped<Sc, Dm> {
        &self.distinct[0]
    }

    /// The rank of the first sub-step's Jacobian at the `first` step (N where it is not finite: Newton's
    /// method reports that case).
    pub(super) fn first_step_rank(&self, first: &FirstStep<Dm>) -> usize {
        let e = self.first();
        let dim = Dm::of(&first.dq);
        let dq = dim.array(|i| self.gammas[0] * first.dq[i]);
        let base = e.scheme.base(first.q.base());
        let z = e.scheme.unknowns(&dq);
        match e.derivatives.first_or_mixed(&e.scheme, &base, &z, true) {
            (_, Some(jacobian)) if Dm::matrix_entries(&jacobian).iter().all(|x| x.is_finite()) => {
                crate::linalg::Factorization::new(dim, &jacobian, RANK_TOLERANCE).map_or(0, |lu| lu.rank)
            }
            _ => dim.n(),
        }
    }

    /// Whether every sub-step's derivatives serve other problems unchanged.
    pub(super) fn renewable(&self) -> bool {
        self.distinct.iter().all(|e| e.renewable)
    }

    /// Marks which closed-form steps serve a state with scheme momenta `momenta`.
    pub(super) fn set_closed_form(&mut self, momenta: &Dm::Array<f64>) {
        for e in &mut self.distinct {
            e.closed_form = e.serves(momenta);
        }
    }
}
