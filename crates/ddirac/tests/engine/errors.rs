//! Bad input and failed steps are reported as [`Error`] values, never as panics, and their messages
//! name what is wrong: the input, the step, or the coordinate.

use crate::common;

use ddirac::mechanics::legendre;
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, TwoBody};
use ddirac::{
    integrate, solve, Connection, Coordinate, Error, InitialMomentum, Input, Method, NewtonOptions, OutputOptions,
    Problem, Rule, System,
};
use num_dual::DualNum;

fn reduced() -> Method {
    Method { rule: Rule::Left, reduced: true, ..Method::default() }
}

fn run_err<S: System<N>, const N: usize>(system: &S, problem: &Problem, method: &Method) -> Error {
    match solve(system, problem, method, &OutputOptions::default()) {
        Ok(s) => panic!("expected an error, got a run ending at {:?}", s.summary.final_q),
        Err(e) => {
            eprintln!("{e}");
            e
        }
    }
}

fn cp_problem() -> Problem {
    ChargedParticle::paper_problem(10)
}

#[test]
fn wrong_sizes_are_rejected() {
    let cp = ChargedParticle::default();
    let short_q = Problem { q0: vec![0.0; 3], ..cp_problem() };
    let e = run_err(&cp, &short_q, &reduced());
    assert!(matches!(&e, Error::Size { what: Input::InitialConfiguration, expected: 4, found: 3 }), "{e:?}");
    assert!(e.to_string().contains("initial configuration q has 3 entries"), "{e}");

    let long_p = Problem { initial: InitialMomentum::Momentum(vec![0.0; 5]), ..cp_problem() };
    let e = run_err(&cp, &long_p, &Method::default());
    assert!(matches!(&e, Error::Size { what: Input::InitialMomentum, expected: 4, found: 5 }), "{e:?}");
    assert!(e.to_string().contains("initial momentum p has 5 entries"), "{e}");

    let short_v = Problem { initial: InitialMomentum::Velocity(vec![1.0]), ..cp_problem() };
    let e = run_err(&cp, &short_v, &Method::default());
    assert!(matches!(&e, Error::Size { what: Input::InitialVelocity, expected: 4, found: 1 }), "{e:?}");
    assert!(e.to_string().contains("initial velocity v"), "{e}");
}

#[test]
fn non_finite_initial_data_is_rejected() {
    let cp = ChargedParticle::default();
    let nan_q = Problem { q0: vec![0.0, f64::NAN, 0.0, 0.0], ..cp_problem() };
    let e = run_err(&cp, &nan_q, &reduced());
    assert!(
        matches!(&e, Error::NonFinite { what: Input::InitialConfiguration, entry: Some(1), value } if value.is_nan()),
        "{e:?}"
    );
    assert!(e.to_string().contains("entry 2 of the initial configuration q"), "{e}");

    let inf_p = Problem { initial: InitialMomentum::Momentum(vec![1.0, 0.0, f64::INFINITY, 1.0]), ..cp_problem() };
    let e = run_err(&cp, &inf_p, &reduced());
    assert!(
        matches!(&e, Error::NonFinite { what: Input::InitialMomentum, entry: Some(2), value } if *value == f64::INFINITY),
        "{e:?}"
    );
    assert!(e.to_string().contains("entry 3 of the initial momentum p"), "{e}");
}

/// Velocities whose Legendre transform is not finite: the error names the momentum they map to.
#[test]
fn velocities_with_a_non_finite_momentum_are_rejected() {
    let problem = Problem::new(0.1, 10, vec![0.0; 4], InitialMomentum::Velocity(vec![1.0, 0.0, 1e308, 1.0]));
    let e = run_err(&ChargedParticle { m: 10.0, b0: 1.0 }, &problem, &Method::default());
    assert!(
        matches!(&e, Error::NonFinite { what: Input::MomentumFromVelocity, entry: Some(2), value } if value.is_infinite()),
        "{e:?}"
    );
    assert_eq!(e.to_string(), "entry 3 of the initial momentum p = ∂L/∂v(q0, v0) is not finite (inf)");
}

/// A built-in system refuses a parameter by name, in a typed field.
#[test]
fn parameters_are_named_in_their_errors() {
    let build = ddirac::systems::find("charged_particle").unwrap().build;
    let e = build(&[("m".into(), -1.0)]).err().expect("a negative mass is refused");
    assert!(matches!(&e, Error::Invalid { what: Input::Parameter(name), .. } if name == "m"), "{e:?}");
    assert_eq!(e.to_string(), "invalid parameter `m`: must be positive, got -1");
    let e = build(&[("B0".into(), f64::NAN)]).err().expect("NaN is refused");
    assert!(matches!(&e, Error::NonFinite { what: Input::Parameter(name), entry: None, .. } if name == "B0"));
    assert_eq!(e.to_string(), "parameter `B0` is not finite (NaN)");
}

