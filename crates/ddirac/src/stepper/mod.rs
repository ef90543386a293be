//! The stepper: a run one step at a time, with a state to save and to restart from.
//!
//! Each step k solves the chosen scheme's equations for chart-local unknowns z (increments, and γ_k
//! for the reduced schemes) by Newton's method from a predictor (the previous steps' unknowns,
//! extrapolated quadratically from the last three, linearly after two; on the first step h · v0
//! from the Legendre transform), then advances the configuration and the momenta. [`Stepper`] owns
//! the predictor, the Newton solve, the chart, the diagnostics and the failure reporting;
//! [`crate::integrate`] and [`crate::solve`] are loops over it.
//!
//! Everything a step changes lives in one place (the stepper's progress), and [`Stepper::state`]
//! copies all of it: a stepper restarted from a state continues bit for bit as the stepper it was
//! taken from.

mod atlas;
mod chart_watch;
mod progress;
mod resolution;
mod row;
mod stages;
mod state;

use std::time::Instant;

use crate::chart::ConfigurationIn;
use crate::diagnostics::{DerivativePath, MomentumMapDrift, OutputError, Row, Summary, Warning, WarningKind};
use crate::dim::Dim;
use crate::mechanics::dirac::LagrangeDirac;
use crate::mechanics::lagrangian::SystemIn;
use crate::mechanics::legendre;
use crate::reduction::reduced::LagrangePoincareDirac;
use crate::reduction::reduced_lagrangian::ReducedLagrangian;
use crate::scheme::{Scheme, StepDerivatives, StepEquations};
use crate::setup::{first_increment, Setup};
use crate::{newton, Connection, CoordinateKind, DiscreteLagrangian, Error, Input, Method, Problem, Split};

pub use atlas::{Stepper, StepperIn};
pub use chart_watch::{KICK, LEGENDRE_DROP, MAX_ANGLE_STEP, SOFT_KICK};
pub use progress::IMPLAUSIBLE_ENERGY_CHANGE;
use progress::{jumped, Progress};
pub use resolution::LOOSE_TOLERANCE_MARGIN;
pub use row::{OwnedRow, OwnedRowIn, StepReport};
use stages::Stages;
pub use stages::MAX_SUBDIVISION;
use state::Memory;
pub use state::{State, StateIn};

/// How many steps a run takes between two calls of its watch ([`crate::integrate_watched`],
/// `run_to_end`): a call every 64 steps costs nothing measurable, and 64 of the slowest steps the engine
/// takes (a few milliseconds, a chain of 50 pendula with dual numbers) are a fraction of a second.
pub const WATCH_STEPS: usize = 64;

/// A run in one chart of the system's atlas ([`crate::atlas::InChart`]): what [`Stepper`] does between chart
/// switches, and all of a run without them.
pub(crate) struct ChartStepper<S, Dm: Dim> {
    context: Context<S, Dm>,
    schemes: Schemes<S, Dm>,
    derivative_path: DerivativePath,
    /// The Jacobian memory of a first step: none kept, with the relative cost of the derivatives.
    fresh_kept: newton::KeptJacobian<Dm>,
    /// The warnings of the check before the first step, with which every record starts.
    check_warnings: Vec<Warning>,
    started: Instant,
    progress: Progress<Dm>,
}

/// The schemes of a run's sub-steps with their step equations and derivatives: unreduced or reduced.
enum Schemes<S, Dm: Dim> {
    Unreduced(Stages<LagrangeDirac<S, Dm>, Dm>),
    Reduced(Stages<LagrangePoincareDirac<S, Dm>, Dm>),
}

struct Equipped<Sc, Dm: Dim> {
    scheme: Sc,
    equations: StepEquations<Dm>,
    derivatives: StepDerivatives<Dm>,
    /// The scheme momenta the derivatives were prepared with: a compiled closed-form step holds the
    /// conserved ones (μ) as constants.
    prepared: Dm::Array<f64>,
    /// Whether the closed-form step, if there is one, serves the current state: its conserved
    /// momenta are those it was prepared with.
    closed_form: bool,
    /// Whether the derivatives serve other problems unchanged ([`Stepper::renew`]).
    renewable: bool,
    /// With [`Method::sensitivities`]: how the tangent map takes the generating function's Hessian
    /// (compiled when the derivatives are).
    tangent: Option<crate::tangent_map::StepTangent>,
}

