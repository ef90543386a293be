//! Text systems of any number of coordinates up to 100 (issue 12): every count of `ddirac::SIZES`
//! (1–16) runs in the engine of its size, every other in a dimension chosen at run time
//! (`issue_12_systems_in_a_dynamic_dimension.rs`); a system can also be run in a larger engine, with
//! padding coordinates that the type-erased system hides
//! (`ddirac::expression::ExpressionSpec::into_dyn_in`).
//!
//! - The padding is invisible: a system run with padding equals the same system run without, row by
//!   row and bit for bit — a chain of 13 in the engine of 16, the double spherical pendulum (reduced,
//!   with a connection) in that of 8, and the spherical pendulum with its atlas switching charts.
//! - Counts outside the sizes run and are right: 17, 33, 49 and 73 uncoupled oscillators against
//!   their exact solution, with the midpoint rule's second order.
//! - The padding takes the system's scale: oscillators with an electron's mass in SI units (entries
//!   of 10⁻³⁰ in every Jacobian) move as those of mass 1.
//! - Errors name the system's own sizes, the stepper restarts bit for bit, the check counts the
//!   system's own coordinates, and every count up to 100 and beyond runs.

use crate::chain_text;
use crate::pendulum_text;
use crate::spherical_pendulum_text::spherical_pendulum;

use chain_text::chain_spec;
use ddirac::expression::{ExpressionError, ExpressionSpec};
use ddirac::{
    Connection, Coordinate, Differentiation, DynState, DynSystem, Error, InitialMomentum, Input, Method, NewtonOptions,
    OutputOptions, Problem, Rule, Summary,
};

/// Every row of a run (k, t, q, p, energy, discrete energy, momentum map, chart) as bits, and the
/// summary.
fn rows(system: &dyn DynSystem, problem: &Problem, method: &Method) -> (Vec<Vec<u64>>, Summary) {
    let mut rows = Vec::new();
    let summary = system
        .integrate(problem, method, &OutputOptions::default(), &mut |row| {
            let numbers = [row.t, row.energy, row.discrete_energy.unwrap_or(f64::NAN), row.chart as f64];
            let all = row.q.iter().chain(row.p).chain(row.momentum_map).chain(&numbers);
            rows.push(std::iter::once(row.k as u64).chain(all.map(|x| x.to_bits())).collect());
            Ok(())
        })
        .unwrap_or_else(|e| panic!("the run failed: {e}"));
    (rows, summary)
}

/// The runs of `spec` padded to `size` and without padding: their rows as bits and their summaries.
fn padded_and_not(
    spec: &ExpressionSpec,
    size: usize,
    problem: &Problem,
    method: &Method,
) -> ([Vec<Vec<u64>>; 2], [Summary; 2]) {
    let exact = spec.clone().into_dyn().unwrap();
    let padded = spec.clone().into_dyn_in(size).unwrap();
    assert_eq!(padded.coordinates(), exact.coordinates());
    let (a, summary_a) = rows(padded.as_ref(), problem, method);
    let (b, summary_b) = rows(exact.as_ref(), problem, method);
    assert_eq!((a.len(), b.len()), (problem.steps + 1, problem.steps + 1));
    ([a, b], [summary_a, summary_b])
}

/// The run of `spec` padded to `size` equals its run without padding, bit for bit; the summaries
/// agree but for the wall time and the size of the compiled programs.
fn padding_is_invisible(spec: &ExpressionSpec, size: usize, problem: &Problem, method: &Method) -> Summary {
    let ([a, b], [summary_a, summary_b]) = padded_and_not(spec, size, problem, method);
    let first_difference = a.iter().zip(&b).position(|(x, y)| x != y);
    assert_eq!(first_difference, None, "padded to {size}: rows differ");
    let path = summary_b.derivatives.clone();
    let comparable = |s: &Summary| Summary { wall_seconds: 0.0, derivatives: path.clone(), ..s.clone() };
    assert_eq!(comparable(&summary_a), comparable(&summary_b));
    summary_b
}

/// The largest difference of the padded and unpadded runs' rows, relative to each entry's largest
/// magnitude over the run.
fn padded_difference(spec: &ExpressionSpec, size: usize, problem: &Problem, method: &Method) -> f64 {
    let ([a, b], _) = padded_and_not(spec, size, problem, method);
    let value = |rows: &[Vec<u64>], i: usize, j: usize| f64::from_bits(rows[i][j]);
    let mut worst: f64 = 0.0;
    for j in 1..a[0].len() {
        let scale = (0..a.len()).map(|i| value(&b, i, j).abs()).fold(1e-300, f64::max);
        for i in 0..a.len() {
            let (x, y) = (value(&a, i, j), value(&b, i, j));
            if !(x.is_nan() && y.is_nan()) {
                worst = worst.max((x - y).abs() / scale);
            }
        }
    }
    worst
}

