//! A chart whose maps are not inverse used to run: one 0.1 % off the inverse of its `from_main`
//! passed the "there and back" test near the pole (at 1e-6), its switches moved the energy by 1.7e-3
//! without a word, and the bob ended 1.09 off on a unit sphere. The check now tests the maps over
//! the chart's domain, and a run (which applies the same test before its first step, and again at
//! each switch) refuses the chart with the same error.

use crate::spherical_pendulum_text::spherical_pendulum;
use ddirac::expression::ExpressionSpec;
use ddirac::{ChartProblem, DynSystem, Error, InitialMomentum, Method, OutputOptions, Problem};

/// Over the top through both caps: released 1 rad from the bottom with polar rate 6.3.
fn problem() -> Problem {
    Problem::new(0.01, 2000, vec![1.0, 0.0], InitialMomentum::Velocity(vec![6.3, 2.0]))
}

fn method() -> Method {
    Method { reduced: true, ..Method::default() }
}

/// The check's verdict and the run's outcome, which must be the same refusal.
fn refused(spec: ExpressionSpec) -> Error {
    let system: Box<dyn DynSystem> = spec.into_dyn().expect("a valid spec");
    let report = system.check(&problem(), &method()).expect("a report");
    let from_check = report.verdict(&method()).expect_err("the check accepts a chart whose maps are not inverse");
    let from_run = system
        .integrate(&problem(), &method(), &OutputOptions::default(), &mut |_| Ok(()))
        .expect_err("a run through a chart whose maps are not inverse");
    assert_eq!(from_check.to_string(), from_run.to_string());
    from_run
}

fn not_inverse(error: &Error, chart: &str) -> f64 {
    match error {
        Error::Chart { chart: name, problem: ChartProblem::NotInverse { deviation, .. } } if name == chart => {
            *deviation
        }
        other => panic!("another error: {other}"),
    }
}

#[test]
fn a_from_main_map_scaled_by_a_thousandth_is_refused() {
    let mut spec = spherical_pendulum();
    spec.charts[0].from_main[0].1 = "1.001*sin(theta)*cos(phi)".into();
    let deviation = not_inverse(&refused(spec), "lower cap");
    assert!(deviation > 1e-4 && deviation < 1e-2, "{deviation:e}");
}

/// Off by 0.1 % of r² only: exact at the pole, where the old test looked.
#[test]
fn a_to_main_map_off_away_from_the_pole_is_refused() {
    let mut spec = spherical_pendulum();
    spec.charts[1].to_main[0].1 = "atan2(sqrt(x^2 + y^2)*(1 + 0.001*(x^2 + y^2)), -sqrt(1 - x^2 - y^2))".into();
    let deviation = not_inverse(&refused(spec), "upper cap");
    assert!(deviation > 1e-6, "{deviation:e}");
}

#[test]
fn the_shipped_atlas_passes_the_check_with_maps_inverse_to_round_off() {
    let system: Box<dyn DynSystem> = spherical_pendulum().into_dyn().expect("a valid spec");
    let report = system.check(&problem(), &method()).expect("a report");
    assert_eq!(report.charts.len(), 2);
    for chart in &report.charts {
        assert!(chart.points >= 20, "{}: {} points", chart.name, chart.points);
        assert!(chart.round_trip < 1e-13, "{}: {:e}", chart.name, chart.round_trip);
        assert!(chart.singular_where_good.is_none());
    }
    assert!(report.verdict(&method()).expect("accepted").is_empty());
}