/// `$body` with `$e` bound to the run's [`Stages`], whichever scheme they are of.
macro_rules! equipped {
    ($schemes:expr, $e:ident => $body:expr) => {
        match $schemes {
            Schemes::Unreduced($e) => $body,
            Schemes::Reduced($e) => $body,
        }
    };
}

/// What the steps and rows of a stepper read but do not change.
struct Context<S, Dm: Dim> {
    system: S,
    dim: Dm,
    method: Method,
    h: f64,
    steps: usize,
    split: Split,
    kinds: Dm::Array<CoordinateKind>,
    wrap_angles: bool,
    /// The Legendre map's pivot ratio at the start of the run ([`legendre::conditioning`]), what the
    /// chart watch compares with.
    legendre_at_start: f64,
}

impl<S: SystemIn<Dm> + Clone, Dm: Dim> ChartStepper<S, Dm> {
    /// Checks `problem` and `method` for `system` as [`crate::integrate`] does, and prepares the
    /// first step: an error for input that a run refuses, or for a hypothesis that fails
    /// ([`crate::CheckReport::verdict`]; the warnings it allows go into the summary). With
    /// `hypotheses` off the hypotheses are taken as tested (a chart of an atlas, whose hypotheses the
    /// run tested over its whole domain before its first step).
    pub fn new(system: S, problem: &Problem, method: &Method, hypotheses: bool) -> Result<Self, Error> {
        let dim = system.dim();
        let setup = Setup::new(&system, problem, method)?;
        let check_warnings =
            if hypotheses { crate::check::findings(&system, problem, method, &setup).verdict(method)? } else { vec![] };
        let coordinates = system.coordinates();
        let kinds = dim.array(|i| coordinates[i].kind);
        let (h, steps) = (problem.step, problem.steps);
        let v0 = dim.array(|i| setup.dq0[i] / h);
        let legendre_at_start = legendre::conditioning_in(dim, &system, &setup.q0, &v0).0;
        let started = Instant::now();
        let (start, warnings) = ((0, setup.q0.clone(), setup.p0.clone()), check_warnings.clone());
        let first = FirstStep {
            q: ConfigurationIn::new(setup.q0.clone(), kinds.clone()),
            p: setup.p0.clone(),
            dq: setup.dq0.clone(),
        };
        let (schemes, derivative_path) = if method.reduced {
            let scheme = |step| -> Result<_, Error> {
                let reduction = ReducedLagrangian::new(system.clone(), method.rule, step, setup.connection.clone())?;
                Ok(LagrangePoincareDirac::new(dim, reduction, method.variant))
            };
            let (stages, path) = Stages::new(method, h, steps, &first, scheme)?;
            (Schemes::Reduced(stages), path)
        } else {
            let scheme =
                |step| Ok(LagrangeDirac { ld: DiscreteLagrangian::new(system.clone(), method.rule, step), dim });
            let (stages, path) = Stages::new(method, h, steps, &first, scheme)?;
            (Schemes::Unreduced(stages), path)
        };
        let rank = equipped!(&schemes, st => st.first_step_rank(&first));
        if rank < dim.n() {
            // The reduced unknowns are sheared by K (g1 − g0 = γ + K (x1 − x0)), which multiplies the
            // condition of the Jacobian by about |K|⁴: when K = 0 determines the motion, K is the cause.
            let k = &setup.connection;
            if method.reduced && !k.is_zero() {
                let flat = Connection::zero(k.n_x(), k.n_g());
                let scheme = |step| -> Result<_, Error> {
                    let reduction = ReducedLagrangian::new(system.clone(), method.rule, step, flat.clone())?;
                    Ok(LagrangePoincareDirac::new(dim, reduction, method.variant))
                };
                let stages = Stages::new(method, h, steps, &first, scheme);
                if stages.is_ok_and(|(stages, _)| stages.first_step_rank(&first) == dim.n()) {
                    let largest = k.matrix().amax();
                    return Err(Error::Invalid {
                        what: Input::Connection,
                        why: crate::Reason::SingularInFloatingPoint { largest, rank, coordinates: dim.n() },
                    });
                }
            }
            return Err(Error::Undetermined { rank, coordinates: dim.n() });
        }
        let fresh_kept = match derivative_path {
            DerivativePath::Compiled { residual, jacobian, .. } => {
                newton::KeptJacobian::with_relative_cost(newton::compiled_relative_cost(dim.n(), residual, jacobian))
            }
            DerivativePath::Dual { .. } => newton::KeptJacobian::new(dim),
        };
        let mut progress = equipped!(&schemes, st => Progress::cold(
            &st.first().scheme, &st.gammas, &fresh_kept, start, &setup.dq0, &kinds, &setup.split, method, warnings
        ));
        progress.monitor.set_window(steps);
        Ok(Self {
            context: Context {
                system,
                dim,
                method: method.clone(),
                h,
                steps,
                split: setup.split,
                kinds,
                wrap_angles: false,
                legendre_at_start,
            },
            schemes,
            derivative_path,
            fresh_kept,
            check_warnings,
            started,
            progress,
        })
    }

