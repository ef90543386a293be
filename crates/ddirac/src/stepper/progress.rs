//! The arithmetic of a step and what it changes: the state of step k, the predictor, the kept
//! Newton Jacobian, the energy watch and the run's record ([`Progress`]); a step solved in closed form
//! or by Newton's method ([`solve_step`]).

use super::resolution::Resolution;
use super::stages::{Stages, MAX_SUBDIVISION};
use super::{chart_watch, Context, Equipped, FirstStep, OwnedRowIn, StepReport};
use crate::chart::ConfigurationIn;
use crate::compiled::LinearStep;
use crate::diagnostics::{Accumulator, NewtonSummary, Warning, WarningKind, Warnings};
use crate::dim::Dim;
use crate::energy_jump::{Jump, JumpAction, Monitor};
use crate::mechanics::lagrangian::SystemIn;
use crate::mechanics::legendre;
use crate::scheme::Scheme;
use crate::{newton, CoordinateKind, EnergyChange, Error, Method, SingularLegendre, Split};

/// Everything a step changes: the state of step k, the solver's memory and the run's record.
#[derive(Debug)]
pub(super) struct Progress<Dm: Dim> {
    pub(super) k: usize,
    pub(super) config: ConfigurationIn<Dm>,
    /// The scheme momenta (see [`Scheme`]).
    pub(super) momenta: Dm::Array<f64>,
    /// The canonical momenta p_k of the energy watch.
    pub(super) p_now: Dm::Array<f64>,
    /// The solver's memory of each sub-step of a step ([`Stages`]; one for the basic method).
    pub(super) stages: Vec<StageMemory<Dm>>,
    pub(super) monitor: Monitor,
    /// The advances of the angles ([`chart_watch::AngleWatch`]).
    pub(super) angles: chart_watch::AngleWatch<Dm>,
    /// The discrete energy of the last step taken (NaN before the first), for the plausibility
    /// test of the next ([`IMPLAUSIBLE_ENERGY_CHANGE`]).
    pub(super) last_energy: f64,
    pub(super) record: Record<Dm>,
}

/// A solved step whose discrete energy differs from the last step's by more than this fraction of
/// the energy's scale is taken as sub-steps instead: Newton's method converged, but most likely to
/// another root of the step equations (a well-resolved step changes the energy by far less; the
/// paper's runs change it by at most 0.3 % in a step, at their closest pole passages).
pub const IMPLAUSIBLE_ENERGY_CHANGE: f64 = 1e-2;

/// What the solve of one sub-step remembers from step to step: its predictor and kept Jacobian.
#[derive(Debug, Clone)]
pub(super) struct StageMemory<Dm: Dim> {
    pub(super) predictor: Predictor<Dm>,
    pub(super) kept: newton::KeptJacobian<Dm>,
}

/// What the summary reports: statistics since the record started, and the warnings.
#[derive(Debug)]
pub(super) struct Record<Dm: Dim> {
    /// The step k0 and the state (q, p) the record starts from.
    pub(super) start: (usize, Dm::Array<f64>, Dm::Array<f64>),
    /// The momentum map at the start.
    pub(super) j0: Vec<f64>,
    pub(super) max_drift: f64,
    /// The largest |p_i| (or trivialized momentum) of any step: the momentum map's scale.
    pub(super) momentum_scale: f64,
    pub(super) energy: Accumulator,
    pub(super) discrete_energy: Accumulator,
    pub(super) newton: NewtonSummary,
    pub(super) warnings: Warnings,
    /// What the steps resolve, for the test of the Newton tolerance against it.
    pub(super) resolution: Resolution<Dm>,
    /// With [`Method::sensitivities`]: d(q_k, p_k)/d(q_k0, p_k0) in the current chart's coordinates
    /// ([`crate::tangent_map`]); NaN from a step without a tangent map on.
    pub(super) tangent: Option<nalgebra::DMatrix<f64>>,
    /// Room for the product of the run's tangent map with a step's.
    tangent_scratch: Option<nalgebra::DMatrix<f64>>,
    /// Whether the run's tangent map has stopped being finite (and the warning been given).
    tangent_lost: bool,
}