#[test]
fn bad_step_and_step_count_are_rejected() {
    let cp = ChargedParticle::default();
    for step in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let e = run_err(&cp, &Problem { step, ..cp_problem() }, &reduced());
        assert!(matches!(&e, Error::Invalid { what, .. } if *what == Input::Step), "step {step}: {e:?}");
        assert!(e.to_string().contains("positive"), "{e}");
    }
    let e = run_err(&cp, &Problem { steps: 0, ..cp_problem() }, &reduced());
    assert!(matches!(&e, Error::Invalid { what, .. } if *what == Input::Steps), "{e:?}");
    let e = solve(&cp, &cp_problem(), &reduced(), &OutputOptions { every: 0, wrap_angles: false }).unwrap_err();
    assert!(matches!(&e, Error::Invalid { what, .. } if *what == Input::Every), "{e:?}");
}

#[test]
fn bad_connections_are_rejected() {
    // K alone: rows of equal length, finite entries.
    let cases = [
        (vec![vec![0.0, f64::NAN, 0.0]], "row 1 of K contains the non-finite value NaN"),
        (vec![vec![0.0; 3], vec![0.0, 0.0, f64::NEG_INFINITY]], "row 2 of K contains the non-finite value -inf"),
        (vec![vec![0.0; 3], vec![0.0; 2]], "row 2 of K has 2 entries, but row 1 has 3"),
    ];
    for (k, text) in cases {
        let e = Connection::new(&k).unwrap_err();
        assert!(matches!(&e, Error::Invalid { what: Input::Connection, .. }), "{k:?}: {e:?}");
        assert!(e.to_string().contains(text), "{k:?}: `{e}` should contain `{text}`");
    }
    // K against the system: the charged particle has n_g = 1, n_x = 3, so K is 1 × 3.
    let cp = ChargedParticle::default();
    let cases = [
        (vec![vec![0.0, 0.0]], "row 1 of K has 2 entries"),
        (vec![vec![0.0; 3], vec![0.0; 3]], "found 2 rows"),
        (vec![], "found 0 rows"),
    ];
    for (k, text) in cases {
        let method = Method { connection: Some(Connection::new(&k).unwrap()), ..reduced() };
        let e = run_err(&cp, &cp_problem(), &method);
        assert!(matches!(&e, Error::Invalid { what: Input::Connection, .. }), "{k:?}: {e:?}");
        assert!(e.to_string().contains(text), "{k:?}: `{e}` should contain `{text}`");
    }
    // Two bodies: K must be 2 × 2.
    let tb = TwoBody::default();
    let problem = Problem::new(0.01, 10, vec![0.0, 0.0, 1.0, 0.0], InitialMomentum::Velocity(vec![0.0, 0.0, 0.0, 1.0]));
    let k = Connection::new(&[vec![-1.0 / 3.0, 0.0, 0.0], vec![-1.0 / 3.0, 0.0, 0.0]]).unwrap();
    let method = Method { rule: Rule::Midpoint, connection: Some(k), ..reduced() };
    let e = run_err(&tb, &problem, &method);
    assert!(matches!(&e, Error::Invalid { what: Input::Connection, .. }), "{e:?}");
}

/// A harmonic oscillator with a single shape coordinate: nothing to reduce.
struct Oscillator;

impl System<1> for Oscillator {
    fn coordinates(&self) -> [Coordinate; 1] {
        [Coordinate::shape("x")]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 1], v: &[D; 1]) -> D {
        (v[0] * v[0] - q[0] * q[0]) * 0.5
    }
}

#[test]
fn reduction_without_a_group_coordinate_is_refused() {
    let problem = Problem::new(0.1, 10, vec![1.0], InitialMomentum::Momentum(vec![0.0]));
    let e = run_err(&Oscillator, &problem, &reduced());
    assert!(matches!(e, Error::NoSymmetry), "{e:?}");
    assert!(e.to_string().contains("group coordinate"), "{e}");
    // The same problem runs unreduced: x_N ≈ cos(1).
    let solution = solve(&Oscillator, &problem, &Method::default(), &OutputOptions::default()).unwrap();
    assert!((solution.summary.final_q[0] - 1f64.cos()).abs() < 1e-3, "{:?}", solution.summary.final_q);
}

