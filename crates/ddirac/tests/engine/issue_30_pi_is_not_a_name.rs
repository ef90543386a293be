//! A parameter, definition or coordinate named `pi` used to replace the constant π in every
//! expression of the spec, silently: `pi = 3` made `sin(pi*x)` a different Lagrangian. Constants are
//! now refused as names, as functions and `t` are, wherever a name is declared.

use ddirac::expression::{ChartSpec, ExpressionError, ExpressionSpec};
use ddirac::{Coordinate, InitialMomentum, Method, Problem};

/// A pendulum-like oscillator that uses π: L = ½ ẋ² + cos(pi x).
fn spec() -> ExpressionSpec {
    ExpressionSpec {
        coordinates: vec![Coordinate::shape("x")],
        lagrangian: "0.5*x_dot^2 + cos(pi*x)".into(),
        ..ExpressionSpec::default()
    }
}

fn refused(spec: ExpressionSpec) -> (String, String) {
    match spec.into_dyn() {
        Err(ExpressionError::InvalidName { name, reason, .. }) => (name, reason),
        Err(other) => panic!("another error: {other}"),
        Ok(_) => panic!("a spec that redefines `pi` was accepted"),
    }
}

#[test]
fn a_parameter_named_pi_is_refused() {
    let (name, reason) = refused(ExpressionSpec { parameters: vec![("pi".into(), 3.0)], ..spec() });
    assert_eq!(name, "pi");
    assert!(reason.contains("constant `pi`"), "{reason}");
}

#[test]
fn a_definition_named_pi_is_refused() {
    let (name, _) = refused(ExpressionSpec { definitions: vec![("pi".into(), "3".into())], ..spec() });
    assert_eq!(name, "pi");
}

#[test]
fn a_coordinate_named_pi_is_refused() {
    let spec = ExpressionSpec {
        coordinates: vec![Coordinate::shape("pi")],
        lagrangian: "0.5*pi_dot^2 - 0.5*pi^2".into(),
        ..ExpressionSpec::default()
    };
    let (name, _) = refused(spec);
    assert_eq!(name, "pi");
}

#[test]
fn a_chart_coordinate_named_pi_is_refused() {
    let spec = ExpressionSpec {
        quality: Some("1".into()),
        charts: vec![ChartSpec {
            name: "shifted".into(),
            coordinates: vec![Coordinate::shape("pi")],
            to_main: vec![("x".into(), "pi - 1".into())],
            from_main: vec![("pi".into(), "x + 1".into())],
            quality: "1".into(),
        }],
        ..spec()
    };
    let (name, _) = refused(spec);
    assert_eq!(name, "pi");
}

/// Without a declaration of its own, `pi` is π: L = ½ ẋ² + cos(π x) oscillates about x = 0 with
/// angular frequency π (period 2), so a small amplitude is back after t = 2 (with `pi` = 3 it would
/// be at cos 6 of it).
#[test]
fn undeclared_pi_is_the_constant() {
    let system = spec().into_dyn().expect("a valid spec");
    let (x0, h) = (1e-3, 1e-3);
    let problem = Problem::new(h, 2000, vec![x0], InitialMomentum::Velocity(vec![0.0]));
    let mut stepper = system.stepper(&problem, &Method::default()).expect("a stepper");
    while !stepper.is_finished() {
        stepper.step().expect("a step");
    }
    let x = stepper.row().q[0];
    // Second-order phase error (π h)² / 24 · 2π ≈ 3e-6 of a period, amplitude nonlinearity ≈ 6e-7.
    assert!((x - x0).abs() < 1e-6 * x0 * 10.0, "x(2) = {x}");
    assert!((x0 * 6f64.cos() - x).abs() > 1e-5, "x(2) = {x}");
}