/// `clone_from` reuses the vectors' memory: the stepper of an atlas saves a step's progress into
/// the same place at every step, without allocating.
impl<Dm: Dim> Clone for Progress<Dm> {
    fn clone(&self) -> Self {
        Self {
            k: self.k,
            config: self.config.clone(),
            momenta: self.momenta.clone(),
            p_now: self.p_now.clone(),
            stages: self.stages.clone(),
            monitor: self.monitor.clone(),
            angles: self.angles.clone(),
            last_energy: self.last_energy,
            record: self.record.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.k = source.k;
        self.config.clone_from(&source.config);
        self.momenta.clone_from(&source.momenta);
        self.p_now.clone_from(&source.p_now);
        self.stages.clone_from(&source.stages);
        self.monitor.clone_from(&source.monitor);
        self.angles.clone_from(&source.angles);
        self.last_energy = source.last_energy;
        self.record.clone_from(&source.record);
    }
}

impl<Dm: Dim> Clone for Record<Dm> {
    fn clone(&self) -> Self {
        Self {
            start: self.start.clone(),
            j0: self.j0.clone(),
            max_drift: self.max_drift,
            momentum_scale: self.momentum_scale,
            energy: self.energy,
            discrete_energy: self.discrete_energy,
            newton: self.newton,
            warnings: self.warnings.clone(),
            resolution: self.resolution.clone(),
            tangent: self.tangent.clone(),
            tangent_scratch: None,
            tangent_lost: self.tangent_lost,
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.start.clone_from(&source.start);
        self.j0.clone_from(&source.j0);
        self.max_drift = source.max_drift;
        self.momentum_scale = source.momentum_scale;
        self.energy = source.energy;
        self.discrete_energy = source.discrete_energy;
        self.newton = source.newton;
        self.warnings.0.clone_from(&source.warnings.0);
        self.resolution.clone_from(&source.resolution);
        self.tangent.clone_from(&source.tangent);
        self.tangent_lost = source.tangent_lost;
    }
}

impl<Dm: Dim> Record<Dm> {
    /// With a tangent map: composes the run's with `map`, the tangent map of the `what` ("step",
    /// "chart switch") at `at` = (k, t_k), and warns once if the run's tangent map stops being finite.
    pub(crate) fn compose_tangent(&mut self, map: &nalgebra::DMatrix<f64>, at: (usize, f64), what: &str) {
        let Some(run) = &mut self.tangent else { return };
        // The product goes into the scratch matrix, which then trades places with the run's map.
        let scratch = self.tangent_scratch.get_or_insert_with(|| run.clone());
        crate::tangent_map::multiply(scratch.as_mut_slice(), map.as_slice(), run.as_slice(), run.nrows());
        std::mem::swap(scratch, run);
        // Once lost, the map stays lost (NaN): the warning is given once.
        if !self.tangent_lost && !all_finite(run.as_slice()) {
            self.tangent_lost = true;
            let cause = if map.iter().all(|x| x.is_finite()) {
                "its entries overflowed: the flow stretches some direction by more than 1e308"
            } else if what == "step" {
                "the linearized step equations are singular or not finite here"
            } else {
                "the charts' maps have no derivative here"
            };
            let message = format!(
                "the tangent map of the flow (method.sensitivities) could not be carried through this {what} \
                 ({cause}): sensitivity.state is not finite from here on"
            );
            self.warnings.push(Warning::new(WarningKind::SensitivityLost, Some(at), message));
        }
    }

    /// Folds the momentum map of the scheme's `momenta` into the largest drift, and the momenta `p`
    /// into its scale (the canonical p where the step has them, else the scheme's momenta).
    pub(super) fn drift(&mut self, split: &Split, momenta: &Dm::Array<f64>, p: &Dm::Array<f64>) {
        let j = split.momentum_map(momenta.as_ref());
        self.max_drift = j.zip(&self.j0).fold(self.max_drift, |m, (j, j0)| m.max((j - j0).abs()));
        self.momentum_scale = largest_magnitude(self.momentum_scale, p.as_ref());
    }
}

impl<Dm: Dim> Progress<Dm> {
    /// The row of step k; its energy goes into the record.
    #[inline]
    pub(super) fn row<S: SystemIn<Dm>>(
        &mut self,
        scheme: &impl Scheme<Dm>,
        context: &Context<S, Dm>,
    ) -> OwnedRowIn<Dm> {
        let p = scheme.p_from_momenta(&self.momenta);
        let mut momentum_map = context.dim.array(|_| 0.0);
        momentum_map.as_mut().iter_mut().zip(context.split.momentum_map(p.as_ref())).for_each(|(slot, j)| *slot = j);
        let energy = legendre::hamiltonian_in(context.dim, &context.system, self.config.base(), &p);
        self.record.energy.push(energy);
        OwnedRowIn {
            k: self.k,
            t: self.k as f64 * context.h,
            q: self.config.output(context.wrap_angles),
            p,
            energy,
            discrete_energy: None,
            momentum_map,
            n_g: context.split.n_g(),
            chart: 0,
        }
    }

    /// The increment q_{k+1} − q_k the predictors expect for the next step (the sum over its
    /// sub-steps).
    pub(super) fn predicted_increment(&self, scheme: &impl Scheme<Dm>) -> Dm::Array<f64> {
        let mut sum = Dm::of(&self.momenta).array(|_| 0.0);
        for memory in &self.stages {
            let dq = scheme.increment(&memory.predictor.predict());
            sum.as_mut().iter_mut().zip(dq.as_ref()).for_each(|(s, d)| *s += d);
        }
        sum
    }

    /// Whether `each` holds at every configuration at the end of a sub-step of the step just taken
    /// from `start` (from the unknowns each sub-step's predictor took last); stops at the first
    /// where it does not, and allocates nothing.
    pub(super) fn all_stage_ends(
        &self,
        scheme: &impl Scheme<Dm>,
        start: &Dm::Array<f64>,
        each: &mut dyn FnMut(&Dm::Array<f64>) -> bool,
    ) -> bool {
        let mut at = start.clone();
        self.stages.iter().all(|memory| {
            let dq = scheme.increment(memory.predictor.newest());
            at.as_mut().iter_mut().zip(dq.as_ref()).for_each(|(a, d)| *a += d);
            each(&at)
        })
    }

