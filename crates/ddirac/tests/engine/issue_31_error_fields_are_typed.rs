//! The errors of a failed run carry what they say as typed fields, not sentences: a Newton failure
//! the chart watch explains carries the coordinate and the conditioning (`SingularLegendre`, tested
//! in `issue_13_pole_passage_is_named`), and the sub-steps it was also tried as; an energy jump
//! that fails the run carries the jump (`EnergyChange`). Each still prints the sentence it printed.

use ddirac::systems::SphericalPendulum;
use ddirac::{
    solve, EnergyChange, EnergyJump, Error, InitialMomentum, JumpAction, Method, NewtonOptions, OutputOptions, Problem,
    WarningKind, MAX_SUBDIVISION,
};

/// The spherical pendulum over the top (energy 15.97 > 2 m g l), reduced midpoint steps of h for
/// T = 20, with the atlas: at h = 0.05 the step does not resolve the passages (the issue-30 case).
fn over_the_top(h: f64, method: Method) -> Result<ddirac::Solution, Error> {
    let steps = (20.0 / h).round() as usize;
    let q0 = vec![0.0, std::f64::consts::PI - 1.0];
    let problem = Problem::new(h, steps, q0, InitialMomentum::Velocity(vec![2.0, -6.3]));
    solve(&SphericalPendulum::default(), &problem, &method, &OutputOptions::default())
}

#[test]
fn a_failing_energy_jump_carries_the_jump_the_warning_describes() {
    let warn = Method { reduced: true, ..Method::default() };
    let warned = over_the_top(0.05, warn.clone()).expect("a warned run completes");
    let jumps: Vec<_> = warned.summary.warnings.iter().filter(|w| w.kind == WarningKind::EnergyJump).collect();
    let fail = Method { energy_jump: EnergyJump { action: JumpAction::Fail, ..EnergyJump::default() }, ..warn };
    match over_the_top(0.05, fail) {
        Err(error @ Error::EnergyJump { .. }) => {
            let text = error.to_string();
            let Error::EnergyJump { step, t, h, change, .. } = error else { unreachable!() };
            assert_eq!(h, 0.05);
            assert!((t - step as f64 * h).abs() < 1e-9, "t = {t}, step {step}");
            match change {
                EnergyChange::Jumped(jump) => {
                    assert_eq!(jump.at, (step, t));
                    assert!(jump.before.is_finite() && jump.after.is_finite() && jump.after != jump.before);
                    // The first jump of the warned run is this one, told in the same words.
                    let first = jumps.first().expect("the warned run warns of the jump it fails on");
                    assert_eq!((first.step, first.t), (Some(step), Some(t)));
                    assert!(text.ends_with(&first.message), "{text}\nagainst\n{}", first.message);
                }
                EnergyChange::Implausible { relative, limit } => {
                    assert!(relative > limit, "{relative} ≤ {limit}");
                    assert!(text.contains(&format!("{:.1} %", relative * 100.0)), "{text}");
                }
            }
        }
        Err(other) => panic!("another error: {other}"),
        Ok(solution) => {
            assert!(jumps.is_empty(), "failing on a jump, a run completed: {:?}", solution.summary.warnings)
        }
    }
}

#[test]
fn a_newton_failure_after_subdivision_carries_the_sub_steps_tried() {
    // One correction allowed: no step, and no sub-step, can converge.
    let newton = NewtonOptions { max_iterations: 1, tolerance: 1e-15, ..NewtonOptions::default() };
    let method = Method { reduced: true, newton, ..Method::default() };
    match over_the_top(0.05, method) {
        Err(error @ Error::Newton { .. }) => {
            let text = error.to_string();
            let Error::Newton { step, sub_steps, iterations, .. } = error else { unreachable!() };
            assert_eq!(step, 0, "the first step fails");
            assert!(iterations <= 1);
            assert_eq!(sub_steps, Some(MAX_SUBDIVISION));
            assert!(text.contains(&format!("nor as 2, 4, …, {MAX_SUBDIVISION} sub-steps")), "{text}");
        }
        other => panic!("not a Newton failure: {:?}", other.map(|s| s.summary.steps)),
    }
}

/// An invalid input says why as a `Reason` with its numbers, and prints the sentence it printed.
#[test]
fn an_invalid_input_carries_its_reason_with_the_numbers() {
    use ddirac::{Connection, Input, Reason};
    let error = Connection::new(&[vec![0.0, 1.0], vec![0.5]]).unwrap_err();
    assert!(matches!(
        &error,
        Error::Invalid { what: Input::Connection, why: Reason::UnequalRows { row: 2, found: 1, first: 2 } }
    ));
    assert_eq!(
        error.to_string(),
        "invalid connection: row 2 of K has 1 entries, but row 1 has 2: K has one entry per shape coordinate in every row"
    );
    let error = Connection::new(&[vec![f64::NAN]]).unwrap_err();
    assert!(matches!(error, Error::Invalid { why: Reason::NonFiniteEntry { row: 1, value }, .. } if value.is_nan()));

    let built_in = ddirac::systems::find("charged_particle").expect("a built-in");
    let error = (built_in.build)(&[("mass".into(), 1.0)]).err().expect("refused");
    let Error::Invalid { what: Input::Parameter(name), why: Reason::UnknownParameter { known } } = error else {
        panic!("{error:?}")
    };
    assert_eq!(name, "mass");
    // The known parameters are the built-in's own, as its defaults list them.
    let defaults: Vec<String> = (built_in.defaults)().into_iter().map(|(n, _)| n.to_string()).collect();
    assert_eq!(known, defaults);
    assert!(known.iter().any(|k| k == "m"), "{known:?}");

    let problem = Problem::new(0.1, 0, vec![0.0; 2], InitialMomentum::Momentum(vec![0.0; 2]));
    let error = solve(&SphericalPendulum::default(), &problem, &Method::default(), &OutputOptions::default());
    assert!(matches!(error, Err(Error::Invalid { what: Input::Steps, why: Reason::Zero })), "{error:?}");
}
