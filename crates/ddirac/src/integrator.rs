//! The generic stepper: joins a [`System`], a [`Problem`] and a [`Method`], owns the predictor, the
//! Newton solve, the reconstruction in re-centred charts, the diagnostics and failure reporting.
//!
//! Each step k solves the chosen scheme's equations for chart-local unknowns z (increments, and γ_k
//! for the reduced schemes) by Newton's method from a predictor (the previous steps' unknowns,
//! extrapolated quadratically from the last three, linearly after two; on the first step h · v0
//! from the Legendre transform), then advances the configuration and the momenta.

use std::time::Instant;

use nalgebra::SVector;

use crate::chart::Configuration;
use crate::diagnostics::{
    Accumulator, DerivativePath, MomentumMapDrift, NewtonSummary, Row, Solution, Summary, Warning, WarningKind,
    Warnings,
};
use crate::energy_jump::{Jump, JumpAction, Monitor};
use crate::mechanics::dirac::LagrangeDirac;
use crate::mechanics::legendre;
use crate::reduction::reduced::LagrangePoincareDirac;
use crate::reduction::reduced_lagrangian::ReducedLagrangian;
use crate::scheme::{Scheme, StepDerivatives, StepEquations};
use crate::{
    newton, Connection, DiscreteLagrangian, Error, InitialMomentum, Method, OutputOptions, Problem, Split, System,
};

/// The error type an output consumer may return.
pub type OutputError = Box<dyn std::error::Error + Send + Sync>;

/// Runs `problem` for `system` with `method`, handing every reported row to `observer`.
///
/// Rows are reported at k = 0, every, 2·every, … and at k = N. The integration stops at the first
/// error, whether from the input, the Newton solve, a non-finite state or the observer.
///
/// ```
/// use ddirac::{integrate, InitialMomentum, Method, OutputOptions, Problem, Rule, systems::ChargedParticle};
/// let problem = Problem::new(0.2, 100, vec![0.0; 4], InitialMomentum::Momentum(vec![1.0, 0.0, 1.0, 1.0]));
/// let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
/// let mut rows = 0;
/// let summary = integrate(&ChargedParticle::default(), &problem, &method, &OutputOptions::default(), &mut |_| {
///     rows += 1;
///     Ok(())
/// })
/// .unwrap();
/// assert_eq!(rows, 101);
/// assert!((summary.reference_error.unwrap() - 0.06626).abs() < 5e-6); // paper, Table 1
/// ```
pub fn integrate<S: System<N>, const N: usize>(
    system: &S,
    problem: &Problem,
    method: &Method,
    output: &OutputOptions,
    observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
) -> Result<Summary, Error> {
    if output.every == 0 {
        return Err(Error::Invalid { what: "output.every".into(), why: "must be at least 1".into() });
    }
    let setup = Setup::new(system, problem, method)?;
    let warnings = crate::check::findings(system, problem, method, &setup).verdict(method)?;
    let ld = DiscreteLagrangian::new(system, method.rule, problem.step);
    let run = Run { system, problem, output, setup: &setup };
    if method.reduced {
        let reduction = ReducedLagrangian::new(system, method.rule, problem.step, setup.connection.clone())?;
        let scheme = LagrangePoincareDirac::new(reduction, method.variant);
        run.go(&scheme, method, warnings, observer)
    } else {
        run.go(&LagrangeDirac { ld }, method, warnings, observer)
    }
}

/// What a run needs before its first step: validated initial data, the split, the connection and a
/// first-step increment h · v0 for the predictor.
pub(crate) struct Setup<const N: usize> {
    pub split: Split,
    pub q0: [f64; N],
    pub p0: [f64; N],
    /// h · v0 with v0 from the inverse Legendre transform (0 where it is not finite).
    pub dq0: [f64; N],
    pub connection: Connection,
}

