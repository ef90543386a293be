//! Runs in a dimension chosen at run time (issue 12: text systems of any number of coordinates).
//!
//! The whole engine — check, schemes, derivatives, Newton's method, stepper, atlas, compositions — is
//! written over a dimension (`ddirac::dim`): `Fixed<N>` (arrays on the stack) or `Dynamic(n)` (`Vec`s,
//! dual numbers in blocks of 8). A system of a fixed dimension run in the dynamic one
//! (`ddirac::mechanics::lagrangian::AsDynamic`) does the same operations in the same order, so its run
//! must equal the fixed run bit for bit: rows, summaries, Newton counts, chart switches, states and
//! restarts. Text specs of more than the largest of `ddirac::SIZES` run in the dynamic dimension: a
//! chain of 120 pendula keeps its energy, and a spec that fits both dimensions gives the same run in
//! both.

use std::f64::consts::PI;

use ddirac::dim::Dynamic;
use ddirac::expression::{ExpressionLagrangian, ExpressionSpec};
use ddirac::mechanics::lagrangian::{AsDynamic, SystemIn};
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, PendulumChain, SphericalPendulum};
use ddirac::{
    solve, Composition, Connection, Differentiation, DynSystem, ErasedDynamic, InitialMomentum, Method, OutputOptions,
    Problem, Rule, Solution, StateIn, StepperIn, System, Variant,
};

use crate::chain_text::chain_spec;

fn bits(rows: &[Vec<f64>]) -> Vec<Vec<u64>> {
    rows.iter().map(|row| row.iter().map(|x| x.to_bits()).collect()).collect()
}

fn scalar_bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

/// The two runs are the same bit for bit, in everything but the wall clock.
fn assert_same(fixed: &Solution, dynamic: &Solution, what: &str) {
    assert_eq!(bits(&fixed.q), bits(&dynamic.q), "{what}: q");
    assert_eq!(bits(&fixed.p), bits(&dynamic.p), "{what}: p");
    assert_eq!(bits(&fixed.momentum_map), bits(&dynamic.momentum_map), "{what}: momentum map");
    assert_eq!(scalar_bits(&fixed.energy), scalar_bits(&dynamic.energy), "{what}: energy");
    assert_eq!(scalar_bits(&fixed.discrete_energy), scalar_bits(&dynamic.discrete_energy), "{what}: discrete energy");
    let (a, b) = (&fixed.summary, &dynamic.summary);
    assert_eq!(a.newton, b.newton, "{what}: Newton");
    assert_eq!(a.derivatives, b.derivatives, "{what}: derivatives");
    assert_eq!(a.chart_switches, b.chart_switches, "{what}: chart switches");
    assert_eq!(scalar_bits(&a.final_q), scalar_bits(&b.final_q), "{what}: final q");
    assert_eq!(a.reference_error.map(f64::to_bits), b.reference_error.map(f64::to_bits), "{what}: reference error");
    assert_eq!(a.warnings.len(), b.warnings.len(), "{what}: warnings");
    assert!(fixed.q.len() > 1, "{what}: a run of more than its first row");
}

fn both<S: System<N> + Clone, const N: usize>(system: S, problem: &Problem, method: &Method, what: &str) -> Solution {
    let output = OutputOptions::default();
    let fixed = solve(&system, problem, method, &output).unwrap_or_else(|e| panic!("{what}: {e}"));
    let dynamic = solve(&AsDynamic(system), problem, method, &output).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_same(&fixed, &dynamic, what);
    fixed
}

#[test]
fn built_in_systems_run_alike_in_a_fixed_and_a_dynamic_dimension() {
    // The charged particle, reduced (+) by the left rule: dual numbers, and the compiled closed form.
    let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
    for differentiation in [Differentiation::Dual, Differentiation::Compiled] {
        let method = Method { differentiation, ..method.clone() };
        let run = both(ChargedParticle::default(), &ChargedParticle::paper_problem(200), &method, "charged particle");
        // Paper, Table 1: N = 200 → 0.01664.
        assert!((run.summary.reference_error.unwrap() - 0.01664).abs() < 5e-6);
    }
    // The double spherical pendulum of §7.2, reduced (−) with a coupling connection, and unreduced by
    // a fourth-order composition.
    let k = Connection::new(&[vec![0.3, -0.2, 0.1]]).unwrap();
    let reduced = Method { reduced: true, variant: Variant::Minus, connection: Some(k), ..Method::default() };
    both(DoubleSphericalPendulum::default(), &DoubleSphericalPendulum::paper_problem(300), &reduced, "pendulum (−)");
    let composed = Method { composition: Composition::TripleJump { order: 4 }, ..Method::default() };
    both(DoubleSphericalPendulum::default(), &DoubleSphericalPendulum::paper_problem(100), &composed, "composition");
    // A chain of 12 angles (chunked Jacobians in the fixed dimension, blocks of 8 in the dynamic
    // one: the same numbers), by dual numbers and compiled.
    let q0: Vec<f64> = (0..12).map(|i| 0.1 * (i as f64 + 1.0).sin()).collect();
    let problem = Problem::new(0.01, 200, q0, InitialMomentum::Momentum(vec![0.0; 12]));
    for differentiation in [Differentiation::Dual, Differentiation::Compiled] {
        let method = Method { differentiation, ..Method::default() };
        both(PendulumChain::<12>::default(), &problem, &method, "chain of 12");
    }
}

#[test]
fn an_atlas_switches_charts_alike_in_both_dimensions() {
    // The spherical pendulum through its lower pole, reduced, switching to the caps' charts and back.
    let (l_z, h) = (0.05, 0.01);
    let problem = Problem::new(h, 1000, vec![0.3, PI - 1.0], InitialMomentum::Momentum(vec![l_z, 0.0]));
    let method = Method { reduced: true, ..Method::default() };
    let run = both(SphericalPendulum::default(), &problem, &method, "atlas");
    assert!(run.summary.chart_switches >= 2, "{}", run.summary.chart_switches);
}

