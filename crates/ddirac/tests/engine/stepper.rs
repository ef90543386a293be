//! The stepper is the one implementation of a run: stepping it by hand reproduces `solve` bit for bit
//! (every q, p, energy, discrete energy and momentum-map entry, and the summary), and a stepper
//! restarted from a saved state continues bit for bit as the uninterrupted run. The pendulum chain of
//! ten links keeps its chord-Newton Jacobian across steps (n ≥ 9), so its restart only matches
//! because the state carries that Jacobian; the charged particle with compiled derivatives takes the
//! closed-form step.

use ddirac::expression::ExpressionSpec;
use ddirac::num_dual::DualNum;
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, PendulumChain};
use ddirac::{
    solve, Coordinate, Differentiation, DynState, DynSystem, Erased, Error, Input, Method, OutputOptions, OwnedRow,
    Problem, Rule, Solution, State, Stepper, Summary, System,
};

/// Steps `stepper` to the end, collecting the rows as `integrate` reports them with `every` = 1.
fn rows_to_end<S: System<N> + Clone, const N: usize>(stepper: &mut Stepper<S, N>) -> Vec<OwnedRow<N>> {
    let mut rows = vec![];
    while !stepper.is_finished() {
        let mut row = stepper.row();
        row.discrete_energy = Some(stepper.step().expect("the step succeeds").discrete_energy);
        rows.push(row);
    }
    rows.push(stepper.row());
    rows
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|v| v.to_bits()).collect()
}

/// Every entry of every row, as bits: k, t, q, p, H, L_d (NaN on the last row), J.
fn row_bits<const N: usize>(row: &OwnedRow<N>) -> Vec<u64> {
    let scalars = [row.k as f64, row.t, row.energy, row.discrete_energy.unwrap_or(f64::NAN)];
    [bits(&scalars), bits(&row.q), bits(&row.p), bits(row.momentum_map())].concat()
}

fn solution_bits(solution: &Solution, k: usize) -> Vec<u64> {
    let scalars = [k as f64, solution.t[k], solution.energy[k], solution.discrete_energy[k]];
    [bits(&scalars), bits(&solution.q[k]), bits(&solution.p[k]), bits(&solution.momentum_map[k])].concat()
}

/// The summary without its wall-clock time, the only entry that may differ between two runs.
fn timeless(summary: Summary) -> Summary {
    Summary { wall_seconds: 0.0, ..summary }
}

/// A stepper stepped by hand gives `solve`'s rows and summary, bit for bit.
fn assert_reproduces_solve<S: System<N>, const N: usize>(name: &str, system: &S, problem: &Problem, method: &Method) {
    let solution = solve(system, problem, method, &OutputOptions::default()).expect("the run succeeds");
    let mut stepper = Stepper::new(system, problem, method).unwrap();
    let rows = rows_to_end(&mut stepper);
    assert_eq!(rows.len(), solution.t.len(), "{name}");
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(row_bits(row), solution_bits(&solution, k), "{name}: row {k} differs");
    }
    assert_eq!(timeless(stepper.finish().unwrap()), timeless(solution.summary), "{name}: summaries differ");
}

/// Runs `split` steps, saves the state, runs on to the end; a second stepper restarted from the state
/// gives the same rows from `split` on and the same summary, bit for bit. Returns the saved state and
/// the rows from `split` on.
fn assert_restarts<S: System<N>, const N: usize>(
    name: &str,
    system: &S,
    problem: &Problem,
    method: &Method,
    split: usize,
) -> (State<N>, Vec<OwnedRow<N>>) {
    let mut first = Stepper::new(system, problem, method).unwrap();
    let mut early = vec![];
    while first.k() < split {
        let mut row = first.row();
        row.discrete_energy = Some(first.step().unwrap().discrete_energy);
        early.push(row);
    }
    let saved = first.state();
    assert!(saved.is_warm() && saved.k() == split, "{name}");
    let rows = rows_to_end(&mut first);
    let summary = first.finish().unwrap();

    let mut second = Stepper::new(system, problem, method).unwrap();
    second.restart(&saved).unwrap();
    assert_eq!((second.k(), second.t()), (split, split as f64 * problem.step), "{name}");
    let again = rows_to_end(&mut second);
    assert_eq!(again.len(), rows.len(), "{name}");
    for (a, b) in rows.iter().zip(&again) {
        assert_eq!(row_bits(a), row_bits(b), "{name}: row {} differs after the restart", a.k);
    }
    // The state carries the record too: the summary covers the whole run.
    assert_eq!(timeless(second.finish().unwrap()), timeless(summary), "{name}: summaries differ");
    // And the saved state is the uninterrupted run's state at `split`.
    let solution = solve(system, problem, method, &OutputOptions::default()).unwrap();
    assert_eq!(bits(saved.q()), bits(&solution.q[split]), "{name}");
    assert_eq!(bits(saved.p()), bits(&solution.p[split]), "{name}");
    assert_eq!(early.len(), split);
    (saved, rows)
}