impl<const N: usize> Setup<N> {
    pub(crate) fn new<S: System<N>>(system: &S, problem: &Problem, method: &Method) -> Result<Self, Error> {
        problem.validate(N)?;
        let coordinates = system.coordinates();
        let split = Split::new(&coordinates);
        let sized = |v: &[f64]| -> [f64; N] { v.try_into().expect("validated size") };
        let q0 = sized(&problem.q0);
        let p0 = match &problem.initial {
            InitialMomentum::Momentum(p) => sized(p),
            InitialMomentum::Velocity(v) => legendre::momentum(system, &q0, &sized(v)),
        };
        if let Some((i, &x)) = p0.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(Error::NonFinite { what: format!("initial momentum of `{}`", coordinates[i].name), value: x });
        }
        let connection = match &method.connection {
            Some(rows) => Connection::new(rows, split.n_x(), split.n_g())?,
            None => Connection::zero(split.n_x(), split.n_g()),
        };
        connection.check_axioms()?;
        let (v0, _) = legendre::velocity(system, &q0, &p0);
        let dq0 = std::array::from_fn(|i| if v0[i].is_finite() { v0[i] * problem.step } else { 0.0 });
        Ok(Self { split, q0, p0, dq0, connection })
    }
}

/// Runs `problem` and keeps every reported row in memory.
///
/// ```
/// use ddirac::{solve, InitialMomentum, Method, OutputOptions, Problem, Rule, systems::ChargedParticle};
/// let problem = Problem::new(2.0, 10, vec![0.0; 4], InitialMomentum::Momentum(vec![1.0, 0.0, 1.0, 1.0]));
/// let method = Method { rule: Rule::Left, ..Method::default() };
/// let solution = solve(&ChargedParticle::default(), &problem, &method, &OutputOptions::default()).unwrap();
/// assert_eq!(solution.t.len(), 11);
/// assert!((solution.summary.reference_error.unwrap() - 1.6781).abs() < 5e-5); // paper, Table 1
/// ```
pub fn solve<S: System<N>, const N: usize>(
    system: &S,
    problem: &Problem,
    method: &Method,
    output: &OutputOptions,
) -> Result<Solution, Error> {
    let (mut t, mut q, mut p, mut energy, mut discrete_energy, mut momentum_map) =
        (vec![], vec![], vec![], vec![], vec![], vec![]);
    let summary = integrate(system, problem, method, output, &mut |row| {
        t.push(row.t);
        q.push(row.q.to_vec());
        p.push(row.p.to_vec());
        energy.push(row.energy);
        discrete_energy.push(row.discrete_energy.unwrap_or(f64::NAN));
        momentum_map.push(row.momentum_map.to_vec());
        Ok(())
    })?;
    Ok(Solution { t, q, p, energy, discrete_energy, momentum_map, summary })
}

struct Run<'a, S, const N: usize> {
    system: &'a S,
    problem: &'a Problem,
    output: &'a OutputOptions,
    setup: &'a Setup<N>,
}