    /// The progress of a first step from `start` = (k, q, p), with predictor increment `dq` (γ · dq
    /// for a sub-step γh of a step) and kept Jacobian `kept`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn cold(
        scheme: &impl Scheme<Dm>,
        gammas: &[f64],
        kept: &newton::KeptJacobian<Dm>,
        start: (usize, Dm::Array<f64>, Dm::Array<f64>),
        dq: &Dm::Array<f64>,
        kinds: &Dm::Array<CoordinateKind>,
        split: &Split,
        method: &Method,
        warnings: Vec<Warning>,
    ) -> Self {
        let dim = Dm::of(dq);
        let (k, q, p) = start.clone();
        let momenta = scheme.momenta_from_p(&p);
        let mut record = Record {
            start,
            j0: split.momentum_map(p.as_ref()).collect(),
            max_drift: 0.0,
            momentum_scale: 0.0,
            energy: Accumulator::default(),
            discrete_energy: Accumulator::default(),
            newton: NewtonSummary::default(),
            warnings: Warnings(warnings),
            resolution: Resolution::new(dim),
            tangent: method.sensitivities.then(|| nalgebra::DMatrix::identity(2 * dim.n(), 2 * dim.n())),
            tangent_scratch: None,
            tangent_lost: false,
        };
        record.drift(split, &momenta, &p);
        Self {
            k,
            config: ConfigurationIn::new(q, kinds.clone()),
            momenta,
            p_now: p,
            stages: gammas
                .iter()
                .map(|&g| {
                    let dq = dim.array(|i| g * dq[i]);
                    StageMemory { predictor: Predictor::new(dim, scheme.unknowns(&dq)), kept: kept.clone() }
                })
                .collect(),
            monitor: Monitor::new(method.energy_jump),
            angles: chart_watch::AngleWatch::new(kinds),
            last_energy: f64::NAN,
            record,
        }
    }

    /// Takes step k as the sub-steps of `stages`. A failed solve or a non-finite state changes nothing
    /// but the kept Jacobians; an energy jump under [`JumpAction::Fail`] is an error after the step is
    /// taken.
    #[inline]
    pub(super) fn step<S: SystemIn<Dm>, Sc: Scheme<Dm>>(
        &mut self,
        stages: &Stages<Sc, Dm>,
        context: &Context<S, Dm>,
    ) -> Result<StepReport, Error> {
        if stages.sequence.len() == 1 {
            let e = stages.first();
            if let Some(linear) = e.derivatives.linear_step().filter(|_| e.closed_form) {
                if let Some(report) = self.step_closed_form(e, linear, context) {
                    return report;
                }
            }
        }
        self.step_solved(stages, context)
    }

    /// Takes step k by solving its equations (Newton's method, or the closed-form step with Newton's
    /// method as its fall-back) and testing the solution; sub-steps where the solve fails or its
    /// energy is implausible.
    #[inline]
    fn step_solved<S: SystemIn<Dm>, Sc: Scheme<Dm>>(
        &mut self,
        stages: &Stages<Sc, Dm>,
        context: &Context<S, Dm>,
    ) -> Result<StepReport, Error> {
        let taken = if stages.sequence.len() == 1 {
            self.take_basic(stages.first(), context)
        } else {
            self.take_composed(stages, None, context)
        };
        let taken = match taken {
            Ok(taken) => match self.implausible(&taken, context) {
                None => taken,
                Some(failure) => self.subdivide(stages, context, failure, Some(taken))?,
            },
            Err(failure @ (Error::Newton { .. } | Error::Diverged { .. })) => {
                self.subdivide(stages, context, failure, None)?
            }
            Err(e) => return Err(e),
        };
        self.commit(taken, context)
    }

    /// Takes step k by the compiled closed-form step `linear` of the basic method when its solution
    /// passes every test [`Progress::step_solved`] makes of it — Newton's residual test, a finite
    /// state, a plausible energy — with the same arithmetic, so that the step is bit for bit the one
    /// [`Progress::step_solved`] takes. `None` (nothing changed) otherwise: [`Progress::step_solved`]
    /// then solves the step again and deals with it (a fall-back to Newton's method, an error, or
    /// sub-steps). The solution goes from the program's outputs to the new state without the
    /// intermediate records of a solve that may fail.
    #[inline(always)]
    fn step_closed_form<S: SystemIn<Dm>, Sc: Scheme<Dm>>(
        &mut self,
        e: &Equipped<Sc, Dm>,
        linear: &LinearStep<Dm>,
        context: &Context<S, Dm>,
    ) -> Option<Result<StepReport, Error>> {
        let dim = context.dim;
        let base = e.scheme.base(self.config.base());
        let s = linear.solve(&base, &self.momenta);
        // As `solve_step`: Newton's residual test with the momenta's scale.
        let scale = largest_magnitude(0.0, self.momenta.as_ref());
        let residual = s.solves(context.method.newton.threshold(scale))?;
        let z = dim.vector(|i| s.z[i]);
        let dq = e.scheme.increment(&z);
        // As `take_basic` (the momenta and the discrete energy are finite by the residual test).
        if !all_finite(dq.as_ref()) {
            return None;
        }
        let pv = (context.method.energy_jump.action != JumpAction::Ignore).then(|| {
            let p_next = e.scheme.p_from_momenta(&s.momenta_next);
            let pv = pv_sum::<Dm>(&self.p_now, &p_next, &dq);
            (pv, p_next)
        });
        if let Some((pv, _)) = &pv {
            if self.implausible_change(*pv, s.value, context.h).is_some() {
                return None;
            }
        }
        let stats = newton::NewtonStats { iterations: 1, residual, jacobians: 1 };
        let (momenta_next, discrete_energy) = (s.momenta_next, s.value);
        let tangent = sub_step_tangent(e, self.config.base(), &z, None);
        let taken =
            Taken { dq, momenta_next, discrete_energy, pv, stats, fell_back: false, z, composed: None, tangent };
        Some(self.commit(taken, context))
    }