/// A cold state (q, p) at the same step continues close to the warm one, but not necessarily bit for
/// bit: it starts with a fresh predictor (h · v from the Legendre transform), no kept Jacobian and a
/// new record. Both continuations solve the same step equations to the Newton tolerance (1e-12), so
/// they differ by round-off grown over the remaining steps. Returns the largest difference of q and p
/// relative to their scale.
fn cold_difference<S: System<N>, const N: usize>(
    system: &S,
    problem: &Problem,
    method: &Method,
    saved: &State<N>,
    warm: &[OwnedRow<N>],
) -> f64 {
    let mut stepper = Stepper::new(system, problem, method).unwrap();
    stepper.restart(&saved.cold()).unwrap();
    let cold = rows_to_end(&mut stepper);
    assert_eq!(cold.len(), warm.len());
    let summary = stepper.finish().unwrap();
    assert_eq!(summary.steps, problem.steps - saved.k(), "a cold record covers the steps from the state on");
    let scale = warm.iter().flat_map(|r| r.q.iter().chain(&r.p)).fold(1.0f64, |m, v| m.max(v.abs()));
    let diff = warm
        .iter()
        .zip(&cold)
        .flat_map(|(w, c)| w.q.iter().chain(&w.p).zip(c.q.iter().chain(&c.p)).map(|(a, b)| (a - b).abs()))
        .fold(0.0f64, f64::max);
    diff / scale
}

fn reduced(rule: Rule) -> Method {
    Method { rule, reduced: true, ..Method::default() }
}

#[test]
fn charged_particle_stepper_reproduces_solve_and_restarts() {
    let (system, problem) = (ChargedParticle::default(), ChargedParticle::paper_problem(200));
    for method in [reduced(Rule::Left), Method { rule: Rule::Left, ..Method::default() }] {
        let name = format!("charged particle, reduced = {}", method.reduced);
        assert_reproduces_solve(&name, &system, &problem, &method);
        let (saved, warm) = assert_restarts(&name, &system, &problem, &method, 77);
        let cold = cold_difference(&system, &problem, &method, &saved, &warm);
        eprintln!("{name}: cold restart at k = 77 differs by {cold:.2e} (relative)");
        assert!(cold < 1e-9, "{name}: {cold:e}");
    }
}

/// Compiled derivatives with the closed-form step (the charged particle's step equations are linear):
/// the stepper keeps the programs compiled by `Stepper::new` across a restart.
#[test]
fn charged_particle_closed_form_step_restarts() {
    let (system, problem) = (ChargedParticle::default(), ChargedParticle::paper_problem(400));
    let method = Method { differentiation: Differentiation::Compiled, ..reduced(Rule::Left) };
    let solution = solve(&system, &problem, &method, &OutputOptions::default()).unwrap();
    let closed_form =
        matches!(solution.summary.derivatives, ddirac::DerivativePath::Compiled { closed_form: Some(_), .. });
    if !closed_form {
        eprintln!("skipped: no native code here ({})", solution.summary.derivatives);
        return;
    }
    assert_reproduces_solve("charged particle, closed form", &system, &problem, &method);
    assert_restarts("charged particle, closed form", &system, &problem, &method, 150);

    // The closed-form step holds the problem's charge μ = p_θ = 1 as a constant. A cold state with
    // the charge 2 (twice the cyclotron frequency) is stepped by Newton's method instead, and agrees
    // with a run prepared for that charge.
    let p0 = [1.0, 0.0, 1.0, 2.0];
    let mut stepper = Stepper::new(&system, &problem, &method).unwrap();
    stepper.restart(&State::new(0, [0.0; 4], p0)).unwrap();
    let rows = rows_to_end(&mut stepper);
    let charge_two = Problem::with_momentum(problem.step, problem.steps, [0.0; 4], p0);
    let expected = solve(&system, &charge_two, &method, &OutputOptions::default()).unwrap();
    let difference = rows
        .iter()
        .zip(&expected.q)
        .flat_map(|(row, q)| row.q.iter().zip(q).map(|(a, b)| (a - b).abs()))
        .fold(0.0f64, f64::max);
    eprintln!("charged particle, charge 2 after a restart: differs from its own run by {difference:.2e}");
    assert!(difference < 1e-9, "{difference:e}");
    let summary = stepper.finish().unwrap();
    assert!(summary.newton.total_iterations > problem.steps, "Newton's method solved the steps: {:?}", summary.newton);
    // The exact helix of charge 2 (radius 1/2): the same order of error as the paper's charge 1.
    assert!(summary.reference_error.unwrap() < 0.05, "{:?}", summary.reference_error);
}

