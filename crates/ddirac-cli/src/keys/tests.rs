//! The keys' rules, each spelling, and their wrong, degenerate and extreme values.

use ddirac::{Coordinate, CoordinateKind, InitialMomentum, Role};

use super::initial::{initial, vector, InitialKey, Values, Which};
use super::method::{method, MethodKey, MethodKeys};
use super::time::{grid, TimeKey, TimeKeys, MAX_STEPS};
use super::Spelling;

fn coordinate(name: &str, role: Role) -> Coordinate {
    Coordinate { name: name.into(), kind: CoordinateKind::Real, role }
}

#[test]
fn a_grid_from_any_two_keys_and_from_three_that_agree() {
    let keys = |step, steps, duration| TimeKeys { step, steps, duration };
    assert_eq!(grid(&keys(Some(0.1), None, Some(2.0)), Spelling::Spec).unwrap(), (0.1, 20));
    assert_eq!(grid(&keys(None, Some(4), Some(2.0)), Spelling::Spec).unwrap(), (0.5, 4));
    assert_eq!(grid(&keys(Some(0.25), Some(8), None), Spelling::Spec).unwrap(), (0.25, 8));
    assert_eq!(grid(&keys(Some(0.25), Some(8), Some(2.0)), Spelling::Argument).unwrap(), (0.25, 8));
}

#[test]
fn a_refused_grid_names_its_keys_in_either_spelling() {
    let inconsistent = TimeKeys { step: Some(0.1), steps: Some(10), duration: Some(2.0) };
    let error = grid(&inconsistent, Spelling::Spec).unwrap_err();
    assert_eq!(error.message, "inconsistent `[time]`: step × steps = 1, but duration = 2");
    assert_eq!(
        error.labels.iter().map(|l| l.0).collect::<Vec<_>>(),
        [TimeKey::Step, TimeKey::Steps, TimeKey::Duration]
    );
    let error = grid(&inconsistent, Spelling::Argument).unwrap_err();
    assert_eq!(error.message, "inconsistent time grid: step × steps = 1, but duration = 2");

    let fraction = TimeKeys { step: Some(0.3), duration: Some(1.0), steps: None };
    assert_eq!(
        grid(&fraction, Spelling::Argument).unwrap_err().text(),
        "`duration / step` = 3.3333333333333335 is not a whole number of steps; choose a step that divides the \
         duration, or give `steps` instead of `step`"
    );
    assert!(grid(&fraction, Spelling::Spec).unwrap_err().message.starts_with("`time.duration / time.step` ="));

    let one = TimeKeys { step: Some(0.1), ..TimeKeys::default() };
    let error = grid(&one, Spelling::Argument).unwrap_err();
    assert_eq!(error.message, "the time grid needs two of `step`, `steps`, `duration`; found only `step`");
    assert_eq!(error.labels[0].0, TimeKey::Grid);
}

#[test]
fn degenerate_and_extreme_grids_are_refused_at_their_keys() {
    for (keys, key, message) in [
        (
            TimeKeys { step: Some(f64::NAN), steps: Some(3), duration: None },
            TimeKey::Step,
            "`step` must be positive and finite",
        ),
        (
            TimeKeys { step: Some(-0.1), steps: Some(3), duration: None },
            TimeKey::Step,
            "`step` must be positive and finite",
        ),
        (TimeKeys { step: Some(0.1), steps: Some(0), duration: None }, TimeKey::Steps, "`steps` must be at least 1"),
        (
            TimeKeys { duration: Some(f64::INFINITY), steps: Some(3), step: None },
            TimeKey::Duration,
            "`duration` must be positive and finite",
        ),
    ] {
        let error = grid(&keys, Spelling::Argument).unwrap_err();
        assert_eq!((error.labels[0].0, error.message.as_str()), (key, message), "{keys:?}");
    }
    let beyond = TimeKeys { step: Some(1e-300), duration: Some(20.0), steps: None };
    assert!(grid(&beyond, Spelling::Spec).unwrap_err().message.contains(&format!("more than the {MAX_STEPS} (2^53)")));
    let too_many = TimeKeys { step: Some(1.0), steps: Some(i64::MAX), duration: None };
    assert!(grid(&too_many, Spelling::Spec)
        .unwrap_err()
        .message
        .starts_with("`[time]` asks for 9223372036854775807 steps"));
    let tiny = TimeKeys { duration: Some(1e-300), steps: Some(1 << 40), step: None };
    assert!(grid(&tiny, Spelling::Spec).unwrap_err().message.contains("is too small to compute with"));
    let overflow = TimeKeys { step: Some(1e300), steps: Some(1 << 40), duration: None };
    assert!(grid(&overflow, Spelling::Spec).unwrap_err().message.contains("is not a finite number"));
}

