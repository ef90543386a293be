//! Runtime inputs instead of baked constants: the step size h and a text Lagrangian's parameters are
//! inputs of the compiled programs, so the runs of a convergence study (four step sizes) and of a
//! parameter sweep compile their programs once.
//!
//! Before, h and the parameters were folded into the programs, and every step size and every
//! parameter value compiled two new native programs. The counts below are of this test process
//! only, which runs this one test.

#[path = "common/pendulum_text.rs"]
mod pendulum_text;

use ddirac::compiled::native_compilations;
use ddirac::expression::ExpressionSystem;
use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{
    solve, DerivativePath, Differentiation, InitialMomentum, Method, OutputOptions, Problem, Solution, System,
};
use pendulum_text::double_spherical_pendulum_spec;

fn run<S: System<4>>(system: &S, step: f64, steps: usize, reduced: bool) -> Solution {
    let problem =
        Problem::new(step, steps, vec![0.0, 2.25, 2.0, 3.0], InitialMomentum::Momentum(vec![0.0, 0.0, 1.0, 1.0]));
    let method = Method { reduced, differentiation: Differentiation::Compiled, atlas: false, ..Method::default() };
    let solution = solve(system, &problem, &method, &OutputOptions::default()).unwrap();
    assert!(matches!(solution.summary.derivatives, DerivativePath::Compiled { .. }));
    solution
}

#[test]
fn four_step_sizes_and_a_parameter_sweep_compile_once() {
    let pendulum = DoubleSphericalPendulum::default();
    for reduced in [false, true] {
        let before = native_compilations();
        let finals: Vec<Solution> =
            [0.08, 0.04, 0.02, 0.01].iter().map(|&h| run(&pendulum, h, (0.8 / h) as usize, reduced)).collect();
        // Two programs (residual; residual and Jacobian), compiled for the first step size only.
        assert_eq!(native_compilations() - before, 2, "reduced {reduced}");
        // The runs are of their own step sizes: the error of q(0.8) falls as h² (one program, four h).
        let reference = run(&pendulum, 0.0025, 320, reduced);
        let errors: Vec<f64> = finals
            .iter()
            .map(|s| {
                s.summary.final_q.iter().zip(&reference.summary.final_q).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
            })
            .collect();
        for pair in errors.windows(2) {
            let ratio = pair[0] / pair[1];
            assert!((3.0..5.5).contains(&ratio), "reduced {reduced}: errors {errors:?}");
        }
    }

    // The same Lagrangian as text, for three values of the second mass: one compile.
    let mut spec = double_spherical_pendulum_spec();
    let m2 = spec.parameters.iter().position(|(name, _)| name == "m2").unwrap();
    let before = native_compilations();
    let mut final_p = vec![];
    for mass in [35.0, 20.0, 50.0] {
        spec.parameters[m2].1 = mass;
        let system = ExpressionSystem::<4>::new(&spec).unwrap();
        let text = run(&system, 0.01, 100, false);
        // Each run is of its own mass: it equals the built-in system with that mass (dual numbers).
        let built_in = DoubleSphericalPendulum { m2: mass, ..DoubleSphericalPendulum::default() };
        let problem =
            Problem::new(0.01, 100, vec![0.0, 2.25, 2.0, 3.0], InitialMomentum::Momentum(vec![0.0, 0.0, 1.0, 1.0]));
        let method = Method { differentiation: Differentiation::Dual, atlas: false, ..Method::default() };
        let dual = solve(&built_in, &problem, &method, &OutputOptions::default()).unwrap();
        for (a, b) in text.summary.final_q.iter().zip(&dual.summary.final_q) {
            assert!((a - b).abs() < 1e-10, "m2 = {mass}: {a} vs {b}");
        }
        final_p.push(text.summary.final_p.clone());
    }
    assert_eq!(native_compilations() - before, 2);
    assert_ne!(final_p[0], final_p[1]);
}
