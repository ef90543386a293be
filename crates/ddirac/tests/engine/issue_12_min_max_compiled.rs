//! `min`, `max` and `abs` of the expression language under `derivatives = "compiled"`.
//!
//! A trace used to fail on `min`/`max` ("inspects the value of an input-dependent number"), so a run
//! that asked for compiled derivatives was refused. `min` and `max` of the language are now
//! operations of the compiled program (one-sided derivatives of the operand picked), so the programs
//! hold on both sides of the kink without guards. The runs below agree with dual numbers and with the
//! exact motion.

use ddirac::compiled::{pair_programs, Traced};
use ddirac::dim::Fixed;
use ddirac::expression::{ExpressionSpec, ExpressionSystem};
use ddirac::{
    solve, Coordinate, DerivativePath, Differentiation, InitialMomentum, Method, OutputOptions, Problem, System,
};

/// L = ½ẋ² − V(x) as text.
fn oscillator(potential: &str) -> ExpressionSystem<1> {
    let spec = ExpressionSpec {
        coordinates: vec![Coordinate::shape("x")],
        lagrangian: format!("0.5*x_dot^2 - ({potential})"),
        parameters: vec![("k1".into(), 4.0), ("k2".into(), 1.0)],
        ..ExpressionSpec::default()
    };
    ExpressionSystem::new(&spec).unwrap()
}

fn run(system: &ExpressionSystem<1>, how: Differentiation, steps: usize) -> ddirac::Solution {
    let problem = Problem::new(0.001, steps, vec![1.0], InitialMomentum::Momentum(vec![0.0]));
    let method = Method { differentiation: how, ..Method::default() };
    solve(system, &problem, &method, &OutputOptions::default()).unwrap()
}

/// A spring stiffer for x > 0 (k1 = 4) than for x < 0 (k2 = 1): x(t) = cos 2t until the crossing at
/// t = π/4 with velocity −2, then x(t) = −2 sin(t − π/4).
#[test]
fn a_piecewise_spring_written_with_max_and_min_compiles_and_follows_the_exact_motion() {
    let system = oscillator("0.5*k1*max(x, 0)^2 + 0.5*k2*min(x, 0)^2");
    let compiled = run(&system, Differentiation::Compiled, 2000);
    assert!(
        matches!(compiled.summary.derivatives, DerivativePath::Compiled { .. }),
        "{}",
        compiled.summary.derivatives
    );
    let dual = run(&system, Differentiation::Dual, 2000);
    for (k, (c, d)) in compiled.q.iter().zip(&dual.q).enumerate() {
        assert!((c[0] - d[0]).abs() < 1e-12, "row {k}: compiled {} vs dual {}", c[0], d[0]);
    }
    let exact = |t: f64| {
        let crossing = std::f64::consts::FRAC_PI_4;
        if t <= crossing {
            (2.0 * t).cos()
        } else {
            -2.0 * (t - crossing).sin()
        }
    };
    for (k, q) in compiled.q.iter().enumerate().step_by(100) {
        let t = compiled.t[k];
        assert!((q[0] - exact(t)).abs() < 1e-5, "t = {t}: {} vs exact {}", q[0], exact(t));
    }
}

/// The programs traced at x = 1 > 0 have no guards and give the force of the other side at x < 0:
/// ∂L/∂x = −k1·x for x > 0, −k2·x for x < 0.
#[test]
fn min_and_max_are_operations_of_the_program_not_guarded_comparisons() {
    let system = oscillator("0.5*k1*max(x, 0)^2 + 0.5*k2*min(x, 0)^2");
    let f = |base: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| system.lagrangian(&[base[0] + a[0]], &[b[0]]);
    let programs = pair_programs(Fixed, f, &[1.0], &[0.0]).unwrap();
    assert!(programs.guards.is_empty(), "{} guards", programs.guards.len());
    let mut out = [0.0; 3];
    for (x, force) in [(0.5, -2.0), (-0.5, 0.5), (-2.0, 2.0)] {
        programs.first.eval(&[x, 0.3], &mut Vec::new(), &mut out);
        assert!((out[1] - force).abs() < 1e-15, "∂L/∂x at {x}: {} vs {force}", out[1]);
        assert!((out[2] - 0.3).abs() < 1e-15, "∂L/∂ẋ at {x}: {}", out[2]);
    }
}

/// V = |x|: a constant force towards 0, x(t) = 1 − t²/2 until t = √2.
#[test]
fn a_v_shaped_potential_written_with_abs_compiles_and_follows_the_exact_motion() {
    let system = oscillator("abs(x)");
    let compiled = run(&system, Differentiation::Compiled, 1400);
    assert!(matches!(compiled.summary.derivatives, DerivativePath::Compiled { .. }));
    let dual = run(&system, Differentiation::Dual, 1400);
    for (c, d) in compiled.q.iter().zip(&dual.q) {
        assert!((c[0] - d[0]).abs() < 1e-12);
    }
    let (t, x) = (compiled.t[1400], compiled.q[1400][0]);
    assert!((x - (1.0 - t * t / 2.0)).abs() < 1e-9, "x({t}) = {x}");
}