#[test]
fn a_dynamic_stepper_restarts_from_a_saved_state_bit_for_bit() {
    let (system, problem) = (AsDynamic(DoubleSphericalPendulum::default()), DoubleSphericalPendulum::paper_problem(60));
    let method = Method { reduced: true, ..Method::default() };
    let mut stepper = StepperIn::new(system.clone(), &problem, &method).unwrap();
    assert_eq!(stepper.dim(), Dynamic(4));
    for _ in 0..25 {
        stepper.step().unwrap();
    }
    let saved: StateIn<Dynamic> = stepper.state();
    let ahead: Vec<_> = (0..20).map(|_| (stepper.step().unwrap(), stepper.row())).collect();
    let mut again = StepperIn::new(system.clone(), &problem, &method).unwrap();
    again.restart(&saved).unwrap();
    let after: Vec<_> = (0..20).map(|_| (again.step().unwrap(), again.row())).collect();
    assert_eq!(ahead, after);
    // The fixed stepper's rows at the same steps.
    let mut fixed = ddirac::Stepper::new(&system.0, &problem, &method).unwrap();
    for _ in 0..45 {
        fixed.step().unwrap();
    }
    assert_eq!(scalar_bits(&fixed.row().q), scalar_bits(&after[19].1.q));
}

#[test]
fn a_text_spec_runs_alike_in_a_fixed_and_a_dynamic_dimension() {
    // A chain of 16 as text: the engine of 16 coordinates (`into_dyn`, the largest of `SIZES`) and the
    // dynamic dimension.
    let spec = chain_spec(16);
    let q0: Vec<f64> = (0..16).map(|i| 0.2 * (0.7 * i as f64).cos()).collect();
    let problem = Problem::new(0.01, 40, q0, InitialMomentum::Momentum(vec![0.0; 16]));
    let fixed: Box<dyn DynSystem> = spec.clone().into_dyn().unwrap();
    let dynamic: Box<dyn DynSystem> = Box::new(ErasedDynamic(ExpressionLagrangian::new(&spec).unwrap()));
    for differentiation in [Differentiation::Dual, Differentiation::Compiled] {
        let method = Method { differentiation, ..Method::default() };
        let rows = |system: &dyn DynSystem| {
            let mut rows = Vec::new();
            let summary = system
                .integrate(&problem, &method, &OutputOptions::default(), &mut |row| {
                    rows.push(row.q.iter().chain(row.p).map(|x| x.to_bits()).collect::<Vec<_>>());
                    Ok(())
                })
                .unwrap();
            (rows, summary.newton, summary.derivatives)
        };
        assert_eq!(rows(fixed.as_ref()), rows(dynamic.as_ref()), "{differentiation:?}");
    }
}

/// The chain of `n` pendula as text, released from a gentle arc at rest.
fn chain_problem(n: usize, steps: usize) -> Problem {
    let q0: Vec<f64> = (0..n).map(|i| 0.05 * (0.3 * i as f64).sin()).collect();
    Problem::new(0.005, steps, q0, InitialMomentum::Momentum(vec![0.0; n]))
}

#[test]
fn a_text_chain_of_120_pendula_runs_in_a_dynamic_dimension_with_its_energy_kept() {
    let n = 120;
    let system = chain_spec(n).into_dyn().unwrap();
    assert_eq!(system.coordinates().len(), n);
    let problem = chain_problem(n, 60);
    let report = system.check(&problem, &Method::default()).unwrap();
    assert_eq!((report.legendre_rank, report.coordinates), (n, n));
    let mut energies = Vec::new();
    let summary = system
        .integrate(&problem, &Method::default(), &OutputOptions::default(), &mut |row| {
            assert_eq!((row.q.len(), row.p.len()), (n, n));
            energies.push(row.energy);
            Ok(())
        })
        .unwrap();
    assert_eq!(summary.coordinates.len(), n);
    assert_eq!(energies.len(), 61);
    // A symplectic run of a small motion: the energy oscillates by far less than its scale.
    let h0 = energies[0];
    let worst = energies.iter().fold(0.0f64, |m, e| m.max((e - h0).abs()));
    assert!(worst < 1e-4 * h0.abs(), "energy moved by {worst:e} of {h0:e}");
    // The stepper of the erased system restarts bit for bit too.
    let mut stepper = system.stepper(&problem, &Method::default()).unwrap();
    for _ in 0..10 {
        stepper.step().unwrap();
    }
    let saved = stepper.state();
    let ahead: Vec<_> = (0..5).map(|_| stepper.step().unwrap()).collect();
    stepper.restart(&saved).unwrap();
    let again: Vec<_> = (0..5).map(|_| stepper.step().unwrap()).collect();
    assert_eq!(ahead, again);
}

#[test]
fn the_dynamic_dimension_of_a_text_system_is_its_own_count() {
    let spec = ExpressionSpec { ..chain_spec(130) };
    let system = ExpressionLagrangian::new(&spec).unwrap();
    assert_eq!(SystemIn::<Dynamic>::dim(&system), Dynamic(130));
    assert_eq!(SystemIn::<Dynamic>::coordinates(&system)[129].name, "th130");
    // Initial data of the wrong size are refused with the system's own size.
    let erased = ErasedDynamic(system);
    let problem = chain_problem(129, 5);
    let error = erased.check(&problem, &Method::default()).unwrap_err();
    assert!(error.to_string().contains("130"), "{error}");
}
