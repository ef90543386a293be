//! For a chart whose group coordinate is not a symmetry, `ddirac check` said "a run would be
//! accepted" while the run refused when it entered the chart; with `check_invariance = false` the
//! run exited 0 without a `not_invariant` warning while its energy went from −3.9 to 38. The check
//! now tests every chart's group coordinates, and the run applies the same verdict before its first
//! step: both refuse, or both accept with the same warning.

use crate::spherical_pendulum_text::spherical_pendulum;
use ddirac::expression::{ChartSpec, ExpressionSpec};
use ddirac::{
    ChartProblem, Coordinate, DynSystem, Error, InitialMomentum, Method, OutputOptions, Problem, WarningKind,
};

/// The spherical pendulum with a third chart: (θ, φ) again, but with θ declared the group
/// coordinate, which L depends on; good everywhere, so the run enters it where the main chart's
/// quality falls.
fn spec() -> ExpressionSpec {
    let mut spec = spherical_pendulum();
    spec.charts = vec![ChartSpec {
        name: "swapped roles".into(),
        coordinates: vec![Coordinate::group("a").angle(), Coordinate::shape("b").angle()],
        to_main: vec![("theta".into(), "a".into()), ("phi".into(), "b".into())],
        from_main: vec![("a".into(), "theta".into()), ("b".into(), "phi".into())],
        quality: "1".into(),
    }];
    spec
}

fn problem() -> Problem {
    Problem::new(0.005, 2000, vec![1.0, 0.0], InitialMomentum::Velocity(vec![0.0, 0.05]))
}

#[test]
fn check_and_run_refuse_a_chart_whose_group_coordinate_is_not_a_symmetry() {
    let system: Box<dyn DynSystem> = spec().into_dyn().expect("a valid spec");
    let method = Method { reduced: true, ..Method::default() };
    let report = system.check(&problem(), &method).expect("a report");
    let from_check = report.verdict(&method).expect_err("the check must refuse what the run refuses");
    let from_run =
        system.integrate(&problem(), &method, &OutputOptions::default(), &mut |_| Ok(())).expect_err("refused");
    assert_eq!(from_check.to_string(), from_run.to_string());
    match from_run {
        Error::Chart { chart, problem: ChartProblem::NotInvariant { coordinate, .. } } => {
            assert_eq!((chart.as_str(), coordinate.as_str()), ("swapped roles", "a"));
        }
        other => panic!("another error: {other}"),
    }
}

/// Reducing by `a` in that chart is wrong: the run either fails there (Newton's method cannot follow
/// the wrong equations) or completes, and then says so; it never completes silently.
#[test]
fn without_the_invariance_check_both_warn() {
    let system: Box<dyn DynSystem> = spec().into_dyn().expect("a valid spec");
    let method = Method { reduced: true, check_invariance: false, ..Method::default() };
    let from_check = system.check(&problem(), &method).unwrap().verdict(&method).expect("accepted");
    assert!(from_check.iter().any(|w| w.kind == WarningKind::NotInvariant), "{from_check:?}");
    match system.integrate(&problem(), &method, &OutputOptions::default(), &mut |_| Ok(())) {
        Ok(summary) => {
            assert!(summary.warnings.iter().any(|w| w.kind == WarningKind::NotInvariant), "{:?}", summary.warnings)
        }
        Err(e @ (Error::Newton { .. } | Error::Diverged { .. })) => eprintln!("the wrong reduction fails: {e}"),
        Err(other) => panic!("another error: {other}"),
    }
    // Before its first step the run carries the check's warning (it is the check's verdict).
    let mut stepper = system.stepper(&problem(), &method).expect("accepted");
    let summary = stepper.summary().expect("a summary before the first step");
    assert!(summary.warnings.iter().any(|w| w.kind == WarningKind::NotInvariant), "{:?}", summary.warnings);
}

#[test]
fn an_unreduced_run_does_not_need_the_chart_symmetry() {
    let system: Box<dyn DynSystem> = spec().into_dyn().expect("a valid spec");
    let method = Method { reduced: false, ..Method::default() };
    assert!(system.check(&problem(), &method).unwrap().verdict(&method).is_ok());
    assert!(system.integrate(&problem(), &method, &OutputOptions::default(), &mut |_| Ok(())).is_ok());
}