    /// Why a solved step cannot be trusted, if it cannot: its discrete energy (when the energy is
    /// watched) moved from the last step's by more than [`IMPLAUSIBLE_ENERGY_CHANGE`] of its scale.
    #[inline]
    fn implausible<S: SystemIn<Dm>>(&self, taken: &Taken<Dm>, context: &Context<S, Dm>) -> Option<Error> {
        let (pv, _) = taken.pv.as_ref()?;
        let relative = self.implausible_change(*pv, taken.discrete_energy, context.h)?;
        Some(implausible_energy(self.k, context.h, relative))
    }

    /// The change of the discrete energy from the last step's, relative to its scale, of a step with
    /// Σ⟨p̄, Δq⟩ = `pv` and discrete energy `discrete_energy`, if it exceeds
    /// [`IMPLAUSIBLE_ENERGY_CHANGE`].
    #[inline(always)]
    fn implausible_change(&self, pv: f64, discrete_energy: f64, h: f64) -> Option<f64> {
        let (pv, energy) = (pv / h, pv / h - discrete_energy / h);
        let scale = self.last_energy.abs().max(pv.abs());
        let change = (energy - self.last_energy).abs();
        (change > IMPLAUSIBLE_ENERGY_CHANGE * scale).then(|| change / scale)
    }

    /// Takes step k, which failed with `failure` (or was `solved` implausibly), as m = 2, 4, … up to
    /// [`MAX_SUBDIVISION`] equal steps of its stages: each is a step of the same scheme, so the step
    /// stays symplectic and the momentum map exact. The predictors start afresh from the step's
    /// increment. When no subdivision converges: the implausible solution if there is one (the energy
    /// watch then judges it), else `failure` with the subdivisions tried.
    #[cold]
    fn subdivide<S: SystemIn<Dm>, Sc: Scheme<Dm>>(
        &mut self,
        stages: &Stages<Sc, Dm>,
        context: &Context<S, Dm>,
        mut failure: Error,
        solved: Option<Taken<Dm>>,
    ) -> Result<Taken<Dm>, Error> {
        let dim = context.dim;
        let scheme = &stages.first().scheme;
        let predicted = self.predicted_increment(scheme);
        let first =
            FirstStep { q: self.config.clone(), p: scheme.p_from_momenta(&self.momenta), dq: predicted.clone() };
        let mut m = 2;
        while m <= MAX_SUBDIVISION {
            let sub = stages.subdivided(m, &context.method, &first)?;
            let mut memory: Vec<StageMemory<Dm>> = sub
                .sequence
                .iter()
                .zip(&sub.gammas)
                .map(|(&d, g)| {
                    let dq = dim.array(|i| g * predicted[i]);
                    StageMemory {
                        predictor: Predictor::new(dim, sub.distinct[d].scheme.unknowns(&dq)),
                        kept: newton::KeptJacobian::new(dim),
                    }
                })
                .collect();
            let last = m == MAX_SUBDIVISION;
            match self.take_composed(&sub, Some(&mut memory), context) {
                Ok(taken) if !last && self.implausible(&taken, context).is_some() => m *= 2,
                Ok(mut taken) => {
                    for (memory, g) in self.stages.iter_mut().zip(&stages.gammas) {
                        let dq = dim.array(|i| g * taken.dq[i]);
                        memory.predictor = Predictor::new(dim, scheme.unknowns(&dq));
                    }
                    if let Some((_, zs)) = &mut taken.composed {
                        zs.clear();
                    }
                    let (k, t) = (self.k, self.k as f64 * context.h);
                    // Where the chart degenerates, a smaller step only gets through: say so.
                    let chart = singular_chart(context, self.config.base(), &taken.dq);
                    let record = &mut self.record;
                    record.newton.subdivided_steps += 1;
                    record.newton.max_subdivision = record.newton.max_subdivision.max(m);
                    let message = format!("a step failed ({failure}) and was taken as {m} sub-steps");
                    record.warnings.push(Warning::new(WarningKind::Subdivided, Some((k, t)), message));
                    if let Some(cause) = chart {
                        let message = format!(
                            "{cause}: a step was taken as {m} sub-steps there; the trajectory cannot be trusted from \
                             here (use coordinates regular here)"
                        );
                        record.warnings.push(Warning::new(WarningKind::SingularChart, Some((k, t)), message));
                    }
                    return Ok(taken);
                }
                Err(Error::Newton { .. } | Error::Diverged { .. }) => m *= 2,
                Err(e) => return Err(e),
            }
        }
        if let Some(solved) = solved {
            return Ok(solved);
        }
        if let Error::Newton { sub_steps, .. } = &mut failure {
            *sub_steps = Some(MAX_SUBDIVISION);
        }
        Err(failure)
    }