/// A plane pendulum whose angle is (wrongly) declared a group coordinate: L depends on it.
struct MislabelledPendulum;

impl System<1> for MislabelledPendulum {
    fn coordinates(&self) -> [Coordinate; 1] {
        [Coordinate::group("swing").angle()]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 1], v: &[D; 1]) -> D {
        v[0] * v[0] * 0.5 + q[0].cos() * 9.8
    }
}

#[test]
fn non_invariant_lagrangian_is_refused_naming_the_coordinate() {
    let problem = Problem::new(0.05, 100, vec![0.3], InitialMomentum::Momentum(vec![0.0]));
    let e = run_err(&MislabelledPendulum, &problem, &reduced());
    assert!(matches!(&e, Error::NotInvariant { coordinate, .. } if coordinate == "swing"), "{e:?}");
    assert!(e.to_string().contains("`swing`"), "{e}");
    // Unreduced, the pendulum is fine.
    assert!(solve(&MislabelledPendulum, &problem, &Method::default(), &OutputOptions::default()).is_ok());
}

#[test]
fn newton_failures_are_errors_naming_the_step() {
    // No iterations allowed: the first step cannot converge (the predictor h·v0 is not a root).
    let method = Method { newton: NewtonOptions { max_iterations: 0, ..NewtonOptions::default() }, ..reduced() };
    let e = run_err(&DoubleSphericalPendulum::default(), &DoubleSphericalPendulum::paper_problem(100), &method);
    assert!(matches!(&e, Error::Newton { step: 0, iterations: 0, .. }), "{e:?}");
    assert!(e.to_string().contains("step 0 (t = 0, h = 1)"), "{e}");

    // A step of half an orbital period through periapsis has no nearby root: it is taken as
    // sub-steps instead (see issue_14_failed_steps_are_subdivided.rs), and the run completes.
    let tb = TwoBody::default();
    let problem =
        Problem::new(1.0, 10, vec![0.3, -0.2, 1.0, 0.0], InitialMomentum::Velocity(vec![0.1, 0.05, 0.0, 1.1]));
    for reduced in [true, false] {
        let method = Method { rule: Rule::Midpoint, reduced, ..Method::default() };
        let summary = solve(&tb, &problem, &method, &OutputOptions::default()).unwrap().summary;
        assert!(summary.newton.subdivided_steps > 0, "reduced = {reduced}: {:?}", summary.newton);
    }

    // A huge step for the pendulum: Newton fails, whichever way, without a panic.
    let problem = Problem { step: 1e6, steps: 10, ..DoubleSphericalPendulum::paper_problem(1) };
    for reduced in [true, false] {
        let method = Method { rule: Rule::Midpoint, reduced, ..Method::default() };
        let e = run_err(&DoubleSphericalPendulum::default(), &problem, &method);
        assert!(matches!(&e, Error::Newton { .. } | Error::Diverged { .. }), "reduced = {reduced}: {e:?}");
        assert!(e.to_string().starts_with("step "), "{e}");
    }
}

#[test]
fn observer_failure_stops_the_run() {
    let mut rows = 0;
    let e = integrate(&ChargedParticle::default(), &cp_problem(), &reduced(), &OutputOptions::default(), &mut |row| {
        rows += 1;
        if row.k == 3 {
            Err("disk full".into())
        } else {
            Ok(())
        }
    })
    .unwrap_err();
    assert!(matches!(e, Error::Output(_)), "{e:?}");
    assert!(e.to_string().contains("disk full"), "{e}");
    assert_eq!(rows, 4, "rows k = 0..=3 were offered, then the run stopped");
}

/// Two point vortices of strengths Γ1, Γ2 in coordinates q = (X, Y, dx, dy) = (x1, y1, x2 − x1,
/// y2 − y1), with G = ℝ² translating (X, Y):
///
/// ```text
/// L = Σ_i ½ Γ_i (x_i ẏ_i − y_i ẋ_i) − H,   H = −(Γ1 Γ2 / 2π) ln |r1 − r2|
/// ```
///
/// L is linear in the velocities (degenerate) and invariant under translations only up to the
/// total derivative ½ Γ_i (a ẏ_i − b ẋ_i), so L_d is not invariant and the reduction of the paper
/// does not apply.
struct PointVortices {
    gamma1: f64,
    gamma2: f64,
}

