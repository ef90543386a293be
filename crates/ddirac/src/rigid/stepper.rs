//! A run of a rigid system one step at a time: the predictor, the sub-steps of a composition, the
//! Newton solves of [`super::step`], and the record (energy, angular momentum, Casimir, orthogonality,
//! Newton statistics, warnings).

use std::time::Instant;

use nalgebra::DVector;

use super::discrete_lagrangian::StepLagrangian;
use super::invariance::test_symmetry;
use super::legendre;
use super::principal_axes::{self, PrincipalStep, Vector3};
use super::problem::{RigidInitial, RigidProblem};
use super::so3::{self, Matrix3};
use super::step::{Point, StepEquations};
use super::system::{PrincipalAxes, RigidSystem, Symmetry};
use crate::diagnostics::{Accumulator, MomentumMapDrift, NewtonSummary, Stats, Warning, WarningKind, Warnings};
use crate::dim::{Dynamic, Fixed};
use crate::energy_jump::{JumpAction, Monitor};
use crate::newton::{KeptJacobian, NewtonFailure};
use crate::{Differentiation, EnergyChange, Error, Input, Method, Reason, Variant, MAX_ANGLE_STEP};

/// A row of a rigid system's trajectory.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidRow {
    /// Step index k.
    pub k: usize,
    /// Time t_k = k h.
    pub t: f64,
    /// The attitude R_k (body to space), rows.
    pub r: Matrix3<f64>,
    /// The body angular momentum Π_k.
    pub pi: [f64; 3],
    /// The shape s_k.
    pub s: Vec<f64>,
    /// The shape momenta p_k.
    pub p: Vec<f64>,
    /// The energy H(R_k, Π_k, s_k, p_k) (NaN where the Legendre transform cannot be inverted).
    pub energy: f64,
    /// The spatial angular momentum R_k Π_k.
    pub momentum_map: [f64; 3],
}

/// The Casimir |Π| of so(3)* over a run (conserved when the Lagrangian is invariant under every
/// rotation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Casimir {
    /// |Π_0|.
    pub initial: f64,
    /// max_k ||Π_k| − |Π_0|| / |Π_0| (the absolute change when |Π_0| = 0).
    pub max_relative_drift: f64,
}

/// What a rigid system's run reports at its end.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidSummary {
    /// The shape coordinates' names.
    pub shape: Vec<String>,
    /// Steps taken.
    pub steps: usize,
    /// The step h.
    pub step: f64,
    /// R_N.
    pub final_r: Matrix3<f64>,
    /// Π_N.
    pub final_pi: [f64; 3],
    /// s_N.
    pub final_s: Vec<f64>,
    /// p_N.
    pub final_p: Vec<f64>,
    /// The energy over all steps.
    pub energy: Stats,
    /// The spatial angular momentum R Π: its first value, and the drift of the components the declared
    /// symmetry conserves ([`Symmetry::conserved_components`]; 0 when none).
    pub momentum_map: MomentumMapDrift,
    /// The declared symmetry.
    pub symmetry: Symmetry,
    /// |Π| over the run.
    pub casimir: Casimir,
    /// max_k of the largest entry of |R_kᵀR_k − I|.
    pub orthogonality: f64,
    /// Newton statistics over all steps.
    pub newton: NewtonSummary,
    /// Wall-clock seconds from the stepper's creation to the summary.
    pub wall_seconds: f64,
    /// What the user should know about the run.
    pub warnings: Vec<Warning>,
}

/// A sub-step of a step (one for the basic method, 3 to 27 for a composition) with its memory.
#[derive(Debug, Clone)]
struct SubStep {
    h: f64,
    kept: KeptJacobian<Dynamic>,
    /// The unknowns (ζ, s_{k+1}) of its last solve and the shape increment they made.
    last: Option<(DVector<f64>, Vec<f64>)>,
    /// The same for a body in principal axes, on the stack: the Jacobian, and ζ of the last two solves.
    principal_kept: KeptJacobian<Fixed<3>>,
    last_zeta: Option<Vector3>,
    before_zeta: Option<Vector3>,
}

/// The record of a run.
#[derive(Debug, Clone)]
struct Record {
    energy: Accumulator,
    monitor: Monitor,
    j0: [f64; 3],
    conserved: &'static [usize],
    max_drift: f64,
    momentum_scale: f64,
    casimir0: f64,
    casimir_drift: f64,
    orthogonality: f64,
    newton: NewtonSummary,
    warnings: Warnings,
}

