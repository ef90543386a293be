//! A user atlas whose maps are not inverses (`atan2` arguments swapped in `to_main`) was silently
//! never used: no point passed the run's "there and back" test, the run reported "0 switches among 3
//! charts" and gave the wrong answer of the main chart through the pole, and `ddirac check` never
//! looked at charts. The check now examines every chart over its domain, and the run refuses it with
//! the check's error.

use crate::spherical_pendulum_text::spherical_pendulum;
use ddirac::{ChartProblem, DynSystem, Error, InitialMomentum, Method, OutputOptions, Problem};

#[test]
fn swapped_atan2_arguments_are_refused_by_check_and_run() {
    let mut spec = spherical_pendulum();
    for chart in &mut spec.charts {
        chart.to_main[1].1 = "atan2(x, y)".into();
    }
    let system: Box<dyn DynSystem> = spec.into_dyn().expect("a valid spec");
    // Through the pole: L_z small.
    let problem = Problem::new(0.005, 2000, vec![1.0, 0.0], InitialMomentum::Velocity(vec![0.0, 0.05]));
    let method = Method { reduced: true, ..Method::default() };
    let report = system.check(&problem, &method).expect("a report");
    assert_eq!(report.charts.len(), 2, "the check examines the charts");
    assert!(report.charts.iter().all(|c| !c.inverse()), "{:?}", report.charts);
    let from_check = report.verdict(&method).expect_err("refused");
    let from_run =
        system.integrate(&problem, &method, &OutputOptions::default(), &mut |_| Ok(())).expect_err("refused");
    assert_eq!(from_check.to_string(), from_run.to_string());
    assert!(matches!(from_run, Error::Chart { problem: ChartProblem::NotInverse { .. }, .. }), "{from_run}");
    // Without the atlas the charts are not used, and the run is the main chart's alone.
    let main_only = Method { atlas: false, ..method };
    assert!(system.check(&problem, &main_only).unwrap().verdict(&main_only).is_ok());
}
