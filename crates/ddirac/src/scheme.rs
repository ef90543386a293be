//! A scheme is a residual: the step equations of one integrator, in chart-local unknowns z.
//!
//! The generic stepper ([`crate::Stepper`]) owns the predictor, the Newton solve, step statistics
//! and failure reporting; a scheme only says how to evaluate its residual and Jacobian, how the
//! momenta advance, and how the solved unknowns move the configuration (reconstruction).

use crate::dim::{Dim, Entry, Fixed};
use crate::Scalar;

use crate::compiled::{
    self, pair_programs_with_runtime_inputs, CompileCost, CompileError, CompiledPair, LinearStep, PairPrograms,
    Refusal, Traced,
};
use crate::dim::{self, FirstDerivatives, PairFunction};
use crate::{DerivativePath, Differentiation};

/// One evaluation of a scheme's step equations at a trial point z.
#[derive(Debug, Clone)]
pub(crate) struct Evaluation<Dm: Dim> {
    /// The residual r(z); its Jacobian ∂r/∂z is the mixed block ∂²f/∂a∂b itself.
    pub residual: Dm::Vector,
    /// L_d(q_k, q_{k+1}) at the trial point (the paper's discrete energy).
    pub discrete_energy: f64,
    /// The scheme momenta at k + 1 if z is accepted.
    pub momenta_next: Dm::Array<f64>,
}

impl<const N: usize> Copy for Evaluation<Fixed<N>> {}

/// The form of every scheme's step equations in the derivatives of its generating function f at
/// (base, 0, z) and the scheme momenta m of step k:
///
/// ```text
/// r_i(z) = ∂f/∂a_i + sign_i · m_i,      m'_i = ∂f/∂b_i where advances_i, m_i elsewhere,
/// ```
///
/// with Jacobian ∂r/∂z = ∂²f/∂a∂b. The unknowns marked `eliminable` are the group unknowns γ of a
/// reduced scheme: row i of r is the momentum-map equation of unknown i, which the conserved μ makes
/// solvable for it alone ([`crate::compiled::LinearStep`] eliminates them when that equation is linear).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct StepEquations<Dm: Dim> {
    /// The factor of m_i in r_i: ±1.
    pub sign: Dm::Array<f64>,
    /// Whether m_i advances to ∂f/∂b_i (otherwise it is conserved).
    pub advances: Dm::Array<bool>,
    /// Whether unknown i is a group unknown with its own momentum-map row.
    pub eliminable: Dm::Array<bool>,
}

impl<const N: usize> Copy for StepEquations<Fixed<N>> {}

impl<Dm: Dim> StepEquations<Dm> {
    /// Residual and by-products from the generating function's derivatives `d` at the trial unknowns.
    #[inline]
    pub fn evaluate(&self, momenta: &Dm::Array<f64>, d: &FirstDerivatives<Dm>) -> Evaluation<Dm> {
        let dim = Dm::of(momenta);
        Evaluation {
            residual: dim.vector(|i| d.da[i] + self.sign[i] * momenta[i]),
            discrete_energy: d.value,
            momenta_next: dim.array(|i| if self.advances[i] { d.db[i] } else { momenta[i] }),
        }
    }
}

/// The step equations of an integrator.
///
/// *Scheme momenta* are the scheme's own momentum variables: p for the unreduced schemes,
/// (w, μ) = λ̂_d(q, p) for the reduced ones, stored at the positions of the x and g coordinates.
pub(crate) trait Scheme<Dm: Dim> {
    /// The chart base for a step from a configuration whose chart base is `q`.
    fn base(&self, q: &Dm::Array<f64>) -> Dm::Array<f64>;

    /// The generating function f(base, a, b) of the step: its derivatives at a = 0, b = z give the
    /// residual, the next momenta and the Jacobian ([`Scheme::evaluate`]). The base is a variable
    /// too when the function is traced for [`crate::compiled`].
    fn generating<D, B>(&self, base: &Dm::Array<B>, a: &Dm::Array<D>, b: &Dm::Array<D>) -> D
    where
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy;

    /// How the residual and the next momenta are formed from the generating function's derivatives.
    fn equations(&self) -> StepEquations<Dm>;