    /// Solves step k as one step of the basic method.
    #[inline(always)]
    fn take_basic<S: SystemIn<Dm>, Sc: Scheme<Dm>>(
        &mut self,
        e: &Equipped<Sc, Dm>,
        context: &Context<S, Dm>,
    ) -> Result<Taken<Dm>, Error> {
        let (k, h) = (self.k, context.h);
        let t = k as f64 * h;
        let memory = &mut self.stages[0];
        let base = e.scheme.base(self.config.base());
        let Solved { z, momenta_next, discrete_energy, stats, fell_back } =
            solve_step(e, &base, &self.momenta, &memory.predictor, &mut memory.kept, &context.method.newton)
                .map_err(|f| newton_failed(context, k, self.config.base(), &e.scheme, &memory.predictor, f))?;
        let dq = e.scheme.increment(&z);
        if !(all_finite(dq.as_ref()) & all_finite(momenta_next.as_ref()) & discrete_energy.is_finite()) {
            return Err(Error::Diverged { step: k, t, h });
        }
        let pv = (context.method.energy_jump.action != JumpAction::Ignore).then(|| {
            let p_next = e.scheme.p_from_momenta(&momenta_next);
            let pv = pv_sum::<Dm>(&self.p_now, &p_next, &dq);
            (pv, p_next)
        });
        let tangent = sub_step_tangent(e, self.config.base(), &z, None);
        Ok(Taken { dq, momenta_next, discrete_energy, pv, stats, fell_back, z, composed: None, tangent })
    }

    /// Solves step k as the sub-steps of a composition, each from where the one before ended, with
    /// the solver memory of each sub-step (`memory`, else the progress's own).
    fn take_composed<S: SystemIn<Dm>, Sc: Scheme<Dm>>(
        &mut self,
        stages: &Stages<Sc, Dm>,
        memory: Option<&mut [StageMemory<Dm>]>,
        context: &Context<S, Dm>,
    ) -> Result<Taken<Dm>, Error> {
        let (k, h) = (self.k, context.h);
        let t = k as f64 * h;
        let watching = context.method.energy_jump.action != JumpAction::Ignore;
        let (mut config, mut momenta, mut p) = (self.config.clone(), self.momenta.clone(), self.p_now.clone());
        let mut dq_step = context.dim.array(|_| 0.0);
        // Σ L_d of the sub-steps (the composed map's generating function) and Σ ⟨p̄, Δq⟩.
        let (mut discrete_energy, mut pv) = (0.0, 0.0);
        let mut stats = newton::NewtonStats::default();
        let mut fell_back = false;
        let mut zs = Vec::with_capacity(stages.sequence.len());
        let mut tangent = None;
        let memories = match memory {
            Some(memory) => memory,
            None => &mut self.stages[..],
        };
        for (memory, &d) in memories.iter_mut().zip(&stages.sequence) {
            let e = &stages.distinct[d];
            let base = e.scheme.base(config.base());
            let solved = solve_step(e, &base, &momenta, &memory.predictor, &mut memory.kept, &context.method.newton)
                .map_err(|f| newton_failed(context, k, config.base(), &e.scheme, &memory.predictor, f))?;
            let dq = e.scheme.increment(&solved.z);
            let finite = dq.as_ref().iter().chain(solved.momenta_next.as_ref()).all(|v| v.is_finite());
            if !finite || !solved.discrete_energy.is_finite() {
                return Err(Error::Diverged { step: k, t, h });
            }
            if watching {
                let p_next = e.scheme.p_from_momenta(&solved.momenta_next);
                pv += pv_sum::<Dm>(&p, &p_next, &dq);
                p = p_next;
            }
            discrete_energy += solved.discrete_energy;
            stats.iterations += solved.stats.iterations;
            stats.jacobians += solved.stats.jacobians;
            stats.residual = stats.residual.max(solved.stats.residual);
            fell_back |= solved.fell_back;
            momenta = solved.momenta_next;
            tangent = sub_step_tangent(e, config.base(), &solved.z, tangent);
            config.advance(&dq);
            dq_step.as_mut().iter_mut().zip(dq.as_ref()).for_each(|(s, d)| *s += d);
            zs.push(solved.z);
        }
        let pv = watching.then_some((pv, p));
        let z = zs[0].clone();
        Ok(Taken {
            dq: dq_step,
            momenta_next: momenta,
            discrete_energy,
            pv,
            stats,
            fell_back,
            z,
            composed: Some((config, zs)),
            tangent,
        })
    }