fn method(rule: Rule, reduced: bool, differentiation: Differentiation) -> Method {
    Method { rule, reduced, differentiation, ..Method::default() }
}

#[test]
fn a_chain_of_13_padded_to_16_runs_bit_for_bit_as_without_padding() {
    let arch = |i: usize| 0.5 * (std::f64::consts::PI * i as f64 / 14.0).sin();
    let problem = Problem::new(0.005, 200, (1..=13).map(arch).collect(), InitialMomentum::Momentum(vec![0.0; 13]));
    for differentiation in [Differentiation::Dual, Differentiation::Compiled] {
        let summary =
            padding_is_invisible(&chain_spec(13), 16, &problem, &method(Rule::Midpoint, false, differentiation));
        assert!(summary.final_q[0] != problem.q0[0], "the chain should move");
    }
}

#[test]
fn the_double_spherical_pendulum_padded_to_8_reduces_as_without_padding() {
    let spec = pendulum_text::double_spherical_pendulum_spec();
    let problem =
        Problem::new(0.05, 300, vec![0.1, 1.0, 0.2, 1.3], InitialMomentum::Velocity(vec![0.05, 0.0, 0.03, 0.0]));
    let connection = Connection::new(&[vec![0.0, -0.5, 0.0]]).unwrap();
    for differentiation in [Differentiation::Dual, Differentiation::Compiled] {
        for connection in [None, Some(connection.clone())] {
            // Classical Newton: bit for bit.
            let classical = NewtonOptions { reuse_jacobian: false, ..NewtonOptions::default() };
            let method = Method { connection, newton: classical, ..method(Rule::Midpoint, true, differentiation) };
            let summary = padding_is_invisible(&spec, 8, &problem, &method);
            assert!(summary.momentum_map.max_drift < 1e-9, "{:e}", summary.momentum_map.max_drift);
            // Chord Newton with compiled derivatives keeps its Jacobian across steps in the engine of
            // 8 (from what a Jacobian costs there against a residual), not in that of 4: the same
            // solution to Newton's tolerance, not the same iterates.
            let chord = Method { newton: NewtonOptions::default(), ..method };
            let difference = padded_difference(&spec, 8, &problem, &chord);
            eprintln!("{differentiation:?}, chord Newton: padded and unpadded rows differ by {difference:.1e}");
            assert!(difference < 1e-10, "{difference:e}");
        }
    }
}

#[test]
fn the_spherical_pendulum_padded_to_4_switches_charts_bit_for_bit_as_without_padding() {
    // Released at 1 rad with a small azimuthal velocity: the bob passes close to the pole, and the
    // run moves to the lower cap and back.
    let problem = Problem::new(0.005, 2000, vec![1.0, 0.0], InitialMomentum::Velocity(vec![0.0, 0.05]));
    for reduced in [false, true] {
        let summary = padding_is_invisible(
            &spherical_pendulum(),
            4,
            &problem,
            &method(Rule::Midpoint, reduced, Differentiation::Auto),
        );
        assert!(summary.chart_switches >= 2, "the run should switch charts: {}", summary.chart_switches);
    }
}

/// `n` uncoupled oscillators x_i with frequencies ω_i = 1 + i/n and mass `m`, released from
/// x_i = 1 at rest, with their exact solutions cos(ω_i t).
fn oscillators(n: usize, m: f64) -> ExpressionSpec {
    let omega = |i: usize| 1.0 + i as f64 / n as f64;
    ExpressionSpec {
        coordinates: (0..n).map(|i| Coordinate::shape(&format!("x{i}"))).collect(),
        lagrangian: (0..n)
            .map(|i| format!("0.5*m*(x{i}_dot^2 - {}*x{i}^2)", omega(i).powi(2)))
            .collect::<Vec<_>>()
            .join(" + "),
        parameters: vec![("m".into(), m)],
        exact_solution: (0..n).map(|i| (format!("x{i}"), format!("cos({}*t)", omega(i)))).collect(),
        ..ExpressionSpec::default()
    }
}

fn oscillator_problem(n: usize, step: f64) -> Problem {
    Problem::new(step, (10.0 / step).round() as usize, vec![1.0; n], InitialMomentum::Momentum(vec![0.0; n]))
}