impl PointVortices {
    fn hamiltonian(&self, q: &[f64]) -> f64 {
        -self.gamma1 * self.gamma2 / (4.0 * std::f64::consts::PI) * (q[2] * q[2] + q[3] * q[3]).ln()
    }
}

impl System<4> for PointVortices {
    fn coordinates(&self) -> [Coordinate; 4] {
        [Coordinate::group("X"), Coordinate::group("Y"), Coordinate::shape("dx"), Coordinate::shape("dy")]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 4], v: &[D; 4]) -> D {
        let (x1, y1, x2, y2) = (q[0], q[1], q[0] + q[2], q[1] + q[3]);
        let (u1, w1, u2, w2) = (v[0], v[1], v[0] + v[2], v[1] + v[3]);
        let symplectic = (x1 * w1 - y1 * u1) * (0.5 * self.gamma1) + (x2 * w2 - y2 * u2) * (0.5 * self.gamma2);
        let h = (q[2] * q[2] + q[3] * q[3]).ln() * (-self.gamma1 * self.gamma2 / (4.0 * std::f64::consts::PI));
        symplectic - h
    }
}

#[test]
fn point_vortices_are_refused_by_reduction_and_run_unreduced() {
    let vortices = PointVortices { gamma1: 1.0, gamma2: 2.0 };
    let q0 = [0.2, -0.1, 1.5, 0.5];
    // On the primary constraint p = ∂L/∂v, which does not depend on v.
    let p0 = legendre::momentum(&vortices, &q0, &[0.0; 4]);
    let p0_other = legendre::momentum(&vortices, &q0, &[0.3, -1.0, 2.0, 0.7]);
    assert!(common::max_abs_diff(&p0, &p0_other) < 1e-15, "∂L/∂v must not depend on v: {p0:?} vs {p0_other:?}");
    let problem = Problem::new(0.05, 1000, q0.to_vec(), InitialMomentum::Momentum(p0.to_vec()));

    let method = Method { rule: Rule::Midpoint, reduced: true, ..Method::default() };
    let e = run_err(&vortices, &problem, &method);
    assert!(matches!(&e, Error::NotInvariant { coordinate, .. } if coordinate == "X"), "{e:?}");
    assert!(e.to_string().contains("`X`"), "{e}");

    // Without the invariance check the reduced step must still fail cleanly (its μ-equation has no
    // unknown, so the step's Jacobian is singular: the motion is undetermined), not panic or return a
    // trajectory.
    let unchecked = Method { check_invariance: false, ..method };
    let e = run_err(&vortices, &problem, &unchecked);
    assert!(matches!(&e, Error::Undetermined { rank: 2, coordinates: 4 }), "{e:?}");

    // Unreduced, the midpoint rule is the implicit midpoint rule for the vortex equations; it
    // conserves the quadratic invariant |r1 − r2|² and hence H.
    let solution =
        solve(&vortices, &problem, &Method { rule: Rule::Midpoint, ..Method::default() }, &OutputOptions::default())
            .expect("the unreduced run succeeds");
    let h0 = vortices.hamiltonian(&q0);
    let h_error = solution.q.iter().map(|q| (vortices.hamiltonian(q) - h0).abs()).fold(0.0, f64::max) / h0.abs();
    let reported = solution.energy.iter().map(|e| (e - h0).abs()).fold(0.0, f64::max) / h0.abs();
    // The separation r1 − r2 turns uniformly at |Ω| = (Γ1 + Γ2) / (2π |r1 − r2|²); the midpoint phase
    // error is O(h²).
    let turned: f64 = solution
        .q
        .windows(2)
        .map(|w| (w[0][2] * w[1][3] - w[0][3] * w[1][2]).atan2(w[0][2] * w[1][2] + w[0][3] * w[1][3]))
        .sum();
    let d2 = q0[2] * q0[2] + q0[3] * q0[3];
    let exact = (vortices.gamma1 + vortices.gamma2) / (2.0 * std::f64::consts::PI * d2) * problem.duration();
    eprintln!(
        "vortices, 1000 midpoint steps: H0 = {h0:.6}, max |H(q_k) − H0|/|H0| = {h_error:.3e}, \
         reported energy max rel. error {reported:.3e}; separation turned by {turned:.6} rad, exact |ΩT| = {exact:.6}"
    );
    assert!(h_error <= 1e-10, "H drifts by {h_error:e}");
    assert!(reported <= 1e-10, "reported energy drifts by {reported:e}");
    assert!((turned.abs() - exact).abs() <= 1e-4 * exact, "turned {turned}, exact {exact}");
}