    /// Commits a solved step: the chart watch, the record, the energy watch, the new state.
    #[inline(always)]
    fn commit<S: SystemIn<Dm>>(&mut self, taken: Taken<Dm>, context: &Context<S, Dm>) -> Result<StepReport, Error> {
        let (method, h, split) = (&context.method, context.h, &context.split);
        let (k, action) = (self.k, method.energy_jump.action);
        let t = k as f64 * h;
        let Taken { dq, momenta_next, discrete_energy, pv, stats, fell_back, z, composed, tangent } = taken;
        if let Some(step) = tangent {
            self.record.compose_tangent(&step, (k, t), "step");
        }
        if let Some(unresolved) = self.angles.watch(&dq) {
            if let Some(warning) = self.fast_angle(context, &dq, unresolved) {
                self.record.warnings.push(warning);
            }
        }
        let record = &mut self.record;
        if Resolution::<Dm>::watches(method.newton.tolerance) {
            record.resolution.push(&dq);
        }
        record.discrete_energy.push(discrete_energy);
        if fell_back {
            let message = "the closed-form step failed its residual test; the step was solved by Newton's method";
            record.warnings.push(Warning::new(WarningKind::NewtonFallback, Some((k, t)), message.into()));
        }
        let canonical = pv.is_some();
        let jump = match pv {
            Some((pv, p_next)) => {
                let pv = pv / h;
                self.last_energy = pv - discrete_energy / h;
                let state = if self.monitor.wants_state_energy() {
                    Some(state_energy(context, &self.config, &composed, &dq, &p_next))
                } else {
                    None
                };
                self.p_now = p_next;
                self.monitor.push((k, t), self.last_energy, pv.abs(), state)
            }
            None => None,
        };
        let jump = jump.map(|jump| {
            let cause = singular_chart(context, self.config.base(), &dq);
            (jump, cause)
        });
        let record = &mut self.record;
        record.newton.total_iterations += stats.iterations;
        record.newton.total_jacobians += stats.jacobians;
        record.newton.max_iterations = record.newton.max_iterations.max(stats.iterations);
        record.newton.max_residual = record.newton.max_residual.max(stats.residual);

        match composed {
            None => {
                self.config.advance(&dq);
                self.stages[0].predictor.push(z);
            }
            Some((config, zs)) => {
                self.config = config;
                self.stages.iter_mut().zip(zs).for_each(|(memory, z)| memory.predictor.push(z));
            }
        }
        self.momenta = momenta_next;
        self.k += 1;
        // The canonical momenta where the energy watch computed them, else the scheme's.
        record.drift(split, &self.momenta, if canonical { &self.p_now } else { &self.momenta });
        if let Some(drift) = self.monitor.take_drift() {
            record.warnings.push(Warning::new(WarningKind::EnergyDrift, Some(drift.at), drift.describe()));
        }
        if let Some((jump, cause)) = jump {
            jumped(jump, cause, action, context.h, &mut record.warnings)?;
        }
        Ok(StepReport { k, discrete_energy, newton: stats })
    }