    /// Adds the warnings of hypotheses tested beyond this chart (the atlas's) to those the run's
    /// record starts with.
    fn add_check_warnings(&mut self, warnings: Vec<Warning>) {
        for warning in warnings {
            self.check_warnings.push(warning.clone());
            self.progress.record.warnings.push(warning);
        }
    }

    /// The increment q_{k+1} − q_k the predictor expects for the next step (the sum over its
    /// sub-steps).
    fn predicted_increment(&self) -> Dm::Array<f64> {
        equipped!(&self.schemes, e => self.progress.predicted_increment(&e.first().scheme))
    }

    /// Whether `each` holds at the end of every sub-step of the step just taken from `start`.
    fn all_stage_ends(&self, start: &Dm::Array<f64>, each: &mut dyn FnMut(&Dm::Array<f64>) -> bool) -> bool {
        equipped!(&self.schemes, e => self.progress.all_stage_ends(&e.first().scheme, start, each))
    }

    /// The canonical momenta p_k.
    fn p(&self) -> Dm::Array<f64> {
        equipped!(&self.schemes, e => e.first().scheme.p_from_momenta(&self.progress.momenta))
    }

    /// Report angles wrapped to (−π, π] (in [`Stepper::row`] and the summary's final q) instead of
    /// continuous; the default is continuous.
    pub fn set_wrap_angles(&mut self, wrap: bool) {
        self.context.wrap_angles = wrap;
    }

    /// The current step index k.
    pub fn k(&self) -> usize {
        self.progress.k
    }

    /// The current time t_k = k h.
    pub fn t(&self) -> f64 {
        self.progress.k as f64 * self.context.h
    }

    /// Whether all N steps are taken.
    pub fn is_finished(&self) -> bool {
        self.progress.k >= self.context.steps
    }

    /// Takes step k → k + 1: solves the step equations, checks the new state, watches the energy.
    ///
    /// Returns [`Error::Interrupted`] when a stop was requested ([`crate::interrupt`]) and an error
    /// when the run is finished, Newton's method fails, the state becomes non-finite or the energy
    /// jumps under [`crate::JumpAction::Fail`]. A failed solve or a non-finite state leaves the
    /// stepper at step k (only its kept Newton Jacobian is dropped; restarting from a saved state
    /// retries the step bit for bit); an energy jump is reported once the step that shows it is taken.
    #[inline]
    pub fn step(&mut self) -> Result<StepReport, Error> {
        if self.is_finished() {
            return Err(Error::Invalid {
                what: Input::Steps,
                why: crate::Reason::Finished { steps: self.context.steps },
            });
        }
        if crate::interrupt::requested() {
            return Err(Error::Interrupted { step: self.k(), t: self.t() });
        }
        equipped!(&self.schemes, e => self.progress.step(e, &self.context))
    }

    /// The row of the current step k: q_k, p_k, the Hamiltonian and the momentum map (the discrete
    /// energy of step k is known once it is taken: [`StepReport::discrete_energy`]). The summary's
    /// energy statistics are over the rows taken.
    pub fn row(&mut self) -> OwnedRowIn<Dm> {
        equipped!(&self.schemes, e => self.progress.row(&e.first().scheme, &self.context))
    }