    /// The configuration increment q_{k+1} − q_k produced by the unknowns `z` (reconstruction).
    fn increment(&self, z: &Dm::Vector) -> Dm::Array<f64>;

    /// The unknowns that produce a configuration increment (the inverse of [`Scheme::increment`]).
    fn unknowns(&self, dq: &Dm::Array<f64>) -> Dm::Vector;

    /// Scheme momenta from canonical momenta p.
    fn momenta_from_p(&self, p: &Dm::Array<f64>) -> Dm::Array<f64>;

    /// Canonical momenta p from scheme momenta.
    fn p_from_momenta(&self, momenta: &Dm::Array<f64>) -> Dm::Array<f64>;

    /// The same scheme with step size `step` (the sub-steps of a composition or of a subdivided step).
    fn resized(&self, step: f64) -> Self
    where
        Self: Sized;
}

/// Under [`Differentiation::Auto`], runs of fewer steps use dual numbers: tracing and compiling take
/// about 1 ms for four coordinates (more for many), what compiled steps save over about two thousand.
/// Longer runs are traced, and compiled if the estimate of [`CompileCost`] says that compiling pays.
pub(crate) const AUTO_MIN_STEPS: usize = 5000;

/// How a run evaluates its scheme's generating function: compiled programs (native code with the
/// `jit` feature, else interpreted) or dual numbers.
pub(crate) enum StepDerivatives<Dm: Dim> {
    /// Compiled derivatives, and the compiled closed-form step when the step equations are linear.
    Compiled {
        pair: Box<CompiledPair<Dm>>,
        linear: Option<Box<LinearStep<Dm>>>,
    },
    Dual,
}

impl<Dm: Dim> StepDerivatives<Dm> {
    /// Compiles the derivatives of `scheme` when `choice` allows it, checking them against dual numbers
    /// at the first step's base and predictor `z` (and the closed-form step, if the equations are
    /// linear, at its solution for the first step's momenta). Under [`Differentiation::Auto`] a
    /// failure means dual numbers (the reason goes into the path), and so does a run of fewer than
    /// [`AUTO_MIN_STEPS`] steps or one whose programs would cost more to compile than its steps
    /// save ([`CompileCost`]; without the `jit` feature, whose interpreted steps would be slower,
    /// unless the step has a closed form); under [`Differentiation::Compiled`] a failure is an error.
    pub fn new(
        scheme: &impl Scheme<Dm>,
        choice: Differentiation,
        steps: usize,
        base: &Dm::Array<f64>,
        z: &Dm::Array<f64>,
        momenta: &Dm::Array<f64>,
    ) -> Result<(Self, DerivativePath), CompileError> {
        let dim = Dm::of(base);
        let dual_numbers = |reason: Option<String>| Ok((Self::Dual, DerivativePath::Dual { reason }));
        if choice == Differentiation::Dual {
            return dual_numbers(None);
        }
        if choice == Differentiation::Auto && steps < AUTO_MIN_STEPS {
            return dual_numbers(Some(format!(
                "{steps} steps: compiling costs more than it saves below {AUTO_MIN_STEPS}"
            )));
        }
        let generating = |base: &Dm::Array<Traced>, a: &Dm::Array<Traced>, b: &Dm::Array<Traced>| {
            scheme.generating::<Traced, Traced>(base, a, b)
        };
        let programs = match (pair_programs_with_runtime_inputs(dim, generating, base, z), choice) {
            (Ok(programs), _) => programs,
            (Err(e), Differentiation::Auto) => return dual_numbers(Some(e.to_string())),
            (Err(e), _) => return Err(e.into()),
        };
        let refusal = match choice {
            Differentiation::Auto => CompileCost::estimate(dim.n(), &programs).refusal(steps),
            _ => None,
        };
        // Native code is refused before it is generated. Interpreted programs (without the `jit`
        // feature) cost nothing to prepare, and a refused run still uses them when its step has a
        // closed form: one evaluation per step instead of Newton's method.
        let refusal = match refusal {
            Some(reason) if cfg!(feature = "jit") => return dual_numbers(Some(reason)),
            refusal => refusal,
        };
        let compiled = CompiledPair::from_programs(dim, &programs).and_then(|pair| {
            let dual = dim::mixed(dim, &Generating { scheme, base }, &dim.array(|_| 0.0), z);
            let first = FirstDerivatives { value: dual.value, da: dual.da, db: dual.db };
            pair.check_against(base, z, (first, dual.dadb), 1e-9)?;
            let equations = scheme.equations();
            let linear = closed_form(generating, &programs, &equations, base, z, momenta)?;
            if let Some(linear) = &linear {
                check_linear(scheme, &equations, linear, base, momenta)?;
            }
            Ok((pair, linear))
        });
        match (compiled, choice) {
            (Ok((_, None)), _) if refusal.is_some() => dual_numbers(refusal),
            (Ok((pair, linear)), _) => {
                let (residual, jacobian) = pair.instructions;
                let closed_form = linear.as_ref().map(|l| l.instructions);
                let path = DerivativePath::Compiled { residual, jacobian, closed_form };
                Ok((Self::Compiled { pair: Box::new(pair), linear: linear.map(Box::new) }, path))
            }
            (Err(e), Differentiation::Auto) => dual_numbers(Some(e.to_string())),
            (Err(e), _) => Err(e),
        }
    }