impl<S: System<N>, const N: usize> Run<'_, S, N> {
    fn go(
        &self,
        scheme: &impl Scheme<N>,
        method: &Method,
        warnings: Vec<Warning>,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
    ) -> Result<Summary, Error> {
        let mut warnings = Warnings(warnings);
        let mut monitor = Monitor::new(method.energy_jump);
        let mut p_now = self.setup.p0;
        let started = Instant::now();
        let (h, steps, split) = (self.problem.step, self.problem.steps, &self.setup.split);
        let coordinates = self.system.coordinates();
        let kinds = coordinates.each_ref().map(|c| c.kind);
        let mut config = Configuration::new(self.setup.q0, kinds);
        let mut momenta = scheme.momenta_from_p(&self.setup.p0);
        let j0 = split.g(&self.setup.p0);
        let mut predictor = Predictor::new(scheme.unknowns(&self.setup.dq0));
        let (mut energy, mut discrete_energy) = (Accumulator::default(), Accumulator::default());
        let mut newton_summary = NewtonSummary::default();
        let equations = scheme.equations();
        let mut max_drift = 0.0f64;
        let (derivatives, derivative_path) = StepDerivatives::new(
            scheme,
            method.differentiation,
            steps,
            &scheme.base(config.base()),
            &predictor.predict().into(),
            &momenta,
        )
        .map_err(Error::NotCompiled)?;
        let mut kept = match derivative_path {
            DerivativePath::Compiled { residual, jacobian, .. } => newton::KeptJacobian::with_relative_cost(
                newton::KeptJacobian::<N>::compiled_relative_cost(residual, jacobian),
            ),
            DerivativePath::Dual { .. } => newton::KeptJacobian::new(),
        };

        let n_g = split.n_g();
        // The scheme momenta hold the momentum map p_g at the group positions (see `Scheme`).
        let momentum_map = |momenta: &[f64; N]| -> [f64; N] {
            let mut j = [0.0; N];
            for (slot, &gj) in j.iter_mut().zip(&split.group) {
                *slot = momenta[gj];
            }
            j
        };
        let mut until_report = 0;
        for k in 0..=steps {
            let t = k as f64 * h;
            max_drift = split.group.iter().zip(&j0).fold(max_drift, |m, (&gj, j0)| m.max((momenta[gj] - j0).abs()));
            let report = until_report == 0 || k == steps;
            until_report = if until_report == 0 { self.output.every - 1 } else { until_report - 1 };
            if k == steps {
                if report {
                    let (q, p, j) = (
                        config.output(self.output.wrap_angles),
                        scheme.p_from_momenta(&momenta),
                        momentum_map(&momenta),
                    );
                    let e = legendre::hamiltonian(self.system, config.base(), &p);
                    energy.push(e);
                    let row = Row { k, t, q: &q, p: &p, energy: e, discrete_energy: None, momentum_map: &j[..n_g] };
                    observer(&row).map_err(Error::Output)?;
                }
                break;
            }

            if crate::interrupt::requested() {
                return Err(Error::Interrupted { step: k, t });
            }
            let base = scheme.base(config.base());
            let Solved { z, momenta_next, discrete_energy: step_energy, stats, fell_back } = self
                .solve_step(scheme, &equations, &derivatives, &base, &momenta, &predictor, &mut kept, &method.newton)
                .map_err(|f| Error::Newton {
                    step: k,
                    t,
                    iterations: f.iterations,
                    residual: f.residual,
                    reason: f.reason,
                })?;
            let dq = scheme.increment(&z);
            if dq.iter().chain(&momenta_next).any(|v| !v.is_finite()) || !step_energy.is_finite() {
                return Err(Error::Diverged { step: k, t, what: "state" });
            }
            discrete_energy.push(step_energy);
            if fell_back {
                let message = "the closed-form step failed its residual test; the step was solved by Newton's method";
                warnings.push(Warning::new(WarningKind::NewtonFallback, Some((k, t)), message.into()));
            }
            if method.energy_jump.action != JumpAction::Ignore {
                let p_next = scheme.p_from_momenta(&momenta_next);
                let pv = p_now.iter().zip(&p_next).zip(&dq).map(|((p0, p1), d)| (p0 + p1) * d).sum::<f64>() * 0.5 / h;
                p_now = p_next;
                let jump = monitor.push((k, t), pv - step_energy / h, pv.abs());
                jumped(jump, method.energy_jump.action, &mut warnings)?;
            }
            newton_summary.total_iterations += stats.iterations;
            newton_summary.total_jacobians += stats.jacobians;
            newton_summary.max_iterations = newton_summary.max_iterations.max(stats.iterations);
            newton_summary.max_residual = newton_summary.max_residual.max(stats.residual);

            if report {
                let (q, p, j) =
                    (config.output(self.output.wrap_angles), scheme.p_from_momenta(&momenta), momentum_map(&momenta));
                let e = legendre::hamiltonian(self.system, config.base(), &p);
                energy.push(e);
                let discrete_energy = Some(step_energy);
                let row = Row { k, t, q: &q, p: &p, energy: e, discrete_energy, momentum_map: &j[..n_g] };
                observer(&row).map_err(Error::Output)?;
            }

            config.advance(&dq);
            momenta = momenta_next;
            predictor.push(z);
        }

        jumped(monitor.finish(), method.energy_jump.action, &mut warnings)?;
        let final_q = config.output(self.output.wrap_angles).to_vec();
        let final_p = scheme.p_from_momenta(&momenta).to_vec();
        let reference_error =
            self.system.exact_solution(&self.setup.q0, &self.setup.p0, self.problem.duration()).and_then(|exact| {
                let unwrapped = config.unwrapped();
                let terms: Vec<f64> =
                    exact.iter().zip(&unwrapped).filter_map(|(e, q)| e.map(|e| (e - q).powi(2))).collect();
                (!terms.is_empty()).then(|| terms.iter().sum::<f64>().sqrt())
            });
        let j_scale = j0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        Ok(Summary {
            coordinates: coordinates.iter().map(|c| c.name.clone()).collect(),
            steps,
            step: h,
            final_q,
            final_p,
            energy: energy.stats(),
            discrete_energy: discrete_energy.stats(),
            momentum_map: MomentumMapDrift {
                initial: j0,
                max_drift,
                max_relative_drift: (j_scale > 0.0).then(|| max_drift / j_scale),
            },
            newton: newton_summary,
            derivatives: derivative_path,
            wall_seconds: started.elapsed().as_secs_f64(),
            reference_error,
            warnings: warnings.0,
        })
    }

    /// Solves one step's equations for the unknowns z: by the compiled closed-form step when the run
    /// has one and it passes Newton's residual test, otherwise by Newton's method from the closed-form
    /// solution if it failed the test, or from the predictor.
    #[allow(clippy::too_many_arguments)]
    fn solve_step(
        &self,
        scheme: &impl Scheme<N>,
        equations: &StepEquations<N>,
        derivatives: &StepDerivatives<N>,
        base: &[f64; N],
        momenta: &[f64; N],
        predictor: &Predictor<N>,
        kept: &mut newton::KeptJacobian<N>,
        options: &newton::NewtonOptions,
    ) -> Result<Solved<N>, newton::NewtonFailure> {
        let scale = momenta.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let closed_form = derivatives.linear_step().map(|l| l.solve(base, momenta));
        if let Some(s) = closed_form {
            if let Some(residual) = s.solves(options.threshold(scale)) {
                let stats = newton::NewtonStats { iterations: 1, residual, jacobians: 1 };
                let (z, momenta_next, discrete_energy) = (s.z.into(), s.momenta_next, s.value);
                return Ok(Solved { z, momenta_next, discrete_energy, stats, fell_back: false });
            }
        }
        let mut z = match closed_form {
            Some(s) if s.z.iter().all(|v| v.is_finite()) => s.z.into(),
            _ => predictor.predict(),
        };
        let mut last = None;
        let stats = newton::solve_with(&mut z, scale, options, kept, |z, with_jacobian| {
            let (d, mixed) = derivatives.first_or_mixed(scheme, base, z, with_jacobian);
            let e = equations.evaluate(momenta, &d, mixed);
            last = Some(e);
            (e.residual, e.jacobian)
        })?;
        let last = last.expect("Newton evaluates at least once");
        let (momenta_next, discrete_energy) = (last.momenta_next, last.discrete_energy);
        Ok(Solved { z, momenta_next, discrete_energy, stats, fell_back: closed_form.is_some() })
    }
}

