//! A loose Newton tolerance used to accept the predictor as the step: Kepler from r = 1 with
//! `tolerance = 1e-3` took 0 iterations at every step, kept r at exactly 1 (a circle instead of the
//! ellipse) and ended 34.7 from the exact orbit, with its energy "conserved" and no warning. Newton's
//! method now takes at least one correction from its starting point, so a loose tolerance costs
//! accuracy in proportion to itself, not the whole solution; and a run whose tolerance allows each
//! step more error than the step's own truncation error says so (`loose_tolerance`).

use ddirac::systems::{DoubleSphericalPendulum, Kepler};
use ddirac::{solve, InitialMomentum, Method, NewtonOptions, OutputOptions, Problem, Summary, WarningKind};

fn method(tolerance: f64) -> Method {
    Method { reduced: true, newton: NewtonOptions { tolerance, ..NewtonOptions::default() }, ..Method::default() }
}

/// The orbit of examples/kepler.toml: from the apocentre r = 1 with angular momentum 0.8, h = 0.002,
/// T = 40 (about ten revolutions).
fn kepler(tolerance: f64) -> Summary {
    let problem = Problem::new(0.002, 20_000, vec![1.0, 0.0], InitialMomentum::Momentum(vec![0.0, 0.8]));
    solve(&Kepler::default(), &problem, &method(tolerance), &OutputOptions { every: 20_000, ..Default::default() })
        .expect("the run completes")
        .summary
}

#[test]
fn a_loose_tolerance_follows_the_kepler_ellipse() {
    let tight = kepler(1e-12);
    let loose = kepler(1e-3);
    // Against Kepler's equation (the exact orbit), not against another run of the engine.
    let (tight_error, loose_error) = (tight.reference_error.unwrap(), loose.reference_error.unwrap());
    assert!(tight_error < 1e-2, "the method's own error {tight_error:e}");
    assert!(loose_error < 2.0 * tight_error, "tolerance 1e-3: error {loose_error:e} against {tight_error:e}");
    assert!(loose.newton.total_iterations >= 20_000, "{:?}", loose.newton);
    // r is no longer frozen at its initial value.
    assert!((loose.final_q[0] - 1.0).abs() > 1e-3, "r = {}", loose.final_q[0]);
    // A step of h = 0.002 errs by about |Δq| (h ω)² ≈ 1e-8; the tolerance allows 1e-3.
    let loose_warning = loose.warnings.iter().find(|w| w.kind == WarningKind::LooseTolerance);
    assert!(loose_warning.is_some_and(|w| w.message.contains("1e-3")), "{:?}", loose.warnings);
    assert!(tight.warnings.is_empty(), "{:?}", tight.warnings);
}

#[test]
fn a_loose_tolerance_follows_the_double_spherical_pendulum() {
    let system = DoubleSphericalPendulum::default();
    let problem = DoubleSphericalPendulum::paper_problem(10_000);
    let output = OutputOptions { every: 10_000, ..Default::default() };
    let tight = solve(&system, &problem, &method(1e-12), &output).expect("the run completes").summary;
    let loose = solve(&system, &problem, &method(1e-4), &output).expect("the run completes").summary;
    let apart = tight.final_q.iter().zip(&loose.final_q).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    // The tight run's own error at this step is far larger than 1e-6 rad; the Newton error must
    // not add to it visibly (it was 0.02 rad).
    assert!(apart < 1e-6, "final q differs by {apart:e} rad");
    assert!(loose.warnings.iter().any(|w| w.kind == WarningKind::LooseTolerance), "{:?}", loose.warnings);
}