    /// The warning for an angle whose advance in the step `dq` from q_k the step did not resolve; none
    /// for a soft kick where the Legendre map is regular.
    #[cold]
    fn fast_angle<S: SystemIn<Dm>>(
        &self,
        context: &Context<S, Dm>,
        dq: &Dm::Array<f64>,
        unresolved: chart_watch::Unresolved,
    ) -> Option<Warning> {
        let chart_watch::Unresolved { angle, by, times_typical, soft } = unresolved;
        let singular = singular_chart(context, self.config.base(), dq);
        if soft && singular.is_none() {
            return None;
        }
        let coordinates = context.system.coordinates();
        let name = &coordinates[angle].name;
        let at = Some((self.k, self.k as f64 * context.h));
        let advanced = if soft {
            let times = times_typical.map_or(String::new(), |r| format!(", {r:.1e} times its typical advance"));
            format!(
                "the step does not resolve the motion where the chart is singular (`{name}` advanced by {by:.3e} \
                 rad{times}, its rate changing by more than half within the step)"
            )
        } else if by.abs() > chart_watch::MAX_ANGLE_STEP {
            format!("`{name}` advanced by {by:.3} rad in one step (more than {} rad)", chart_watch::MAX_ANGLE_STEP)
        } else {
            let times = times_typical.map_or(String::new(), |r| format!(", {r:.1e} times its typical advance,"));
            format!(
                "`{name}` advanced by {by:.3e} rad in one step{times} and its rate changed by more than half within \
                 the step"
            )
        };
        Some(match singular {
            Some(cause) => Warning::new(
                WarningKind::SingularChart,
                at,
                format!(
                    "{advanced}; {cause}: the trajectory cannot be trusted from here (use coordinates regular here)"
                ),
            ),
            None => Warning::new(
                WarningKind::UnderResolved,
                at,
                format!("{advanced}: the step does not resolve the motion (try a smaller step)"),
            ),
        })
    }
}

/// H(q_{k+1}, p_{k+1}) of the state a step reached from `config` (by the increment `dq`, or to the
/// configuration of a composed step).
#[cold]
fn state_energy<S: SystemIn<Dm>, Dm: Dim>(
    context: &Context<S, Dm>,
    config: &ConfigurationIn<Dm>,
    composed: &Option<(ConfigurationIn<Dm>, Vec<Dm::Vector>)>,
    dq: &Dm::Array<f64>,
    p_next: &Dm::Array<f64>,
) -> f64 {
    let q_next = match composed {
        Some((reached, _)) => reached.base().clone(),
        None => context.dim.array(|i| config.base()[i] + dq[i]),
    };
    legendre::hamiltonian_in(context.dim, &context.system, &q_next, p_next)
}

/// The chart watch's diagnosis at `q` for the increment `dq` ([`chart_watch::singular_chart`]).
#[cold]
fn singular_chart<S: SystemIn<Dm>, Dm: Dim>(
    context: &Context<S, Dm>,
    q: &Dm::Array<f64>,
    dq: &Dm::Array<f64>,
) -> Option<SingularLegendre> {
    let v = context.dim.array(|i| dq[i] / context.h);
    chart_watch::singular_chart(&context.system, context.legendre_at_start, q, &v)
}

/// A jump of the energy as the method asks: an error, or a warning.
#[cold]
pub(super) fn jumped(
    jump: Jump,
    cause: Option<SingularLegendre>,
    action: JumpAction,
    h: f64,
    warnings: &mut Warnings,
) -> Result<(), Error> {
    if action == JumpAction::Fail {
        let (step, t) = jump.at;
        return Err(Error::EnergyJump { step, t, h, change: EnergyChange::Jumped(jump), singular: cause });
    }
    let message = match cause {
        Some(cause) => format!("{}; {cause}", jump.describe()),
        None => jump.describe(),
    };
    warnings.push(Warning::new(WarningKind::EnergyJump, Some(jump.at), message));
    Ok(())
}

/// A step solved but not yet taken: the increment of the configuration, the next momenta, the
/// discrete energy (Σ L_d of the sub-steps), Σ⟨p̄, Δq⟩ with the next canonical momenta when the energy
/// is watched, how the solves went, the unknowns (of the first sub-step) and, for a composition, the
/// configuration it reached with each sub-step's unknowns.
struct Taken<Dm: Dim> {
    dq: Dm::Array<f64>,
    momenta_next: Dm::Array<f64>,
    discrete_energy: f64,
    pv: Option<(f64, Dm::Array<f64>)>,
    stats: newton::NewtonStats,
    fell_back: bool,
    z: Dm::Vector,
    composed: Option<(ConfigurationIn<Dm>, Vec<Dm::Vector>)>,
    /// With [`Method::sensitivities`]: the step's tangent map in (q, p) (NaN where a sub-step has none).
    tangent: Option<nalgebra::DMatrix<f64>>,
}

/// With [`Method::sensitivities`], the tangent map of a sub-step of `e` from chart base `q`
/// solved by `z`, after the tangent map `before` of the step's earlier sub-steps (NaN where a
/// sub-step has none); `None` otherwise.
fn sub_step_tangent<Sc: Scheme<Dm>, Dm: Dim>(
    e: &Equipped<Sc, Dm>,
    q: &Dm::Array<f64>,
    z: &Dm::Vector,
    before: Option<nalgebra::DMatrix<f64>>,
) -> Option<nalgebra::DMatrix<f64>> {
    Some(e.tangent.as_ref()?.step(&e.scheme, q, z, before))
}

/// The largest of `start` (not NaN) and the |v| of `values`, NaN entries skipped: the fold of
/// `f64::max` over them, in one comparison per entry.
#[inline(always)]
pub(super) fn largest_magnitude(start: f64, values: &[f64]) -> f64 {
    values.iter().fold(start, |m, v| if v.abs() > m { v.abs() } else { m })
}

/// Whether every entry is finite, without a branch per entry.
#[inline(always)]
fn all_finite(values: &[f64]) -> bool {
    values.iter().fold(true, |all, v| all & v.is_finite())
}

/// ½ Σ (p0 + p1) · dq: ⟨p̄, Δq⟩ of a step from p0 to p1.
#[inline(always)]
fn pv_sum<Dm: Dim>(p0: &Dm::Array<f64>, p1: &Dm::Array<f64>, dq: &Dm::Array<f64>) -> f64 {
    p0.as_ref().iter().zip(p1.as_ref()).zip(dq.as_ref()).map(|((p0, p1), d)| (p0 + p1) * d).sum::<f64>() * 0.5
}

/// The failure of a step whose discrete energy moved by `relative` of its scale.
#[cold]
fn implausible_energy(k: usize, h: f64, relative: f64) -> Error {
    let change = EnergyChange::Implausible { relative, limit: IMPLAUSIBLE_ENERGY_CHANGE };
    Error::EnergyJump { step: k, t: k as f64 * h, h, change, singular: None }
}

/// The error of a failed solve at step k from `q`, with the chart watch's diagnosis at the
/// predicted increment.
#[cold]
fn newton_failed<S: SystemIn<Dm>, Sc: Scheme<Dm>, Dm: Dim>(
    context: &Context<S, Dm>,
    k: usize,
    q: &Dm::Array<f64>,
    scheme: &Sc,
    predictor: &Predictor<Dm>,
    f: newton::NewtonFailure,
) -> Error {
    let predicted = scheme.increment(&predictor.predict());
    let singular = singular_chart(context, q, &predicted);
    let (h, t) = (context.h, k as f64 * context.h);
    let (iterations, residual, reason) = (f.iterations, f.residual, f.reason);
    Error::Newton { step: k, t, h, iterations, residual, reason, singular, sub_steps: None }
}

/// A solved step: its unknowns, the momenta and discrete energy they give, and how the solve went.
struct Solved<Dm: Dim> {
    z: Dm::Vector,
    momenta_next: Dm::Array<f64>,
    discrete_energy: f64,
    stats: newton::NewtonStats,
    /// Whether the closed-form step failed its test and Newton's method solved the step.
    fell_back: bool,
}

/// Solves one step's equations for the unknowns z: by the compiled closed-form step when the run
/// has one and it passes Newton's residual test, otherwise by Newton's method from the closed-form
/// solution if it failed the test, or from the predictor.
#[inline]
fn solve_step<Sc: Scheme<Dm>, Dm: Dim>(
    e: &Equipped<Sc, Dm>,
    base: &Dm::Array<f64>,
    momenta: &Dm::Array<f64>,
    predictor: &Predictor<Dm>,
    kept: &mut newton::KeptJacobian<Dm>,
    options: &newton::NewtonOptions,
) -> Result<Solved<Dm>, newton::NewtonFailure> {
    let Equipped { scheme, equations, derivatives, .. } = e;
    let dim = predictor.dim;
    let scale = largest_magnitude(0.0, momenta.as_ref());
    let closed_form = derivatives.linear_step().filter(|_| e.closed_form).map(|l| l.solve(base, momenta));
    let fell_back = closed_form.is_some();
    let mut z = match closed_form {
        Some(s) => {
            if let Some(residual) = s.solves(options.threshold(scale)) {
                let stats = newton::NewtonStats { iterations: 1, residual, jacobians: 1 };
                let (z, momenta_next, discrete_energy) = (dim.vector(|i| s.z[i]), s.momenta_next, s.value);
                return Ok(Solved { z, momenta_next, discrete_energy, stats, fell_back: false });
            }
            if s.z.as_ref().iter().all(|v| v.is_finite()) {
                dim.vector(|i| s.z[i])
            } else {
                predictor.predict()
            }
        }
        None => predictor.predict(),
    };
    // Only the by-products are kept from each evaluation: the Jacobian goes straight to the solver
    // (copying an N × N block per evaluation showed as 7 % of a chain of 8's step).
    let mut last = None;
    let stats = newton::solve_in(dim, &mut z, scale, options, kept, |z, with_jacobian| {
        let (d, mixed) = derivatives.first_or_mixed(scheme, base, z, with_jacobian);
        let e = equations.evaluate(momenta, &d);
        last = Some((e.momenta_next, e.discrete_energy));
        (e.residual, mixed)
    })?;
    let (momenta_next, discrete_energy) = last.expect("Newton evaluates at least once");
    Ok(Solved { z, momenta_next, discrete_energy, stats, fell_back })
}

/// Where a step's Newton iteration starts: the unknowns of the previous steps extrapolated
/// quadratically from the last three (linearly after two, the last one after one), and a first guess
/// before any.
#[derive(Debug, Clone)]
pub(super) struct Predictor<Dm: Dim> {
    dim: Dm,
    /// The last three unknowns, a ring: the newest at `newest`, the older ones after it (cyclically).
    last: [Dm::Vector; 3],
    newest: usize,
    count: usize,
}

impl<Dm: Dim> Predictor<Dm> {
    fn new(dim: Dm, first: Dm::Vector) -> Self {
        Self { dim, last: [first.clone(), first.clone(), first], newest: 0, count: 0 }
    }