#[test]
fn seventeen_33_49_and_73_oscillators_follow_their_exact_solution_to_second_order() {
    for n in [17, 33, 49, 73] {
        assert!(!ddirac::SIZES.contains(&n));
        let system = oscillators(n, 1.0).into_dyn().unwrap();
        assert_eq!(system.coordinates().len(), n);
        let error = |step: f64| {
            let method = method(Rule::Midpoint, false, Differentiation::Auto);
            let problem = oscillator_problem(n, step);
            let (rows, summary) = rows(system.as_ref(), &problem, &method);
            assert_eq!(summary.final_q.len(), n);
            assert!(rows.iter().all(|row| row.len() == 1 + 2 * n + 4));
            // The midpoint rule turns each oscillator's (x, p/ω) by 2 atan(ωh/2) per step, exactly:
            // x_k = cos(2k atan(ωh/2)).
            for (i, x) in summary.final_q.iter().enumerate() {
                let omega = 1.0 + i as f64 / n as f64;
                let discrete = (2.0 * problem.steps as f64 * (omega * step / 2.0).atan()).cos();
                assert!((x - discrete).abs() < 1e-11, "x{i}: {x} against {discrete}");
            }
            summary.reference_error.expect("the spec has exact solutions")
        };
        let (coarse, fine) = (error(0.02), error(0.01));
        eprintln!("{n} oscillators: error {coarse:.3e} at h = 0.02, {fine:.3e} at h = 0.01");
        assert!((coarse / fine - 4.0).abs() < 0.1, "second order: ratio {}", coarse / fine);
    }
}

#[test]
fn thirteen_oscillators_padded_to_16_with_an_electrons_mass_move_as_those_of_mass_1() {
    let electron = 9.109e-31;
    let n = 13;
    let problem = oscillator_problem(n, 0.02);
    let padded = |m: f64| oscillators(n, m).into_dyn_in(16).unwrap();
    let (heavy, light) = (padded(1.0), padded(electron));
    let method = method(Rule::Midpoint, false, Differentiation::Auto);
    let report = light.check(&problem, &method).unwrap();
    assert_eq!((report.legendre_rank, report.coordinates), (n, n));
    let (a, b) = (rows(heavy.as_ref(), &problem, &method).1, rows(light.as_ref(), &problem, &method).1);
    let difference = a.final_q.iter().zip(&b.final_q).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    assert!(difference < 1e-12, "{difference:e}");
    assert!(b.final_p.iter().all(|p| p.abs() < 10.0 * electron));
}

#[test]
fn errors_of_a_padded_system_name_its_own_sizes() {
    let system = oscillators(13, 1.0).into_dyn_in(16).unwrap();
    let method = method(Rule::Midpoint, false, Differentiation::Auto);
    let short = Problem::new(0.01, 10, vec![1.0; 12], InitialMomentum::Momentum(vec![0.0; 13]));
    let error = system.integrate(&short, &method, &OutputOptions::default(), &mut |_| Ok(())).unwrap_err();
    assert!(matches!(error, Error::Size { what: Input::InitialConfiguration, expected: 13, found: 12 }), "{error:?}");
    let long = Problem::new(0.01, 10, vec![1.0; 13], InitialMomentum::Velocity(vec![0.0; 16]));
    let error = system.check(&long, &method).unwrap_err();
    assert!(matches!(error, Error::Size { what: Input::InitialVelocity, expected: 13, found: 16 }), "{error:?}");
    let mut nan = oscillator_problem(13, 0.01);
    nan.q0[12] = f64::NAN;
    let error = system.stepper(&nan, &method).err().expect("refused");
    assert!(matches!(error, Error::NonFinite { what: Input::InitialConfiguration, entry: Some(12), .. }), "{error:?}");

    let mut stepper = system.stepper(&oscillator_problem(13, 0.01), &method).unwrap();
    let error = stepper.restart(&DynState::new(0, vec![0.0; 16], vec![0.0; 16])).unwrap_err();
    assert!(matches!(error, Error::Size { what: Input::State, expected: 13, found: 16 }), "{error:?}");
}

#[test]
fn a_connection_of_a_padded_system_has_its_own_shape_coordinates() {
    // The spherical pendulum with a third, uncoupled shape coordinate z: 3 coordinates in the engine
    // of 4. K has one entry per shape coordinate (theta, z): two, not three.
    let mut spec = spherical_pendulum();
    spec.charts.clear();
    spec.quality = None;
    spec.coordinates.push(Coordinate::shape("z"));
    spec.lagrangian.push_str(" + 0.5*z_dot^2 - 0.5*z^2");
    let system = spec.into_dyn().unwrap();
    let problem = Problem::new(0.01, 100, vec![1.0, 0.0, 0.5], InitialMomentum::Velocity(vec![0.0, 2.0, 0.0]));
    let reduced = |connection: Vec<f64>| Method {
        connection: Some(Connection::new(&[connection]).unwrap()),
        ..method(Rule::Midpoint, true, Differentiation::Auto)
    };
    let error = system.check(&problem, &reduced(vec![0.0, 0.0, 0.0])).unwrap_err();
    assert!(matches!(error, Error::Invalid { what: Input::Connection, .. }), "{error:?}");
    assert!(error.to_string().contains("expected one per shape coordinate (2)"), "{error}");
    let (unreduced, _) = rows(system.as_ref(), &problem, &method(Rule::Midpoint, false, Differentiation::Auto));
    let (with_k, _) = rows(system.as_ref(), &problem, &reduced(vec![0.0, 0.0]));
    let q = |row: &Vec<u64>| row[1..4].iter().map(|&b| f64::from_bits(b)).collect::<Vec<_>>();
    let difference = q(&unreduced[100]).iter().zip(q(&with_k[100])).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(difference < 1e-9, "reduced and unreduced runs agree: {difference:e}");
}

