//! Composition methods ([`ddirac::composition`]): a step as sub-steps γᵢh of the basic symmetric
//! step. Held against exact solutions (observed orders 4, 6 and 8), against the unreduced composed
//! flow (reduction commutes with composition), and against the structure a composition must keep:
//! the momentum map exactly, a symplectic and time-symmetric one-step map.

use crate::common;

use common::{log_log_slope, max_scaled_row_diff, relative_diff, run};
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, Kepler, TwoBody};
use ddirac::{
    solve, Composition, Differentiation, Error, InitialMomentum, Input, Method, NewtonOptions, OutputOptions, Problem,
    Rule, State, Stepper, System, Variant,
};

/// Every set with the step counts over which its error is in its asymptotic regime and above
/// round-off, on the charged particle (T = 20) and on Kepler's eccentric orbit (T = 20).
const SETS: [(Composition, [usize; 4], [usize; 4]); 6] = [
    (Composition::Suzuki5, [50, 100, 200, 400], [400, 800, 1600, 3200]),
    (Composition::TripleJump { order: 4 }, [100, 200, 400, 800], [800, 1600, 3200, 6400]),
    (Composition::KahanLi9, [25, 50, 100, 200], [400, 800, 1600, 3200]),
    (Composition::TripleJump { order: 6 }, [100, 200, 400, 800], [800, 1600, 3200, 6400]),
    (Composition::KahanLi17, [20, 28, 40, 56], [400, 504, 635, 800]),
    (Composition::TripleJump { order: 8 }, [100, 141, 200, 283], [1600, 2263, 3200, 4525]),
];

fn composed(rule: Rule, variant: Variant, reduced: bool, composition: Composition) -> Method {
    Method { rule, variant, reduced, composition, ..Method::default() }
}

/// Kepler's orbit from r = 1 with p_φ = 0.7 (eccentricity 0.51, period ≈ 2.9) over T = 20.
fn kepler_problem(steps: usize) -> Problem {
    Problem::new(20.0 / steps as f64, steps, vec![1.0, 0.0], InitialMomentum::Momentum(vec![0.0, 0.7]))
}

/// The slope of the error against h over `steps`, with the errors.
fn observed_order<S: System<N>, const N: usize>(
    system: &S,
    problem: impl Fn(usize) -> Problem,
    steps: &[usize],
    method: &Method,
) -> (f64, Vec<f64>) {
    let (h, errors): (Vec<f64>, Vec<f64>) = steps
        .iter()
        .map(|&n| {
            let problem = problem(n);
            (problem.step, run(system, &problem, method).summary.reference_error.expect("an exact solution"))
        })
        .unzip();
    (log_log_slope(&h, &errors), errors)
}

#[test]
fn compositions_reach_their_orders_on_the_charged_particle_and_kepler_in_every_form() {
    let mut worst: f64 = 0.0;
    for (composition, particle_steps, kepler_steps) in SETS {
        let order = f64::from(composition.order());
        for rule in [Rule::Midpoint, Rule::Trapezoid] {
            for variant in [Variant::Plus, Variant::Minus] {
                for reduced in [false, true] {
                    let method = composed(rule, variant, reduced, composition);
                    let runs = [
                        (
                            "charged particle",
                            observed_order(
                                &ChargedParticle::default(),
                                ChargedParticle::paper_problem,
                                &particle_steps,
                                &method,
                            ),
                        ),
                        ("Kepler", observed_order(&Kepler::default(), kepler_problem, &kepler_steps, &method)),
                    ];
                    for (system, (slope, errors)) in runs {
                        let form = format!("{composition}, {rule:?}, {variant:?}, reduced {reduced}, {system}");
                        eprintln!("{form}: slope {slope:.3}, errors {errors:?}");
                        assert!((slope - order).abs() <= 0.15, "{form}: observed order {slope:.3}, errors {errors:?}");
                        worst = worst.max((slope - order).abs());
                    }
                }
            }
        }
    }
    eprintln!("largest deviation of an observed order: {worst:.3}");
}