    /// Whether these derivatives, prepared at one first step under `choice` for `steps` steps, are
    /// those [`StepDerivatives::new`] would prepare at any other first step that they pass
    /// [`StepDerivatives::serve_first_step`] at: dual numbers chosen without looking at the first
    /// step (asked for, or a run too short to compile), or compiled programs of a trace without
    /// guards and without a closed-form step (a trace without guards gives the same programs at every
    /// point; a closed form holds the first step's pivot order and conserved momenta).
    pub fn independent_of_first_step(&self, choice: Differentiation, steps: usize) -> bool {
        match self {
            Self::Dual => {
                choice == Differentiation::Dual || (choice == Differentiation::Auto && steps < AUTO_MIN_STEPS)
            }
            Self::Compiled { pair, linear } => linear.is_none() && pair.is_unguarded(),
        }
    }

    /// Whether these derivatives pass, at the first step (`base`, `z`), the check against dual
    /// numbers that [`StepDerivatives::new`] makes at the step it prepares them at.
    pub fn serve_first_step(&self, scheme: &impl Scheme<Dm>, base: &Dm::Array<f64>, z: &Dm::Array<f64>) -> bool {
        match self {
            Self::Dual => true,
            Self::Compiled { pair, .. } => {
                let dim = Dm::of(base);
                let dual = dim::mixed(dim, &Generating { scheme, base }, &dim.array(|_| 0.0), z);
                let first = FirstDerivatives { value: dual.value, da: dual.da, db: dual.db };
                pair.check_against(base, z, (first, dual.dadb), 1e-9).is_ok()
            }
        }
    }

    /// The derivatives of the same scheme with step size `step` (a composition's other sub-step
    /// sizes), without tracing again: compiled programs of an unguarded trace that take h as a runtime
    /// input, with h set to `step`. `None` otherwise (dual numbers cost nothing to prepare; a
    /// closed-form step holds h as a constant).
    pub fn for_step(&self, step: f64) -> Option<Self> {
        match self {
            Self::Compiled { pair, linear: None } if pair.is_unguarded() => {
                pair.with_step(step).map(|pair| Self::Compiled { pair: Box::new(pair), linear: None })
            }
            _ => None,
        }
    }

    /// The compiled closed-form step, if the run has one.
    #[inline]
    pub fn linear_step(&self) -> Option<&LinearStep<Dm>> {
        match self {
            Self::Compiled { linear, .. } => linear.as_deref(),
            Self::Dual => None,
        }
    }

    /// The generating function's value, first derivatives and, if `with_mixed`, mixed block at
    /// (`base`, 0, `z`).
    #[inline]
    pub fn first_or_mixed(
        &self,
        scheme: &impl Scheme<Dm>,
        base: &Dm::Array<f64>,
        z: &Dm::Vector,
        with_mixed: bool,
    ) -> (FirstDerivatives<Dm>, Option<Dm::Matrix>) {
        let dim = Dm::of(base);
        let z = dim.array(|i| z[i]);
        let compiled = match self {
            Self::Compiled { pair, .. } => pair.first_or_mixed(base, &z, with_mixed),
            Self::Dual => None,
        };
        // Where a guard of the trace fails (another branch of a comparison), dual numbers answer.
        compiled.unwrap_or_else(|| {
            dim::first_or_mixed(dim, &Generating { scheme, base }, &dim.array(|_| 0.0), &z, with_mixed)
        })
    }
}