    /// Steps to the end, handing the rows of every `every`-th step and of the last to `observer`
    /// (what [`crate::integrate`] reports), each with the discrete energy of its step. The same
    /// steps and rows as [`Stepper::step`] and [`Stepper::row`], without choosing the scheme at each
    /// step. `watch` is called with k every [`crate::WATCH_STEPS`] steps (from k = 0). After an error
    /// the stepper stays at the step that failed, as after [`Stepper::step`].
    pub fn run_to_end(
        &mut self,
        every: usize,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
        watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
    ) -> Result<(), Error> {
        let (context, progress) = (&self.context, &mut self.progress);
        equipped!(&self.schemes, e => {
            let mut until_report = 0;
            let mut until_watch = 0;
            while progress.k < context.steps {
                if crate::interrupt::requested() {
                    return Err(Error::Interrupted { step: progress.k, t: progress.k as f64 * context.h });
                }
                if until_watch == 0 {
                    watch(progress.k).map_err(Error::Output)?;
                    until_watch = WATCH_STEPS;
                }
                until_watch -= 1;
                // The row of step k carries L_d(q_k, q_{k+1}): it is taken before the step, reported
                // after it.
                let row = (until_report == 0).then(|| progress.row(&e.first().scheme, context));
                until_report = if until_report == 0 { every - 1 } else { until_report - 1 };
                let step = progress.step(e, context)?;
                if let Some(mut row) = row {
                    row.discrete_energy = Some(step.discrete_energy);
                    observer(&row.as_row()).map_err(Error::Output)?;
                }
            }
            observer(&progress.row(&e.first().scheme, context).as_row()).map_err(Error::Output)
        })
    }

    /// The state of step k, with all that a stepper of the same system, method and step needs to
    /// continue from it bit for bit.
    pub fn state(&self) -> StateIn<Dm> {
        let progress = &self.progress;
        let p = equipped!(&self.schemes, e => e.first().scheme.p_from_momenta(&progress.momenta));
        let (method, h) = (self.context.method.clone(), self.context.h);
        let (chart, near) = (0, progress.config.unwrapped());
        let memory = Memory { method, h, progress: progress.clone(), chart, glued: false, near };
        StateIn { k: progress.k, q: progress.config.unwrapped(), p, memory: Some(Box::new(memory)) }
    }

