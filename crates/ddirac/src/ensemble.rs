//! An ensemble: many runs that share a method and a time grid and differ in initial data and/or
//! parameters, in parallel on rayon's threads.
//!
//! Each member is run exactly as [`crate::integrate`] runs it (the same stepper, the same steps,
//! the same rows), so member k of an ensemble equals the single run of its system and problem bit
//! for bit, whichever thread runs it and whatever ran before on that thread. What members share is
//! made once: the system (for a text Lagrangian its parsed and lowered expression) by the caller,
//! who lends it; the traced and compiled derivatives by the stepper, which members of a shared
//! system that run one after another on a thread renew ([`crate::Stepper::renew`]) where the
//! derivatives serve them unchanged — dual numbers chosen without looking at the initial data, or
//! programs of a trace without guards or closed-form step, checked at each member's first step.
//! Where they might not serve (a closed-form step holds the first member's conserved momenta; a
//! guarded trace holds the branch of its first step), a member prepares its own stepper, whose
//! native code then comes from the cache of prepared programs
//! ([`crate::compiled::native_compilations`]): members that differ only in initial data, or in
//! the parameters of a text system (runtime inputs of the programs), compile once.
//!
//! A member that fails (Newton's method, a non-finite state, an energy jump made an error, or a
//! refusal before its first step) is recorded as failed with its reason, step and state; the others
//! go on. A stop request ([`crate::interrupt`]) or an error of the caller's sink stops the ensemble.

use rayon::prelude::*;

use crate::diagnostics::OutputError;
use crate::diagnostics::Row;
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::{DynStepper, DynSystem, Error, InitialMomentum, Input, Method, OutputOptions, Problem, Summary};

/// The system of one member: shared by the ensemble, or the member's own (a parameter sweep of a
/// built-in system, or of a text system's parameters).
pub enum MemberSystem<'a> {
    /// Borrowed from the caller, the same for many members.
    Shared(&'a dyn DynSystem),
    /// Made for this member.
    Own(Box<dyn DynSystem>),
}

/// Rows kept of one member's run: those [`crate::integrate`] reports with the same
/// [`OutputOptions`] (every `every`-th step and the last).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Rows {
    /// Times.
    pub t: Vec<f64>,
    /// Configurations, row after row (rows × n).
    pub q: Vec<f64>,
    /// Momenta, row after row (rows × n).
    pub p: Vec<f64>,
    /// The Hamiltonian of each row.
    pub energy: Vec<f64>,
}

/// How a member ended.
#[derive(Debug)]
pub enum Status {
    /// All steps taken; the run's summary.
    Finished(Box<Summary>),
    /// The run stopped at `step` (time `t`), or was refused before its first step (`step` 0).
    Failed {
        /// The step that failed (the state reported is that of this step).
        step: usize,
        /// Its time.
        t: f64,
        /// Why.
        error: Error,
    },
}

/// One member's result: its status, its last state and the rows kept.
#[derive(Debug)]
pub struct Outcome {
    /// Finished with a summary, or failed with its reason.
    pub status: Status,
    /// The configuration reached: q_N, or that of the failed step (q0 for a refused member).
    pub final_q: Vec<f64>,
    /// The momenta reached (p0 for a refused member, NaN where only v0 was given).
    pub final_p: Vec<f64>,
    /// The rows kept, if asked for; a failed member's end at its last reported row.
    pub rows: Option<Rows>,
}

impl Outcome {
    /// Whether the member took all its steps.
    pub fn is_finished(&self) -> bool {
        matches!(self.status, Status::Finished(_))
    }
}

/// Runs one member as [`crate::integrate`] would, keeping its rows if `keep_rows`.
///
/// Returns an error only for a stop request ([`Error::Interrupted`]) or an error of `watch`; every
/// other failure is the member's own and is in its [`Outcome`].
pub fn run_member(
    system: &dyn DynSystem,
    problem: &Problem,
    method: &Method,
    output: &OutputOptions,
    keep_rows: bool,
    watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
) -> Result<Outcome, Error> {
    let mut stepper = None;
    run_with(&mut stepper, system, problem, method, output, keep_rows, watch).map(|(outcome, _)| outcome)
}

