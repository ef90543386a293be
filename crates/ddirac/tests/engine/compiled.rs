//! Compiled derivatives against dual numbers: every built-in system, rule, variant, reduced and
//! unreduced, and a system written as text run the same trajectories both ways (within what the
//! Newton tolerance allows), and a Lagrangian that branches on a value is refused, not compiled.

use crate::common;
use crate::pendulum_text;

use common::max_scaled_row_diff;
use ddirac::expression::ExpressionSystem;
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, HeavyTop, Kepler, PendulumChain, TwoBody};
use ddirac::{
    solve, Coordinate, DerivativePath, Differentiation, Error, InitialMomentum, Method, OutputOptions, Problem, Rule,
    Solution, System, Variant,
};
use num_dual::DualNum;
use pendulum_text::double_spherical_pendulum_spec;

fn run<S: System<N>, const N: usize>(system: &S, problem: &Problem, method: &Method, how: Differentiation) -> Solution {
    let method = Method { differentiation: how, ..method.clone() };
    solve(system, problem, &method, &OutputOptions::default()).unwrap_or_else(|e| panic!("{method:?}: {e}"))
}

/// Runs both ways; returns the largest scaled row difference of q and p.
fn compare<S: System<N>, const N: usize>(name: &str, system: &S, problem: &Problem, method: &Method) -> f64 {
    let compiled = run(system, problem, method, Differentiation::Compiled);
    let dual = run(system, problem, method, Differentiation::Dual);
    assert!(
        matches!(compiled.summary.derivatives, DerivativePath::Compiled { .. }),
        "{name}: {}",
        compiled.summary.derivatives
    );
    assert_eq!(dual.summary.derivatives, DerivativePath::Dual { reason: None });
    let d = max_scaled_row_diff(&compiled.q, &dual.q).max(max_scaled_row_diff(&compiled.p, &dual.p));
    eprintln!("{name}: compiled vs dual {d:.1e} ({})", compiled.summary.derivatives);
    d
}

fn methods(reduced_too: bool) -> Vec<Method> {
    let mut out = vec![];
    for rule in Rule::ALL {
        for variant in [Variant::Plus, Variant::Minus] {
            for reduced in [false, true] {
                if reduced && !reduced_too {
                    continue;
                }
                out.push(Method { rule, variant, reduced, ..Method::default() });
            }
        }
    }
    out
}

#[test]
fn charged_particle_every_method() {
    for method in methods(true) {
        let name = format!("charged particle {method:?}");
        let d = compare(&name, &ChargedParticle::default(), &ChargedParticle::paper_problem(400), &method);
        assert!(d < 1e-10, "{name}: {d:e}");
    }
}

#[test]
fn double_spherical_pendulum_every_method() {
    let mut problem = DoubleSphericalPendulum::paper_problem(10_000);
    problem.steps = 500;
    for method in methods(true) {
        let name = format!("double spherical pendulum {method:?}");
        let d = compare(&name, &DoubleSphericalPendulum::default(), &problem, &method);
        assert!(d < 1e-9, "{name}: {d:e}");
    }
}

#[test]
fn kepler_heavy_top_two_body_and_chain() {
    let kepler = Problem::new(0.01, 500, vec![1.0, 0.3], InitialMomentum::Momentum(vec![0.2, 1.2]));
    let top = Problem::new(1e-3, 500, vec![0.0, 0.6, 0.0], InitialMomentum::Velocity(vec![0.4, 0.0, 30.0]));
    for method in methods(true) {
        let d = compare("kepler", &Kepler::default(), &kepler, &method);
        assert!(d < 1e-10, "kepler {method:?}: {d:e}");
        let d = compare("heavy top", &HeavyTop::default(), &top, &method);
        assert!(d < 1e-10, "heavy top {method:?}: {d:e}");
    }
    let two_body = TwoBody::default();
    let problem =
        Problem::new(0.01, 300, vec![0.0, 0.0, 1.0, 0.0], InitialMomentum::Velocity(vec![0.0, 0.0, 0.0, 0.8]));
    let method =
        Method { reduced: true, connection: Some(two_body.centre_of_mass_connection().unwrap()), ..Method::default() };
    let d = compare("two body, centre-of-mass connection", &two_body, &problem, &method);
    assert!(d < 1e-10, "two body: {d:e}");
    let chain = PendulumChain::<12>::default();
    let d = compare("chain of 12", &chain, &PendulumChain::<12>::problem(200, 0.01), &Method::default());
    assert!(d < 1e-9, "chain: {d:e}");
}

#[test]
fn a_system_written_as_text() {
    let system = ExpressionSystem::<4>::new(&double_spherical_pendulum_spec()).unwrap();
    let mut problem = DoubleSphericalPendulum::paper_problem(10_000);
    problem.steps = 500;
    for reduced in [false, true] {
        let method = Method { reduced, ..Method::default() };
        let d = compare("double spherical pendulum as text", &system, &problem, &method);
        assert!(d < 1e-9, "text, reduced {reduced}: {d:e}");
    }
}

/// A free particle whose Lagrangian switches formula on the sign of a coordinate: tracing would
/// record only one branch.
struct Branching;

impl System<1> for Branching {
    fn coordinates(&self) -> [Coordinate; 1] {
        [Coordinate::shape("x")]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 1], v: &[D; 1]) -> D {
        let potential = if q[0].re() > 0.0 { q[0] * q[0] } else { q[0] * q[0] * 2.0 };
        v[0] * v[0] * 0.5 - potential
    }
}

#[test]
fn a_lagrangian_that_branches_on_a_value_is_not_compiled() {
    let problem = Problem::new(0.002, 5000, vec![0.5], InitialMomentum::Momentum(vec![0.0]));
    let auto = run(&Branching, &problem, &Method::default(), Differentiation::Auto);
    let DerivativePath::Dual { reason: Some(reason) } = &auto.summary.derivatives else {
        panic!("compiled a branching Lagrangian: {}", auto.summary.derivatives)
    };
    assert!(reason.contains("inspect") || reason.contains("value"), "{reason}");
    let dual = run(&Branching, &problem, &Method::default(), Differentiation::Dual);
    assert_eq!(auto.q, dual.q);
    let method = Method { differentiation: Differentiation::Compiled, ..Method::default() };
    let err = solve(&Branching, &problem, &method, &OutputOptions::default()).unwrap_err();
    assert!(matches!(err, Error::NotCompiled(_)), "{err}");
}
