//! A step that fails (Newton's method, a non-finite state) or converges implausibly (its discrete
//! energy moves by more than [`ddirac::IMPLAUSIBLE_ENERGY_CHANGE`] of its scale in one step) is taken
//! again as m = 2, 4, … equal sub-steps, each a step of the same scheme.
//!
//! Before, the paper's double spherical pendulum (§7.2) at h = 0.01 died at step 262 314 of 10⁶
//! (Newton's method, at a close passage of a pole of its spherical chart). Now the run completes,
//! counts the subdivided steps in its summary and warns once; the momentum map stays exact. The
//! energy is not yet trustworthy after the closest passages (the run says so with `energy_jump` and
//! `singular_chart` warnings): that needs a chart without the pole, not a smaller step.

use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{solve, Method, OutputOptions, Problem, WarningKind};

/// The paper's method in the paper's chart: the atlas would avoid the failures studied here.
fn paper_method(reduced: bool) -> Method {
    Method { reduced, atlas: false, ..Method::default() }
}

#[test]
fn the_double_spherical_pendulum_runs_a_million_steps_of_h_0_01() {
    let system = DoubleSphericalPendulum::default();
    let problem = Problem { step: 0.01, steps: 1_000_000, ..DoubleSphericalPendulum::paper_problem(10_000) };
    let output = OutputOptions { every: 1_000_000, ..OutputOptions::default() };
    for reduced in [false, true] {
        let summary = solve(&system, &problem, &paper_method(reduced), &output)
            .unwrap_or_else(|e| panic!("reduced {reduced}: the run failed: {e}"))
            .summary;
        let newton = summary.newton;
        eprintln!(
            "reduced {reduced}: {} steps subdivided, up to {} sub-steps; momentum map drift {:e}; warnings {:?}",
            newton.subdivided_steps,
            newton.max_subdivision,
            summary.momentum_map.max_drift,
            summary.warnings.iter().map(|w| w.kind.name()).collect::<Vec<_>>()
        );
        assert_eq!(summary.steps, 1_000_000);
        assert!(newton.subdivided_steps > 0 && newton.max_subdivision >= 2, "reduced {reduced}: {newton:?}");
        let subdivided: Vec<_> = summary.warnings.iter().filter(|w| w.kind == WarningKind::Subdivided).collect();
        assert_eq!(subdivided.len(), 1, "one warning for all subdivided steps");
        assert_eq!(subdivided[0].count, newton.subdivided_steps);
        // p_ϑ1 starts at 0; the reduced run holds it exactly, the unreduced one to round-off of the
        // momenta (of order 10⁵ near the poles).
        let bound = if reduced { 0.0 } else { 1e-5 };
        assert!(
            summary.momentum_map.max_drift <= bound,
            "reduced {reduced}: drift {:e}",
            summary.momentum_map.max_drift
        );
    }
}

/// Steps that converge plausibly are untouched: the paper's run (10⁴ steps, T = 100), whose closest
/// pole passages move the energy by 0.2 % in a step, subdivides none.
#[test]
fn the_papers_run_subdivides_no_step() {
    let system = DoubleSphericalPendulum::default();
    for reduced in [false, true] {
        let problem = DoubleSphericalPendulum::paper_problem(10_000);
        let summary = solve(&system, &problem, &paper_method(reduced), &OutputOptions::default()).unwrap().summary;
        assert_eq!((summary.newton.subdivided_steps, summary.newton.max_subdivision), (0, 0), "reduced {reduced}");
        assert!(summary.warnings.iter().all(|w| w.kind != WarningKind::Subdivided));
    }
}