#[test]
fn a_padded_stepper_restarts_bit_for_bit_and_the_check_counts_the_systems_own_coordinates() {
    let system = chain_spec(13).into_dyn_in(16).unwrap();
    let arch = |i: usize| 0.5 * (std::f64::consts::PI * i as f64 / 14.0).sin();
    let problem = Problem::new(0.005, 40, (1..=13).map(arch).collect(), InitialMomentum::Momentum(vec![0.0; 13]));
    let method = method(Rule::Midpoint, false, Differentiation::Auto);
    let report = system.check(&problem, &method).unwrap();
    assert_eq!((report.legendre_rank, report.coordinates), (13, 13));
    assert!(report.regular());

    let mut stepper = system.stepper(&problem, &method).unwrap();
    for _ in 0..10 {
        stepper.step().unwrap();
    }
    let saved = stepper.state();
    assert_eq!((saved.q().len(), saved.p().len()), (13, 13));
    let ahead: Vec<_> = (0..5).map(|_| (stepper.step().unwrap(), stepper.row())).collect();
    assert_eq!(ahead[4].1.q.len(), 13);
    stepper.restart(&saved).unwrap();
    let again: Vec<_> = (0..5).map(|_| (stepper.step().unwrap(), stepper.row())).collect();
    assert_eq!(ahead, again);
    // From q and p only, the step equals a fresh stepper's first step from there.
    stepper.restart(&saved.cold()).unwrap();
    let cold = stepper.step().unwrap();
    assert_eq!(cold.k, ahead[0].0.k);
    let summary = stepper.finish().unwrap();
    assert_eq!((summary.coordinates.len(), summary.final_q.len(), summary.final_p.len()), (13, 13, 13));
}

#[test]
fn engine_sizes_are_checked_and_every_count_runs() {
    let error = chain_spec(3).into_dyn_in(2).err().expect("refused");
    assert!(matches!(error, ExpressionError::EngineSize { size: 2, found: 3 }), "{error:?}");
    let error = chain_spec(3).into_dyn_in(17).err().expect("refused");
    assert!(matches!(error, ExpressionError::EngineSize { size: 17, found: 3 }), "{error:?}");
    for n in (1..=100).chain([101, 128, 200]) {
        assert_eq!(chain_spec(n).into_dyn().unwrap().coordinates().len(), n);
    }
}

#[test]
fn text_chains_of_13_to_17_and_65_run_on_a_thread_of_2_mib() {
    // 13 coordinates padded to the engine of 16 and 16 in that of 16, the largest engine with arrays
    // on the stack, whose steps fit any thread of 2 MiB (`ddirac::stack::ON_ANY_THREAD`); 17 and 65
    // run in a dynamic dimension, on the heap.
    let run = || {
        for (n, size) in [(13, Some(16)), (16, None), (17, None), (65, None)] {
            let spec = chain_spec(n);
            let system = match size {
                Some(size) => spec.into_dyn_in(size).unwrap(),
                None => spec.into_dyn().unwrap(),
            };
            let arch = |i: usize| 0.5 * (std::f64::consts::PI * i as f64 / (n + 1) as f64).sin();
            let q0 = (1..=n).map(arch).collect();
            let problem = Problem::new(0.005, 3, q0, InitialMomentum::Momentum(vec![0.0; n]));
            let method = method(Rule::Midpoint, false, Differentiation::Dual);
            assert!(system.check(&problem, &method).unwrap().regular());
            let mut stepper = system.stepper(&problem, &method).unwrap();
            stepper.step().unwrap();
            let saved = stepper.state();
            let ahead = (stepper.step().unwrap(), stepper.row());
            stepper.restart(&saved).unwrap();
            assert_eq!((stepper.step().unwrap(), stepper.row()), ahead);
            assert_eq!(ahead.1.q.len(), n);
        }
    };
    std::thread::Builder::new().stack_size(2 << 20).spawn(run).unwrap().join().unwrap();
}