/// Reduction commutes with composition: the reduced composed run reconstructs the unreduced
/// composed run, on the paper's double spherical pendulum (§7.2, T = 10) and on two bodies with the
/// centre-of-mass connection K ≠ 0.
#[test]
fn reduced_composed_runs_equal_unreduced_composed_runs() {
    for composition in [Composition::Suzuki5, Composition::KahanLi9, Composition::KahanLi17] {
        for variant in [Variant::Plus, Variant::Minus] {
            let system = DoubleSphericalPendulum::default();
            let problem = DoubleSphericalPendulum::paper_problem(1000);
            let problem = Problem { steps: 500, ..problem };
            let unreduced = run(&system, &problem, &composed(Rule::Midpoint, variant, false, composition));
            let reduced = run(&system, &problem, &composed(Rule::Midpoint, variant, true, composition));
            let dq = max_scaled_row_diff(&reduced.q, &unreduced.q);
            let dp = max_scaled_row_diff(&reduced.p, &unreduced.p);
            eprintln!(
                "double spherical pendulum, {composition}, {variant:?}: rows differ by {dq:.2e} (q), {dp:.2e} (p)"
            );
            assert!(dq <= 1e-11 && dp <= 1e-10, "{composition}, {variant:?}: q rows {dq:e}, p rows {dp:e}");

            let system = TwoBody::default();
            let k = Some(system.centre_of_mass_connection().unwrap());
            let problem = Problem::new(
                0.02,
                500,
                vec![0.3, -0.2, 1.0, 0.0],
                InitialMomentum::Velocity(vec![0.1, 0.05, 0.0, 1.1]),
            );
            let unreduced = run(&system, &problem, &composed(Rule::Trapezoid, variant, false, composition));
            let mut method = composed(Rule::Trapezoid, variant, true, composition);
            method.connection = k;
            let reduced = run(&system, &problem, &method);
            let dq = max_scaled_row_diff(&reduced.q, &unreduced.q);
            let dp = max_scaled_row_diff(&reduced.p, &unreduced.p);
            eprintln!("two bodies with K ≠ 0, {composition}, {variant:?}: rows differ by {dq:.2e} (q), {dp:.2e} (p)");
            assert!(dq <= 1e-11 && dp <= 1e-10, "{composition}, {variant:?}: q rows {dq:e}, p rows {dp:e}");
            assert!(relative_diff(&reduced.summary.final_p, &unreduced.summary.final_p) <= 1e-11);
        }
    }
}

/// The momentum map (p_φ of Kepler, the total momentum of two bodies) is conserved to round-off by
/// composed runs, reduced and unreduced, although the sub-steps go backwards in time.
#[test]
fn composed_runs_conserve_the_momentum_map_exactly() {
    for composition in [Composition::TripleJump { order: 4 }, Composition::KahanLi9, Composition::KahanLi17] {
        for reduced in [false, true] {
            let method = composed(Rule::Midpoint, Variant::Plus, reduced, composition);
            let summary = run(&Kepler::default(), &kepler_problem(400), &method).summary;
            let drift = summary.momentum_map.max_relative_drift.unwrap();
            let system = TwoBody::default();
            let problem = Problem::new(
                0.02,
                500,
                vec![0.3, -0.2, 1.0, 0.0],
                InitialMomentum::Velocity(vec![0.1, 0.05, 0.0, 1.1]),
            );
            let two_body = run(&system, &problem, &method).summary.momentum_map.max_relative_drift.unwrap();
            eprintln!("{composition}, reduced {reduced}: momentum map drift {drift:.2e} (Kepler), {two_body:.2e} (two bodies)");
            assert!(drift <= 1e-13 && two_body <= 1e-13, "{composition}, reduced {reduced}: {drift:e}, {two_body:e}");
        }
    }
}

/// One composed step (q, p) ↦ (q', p') from a cold state of `stepper`.
fn one_step<S: System<N> + Clone, const N: usize>(stepper: &mut Stepper<S, N>, q: [f64; N], p: [f64; N]) -> Vec<f64> {
    stepper.restart(&State::new(0, q, p)).unwrap();
    stepper.step().unwrap();
    let row = stepper.row();
    row.q.iter().chain(&row.p).copied().collect()
}

/// The finite-difference Jacobian M of the composed one-step map of two bodies (the reduced runs
/// with the centre-of-mass connection K ≠ 0) satisfies MᵀJM = J (symplecticity).
#[test]
fn the_composed_one_step_map_is_symplectic() {
    let system = TwoBody::default();
    let problem =
        Problem::new(0.05, 100, vec![0.3, -0.2, 1.0, 0.0], InitialMomentum::Velocity(vec![0.1, 0.05, 0.0, 1.1]));
    let (q0, p0) = ([0.3, -0.2, 1.0, 0.1], [0.2, 0.1, -0.3, 0.6]);
    for composition in [Composition::Suzuki5, Composition::KahanLi9, Composition::KahanLi17] {
        for reduced in [false, true] {
            // Newton's method solved to round-off, so that its stopping point does not blur the differences.
            let mut method = composed(Rule::Midpoint, Variant::Plus, reduced, composition);
            method.newton = NewtonOptions { tolerance: 1e-15, reuse_jacobian: false, ..NewtonOptions::default() };
            if reduced {
                method.connection = Some(system.centre_of_mass_connection().unwrap());
            }
            let mut stepper = Stepper::new(&system, &problem, &method).unwrap();
            let eps = 1e-5;
            let columns: Vec<Vec<f64>> = (0..8)
                .map(|j| {
                    let mut shifted = |by: f64| {
                        let (mut q, mut p) = (q0, p0);
                        if j < 4 {
                            q[j] += by
                        } else {
                            p[j - 4] += by
                        }
                        one_step(&mut stepper, q, p)
                    };
                    let (plus, minus) = (shifted(eps), shifted(-eps));
                    plus.iter().zip(&minus).map(|(a, b)| (a - b) / (2.0 * eps)).collect()
                })
                .collect();
            let m = |i: usize, j: usize| columns[j][i];
            let j_form = |i: usize, j: usize| match (i < 4, j < 4) {
                (true, false) if j - 4 == i => 1.0,
                (false, true) if i - 4 == j => -1.0,
                _ => 0.0,
            };
            let mut worst: f64 = 0.0;
            for a in 0..8 {
                for b in 0..8 {
                    let mtjm: f64 = (0..8)
                        .flat_map(|i| (0..8).map(move |j| (i, j)))
                        .map(|(i, j)| m(i, a) * j_form(i, j) * m(j, b))
                        .sum();
                    worst = worst.max((mtjm - j_form(a, b)).abs());
                }
            }
            // The map moves: M is not the identity.
            let moved = (0..8).map(|i| (m(i, i) - 1.0).abs()).fold(0.0, f64::max) + m(0, 4).abs();
            eprintln!("{composition}, reduced {reduced}: max |MᵀJM − J| = {worst:.2e} (M − I up to {moved:.2e})");
            assert!(moved > 1e-2, "{composition}: the one-step map hardly moves");
            assert!(worst <= 1e-8, "{composition}, reduced {reduced}: MᵀJM − J reaches {worst:e}");
        }
    }
}