#[test]
fn double_spherical_pendulum_reduced_stepper_reproduces_solve_and_restarts() {
    let system = DoubleSphericalPendulum::default();
    let problem = Problem { steps: 300, ..DoubleSphericalPendulum::paper_problem(10_000) };
    let method = reduced(Rule::Midpoint);
    assert_reproduces_solve("double spherical pendulum", &system, &problem, &method);
    let (saved, warm) = assert_restarts("double spherical pendulum", &system, &problem, &method, 123);
    let cold = cold_difference(&system, &problem, &method, &saved, &warm);
    eprintln!("double spherical pendulum: cold restart at k = 123 differs by {cold:.2e} (relative)");
    assert!(cold < 1e-9, "{cold:e}");
}

/// Ten links: chord Newton keeps its factorized Jacobian from one step to the next, so the
/// continuation after a restart depends on the Jacobian the state carries.
#[test]
fn pendulum_chain_of_ten_links_restarts_with_its_kept_jacobian() {
    let system = PendulumChain::<10>::default();
    let problem = PendulumChain::<10>::problem(200, 0.01);
    let method = Method::default();
    assert_reproduces_solve("chain of 10", &system, &problem, &method);
    let (saved, warm) = assert_restarts("chain of 10", &system, &problem, &method, 90);

    // Jacobians are kept across steps: far fewer Jacobians than steps.
    let summary = solve(&system, &problem, &method, &OutputOptions::default()).unwrap().summary;
    assert!(summary.newton.total_jacobians < problem.steps / 2, "{:?}", summary.newton);

    // Without the memory the continuation is not the same bits (a fresh Jacobian and predictor) ...
    let mut cold = Stepper::new(&system, &problem, &method).unwrap();
    cold.restart(&saved.cold()).unwrap();
    let cold_rows = rows_to_end(&mut cold);
    assert!(warm.iter().zip(&cold_rows).any(|(w, c)| row_bits(w) != row_bits(c)), "the memory made no difference");
    // ... but it is close.
    let difference = cold_difference(&system, &problem, &method, &saved, &warm);
    eprintln!("chain of 10: cold restart at k = 90 differs by {difference:.2e} (relative)");
    assert!(difference < 1e-9, "{difference:e}");
}

/// A cold state at k = 0 from the problem's own initial data is the run itself.
#[test]
fn a_cold_state_from_the_initial_data_is_the_run() {
    let (system, problem) = (ChargedParticle::default(), ChargedParticle::paper_problem(100));
    let method = reduced(Rule::Left);
    let solution = solve(&system, &problem, &method, &OutputOptions::default()).unwrap();
    let (q0, initial) = problem.initial_data::<4>().unwrap();
    let ddirac::InitialData::Momentum(p0) = initial else { panic!("momenta") };
    let mut stepper = Stepper::new(&system, &problem, &method).unwrap();
    stepper.step().unwrap();
    stepper.restart(&State::new(0, q0, p0)).unwrap();
    let rows = rows_to_end(&mut stepper);
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(row_bits(row), solution_bits(&solution, k), "row {k}");
    }
    assert_eq!(timeless(stepper.finish().unwrap()), timeless(solution.summary));
}

#[test]
fn restarts_that_cannot_continue_are_refused() {
    let (system, problem) = (ChargedParticle::default(), ChargedParticle::paper_problem(100));
    let mut stepper = Stepper::new(&system, &problem, &reduced(Rule::Left)).unwrap();
    stepper.step().unwrap();
    let saved = stepper.state();

    // Another method or step: the memory does not apply.
    let mut other = Stepper::new(&system, &problem, &reduced(Rule::Right)).unwrap();
    let e = other.restart(&saved).unwrap_err();
    assert!(matches!(&e, Error::Invalid { what: Input::State, .. }), "{e:?}");
    assert!(e.to_string().contains("another method or step"), "{e}");
    let mut finer = Stepper::new(&system, &ChargedParticle::paper_problem(200), &reduced(Rule::Left)).unwrap();
    assert!(finer.restart(&saved).is_err());
    // Its cold form does.
    finer.restart(&saved.cold()).unwrap();
    assert_eq!(finer.k(), 1);

    let e = stepper.restart(&State::new(101, [0.0; 4], [0.0; 4])).unwrap_err();
    assert!(e.to_string().contains("step 101 is beyond the problem's last step 100"), "{e}");
    let e = stepper.restart(&State::new(0, [0.0; 4], [1.0, f64::NAN, 1.0, 1.0])).unwrap_err();
    assert!(matches!(e, Error::NonFinite { what: Input::State, entry: Some(5), .. }), "{e:?}");
    assert_eq!(e.to_string(), "entry 6 of the state (q, p) is not finite (NaN)");

    // A degenerate Lagrangian: a cold state must lie on the primary constraint p = ∂L/∂v.
    let problem = Problem::with_momentum(0.01, 10, [0.5, 0.0], [0.0, 0.5]);
    let mut oscillator = Stepper::new(&FirstOrder, &problem, &Method::default()).unwrap();
    oscillator.restart(&State::new(3, [0.2, 0.1], [0.0, 0.2])).unwrap();
    let e = oscillator.restart(&State::new(3, [0.2, 0.1], [1.0, 0.2])).unwrap_err();
    assert!(matches!(e, Error::OffPrimaryConstraint { rank: 0, coordinates: 2, .. }), "{e:?}");

    // A finished run takes no more steps.
    while !stepper.is_finished() {
        stepper.step().unwrap();
    }
    let e = stepper.step().unwrap_err();
    assert!(matches!(e, Error::Invalid { what: Input::Steps, .. }), "{e:?}");
}