#[test]
fn method_keys_not_given_take_the_library_s_defaults() {
    assert_eq!(method(&MethodKeys::default(), &[], Spelling::Spec).unwrap(), ddirac::Method::default());
    let keys = MethodKeys {
        rule: Some("trapezoid".into()),
        variant: Some("minus".into()),
        jacobian: Some("fresh".into()),
        tolerance: Some(1e-9),
        max_iterations: Some(7),
        order: Some(6),
        composition: Some("triple-jump".into()),
        atlas: Some(false),
        ..MethodKeys::default()
    };
    let m = method(&keys, &[], Spelling::Argument).unwrap();
    assert_eq!((m.rule.name(), m.variant, m.newton.reuse_jacobian), ("trapezoid", ddirac::Variant::Minus, false));
    assert_eq!((m.newton.tolerance, m.newton.max_iterations, m.composition.order(), m.atlas), (1e-9, 7, 6, false));
    assert_eq!(m.composition.name(), "triple-jump");
}

#[test]
fn a_refused_method_key_is_named_as_its_front_end_writes_it() {
    let refuse = |keys: MethodKeys, spelling| method(&keys, &[], spelling).unwrap_err();
    let error = refuse(MethodKeys { tolerance: Some(-1.0), ..MethodKeys::default() }, Spelling::Argument);
    assert_eq!((error.labels[0].0, error.message.as_str()), (MethodKey::Tolerance, "`tolerance` must be positive"));
    let error = refuse(MethodKeys { tolerance: Some(f64::NAN), ..MethodKeys::default() }, Spelling::Spec);
    assert_eq!(error.message, "`method.tolerance` is not finite (NaN)");
    let error = refuse(MethodKeys { energy_jump_threshold: Some(0.0), ..MethodKeys::default() }, Spelling::Spec);
    assert_eq!(error.message, "`method.energy_jump_threshold` must be positive");
    let error = refuse(MethodKeys { max_iterations: Some(0), ..MethodKeys::default() }, Spelling::Argument);
    assert_eq!(error.message, "`max_iterations` must be at least 1");
    let error = refuse(MethodKeys { order: Some(3), ..MethodKeys::default() }, Spelling::Spec);
    assert_eq!(
        error.text(),
        "there is no method of order 3; `method.order` is 2 (the basic step), 4, 6 or 8 (compositions of it)"
    );
    let error = refuse(MethodKeys { order: Some(i64::MAX), ..MethodKeys::default() }, Spelling::Spec);
    assert_eq!(error.labels[0].0, MethodKey::Order);
    let error = refuse(MethodKeys { composition: Some("kahan-li".into()), ..MethodKeys::default() }, Spelling::Spec);
    assert_eq!(error.labels[0].0, MethodKey::Composition);
    for (keys, key) in [
        (MethodKeys { rule: Some("simpson".into()), ..MethodKeys::default() }, MethodKey::Rule),
        (MethodKeys { variant: Some("Plus".into()), ..MethodKeys::default() }, MethodKey::Variant),
        (MethodKeys { jacobian: Some("".into()), ..MethodKeys::default() }, MethodKey::Jacobian),
        (MethodKeys { derivatives: Some("symbolic".into()), ..MethodKeys::default() }, MethodKey::Derivatives),
        (MethodKeys { on_energy_jump: Some("panic".into()), ..MethodKeys::default() }, MethodKey::OnEnergyJump),
    ] {
        let (spec, argument) = (refuse(keys.clone(), Spelling::Spec), refuse(keys, Spelling::Argument));
        assert_eq!((spec.labels[0].0, argument.labels[0].0), (key, key));
        let name = key.name();
        assert!(spec.help.as_ref().unwrap().starts_with(&format!("`method.{name}` is")), "{spec:?}");
        assert!(argument.help.as_ref().unwrap().starts_with(&format!("`{name}` is")), "{argument:?}");
        assert_eq!(spec.message, argument.message);
    }
}

#[test]
fn the_connection_is_checked_against_the_system_s_coordinates() {
    let coordinates = [coordinate("x", Role::Shape), coordinate("y", Role::Shape), coordinate("theta", Role::Group)];
    let with = |rows: Vec<Vec<f64>>| MethodKeys { connection: Some(rows), ..MethodKeys::default() };
    let m = method(&with(vec![vec![0.5, -1.0]]), &coordinates, Spelling::Spec).unwrap();
    assert!(m.connection.is_some());
    let error = method(&with(vec![]), &coordinates, Spelling::Spec).unwrap_err();
    assert_eq!(
        (error.labels[0].0, error.message.as_str()),
        (MethodKey::Connection, "`method.connection` has 0 rows, expected 1")
    );
    let error = method(&with(vec![vec![1.0]]), &coordinates, Spelling::Argument).unwrap_err();
    assert_eq!(error.labels[0], (MethodKey::ConnectionRow(0), "row for `theta`".to_owned()));
    assert_eq!(error.message, "row 1 of `connection` has 1 entries, expected 2");
    let error = method(&with(vec![vec![1.0, f64::INFINITY]]), &coordinates, Spelling::Spec).unwrap_err();
    assert_eq!(error.labels[0].0, MethodKey::ConnectionEntry(0, 1));
    assert_eq!(error.message, "an entry of `method.connection` is not finite (inf)");
}