/// A symmetric composition of a symmetric step is symmetric; with a Lagrangian even in the
/// velocities the run is reversible: 200 steps forward, the momenta reversed, 200 steps forward
/// return to the start with reversed momenta.
#[test]
fn composed_runs_are_time_symmetric() {
    let system = Kepler::default();
    for composition in [Composition::Suzuki5, Composition::KahanLi9, Composition::KahanLi17] {
        for (rule, reduced) in [(Rule::Midpoint, false), (Rule::Trapezoid, true)] {
            let method = composed(rule, Variant::Plus, reduced, composition);
            let forward = run(&system, &Problem { steps: 200, ..kepler_problem(400) }, &method).summary;
            let back_p: Vec<f64> = forward.final_p.iter().map(|p| -p).collect();
            let problem = Problem::new(0.05, 200, forward.final_q.clone(), InitialMomentum::Momentum(back_p));
            let back = run(&system, &problem, &method).summary;
            let dq = (back.final_q[0] - 1.0).abs().max(back.final_q[1].abs());
            let dp = back.final_p[0].abs().max((back.final_p[1] + 0.7).abs());
            eprintln!(
                "{composition}, {rule:?}, reduced {reduced}: back at the start within {dq:.2e} (q), {dp:.2e} (p)"
            );
            assert!(dq <= 1e-11 && dp <= 1e-11, "{composition}: returns within {dq:e} (q), {dp:e} (p)");
        }
    }
}

/// The left and right rules are not symmetric: composing them is refused, naming the composition.
#[test]
fn a_composition_of_a_rule_that_is_not_symmetric_is_refused() {
    for rule in [Rule::Left, Rule::Right] {
        let method = composed(rule, Variant::Plus, false, Composition::Suzuki5);
        let problem = ChargedParticle::paper_problem(100);
        let error = Stepper::new(&ChargedParticle::default(), &problem, &method).err().expect("refused");
        match &error {
            Error::Invalid { what: Input::Composition, why } => {
                assert_eq!(why, &ddirac::Reason::NotSymmetric { order: 4, rule: rule.name() });
                assert!(why.to_string().contains("symmetric"), "{why}");
            }
            other => panic!("expected a refused composition, got {other}"),
        }
        assert!(ddirac::check(&ChargedParticle::default(), &problem, &method).is_err());
    }
}

/// The sub-steps that share the first one's trace (its programs with their own h as input) step as
/// dual numbers do at each sub-step size: a run of order 8 ends where the same run on dual numbers
/// ends, to round-off.
#[test]
fn the_sub_steps_sharing_one_trace_step_as_dual_numbers_do() {
    let system = DoubleSphericalPendulum::default();
    let problem = Problem { steps: 200, ..DoubleSphericalPendulum::paper_problem(10_000) };
    for composition in [Composition::KahanLi17, Composition::Suzuki5] {
        let end = |differentiation| {
            let method = Method { composition, differentiation, atlas: false, ..Method::default() };
            solve(&system, &problem, &method, &OutputOptions::default()).unwrap().summary.final_q
        };
        let (compiled, dual) = (end(Differentiation::Compiled), end(Differentiation::Dual));
        let apart = compiled.iter().zip(&dual).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        eprintln!("{composition:?}: compiled against dual numbers {apart:.1e}");
        assert!(apart < 1e-11, "{composition:?}: {apart:e}");
    }
}