/// The closed-form step of `equations` ([`LinearStep`]), unless they were found not affine before:
/// equations are known by their compiled derivatives `programs` (h and the parameters as runtime
/// inputs) and what the closed form is sought with besides the point (the runtime inputs' values, the
/// conserved momenta, which are constants of it, the signs and the roles of the unknowns).
fn closed_form<Dm: Dim, F>(
    generating: F,
    programs: &PairPrograms,
    equations: &StepEquations<Dm>,
    base: &Dm::Array<f64>,
    z: &Dm::Array<f64>,
    momenta: &Dm::Array<f64>,
) -> Result<Option<LinearStep<Dm>>, CompileError>
where
    F: Fn(&Dm::Array<Traced>, &Dm::Array<Traced>, &Dm::Array<Traced>) -> Traced,
{
    let (dim, n) = (Dm::of(base), Dm::of(base).n());
    let (sign, advances, eliminable) =
        (equations.sign.as_ref(), equations.advances.as_ref(), equations.eliminable.as_ref());
    let conserved = (0..n).filter(|&i| !advances[i]).map(|i| momenta[i].to_bits());
    let runtime = programs.runtime.iter().map(|(_, v)| v.to_bits());
    let roles = (0..n).map(|i| sign[i].to_bits() ^ u64::from(advances[i]) << 1 ^ u64::from(eliminable[i]));
    let key = (programs.mixed.clone(), runtime.chain(conserved).chain(roles).collect::<Vec<u64>>());
    if compiled::known_not_affine(&key) {
        return Ok(None);
    }
    match LinearStep::new(dim, generating, base, z, momenta.as_ref(), sign, advances, eliminable)? {
        Ok(linear) => Ok(Some(linear)),
        Err(refusal) => {
            if refusal == Refusal::NotAffine {
                compiled::remember_not_affine(key);
            }
            Ok(None)
        }
    }
}

/// Checks the closed-form step at (`base`, `momenta`) against dual numbers at its solution: the
/// residual of the step equations vanishes there (relative 1e-9), and the value and the next
/// momenta agree.
fn check_linear<Dm: Dim>(
    scheme: &impl Scheme<Dm>,
    equations: &StepEquations<Dm>,
    linear: &LinearStep<Dm>,
    base: &Dm::Array<f64>,
    momenta: &Dm::Array<f64>,
) -> Result<(), CompileError> {
    let dim = Dm::of(base);
    let solution = linear.solve(base, momenta);
    let (dual, _) = dim::first_or_mixed(dim, &Generating { scheme, base }, &dim.array(|_| 0.0), &solution.z, false);
    let evaluation = equations.evaluate(momenta, &dual);
    let scale = momenta.as_ref().iter().chain(Dm::entries(&dual.da)).fold(1.0f64, |m, x| m.max(x.abs()));
    let closest = |c: f64, d: f64, s: f64| (c - d).abs() <= 1e-9 * s;
    let next = evaluation.momenta_next;
    let next_scale = next.as_ref().iter().fold(1.0f64, |m, x| m.max(x.abs()));
    let checks = [
        ("closed-form residual", Dm::amax(&evaluation.residual), 0.0, scale),
        ("value", solution.value, dual.value, dual.value.abs().max(1.0)),
    ];
    let momenta = (0..dim.n()).map(|i| ("next momenta", solution.momenta_next[i], next[i], next_scale));
    match checks.into_iter().chain(momenta).find(|&(_, c, d, s)| !closest(c, d, s)) {
        Some((what, compiled, dual, _)) => Err(CompileError::Disagrees { what, compiled, dual }),
        None => Ok(()),
    }
}

/// A scheme's generating function at a fixed base, as a function of the two blocks.
struct Generating<'s, Sc, Dm: Dim> {
    scheme: &'s Sc,
    base: &'s Dm::Array<f64>,
}

impl<Sc: Scheme<Dm>, Dm: Dim> PairFunction<Dm> for Generating<'_, Sc, Dm> {
    #[inline]
    fn eval<D: Scalar>(&self, a: &Dm::Array<D>, b: &Dm::Array<D>) -> D {
        self.scheme.generating::<D, f64>(self.base, a, b)
    }
}