/// [`run_member`] with the stepper of the member before on this thread, if any, renewed for this
/// member when its derivatives serve it unchanged ([`crate::Stepper::renew`]); returns whether it
/// was, and leaves the member's stepper in `slot`.
fn run_with<'a>(
    slot: &mut Option<Box<dyn DynStepper + 'a>>,
    system: &'a dyn DynSystem,
    problem: &Problem,
    method: &Method,
    output: &OutputOptions,
    keep_rows: bool,
    watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
) -> Result<(Outcome, bool), Error> {
    let refused = |error: Error| {
        let p0 = match &problem.initial {
            InitialMomentum::Momentum(p) => p.clone(),
            InitialMomentum::Velocity(v) => vec![f64::NAN; v.len()],
        };
        Outcome {
            status: Status::Failed { step: 0, t: 0.0, error },
            final_q: problem.q0.clone(),
            final_p: p0,
            rows: None,
        }
    };
    if output.every == 0 {
        return Ok((refused(Error::Invalid { what: Input::Every, why: crate::Reason::Zero }), false));
    }
    let renewed = match slot.as_mut().map(|stepper| stepper.renew(problem)) {
        Some(Ok(renewed)) => renewed,
        Some(Err(error)) => return Ok((refused(error), false)),
        None => false,
    };
    if !renewed {
        *slot = None;
        match system.stepper(problem, method) {
            Ok(stepper) => *slot = Some(stepper),
            Err(error) => return Ok((refused(error), false)),
        }
    }
    let stepper = slot.as_mut().expect("made above");
    stepper.set_wrap_angles(output.wrap_angles);
    let mut rows = keep_rows.then(Rows::default);
    let mut observer = |row: &Row<'_>| -> Result<(), OutputError> {
        if let Some(rows) = &mut rows {
            rows.t.push(row.t);
            rows.q.extend_from_slice(row.q);
            rows.p.extend_from_slice(row.p);
            rows.energy.push(row.energy);
        }
        Ok(())
    };
    let ended = stepper.run_to_end(output.every, &mut observer, watch);
    let (step, t) = (stepper.k(), stepper.t());
    let status = match ended {
        Err(error @ (Error::Interrupted { .. } | Error::Output(_))) => return Err(error),
        Err(error) => Status::Failed { step, t, error },
        Ok(()) => match stepper.summary() {
            Ok(summary) => {
                let (final_q, final_p) = (summary.final_q.clone(), summary.final_p.clone());
                let outcome = Outcome { status: Status::Finished(Box::new(summary)), final_q, final_p, rows };
                return Ok((outcome, renewed));
            }
            Err(error) => Status::Failed { step, t, error },
        },
    };
    let row = stepper.row();
    Ok((Outcome { status, final_q: row.q, final_p: row.p, rows }, renewed))
}

/// How an ensemble's members were prepared.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Preparations {
    /// Members that prepared a stepper of their own (traced and, when they compile, looked up or
    /// compiled their programs).
    pub prepared: usize,
    /// Members run by the stepper of the member before them on the same thread, renewed for them with
    /// its derivatives ([`crate::Stepper::renew`]).
    pub renewed: usize,
}

/// Runs members `range` in parallel on the current rayon pool (`ThreadPool::install` chooses it),
/// each as [`run_member`] runs it; `member(i)` gives member i's system and problem, `sink(i,
/// outcome)` takes its outcome (in any order; from any thread).
///
/// Members of a shared system run on one thread after another renew one stepper
/// ([`crate::Stepper::renew`]): they share its traced and compiled derivatives where these serve
/// them unchanged, and are prepared anew where not, so that every member is its single run.
///
/// An error of `member` (a member the caller cannot build) or of `sink` stops the ensemble with
/// that error as [`Error::Output`]; a stop request stops it with [`Error::Interrupted`]. Members
/// already running end first.
pub fn run<'a>(
    range: std::ops::Range<usize>,
    member: &(dyn Fn(usize) -> Result<(MemberSystem<'a>, Problem), OutputError> + Sync),
    method: &Method,
    output: &OutputOptions,
    keep_rows: bool,
    sink: &(dyn Fn(usize, Outcome) -> Result<(), OutputError> + Sync),
) -> Result<Preparations, Error> {
    let (prepared, renewed) = (AtomicUsize::new(0), AtomicUsize::new(0));
    // Per rayon job: the shared system of the last member and its stepper.
    type Kept<'a> = Option<(usize, Box<dyn DynStepper + 'a>)>;
    range.into_par_iter().try_for_each_init(
        || -> Kept<'a> { None },
        |kept, i| {
            if crate::interrupt::requested() {
                return Err(Error::Interrupted { step: 0, t: 0.0 });
            }
            let (system, problem) = member(i).map_err(Error::Output)?;
            let watch = &mut |_| Ok(());
            let (outcome, reused) = match system {
                MemberSystem::Shared(shared) => {
                    let key = shared as *const dyn DynSystem as *const () as usize;
                    let mut slot = match kept.take() {
                        Some((k, stepper)) if k == key => Some(stepper),
                        _ => None,
                    };
                    let result = run_with(&mut slot, shared, &problem, method, output, keep_rows, watch)?;
                    *kept = slot.map(|stepper| (key, stepper));
                    result
                }
                MemberSystem::Own(own) => {
                    run_with(&mut None, own.as_ref(), &problem, method, output, keep_rows, watch)?
                }
            };
            let counter = if reused { &renewed } else { &prepared };
            counter.fetch_add(1, Ordering::Relaxed);
            sink(i, outcome).map_err(Error::Output)
        },
    )?;
    Ok(Preparations { prepared: prepared.into_inner(), renewed: renewed.into_inner() })
}