/// A rigid system's run, one step at a time.
pub struct RigidStepper<'s, S> {
    system: &'s S,
    problem: RigidProblem,
    method: Method,
    shape: usize,
    /// The body's form when it is in principal axes ([`RigidSystem::principal_axes`]): its steps are
    /// solved in closed form.
    principal: Option<PrincipalAxes>,
    subs: Vec<SubStep>,
    point: Point,
    /// (Ω_k, ṡ_k) from the Legendre transform of the point, when it could be inverted.
    velocities: Option<DVector<f64>>,
    energy: f64,
    k: usize,
    record: Record,
    started: Instant,
}

/// Refuses the parts of a method that have no meaning on SO(3) × S.
fn validate_method(method: &Method) -> Result<(), Error> {
    let refuse = |what: &str, why: &str| {
        Err(Error::Invalid { what: Input::Argument(what.into()), why: Reason::Other(why.into()) })
    };
    if method.variant == Variant::Minus {
        return refuse(
            "method.variant",
            "the (−) equations belong to the abelian reduction with a connection; a rigid body's steps are the \
             discrete Hamilton–Pontryagin equations on SO(3), with no (+)/(−) choice (use `plus`)",
        );
    }
    if method.connection.is_some() {
        return refuse("method.connection", "a rigid body is reduced by SO(3) itself, without a connection K");
    }
    if method.differentiation == Differentiation::Compiled {
        return refuse(
            "method.derivatives",
            "compiled derivatives are not available for rigid bodies yet; use `dual` or `auto` (dual numbers)",
        );
    }
    crate::setup::check_symmetric(method)
}

impl<'s, S: RigidSystem> RigidStepper<'s, S> {
    /// Validates the problem and the method, tests the declared symmetry, and prepares the first step.
    pub fn new(system: &'s S, problem: RigidProblem, method: &Method) -> Result<Self, Error> {
        let shape = system.shape().len();
        problem.validate(shape)?;
        validate_method(method)?;
        let principal = principal_axes::declared(system)?;
        let symmetry = system.symmetry();
        if method.reduced && symmetry != Symmetry::Rotations {
            return Err(Error::NotReducible { symmetry: symmetry.name() });
        }
        let r = problem.r0;
        let s = problem.s0.clone();
        let (pi, p, velocities) = match &problem.initial {
            RigidInitial::Momentum { pi, p } => {
                let guess = vec![0.0; 3 + shape];
                (*pi, p.clone(), legendre::velocities(system, &r, pi, &s, p, &guess))
            }
            RigidInitial::Velocity { omega, v } => {
                let (_, pi, p) = legendre::momenta(system, &r, omega, &s, v);
                if let Some((entry, &value)) = pi.iter().chain(&p).enumerate().find(|(_, x)| !x.is_finite()) {
                    return Err(Error::NonFinite { what: Input::MomentumFromVelocity, entry: Some(entry), value });
                }
                let w = DVector::from_iterator(3 + shape, omega.iter().chain(v).copied());
                (pi, p, Some(w))
            }
        };
        let energy = velocities.as_ref().map_or(f64::NAN, |w| legendre::energy(system, &r, &s, w));
        if velocities.is_some() && !energy.is_finite() {
            let what = match &problem.initial {
                RigidInitial::Momentum { .. } => Input::InitialAngularMomentum,
                RigidInitial::Velocity { .. } => Input::InitialAngularVelocity,
            };
            return Err(Error::Invalid { what, why: Reason::EnergyOverflow { energy } });
        }
        if method.check_invariance {
            let w = velocities.clone().unwrap_or_else(|| DVector::zeros(3 + shape));
            test_symmetry(system, &r, &[w[0], w[1], w[2]], &s, &w.as_slice()[3..])?;
        }
        let subs = method
            .composition
            .coefficients()
            .into_iter()
            .map(|gamma| SubStep {
                h: gamma * problem.step,
                kept: KeptJacobian::new(Dynamic(3 + shape)),
                last: None,
                principal_kept: KeptJacobian::new(Fixed),
                last_zeta: None,
                before_zeta: None,
            })
            .collect();
        let point = Point { r, pi, s, p };
        let j0 = so3::apply(&point.r, &point.pi);
        let casimir0 = so3::dot(&point.pi, &point.pi).sqrt();
        let mut monitor = Monitor::new(method.energy_jump);
        monitor.set_window(problem.steps);
        let mut record = Record {
            energy: Accumulator::default(),
            monitor,
            j0,
            conserved: symmetry.conserved_components(),
            max_drift: 0.0,
            momentum_scale: largest(&j0).max(largest(&point.pi)).max(largest(&point.p)),
            casimir0,
            casimir_drift: 0.0,
            orthogonality: so3::orthogonality_error(&point.r),
            newton: NewtonSummary::default(),
            warnings: Warnings(Vec::new()),
        };
        record.energy.push(energy);
        if velocities.is_none() {
            let message = "the Legendre transform ∂ℓ/∂(Ω, ṡ) cannot be inverted at the initial data (a degenerate \
                           Lagrangian): the energy is not reported"
                .to_string();
            record.warnings.push(Warning::new(WarningKind::NoEnergy, None, message));
        }
        let method = method.clone();
        Ok(Self {
            system,
            problem,
            method,
            shape,
            principal,
            subs,
            point,
            velocities,
            energy,
            k: 0,
            record,
            started: Instant::now(),
        })
    }

