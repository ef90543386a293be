//! `rigid`: the free rigid body's step on SO(3) (`ddirac::rigid`, midpoint rule at the group midpoint,
//! unreduced and reduced by SO(3)) against a hand-written Lie group variational integrator
//! ([`super::lgvi`]), 10³ steps of h = 0.01 from Π0 = (0.3, 2, 0.5) with I = (1, 2, 3); the final Π's
//! error against RK4 of Euler's equations (converged to round-off) is printed for each, so that the
//! times compare methods of like accuracy (both are of order 2).

use ddirac::rigid::{integrate_rigid, RigidInitial, RigidProblem};
use ddirac::systems::RigidBody;
use ddirac::Method;
use serde::Serialize;
use serde_json::Value;

use super::harness::{compare, Comparison, Contender, Pair, Target};
use super::lgvi::{self, State};
use super::{print, to_json, Settings};

/// The target of the issue that asked for the group: ddirac's free-body step within 1.5× of the
/// hand-written one.
const TARGET: Target = Target::AtMost(1.5);

#[derive(Serialize)]
struct Report {
    errors: Vec<(String, f64)>,
    comparison: Comparison,
}

const INERTIA: [f64; 3] = [1.0, 2.0, 3.0];
const PI0: [f64; 3] = [0.3, 2.0, 0.5];
const H: f64 = 0.01;

/// Euler's equations Π̇ = Π × I⁻¹Π by RK4 with `n` steps over `t`.
fn reference(t: f64, n: usize) -> [f64; 3] {
    let cross =
        |a: [f64; 3], b: [f64; 3]| [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    let field = |p: [f64; 3]| cross(p, [0, 1, 2].map(|i| p[i] / INERTIA[i]));
    let h = t / n as f64;
    let mut p = PI0;
    for _ in 0..n {
        let k1 = field(p);
        let k2 = field([0, 1, 2].map(|i| p[i] + h / 2.0 * k1[i]));
        let k3 = field([0, 1, 2].map(|i| p[i] + h / 2.0 * k2[i]));
        let k4 = field([0, 1, 2].map(|i| p[i] + h * k3[i]));
        p = [0, 1, 2].map(|i| p[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    p
}

fn gap(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

/// Runs the group.
pub fn run(settings: &Settings) -> Result<Value, miette::Report> {
    let steps = if settings.quick { 100 } else { 1000 };
    print::heading("rigid", "the free rigid body's step on SO(3) against a hand-written LGVI");
    let body = RigidBody::free(INERTIA[0], INERTIA[1], INERTIA[2]);
    let identity = ddirac::rigid::so3::identity();
    let problem = RigidProblem::new(H, steps, identity, RigidInitial::Momentum { pi: PI0, p: vec![] });
    let exact = reference(H * steps as f64, 100 * steps);
    let mut errors = vec![];
    let mut contenders = vec![];
    for (name, reduced) in [("ddirac, unreduced", false), ("ddirac, reduced by SO(3)", true)] {
        let method = Method { reduced, ..Method::default() };
        let run = {
            let (body, problem, method) = (body, problem.clone(), method.clone());
            move || integrate_rigid(&body, problem.clone(), &method, usize::MAX, |_| {})
        };
        let summary = run().map_err(|e| miette::miette!("the rigid body's run failed: {e}"))?;
        errors.push((name.to_owned(), gap(summary.final_pi, exact)));
        let timed = run;
        contenders.push(Contender::new(name, steps, move || {
            std::hint::black_box(timed().map_err(|e| miette::miette!("{e}"))?);
            Ok(())
        }));
    }
    let state = State { r: identity, pi: PI0 };
    let end = lgvi::integrate(INERTIA, state, H, steps, 1e-12);
    errors.push(("LGVI by hand".to_owned(), gap(end.pi, exact)));
    contenders.push(Contender::new("LGVI by hand", steps, move || {
        std::hint::black_box(lgvi::integrate(INERTIA, std::hint::black_box(state), H, steps, 1e-12));
        Ok(())
    }));
    for (name, error) in &errors {
        println!("  final |ΔΠ|∞ against RK4 after {steps} steps: {name:<26} {error:.3e}");
    }
    let pairs = [
        Pair::new("ddirac, unreduced", "LGVI by hand").target(TARGET),
        Pair::new("ddirac, reduced by SO(3)", "LGVI by hand").target(TARGET),
    ];
    let title = format!("free rigid body I = (1, 2, 3), h = {H}, {steps} steps; ratios of time per step");
    let comparison = compare(title, settings.schedule, contenders, &pairs)?;
    print::comparison(&comparison);
    to_json(&Report { errors, comparison })
}