    /// Continues from `state`: from a state taken from a stepper of the same system, method and step
    /// exactly as that stepper would have continued (its record too, so that the summary covers the
    /// whole run); from a cold state as on a first step from (q, p), with a new record. The
    /// derivatives prepared by [`Stepper::new`] are kept. A compiled closed-form step holds the
    /// conserved momenta μ of the problem as constants: from a state with another μ the steps are
    /// solved by Newton's method on the same equations instead.
    ///
    /// An error for a state beyond the problem's last step, a warm state from another method or
    /// step (restart from its [`State::cold`] form instead), or a cold state with a non-finite
    /// entry or, for a degenerate Lagrangian, with p off the primary constraint p = ∂L/∂v. The other
    /// hypotheses [`Stepper::new`] tested near the problem's initial data (invariance, periodicity)
    /// are not tested again for a cold state.
    pub fn restart(&mut self, state: &StateIn<Dm>) -> Result<(), Error> {
        if state.k > self.context.steps {
            let why = crate::Reason::BeyondLastStep { step: state.k, last: self.context.steps };
            return Err(Error::Invalid { what: Input::State, why });
        }
        if let Some(memory) = &state.memory {
            if memory.method != self.context.method || memory.h.to_bits() != self.context.h.to_bits() {
                return Err(Error::Invalid { what: Input::State, why: crate::Reason::AnotherMethod });
            }
            self.progress = memory.progress.clone();
            equipped!(&mut self.schemes, e => e.set_closed_form(&self.progress.momenta));
            return Ok(());
        }
        let (q, p) = (state.q.as_ref(), state.p.as_ref());
        if let Some((i, &value)) = q.iter().chain(p).enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(Error::NonFinite { what: Input::State, entry: Some(i), value });
        }
        let (system, dim) = (&self.context.system, self.context.dim);
        let (v, mismatch) = legendre::velocity_in(dim, system, &state.q, &state.p);
        let scale = p.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if mismatch > crate::CONSTRAINT_TOLERANCE * (1.0 + scale) {
            let rank = legendre::rank_in(dim, system, &state.q, &v);
            if rank < dim.n() {
                return Err(Error::OffPrimaryConstraint { rank, coordinates: dim.n(), mismatch });
            }
        }
        let dq = first_increment::<Dm>(&v, self.context.h);
        let start = (state.k, state.q.clone(), state.p.clone());
        let warnings = self.check_warnings.clone();
        let (kinds, split, method) = (&self.context.kinds, &self.context.split, &self.context.method);
        let mut progress = equipped!(&self.schemes, e => Progress::cold(&e.first().scheme, &e.gammas, &self.fresh_kept, start, &dq, kinds, split, method, warnings));
        progress.monitor.set_window(self.context.steps - state.k);
        self.progress = progress;
        equipped!(&mut self.schemes, e => e.set_closed_form(&self.progress.momenta));
        Ok(())
    }

    /// Prepares this stepper for `problem` as [`Stepper::new`] prepares a new stepper of the same
    /// system and method, keeping the derivatives when they serve the problem unchanged (an
    /// ensemble's members that differ in initial data trace and compile once): `Ok(true)` then, and
    /// the run that follows is that of a new stepper, bit for bit. `Ok(false)` when a new stepper
    /// might differ — another step size or number of steps, a compiled closed-form step (it holds the
    /// first step's conserved momenta), a trace with guards, compiled programs that fail their check
    /// against dual numbers at the new first step, dual numbers chosen at the first step — and the
    /// caller makes a new stepper. An error is the one [`Stepper::new`] gives for `problem` (its input
    /// and the check of the method's hypotheses near its initial data are tested anew).
    pub fn renew(&mut self, problem: &Problem) -> Result<bool, Error> {
        let (h, steps) = (problem.step, problem.steps);
        let renewable = equipped!(&self.schemes, e => e.renewable());
        if h.to_bits() != self.context.h.to_bits() || steps != self.context.steps || !renewable {
            return Ok(false);
        }
        let (system, method) = (&self.context.system, &self.context.method);
        let setup = Setup::new(system, problem, method)?;
        let check_warnings = crate::check::findings(system, problem, method, &setup).verdict(method)?;
        let started = Instant::now();
        let dim = self.context.dim;
        let v0 = dim.array(|i| setup.dq0[i] / h);
        let legendre_at_start = legendre::conditioning_in(dim, system, &setup.q0, &v0).0;
        let (kinds, split) = (&self.context.kinds, &self.context.split);
        let (start, warnings) = ((0, setup.q0.clone(), setup.p0.clone()), check_warnings.clone());
        let mut progress = equipped!(&self.schemes, e => Progress::cold(&e.first().scheme, &e.gammas, &self.fresh_kept, start, &setup.dq0, kinds, split, method, warnings));
        progress.monitor.set_window(steps);
        let serve = equipped!(&self.schemes, e => e.sequence.iter().zip(&progress.stages).all(|(&d, memory)| {
            let e = &e.distinct[d];
            let predicted = memory.predictor.predict();
            let z = dim.array(|i| predicted[i]);
            e.derivatives.serve_first_step(&e.scheme, &e.scheme.base(progress.config.base()), &z)
        }));
        if !serve {
            return Ok(false);
        }
        self.progress = progress;
        self.check_warnings = check_warnings;
        self.context.legendre_at_start = legendre_at_start;
        self.started = started;
        Ok(true)
    }

    /// What [`Stepper::finish`] gives, leaving the stepper to be renewed ([`Stepper::renew`]) or
    /// restarted.
    pub fn summary(&mut self) -> Result<Summary, Error> {
        let progress = &self.progress;
        let (k, config, momenta) = (progress.k, &progress.config, &progress.momenta);
        let (mut monitor, mut record) = (progress.monitor.clone(), progress.record.clone());
        if let Some(jump) = monitor.finish() {
            jumped(jump, None, self.context.method.energy_jump.action, self.context.h, &mut record.warnings)?;
        }
        let method = &self.context.method;
        if let Some(message) = record.resolution.loose(method.newton.tolerance, method.composition.order()) {
            record.warnings.push(Warning::new(WarningKind::LooseTolerance, None, message));
        }
        let final_q = config.output(self.context.wrap_angles).as_ref().to_vec();
        let final_p = equipped!(&self.schemes, e => e.first().scheme.p_from_momenta(momenta)).as_ref().to_vec();
        let (k0, q0, p0) = &record.start;
        let reference_error =
            self.context.system.exact_solution(q0, p0, (k - k0) as f64 * self.context.h).and_then(|exact| {
                let unwrapped = config.unwrapped();
                reference_error(exact.as_ref(), unwrapped.as_ref())
            });
        let j_scale = record.j0.iter().fold(record.momentum_scale, |m, v| m.max(v.abs()));
        Ok(Summary {
            coordinates: self.context.system.coordinates().as_ref().iter().map(|c| c.name.clone()).collect(),
            steps: k - k0,
            step: self.context.h,
            final_q,
            final_p,
            energy: record.energy.stats(),
            discrete_energy: record.discrete_energy.stats(),
            momentum_map: MomentumMapDrift {
                max_relative_drift: (j_scale > 0.0).then(|| record.max_drift / j_scale),
                initial: record.j0.clone(),
                max_drift: record.max_drift,
                scale: j_scale,
            },
            newton: record.newton,
            derivatives: self.derivative_path.clone(),
            wall_seconds: self.started.elapsed().as_secs_f64(),
            reference_error,
            chart_switches: 0,
            warnings: record.warnings.0,
            sensitivity: record.tangent.as_ref().map(rows),
        })
    }
}