    /// The step index k.
    pub fn k(&self) -> usize {
        self.k
    }

    /// Whether all steps are taken.
    pub fn is_finished(&self) -> bool {
        self.k >= self.problem.steps
    }

    /// The current row.
    pub fn row(&self) -> RigidRow {
        let Point { r, pi, s, p } = &self.point;
        RigidRow {
            k: self.k,
            t: self.k as f64 * self.problem.step,
            r: *r,
            pi: *pi,
            s: s.clone(),
            p: p.clone(),
            energy: self.energy,
            momentum_map: so3::apply(r, pi),
        }
    }

    /// Takes step k → k + 1 (all sub-steps of a composition).
    pub fn step(&mut self) -> Result<(), Error> {
        if self.is_finished() {
            let why = Reason::Finished { steps: self.problem.steps };
            return Err(Error::Invalid { what: Input::Steps, why });
        }
        let (k, h) = (self.k, self.problem.step);
        let t = k as f64 * h;
        let mut point = self.point.clone();
        let mut velocities = self.velocities.as_ref();
        let newton_error = |failure: NewtonFailure| Error::Newton {
            step: k,
            t,
            h,
            iterations: failure.iterations,
            residual: failure.residual,
            reason: failure.reason,
            singular: None,
            sub_steps: None,
        };
        // The body's rotation in the step: the sum of the sub-steps' angles 2 arctan(|ζ|/2).
        let mut turned = 0.0;
        for sub in &mut self.subs {
            let (next, stats, zeta) = match &self.principal {
                Some(form) => {
                    // ζ changes smoothly from step to step: extrapolated from the last two solves (an
                    // error of O(h³) where the last alone has O(h²)), saving a Newton correction.
                    let mut x = match (sub.last_zeta, sub.before_zeta) {
                        (Some(last), Some(before)) => 2.0 * last - before,
                        (Some(last), None) => last,
                        _ => Vector3::from_fn(|i, _| velocities.map_or(0.0, |w| sub.h * w[i])),
                    };
                    let equations = PrincipalStep::new(form, &point, sub.h, self.method.rule, self.method.reduced);
                    let (next, stats) =
                        equations.solve(&mut x, &self.method.newton, &mut sub.principal_kept).map_err(newton_error)?;
                    sub.before_zeta = sub.last_zeta.replace(x);
                    (next, stats, [x[0], x[1], x[2]])
                }
                None => {
                    let f = StepLagrangian {
                        system: self.system,
                        attitude: point.r,
                        h: sub.h,
                        rule: self.method.rule,
                        reduced: self.method.reduced,
                        shape: self.shape,
                    };
                    let mut x = predict(sub, &point, velocities, self.shape);
                    let equations = StepEquations { f, from: &point };
                    let (next, stats) =
                        equations.solve(&mut x, &self.method.newton, &mut sub.kept).map_err(newton_error)?;
                    let increment = (0..self.shape).map(|i| next.s[i] - point.s[i]).collect();
                    let zeta = [x[0], x[1], x[2]];
                    sub.last = Some((x, increment));
                    (next, stats, zeta)
                }
            };
            let finite = next.r.iter().flatten().chain(&next.pi).chain(&next.s).chain(&next.p).all(|x| x.is_finite());
            if !finite {
                return Err(Error::Diverged { step: k, t, h });
            }
            turned += 2.0 * (0.5 * so3::dot(&zeta, &zeta).sqrt()).atan();
            let newton = &mut self.record.newton;
            newton.total_iterations += stats.iterations;
            newton.total_jacobians += stats.jacobians;
            newton.max_iterations = newton.max_iterations.max(stats.iterations);
            newton.max_residual = newton.max_residual.max(stats.residual);
            velocities = None;
            point = next;
        }
        match &self.principal {
            Some(form) => {
                let omega = form.velocity(&point.pi);
                match &mut self.velocities {
                    Some(w) => w.copy_from_slice(&omega),
                    none => *none = Some(DVector::from_column_slice(&omega)),
                }
                self.energy = form.energy(&point.r, &point.pi);
            }
            None => {
                let guess =
                    self.velocities.as_ref().map_or_else(|| vec![0.0; 3 + self.shape], |w| w.as_slice().to_vec());
                self.velocities = legendre::velocities(self.system, &point.r, &point.pi, &point.s, &point.p, &guess);
                self.energy =
                    self.velocities.as_ref().map_or(f64::NAN, |w| legendre::energy(self.system, &point.r, &point.s, w));
            }
        }
        self.point = point;
        self.k += 1;
        if turned > MAX_ANGLE_STEP {
            let message = format!(
                "the body turned by {turned:.3} rad in one step (more than {MAX_ANGLE_STEP} rad): the step does not \
                 resolve the rotation (try a smaller step)"
            );
            self.record.warnings.push(Warning::new(WarningKind::UnderResolved, Some((k, t)), message));
        }
        self.watch((k, t))
    }