/// A jump of the energy as the method asks: an error, or a warning.
fn jumped(jump: Option<Jump>, action: JumpAction, warnings: &mut Warnings) -> Result<(), Error> {
    match jump {
        Some(jump) if action == JumpAction::Fail => {
            let (step, t) = jump.at;
            Err(Error::EnergyJump { step, t, message: jump.describe() })
        }
        Some(jump) => {
            warnings.push(Warning::new(WarningKind::EnergyJump, Some(jump.at), jump.describe()));
            Ok(())
        }
        None => Ok(()),
    }
}

/// A solved step: its unknowns, the momenta and discrete energy they give, and how the solve went.
struct Solved<const N: usize> {
    z: SVector<f64, N>,
    momenta_next: [f64; N],
    discrete_energy: f64,
    stats: newton::NewtonStats,
    /// Whether the closed-form step failed its test and Newton's method solved the step.
    fell_back: bool,
}

/// Where a step's Newton iteration starts: the unknowns of the previous steps extrapolated
/// quadratically from the last three (linearly after two, the last one after one), and a first guess
/// before any.
struct Predictor<const N: usize> {
    last: [SVector<f64, N>; 3],
    count: usize,
}

impl<const N: usize> Predictor<N> {
    fn new(first: SVector<f64, N>) -> Self {
        Self { last: [first; 3], count: 0 }
    }

    fn push(&mut self, z: SVector<f64, N>) {
        self.last = [z, self.last[0], self.last[1]];
        self.count += 1;
    }

    fn predict(&self) -> SVector<f64, N> {
        let [z, z1, z2] = self.last;
        match self.count {
            0 | 1 => z,
            2 => 2.0 * z - z1,
            _ => 3.0 * (z - z1) + z2,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The predictor reproduces polynomials of the degree it extrapolates with: constant after one
    /// step, linear after two, quadratic from three on.
    #[test]
    fn predictor_is_exact_for_polynomials_of_its_degree() {
        let polynomial = |degree: i32, k: f64| SVector::<f64, 2>::new(k.powi(degree) - 2.0 * k, 0.5 * k.powi(degree));
        for (count, degree) in [(1, 0), (2, 1), (3, 2), (6, 2)] {
            let mut predictor = Predictor::new(SVector::zeros());
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