/// The first step of a run, at which its derivatives are prepared and checked.
struct FirstStep<Dm: Dim> {
    q: ConfigurationIn<Dm>,
    p: Dm::Array<f64>,
    /// The predictor's increment h · v0.
    dq: Dm::Array<f64>,
}

impl<Sc: Scheme<Dm>, Dm: Dim> Equipped<Sc, Dm> {
    /// The scheme of a sub-step γh with its equations and the derivatives of its generating function,
    /// prepared for `steps` evaluations at the `first` step (with the predictor's increment γ · dq).
    fn new(
        scheme: Sc,
        method: &Method,
        steps: usize,
        first: &FirstStep<Dm>,
        gamma: f64,
    ) -> Result<(Self, DerivativePath), Error> {
        // γ = 1 gives the increment itself, bit for bit.
        let dim = Dm::of(&first.dq);
        let dq = dim.array(|i| gamma * first.dq[i]);
        let momenta = scheme.momenta_from_p(&first.p);
        let base = scheme.base(first.q.base());
        let prepare = |dq: &Dm::Array<f64>| {
            let z = scheme.unknowns(dq);
            StepDerivatives::new(&scheme, method.differentiation, steps, &base, &dim.array(|i| z[i]), &momenta)
        };
        // A long step's predicted point may leave the chart's domain (the disc of a hemisphere's
        // projection) where the step itself, solved by Newton's method or subdivided, does not: the
        // derivatives are then prepared at the step's start (a zero increment), a point of the domain.
        let (derivatives, path) = prepare(&dq)
            .or_else(|e| {
                if dq.as_ref().iter().any(|d| *d != 0.0) {
                    prepare(&dim.array(|_| 0.0)).map_err(|_| e)
                } else {
                    Err(e)
                }
            })
            .map_err(Error::NotCompiled)?;
        let (equations, prepared) = (scheme.equations(), momenta);
        let renewable = derivatives.independent_of_first_step(method.differentiation, steps);
        let tangent = method.sensitivities.then(|| {
            let hessian = match &derivatives {
                StepDerivatives::Compiled { .. } => {
                    let z = scheme.unknowns(&dq);
                    crate::tangent_map::Hessian::compiled(&scheme, &base, &dim.array(|i| z[i]))
                }
                StepDerivatives::Dual => crate::tangent_map::Hessian::Dual,
            };
            crate::tangent_map::StepTangent::new(&scheme, dim, hessian)
        });
        Ok((Self { equations, scheme, derivatives, prepared, closed_form: true, renewable, tangent }, path))
    }

    /// The scheme of another sub-step with `derivatives` shared from the scheme `other` prepared
    /// ([`StepDerivatives::for_step`]: the same programs with the other sub-step's h).
    fn sharing(other: &Self, scheme: Sc, derivatives: StepDerivatives<Dm>, first: &FirstStep<Dm>, step: f64) -> Self {
        let (equations, prepared) = (scheme.equations(), scheme.momenta_from_p(&first.p));
        let tangent = other.tangent.as_ref().map(|t| t.for_step(step));
        Self { equations, scheme, derivatives, prepared, closed_form: true, renewable: other.renewable, tangent }
    }

    /// Whether the closed-form step serves a state with scheme momenta `momenta`: the momenta it holds
    /// as constants, those that do not advance, are the same.
    fn serves(&self, momenta: &Dm::Array<f64>) -> bool {
        (0..momenta.as_ref().len())
            .all(|i| self.equations.advances[i] || momenta[i].to_bits() == self.prepared[i].to_bits())
    }
}

/// The rows of a matrix.
pub(crate) fn rows(m: &nalgebra::DMatrix<f64>) -> Vec<Vec<f64>> {
    m.row_iter().map(|row| row.iter().copied().collect()).collect()
}

/// The distance √Σ (exact − q)² over the coordinates with an exact value, if any has one.
fn reference_error(exact: &[Option<f64>], q: &[f64]) -> Option<f64> {
    let terms: Vec<f64> = exact.iter().zip(q).filter_map(|(e, q)| e.map(|e| (e - q).powi(2))).collect();
    (!terms.is_empty()).then(|| terms.iter().sum::<f64>().sqrt())
}