    /// Records the step that reached the current point.
    fn watch(&mut self, at: (usize, f64)) -> Result<(), Error> {
        let record = &mut self.record;
        let Point { r, pi, p, .. } = &self.point;
        record.energy.push(self.energy);
        let j = so3::apply(r, pi);
        for &i in record.conserved {
            record.max_drift = record.max_drift.max((j[i] - record.j0[i]).abs());
        }
        record.momentum_scale = record.momentum_scale.max(largest(pi)).max(largest(p));
        let casimir = so3::dot(pi, pi).sqrt();
        let change = (casimir - record.casimir0).abs();
        record.casimir_drift =
            record.casimir_drift.max(if record.casimir0 > 0.0 { change / record.casimir0 } else { change });
        record.orthogonality = record.orthogonality.max(so3::orthogonality_error(r));
        if self.energy.is_nan() {
            return Ok(());
        }
        let kinetic = match &self.velocities {
            Some(w) => (pi[0] * w[0] + pi[1] * w[1] + pi[2] * w[2]).abs(),
            None => 0.0,
        };
        let jump = record.monitor.push(at, self.energy, kinetic, Some(self.energy));
        if let Some(drift) = record.monitor.take_drift() {
            record.warnings.push(Warning::new(WarningKind::EnergyDrift, Some(drift.at), drift.describe()));
        }
        if let Some(jump) = jump {
            if self.method.energy_jump.action == JumpAction::Fail {
                let (step, t) = jump.at;
                return Err(Error::EnergyJump {
                    step,
                    t,
                    h: self.problem.step,
                    change: EnergyChange::Jumped(jump),
                    singular: None,
                });
            }
            record.warnings.push(Warning::new(WarningKind::EnergyJump, Some(jump.at), jump.describe()));
        }
        Ok(())
    }

    /// The summary of the steps taken so far.
    pub fn summary(&mut self) -> RigidSummary {
        if let Some(jump) = self.record.monitor.finish() {
            self.record.warnings.push(Warning::new(WarningKind::EnergyJump, Some(jump.at), jump.describe()));
        }
        let record = &self.record;
        let scale = record.momentum_scale;
        RigidSummary {
            shape: self.system.shape().into_iter().map(|c| c.name).collect(),
            steps: self.k,
            step: self.problem.step,
            final_r: self.point.r,
            final_pi: self.point.pi,
            final_s: self.point.s.clone(),
            final_p: self.point.p.clone(),
            energy: record.energy.stats(),
            momentum_map: MomentumMapDrift {
                initial: record.j0.to_vec(),
                max_drift: record.max_drift,
                scale,
                max_relative_drift: (scale > 0.0).then(|| record.max_drift / scale),
            },
            symmetry: self.system.symmetry(),
            casimir: Casimir { initial: record.casimir0, max_relative_drift: record.casimir_drift },
            orthogonality: record.orthogonality,
            newton: record.newton,
            wall_seconds: self.started.elapsed().as_secs_f64(),
            warnings: record.warnings.0.clone(),
        }
    }
}

/// The predicted unknowns (ζ, s_{k+1}) of a sub-step: its last solve's (the body velocity and the shape
/// increment change by O(h) from step to step), or at the first step h times the velocities of the
/// Legendre transform (0 where it cannot be inverted).
fn predict(sub: &SubStep, point: &Point, velocities: Option<&DVector<f64>>, shape: usize) -> DVector<f64> {
    match (&sub.last, velocities) {
        (Some((x, increment)), _) => {
            DVector::from_fn(3 + shape, |i, _| if i < 3 { x[i] } else { point.s[i - 3] + increment[i - 3] })
        }
        (None, Some(w)) => {
            DVector::from_fn(3 + shape, |i, _| if i < 3 { sub.h * w[i] } else { point.s[i - 3] + sub.h * w[i] })
        }
        (None, None) => DVector::from_fn(3 + shape, |i, _| if i < 3 { 0.0 } else { point.s[i - 3] }),
    }
}

fn largest(values: &[f64]) -> f64 {
    values.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}
