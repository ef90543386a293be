//! Whole runs: [`integrate`] streams the reported rows of a [`Stepper`] run to an observer, [`solve`]
//! keeps them in memory.

use crate::diagnostics::{OutputError, Row, Solution, Summary};
use crate::dim::Dim;
use crate::mechanics::lagrangian::{Borrowed, SystemIn};
use crate::{Error, Input, Method, OutputOptions, Problem, StepperIn};

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
pub fn integrate<S: SystemIn<Dm>, Dm: Dim>(
    system: &S,
    problem: &Problem,
    method: &Method,
    output: &OutputOptions,
    observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
) -> Result<Summary, Error> {
    if output.every == 0 {
        return Err(Error::Invalid { what: Input::Every, why: crate::Reason::Zero });
    }
    integrate_watched(system, problem, method, output, observer, &mut |_| Ok(()))
}

/// [`integrate`], calling `watch(k)` before step k every [`WATCH_STEPS`](crate::WATCH_STEPS) steps (and before the
/// first): a caller that must look at something while a run goes on (Python's signal handlers) does
/// it there; an error from it stops the run with [`Error::Output`] as an observer's does.
///
/// ```
/// use ddirac::{integrate_watched, systems::ChargedParticle, Method, OutputOptions, WATCH_STEPS};
/// let (system, problem) = (ChargedParticle::default(), ChargedParticle::paper_problem(150));
/// let mut watched = vec![];
/// let mut watch = |k: usize| -> Result<(), ddirac::OutputError> { watched.push(k); Ok(()) };
/// integrate_watched(&system, &problem, &Method::default(), &OutputOptions::default(), &mut |_| Ok(()), &mut watch)
///     .unwrap();
/// assert_eq!(watched, [0, WATCH_STEPS, 2 * WATCH_STEPS]);
/// ```
pub fn integrate_watched<S: SystemIn<Dm>, Dm: Dim>(
    system: &S,
    problem: &Problem,
    method: &Method,
    output: &OutputOptions,
    observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
    watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
) -> Result<Summary, Error> {
    if output.every == 0 {
        return Err(Error::Invalid { what: Input::Every, why: crate::Reason::Zero });
    }
    let mut stepper = StepperIn::new(Borrowed(system), problem, method)?;
    stepper.set_wrap_angles(output.wrap_angles);
    stepper.run_to_end(output.every, observer, watch)?;
    stepper.finish()
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
pub fn solve<S: SystemIn<Dm>, Dm: Dim>(
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