    /// Takes the unknowns of a step: they overwrite the oldest, which becomes the newest (no copies of
    /// the others).
    #[inline]
    fn push(&mut self, z: Dm::Vector) {
        self.newest = if self.newest == 0 { 2 } else { self.newest - 1 };
        self.last[self.newest] = z;
        self.count += 1;
    }

    /// The unknowns taken last.
    pub(super) fn newest(&self) -> &Dm::Vector {
        &self.last[self.newest]
    }

    pub(super) fn predict(&self) -> Dm::Vector {
        let at = |age: usize| &self.last[(self.newest + age) % 3];
        let (z, z1, z2) = (at(0), at(1), at(2));
        match self.count {
            0 | 1 => z.clone(),
            2 => self.dim.vector(|i| 2.0 * z[i] - z1[i]),
            _ => self.dim.vector(|i| 3.0 * (z[i] - z1[i]) + z2[i]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dim::Fixed;
    use nalgebra::SVector;

    /// The predictor reproduces polynomials of the degree it extrapolates with: constant after one
    /// step, linear after two, quadratic from three on.
    #[test]
    fn predictor_is_exact_for_polynomials_of_its_degree() {
        let polynomial = |degree: i32, k: f64| SVector::<f64, 2>::new(k.powi(degree) - 2.0 * k, 0.5 * k.powi(degree));
        for (count, degree) in [(1, 0), (2, 1), (3, 2), (6, 2)] {
            let mut predictor = Predictor::new(Fixed::<2>, SVector::zeros());
            for k in 0..count {
                let z = if degree == 0 { SVector::repeat(3.0) } else { polynomial(degree, k as f64) };
                predictor.push(z);
            }
            let expected = if degree == 0 { SVector::repeat(3.0) } else { polynomial(degree, count as f64) };
            let error = (predictor.predict() - expected).amax();
            assert!(error < 1e-12 * (1.0 + expected.amax()), "{count} steps, degree {degree}: error {error:e}");
        }
    }
}
