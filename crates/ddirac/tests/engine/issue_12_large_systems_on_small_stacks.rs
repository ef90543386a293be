//! A system of 50 coordinates run on threads of 2 MiB, the stack Rust gives a spawned thread (rayon's
//! workers: `ddirac ensemble` of a chain of 50 pendula aborted with a stack overflow). The stepper's
//! entry points and `check` now continue on a stack from the heap when the thread's is short
//! (`ddirac::stack`), so these runs finish, and equal the same runs on a large stack bit for bit.

use ddirac::ensemble::{run, MemberSystem, Outcome};
use ddirac::systems::{find, PendulumChain};
use ddirac::{check, Differentiation, DynSystem, Method, OutputOptions, Rule, Stepper};
use std::sync::Mutex;

const SMALL: usize = 2 << 20;

fn on_stack<T: Send + 'static>(bytes: usize, f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new().stack_size(bytes).spawn(f).unwrap().join().expect("the thread finished")
}

fn method(differentiation: Differentiation) -> Method {
    Method { rule: Rule::Midpoint, differentiation, ..Method::default() }
}

/// Set-up, check, steps, rows, a saved state and a restart, and the summary of a chain of 50.
fn stepped(differentiation: Differentiation) -> (Vec<f64>, Vec<f64>, usize) {
    let problem = PendulumChain::<50>::problem(6, 1e-3);
    let method = method(differentiation);
    let report = check(&PendulumChain::<50>::default(), &problem, &method).expect("checked");
    let mut stepper = Stepper::new(PendulumChain::<50>::default(), &problem, &method).expect("prepared");
    stepper.step().expect("step 1");
    let saved = stepper.state();
    stepper.step().expect("step 2");
    let second = stepper.row().q.to_vec();
    stepper.restart(&saved).expect("restarted");
    stepper.step().expect("step 2 again");
    assert_eq!(stepper.row().q.to_vec(), second);
    while !stepper.is_finished() {
        stepper.step().expect("a step");
    }
    (stepper.summary().expect("summary").final_q, second, report.invariance.len())
}

#[test]
fn a_chain_of_fifty_steps_on_a_thread_of_two_mebibytes() {
    for differentiation in [Differentiation::Dual, Differentiation::Compiled] {
        let small = on_stack(SMALL, move || stepped(differentiation));
        let large = on_stack(64 << 20, move || stepped(differentiation));
        assert_eq!(small, large, "{differentiation:?}");
    }
}

#[test]
fn an_ensemble_of_chains_of_fifty_runs_on_rayon_threads() {
    let chain = (find("pendulum_chain").unwrap().build)(&[("links".into(), 50.0)]).unwrap();
    let problem = PendulumChain::<50>::problem(4, 1e-3);
    let member = |i: usize| {
        let mut problem = problem.clone();
        problem.q0[0] += 0.01 * i as f64;
        Ok((MemberSystem::Shared(chain.as_ref() as &dyn DynSystem), problem))
    };
    let outcomes: Mutex<Vec<(usize, Outcome)>> = Mutex::new(Vec::new());
    let sink = |i: usize, outcome: Outcome| {
        outcomes.lock().unwrap().push((i, outcome));
        Ok(())
    };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).stack_size(SMALL).build().unwrap();
    let dual = method(Differentiation::Dual);
    pool.install(|| run(0..4, &member, &dual, &OutputOptions::default(), false, &sink)).expect("the ensemble ran");
    let mut outcomes = outcomes.into_inner().unwrap();
    outcomes.sort_by_key(|(i, _)| *i);
    assert_eq!(outcomes.len(), 4);
    for (i, outcome) in outcomes {
        assert!(outcome.is_finished(), "member {i}: {:?}", outcome.status);
        let alone = on_stack(64 << 20, {
            let (chain, mut problem, dual) = (find("pendulum_chain").unwrap(), problem.clone(), dual.clone());
            move || {
                problem.q0[0] += 0.01 * i as f64;
                let system = (chain.build)(&[("links".into(), 50.0)]).unwrap();
                system.integrate(&problem, &dual, &OutputOptions::default(), &mut |_| Ok(())).unwrap().final_q
            }
        });
        assert_eq!(outcome.final_q, alone, "member {i}");
    }
}

#[test]
fn the_stack_kept_free_grows_with_the_square_of_the_size() {
    assert_eq!(ddirac::stack::needed(0), 256 << 10);
    assert!(ddirac::stack::needed(50) > 4 << 20, "a step of 50 was measured to need more than 2 MiB");
    assert!(ddirac::stack::needed(ddirac::stack::ON_ANY_THREAD) < SMALL / 2);
}