#[cfg(test)]
mod tests {
    use std::sync::Mutex;

    use super::*;
    use crate::systems::ChargedParticle;
    use crate::{Erased, Rule};

    #[test]
    fn members_equal_single_runs_bit_for_bit_and_a_failure_stays_in_its_member() {
        let system = Erased(ChargedParticle::default());
        let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
        let output = OutputOptions { every: 3, wrap_angles: false };
        let problem = |i: usize| {
            let p = if i == 2 { f64::NAN } else { 1.0 + 0.1 * i as f64 };
            Problem::new(0.2, 40, vec![0.0; 4], InitialMomentum::Momentum(vec![p, 0.0, 1.0, 1.0]))
        };
        let outcomes = Mutex::new(vec![]);
        let member = |i| Ok((MemberSystem::Shared(&system as &dyn DynSystem), problem(i)));
        let sink = |i, outcome| -> Result<(), OutputError> {
            outcomes.lock().unwrap().push((i, outcome));
            Ok(())
        };
        run(0..5, &member, &method, &output, true, &sink).unwrap();
        // The closed-form step holds each member's own μ: every member prepares its own stepper.
        let mut outcomes = outcomes.into_inner().unwrap();
        outcomes.sort_by_key(|(i, _)| *i);
        for (i, outcome) in &outcomes {
            if *i == 2 {
                assert!(matches!(outcome.status, Status::Failed { step: 0, error: Error::NonFinite { .. }, .. }));
                continue;
            }
            let single = crate::solve(&system.0, &problem(*i), &method, &output).unwrap();
            let Status::Finished(summary) = &outcome.status else { panic!("member {i}: {:?}", outcome.status) };
            assert_eq!(summary.final_q, single.summary.final_q);
            assert_eq!(summary.final_p, single.summary.final_p);
            assert_eq!(outcome.final_q, single.summary.final_q);
            let rows = outcome.rows.as_ref().unwrap();
            assert_eq!(rows.t, single.t);
            assert_eq!(rows.q, single.q.concat());
            assert_eq!(rows.energy, single.energy);
        }
    }

    #[test]
    fn members_on_one_thread_renew_one_stepper_and_still_equal_their_single_runs() {
        use crate::systems::DoubleSphericalPendulum;
        let system = Erased(DoubleSphericalPendulum::default());
        let method = Method { reduced: true, differentiation: crate::Differentiation::Compiled, ..Method::default() };
        let output = OutputOptions { every: 50, wrap_angles: false };
        let problem = |i: usize| {
            let mut problem = Problem { steps: 300, ..DoubleSphericalPendulum::paper_problem(10_000) };
            problem.q0[1] = 2.25 + 0.02 * i as f64;
            if i == 3 {
                problem.q0[0] = f64::NAN; // refused; the next member still renews the stepper
            }
            problem
        };
        let outcomes = Mutex::new(vec![]);
        let member = |i| Ok((MemberSystem::Shared(&system as &dyn DynSystem), problem(i)));
        let sink = |i, outcome| -> Result<(), OutputError> {
            outcomes.lock().unwrap().push((i, outcome));
            Ok(())
        };
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let preparations = pool.install(|| run(0..6, &member, &method, &output, true, &sink)).unwrap();
        // Rayon may cut the range into a few jobs even on one thread, each starting without a stepper;
        // member 3 (refused) counts as prepared.
        assert_eq!(preparations.prepared + preparations.renewed, 6);
        assert!(preparations.renewed >= 3, "{preparations:?}");
        for (i, outcome) in outcomes.into_inner().unwrap() {
            if i == 3 {
                assert!(matches!(outcome.status, Status::Failed { step: 0, error: Error::NonFinite { .. }, .. }));
                continue;
            }
            let single = crate::solve(&system.0, &problem(i), &method, &output).unwrap();
            let Status::Finished(summary) = &outcome.status else { panic!("member {i}: {:?}", outcome.status) };
            assert!(matches!(summary.derivatives, crate::DerivativePath::Compiled { closed_form: None, .. }));
            assert_eq!(summary.final_q, single.summary.final_q, "member {i}");
            assert_eq!(summary.final_p, single.summary.final_p, "member {i}");
            assert_eq!(summary.energy, single.summary.energy, "member {i}");
            assert_eq!(summary.newton, single.summary.newton, "member {i}");
            assert_eq!(outcome.rows.unwrap().q, single.q.concat(), "member {i}");
        }
    }
}
