//! The energy watch used to start afresh at every chart switch, so a jump or a drift was measured
//! only against the stretch since the last switch. The spherical pendulum going over the top at
//! h = 0.05 had its energy go from 15.9 to 27.7 (+74 %) with a `subdivided` warning only. The
//! watch (and the energy of the last step, which the plausibility test of the next step compares
//! with) now carries over switches: the run's diagnostics span the whole run.

use ddirac::systems::SphericalPendulum;
use ddirac::{solve, Composition, InitialMomentum, Method, OutputOptions, Problem, Solution, WarningKind};

/// The spherical pendulum released 1 rad from the downward vertical with polar rate 6.3 and
/// azimuthal rate 2 (energy 15.97 > 2 m g l: it goes over the top), reduced midpoint steps of h for
/// T = 20, with the atlas.
fn over_the_top(h: f64, composition: Composition) -> Solution {
    let steps = (20.0 / h).round() as usize;
    let q0 = vec![0.0, std::f64::consts::PI - 1.0];
    let problem = Problem::new(h, steps, q0, InitialMomentum::Velocity(vec![2.0, -6.3]));
    let method = Method { reduced: true, composition, ..Method::default() };
    solve(&SphericalPendulum::default(), &problem, &method, &OutputOptions::default()).expect("the run completes")
}

/// The largest departure of H(q_k, p_k) from its initial value, relative to it.
fn energy_departure(solution: &Solution) -> f64 {
    let e0 = solution.energy[0];
    solution.energy.iter().fold(0.0f64, |m, e| m.max((e - e0).abs())) / e0.abs()
}

fn energy_warned(solution: &Solution) -> bool {
    solution.summary.warnings.iter().any(|w| matches!(w.kind, WarningKind::EnergyDrift | WarningKind::EnergyJump))
}

#[test]
fn an_energy_that_leaves_its_level_across_switches_is_reported() {
    let solution = over_the_top(0.05, Composition::Basic);
    assert!(solution.summary.chart_switches > 10, "{} switches", solution.summary.chart_switches);
    let departure = energy_departure(&solution);
    // The step does not resolve the motion: the energy leaves its level, passage after passage, by
    // far more than the bounded error of a resolved step (below 1 % at h = 0.005).
    assert!(departure > 0.1, "departure {departure}");
    assert!(energy_warned(&solution), "no energy warning: {:?}", solution.summary.warnings);
}

#[test]
fn a_resolved_run_through_the_switches_has_no_energy_warning() {
    let solution = over_the_top(0.005, Composition::Basic);
    assert!(solution.summary.chart_switches > 10);
    assert!(energy_departure(&solution) < 1e-2);
    assert!(solution.summary.warnings.is_empty(), "{:?}", solution.summary.warnings);
}

/// Order 6 (triple jump) at h = 0.02: each of its sub-steps is −1.7 h to 1.3 h long, too long for
/// the passages near the poles; the energy of single steps moved by 10⁴ times the typical change.
#[test]
fn a_composition_whose_energy_jumps_across_switches_is_reported() {
    let solution = over_the_top(0.02, Composition::TripleJump { order: 6 });
    let changes: Vec<f64> = solution.energy.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
    let mut sorted = changes.clone();
    sorted.sort_by(f64::total_cmp);
    let (median, largest) = (sorted[sorted.len() / 2], sorted[sorted.len() - 1]);
    let e0 = solution.energy[0].abs();
    if largest > 1e3 * median && largest > 1e-3 * e0 || energy_departure(&solution) > 0.1 {
        assert!(
            energy_warned(&solution) || !solution.summary.warnings.is_empty(),
            "energy steps up to {:.1e} times the median change, no warning",
            largest / median
        );
    }
}