/// What the tests of the schemes share: a system seen in a dynamic dimension, and steps of a scheme
/// in a fixed and a dynamic dimension held against each other and against the library's run.
#[cfg(test)]
pub(crate) mod testing {
    use super::*;
    use crate::dim::{Column, Dynamic};
    use crate::newton::{self, NewtonOptions};
    use crate::System;

    pub(crate) use crate::mechanics::lagrangian::AsDynamic;

    /// `steps` steps of `scheme` from (q, p), each solved by classical Newton from z = 0: the
    /// configurations and canonical momenta after each.
    pub(crate) fn run<Dm: Dim>(
        scheme: &impl Scheme<Dm>,
        choice: Differentiation,
        q: Dm::Array<f64>,
        p: Dm::Array<f64>,
        steps: usize,
    ) -> Vec<(Vec<f64>, Vec<f64>)>
    where
        Dm::Vector: Column<Dim = Dm>,
    {
        let (dim, equations) = (Dm::of(&q), scheme.equations());
        let (mut q, mut momenta) = (q, scheme.momenta_from_p(&p));
        let zero = dim.array(|_| 0.0);
        let (derivatives, _) = StepDerivatives::new(scheme, choice, steps, &scheme.base(&q), &zero, &momenta).unwrap();
        let mut out = Vec::new();
        for _ in 0..steps {
            let base = scheme.base(&q);
            let mut z = scheme.unknowns(&zero);
            newton::solve(&mut z, 1.0, &NewtonOptions::default(), |z| {
                let (first, mixed) = derivatives.first_or_mixed(scheme, &base, z, true);
                (equations.evaluate(&momenta, &first).residual, mixed.unwrap())
            })
            .unwrap();
            let (first, _) = derivatives.first_or_mixed(scheme, &base, &z, false);
            momenta = equations.evaluate(&momenta, &first).momenta_next;
            let dq = scheme.increment(&z);
            q = dim.array(|i| q[i] + dq[i]);
            out.push((q.as_ref().to_vec(), scheme.p_from_momenta(&momenta).as_ref().to_vec()));
        }
        out
    }

    /// `fixed` and `dynamic`, the same scheme of `system` in `Fixed<N>` and `Dynamic(N)`, take the same
    /// `steps` steps from (q, p) bit for bit under `method.differentiation`, and the last agrees with
    /// the library's run of `system` by `method` (its own predictor and Newton iterates, so within
    /// the Newton tolerance, relative to max(1, |·|)).
    pub(crate) fn assert_alike<S: System<N>, const N: usize>(
        system: &S,
        fixed: &impl Scheme<Fixed<N>>,
        dynamic: &impl Scheme<Dynamic>,
        method: &crate::Method,
        q: [f64; N],
        p: [f64; N],
        steps: usize,
    ) {
        let choice = method.differentiation;
        let a = run(fixed, choice, q, p, steps);
        let b = run(dynamic, choice, q.to_vec(), p.to_vec(), steps);
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        for (k, ((qa, pa), (qb, pb))) in a.iter().zip(&b).enumerate() {
            assert_eq!(bits(qa), bits(qb), "{method:?}: q after step {}", k + 1);
            assert_eq!(bits(pa), bits(pb), "{method:?}: p after step {}", k + 1);
        }
        let problem = crate::Problem::with_momentum(0.01, steps, q, p);
        let method =
            crate::Method { newton: NewtonOptions { reuse_jacobian: false, ..method.newton }, ..method.clone() };
        let options = crate::OutputOptions { every: 1, wrap_angles: false };
        let solution = crate::solve(system, &problem, &method, &options).unwrap();
        let (last_q, last_p) = (solution.q.last().unwrap(), solution.p.last().unwrap());
        let (qb, pb) = b.last().unwrap();
        let close = |x: f64, y: f64| (x - y).abs() < 1e-11 * x.abs().max(1.0);
        for i in 0..N {
            assert!(close(last_q[i], qb[i]), "{method:?}: q[{i}] {} against {}", last_q[i], qb[i]);
            assert!(close(last_p[i], pb[i]), "{method:?}: p[{i}] {} against {}", last_p[i], pb[i]);
        }
    }
}