#[test]
fn initial_data_in_order_or_by_name_give_the_same_vector() {
    let names = ["x", "theta"];
    let by_name = Values::ByName(vec![("theta".into(), 1.0), ("x".into(), 0.5)]);
    let in_order = Values::InOrder(vec![0.5, 1.0]);
    assert_eq!(vector(&by_name, Which::Q, &names, Spelling::Spec).unwrap(), [0.5, 1.0]);
    assert_eq!(vector(&in_order, Which::Q, &names, Spelling::Spec).unwrap(), [0.5, 1.0]);
    let (q, p) = initial(&in_order, None, Some(&by_name), &names, Spelling::Argument).unwrap();
    assert_eq!((q, p), (vec![0.5, 1.0], InitialMomentum::Velocity(vec![0.5, 1.0])));
}

#[test]
fn wrong_initial_data_is_refused_at_the_entry() {
    let names = ["x", "theta"];
    let refuse = |values: Values, which| vector(&values, which, &names, Spelling::Argument).unwrap_err();
    let error = refuse(Values::InOrder(vec![0.0]), Which::P);
    assert_eq!(
        (error.labels[0].0, error.message.as_str()),
        (InitialKey::Vector(Which::P), "`p0` has 1 entries, but the system has 2 coordinates")
    );
    let error = refuse(Values::InOrder(vec![0.0, f64::NAN]), Which::Q);
    assert_eq!(
        (error.labels[0].0, error.message.as_str()),
        (InitialKey::Entry(Which::Q, 1), "`q0` entry for `theta` is not finite (NaN)")
    );
    let error = refuse(Values::ByName(vec![("x".into(), 0.0), ("y".into(), 0.0)]), Which::V);
    assert_eq!(
        (error.labels[0].0, error.message.as_str()),
        (InitialKey::Name(Which::V, 1), "`v0` gives a value for `y`, which is not a coordinate")
    );
    let error = refuse(Values::ByName(vec![("x".into(), 0.0), ("x".into(), 1.0)]), Which::Q);
    assert_eq!(
        (error.labels[0].0, error.message.as_str()),
        (InitialKey::Name(Which::Q, 1), "`q0` gives coordinate `x` twice")
    );
    let error = refuse(Values::ByName(vec![("theta".into(), 0.0)]), Which::Q);
    assert_eq!(error.message, "`q0` has no value for `x`");
    let error = refuse(Values::ByName(vec![("x".into(), 0.0), ("theta".into(), f64::NEG_INFINITY)]), Which::Q);
    assert_eq!(error.labels[0].0, InitialKey::Entry(Which::Q, 1));

    let q = Values::InOrder(vec![0.0, 0.0]);
    let neither = initial(&q, None, None, &names, Spelling::Spec).unwrap_err();
    assert_eq!((neither.labels[0].0, neither.message.as_str()), (InitialKey::Table, "`[initial]` needs `p` or `v`"));
    let both = initial(&q, Some(&q), Some(&q), &names, Spelling::Argument).unwrap_err();
    assert_eq!(both.message, "the initial data takes `p0` or `v0`, not both");
    assert_eq!(both.labels.len(), 2);
    let none = initial(&Values::InOrder(vec![]), Some(&Values::InOrder(vec![])), None, &[], Spelling::Spec);
    assert_eq!(none.unwrap(), (vec![], InitialMomentum::Momentum(vec![])));
}

#[test]
fn the_keys_of_a_method_give_that_method_back() {
    let coordinates = [coordinate("x", Role::Shape), coordinate("theta", Role::Group)];
    for keys in [
        MethodKeys::default(),
        MethodKeys {
            rule: Some("midpoint".into()),
            variant: Some("minus".into()),
            reduced: Some(true),
            connection: Some(vec![vec![0.25]]),
            jacobian: Some("fresh".into()),
            derivatives: Some("dual".into()),
            check_invariance: Some(false),
            on_energy_jump: Some("error".into()),
            energy_jump_threshold: Some(0.5),
            order: Some(8),
            atlas: Some(false),
            ..MethodKeys::default()
        },
    ] {
        let m = method(&keys, &coordinates, Spelling::Spec).unwrap();
        assert_eq!(method(&MethodKeys::of(&m), &coordinates, Spelling::Spec).unwrap(), m);
    }
}