/// L = x ẏ − ½ (x² + y²): linear in the velocities, so p = ∂L/∂v = (0, x) whatever v (the harmonic
/// oscillator in first-order form).
struct FirstOrder;

impl System<2> for FirstOrder {
    fn coordinates(&self) -> [Coordinate; 2] {
        [Coordinate::shape("x"), Coordinate::shape("y")]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 2], v: &[D; 2]) -> D {
        q[0] * v[1] - (q[0] * q[0] + q[1] * q[1]) * 0.5
    }
}

/// The type-erased stepper of a text Lagrangian: the same rows as its `integrate`, a bit-for-bit
/// restart through `DynState`, and sizes checked for cold states.
#[test]
fn erased_stepper_of_an_expression_system_reproduces_integrate_and_restarts() {
    // The charged particle of the paper, in text.
    let spec = ExpressionSpec {
        coordinates: ["q1", "q2", "q3"]
            .map(Coordinate::shape)
            .into_iter()
            .chain([Coordinate::group("theta").angle()])
            .collect(),
        lagrangian: "0.5*(q1_dot^2 + q2_dot^2 + q3_dot^2) + 0.5*(theta_dot + 0.5*B0*(q1*q2_dot - q2*q1_dot))^2".into(),
        parameters: vec![("B0".into(), 1.0)],
        ..ExpressionSpec::default()
    };
    let system: Box<dyn DynSystem> = spec.into_dyn().unwrap();
    let problem = ChargedParticle::paper_problem(100);
    let method = reduced(Rule::Left);
    let mut expected = vec![];
    system
        .integrate(&problem, &method, &OutputOptions::default(), &mut |row| {
            expected.push([bits(row.q), bits(row.p), bits(&[row.energy])].concat());
            Ok(())
        })
        .unwrap();

    let mut stepper = system.stepper(&problem, &method).unwrap();
    let mut saved: Option<DynState> = None;
    let mut rows = vec![];
    while !stepper.is_finished() {
        if stepper.k() == 40 {
            saved = Some(stepper.state());
        }
        let row = stepper.row();
        rows.push([bits(&row.q), bits(&row.p), bits(&[row.energy])].concat());
        stepper.step().unwrap();
    }
    let row = stepper.row();
    rows.push([bits(&row.q), bits(&row.p), bits(&[row.energy])].concat());
    assert_eq!(rows, expected);

    let saved = saved.unwrap();
    assert!(saved.is_warm() && saved.q().len() == 4);
    stepper.restart(&saved).unwrap();
    let mut again = vec![];
    while !stepper.is_finished() {
        let row = stepper.row();
        again.push([bits(&row.q), bits(&row.p), bits(&[row.energy])].concat());
        stepper.step().unwrap();
    }
    let row = stepper.row();
    again.push([bits(&row.q), bits(&row.p), bits(&[row.energy])].concat());
    assert_eq!(again, expected[40..]);

    let e = stepper.restart(&DynState::new(0, vec![0.0; 3], vec![0.0; 4])).unwrap_err();
    assert!(matches!(e, Error::Size { what: Input::State, expected: 4, found: 3 }), "{e:?}");
    // A state of another dimension, even a warm one, is refused.
    let chain: Box<dyn DynSystem> = Box::new(Erased(PendulumChain::<3>::default()));
    let chain_state = chain.stepper(&PendulumChain::<3>::problem(10, 0.01), &Method::default()).unwrap().state();
    assert!(matches!(stepper.restart(&chain_state), Err(Error::Size { what: Input::State, expected: 4, found: 3 })));
}
