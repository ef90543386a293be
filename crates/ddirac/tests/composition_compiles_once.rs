//! The sub-steps of a composition share their compiled programs: the step size is a runtime input of
//! the programs (issue 12), so the 17 sub-steps of Kahan–Li's order 8, of 9 distinct sizes γh, compile
//! the two programs of the double spherical pendulum once, and another composition of the same run
//! compiles nothing. (A compiled closed-form step folds h into its constants, so each distinct size
//! has its own; the pendulum's steps are not linear and have none.) The counts are of this test
//! process, whose tests run one at a time (`ONE_AT_A_TIME`): the compiled programs are cached in the
//! process, so a test that compiles the same programs on another thread changes the count.

use std::sync::Mutex;

use ddirac::compiled::native_compilations;
use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{solve, Composition, DerivativePath, Differentiation, Method, OutputOptions, Problem};

/// Held by each test of this process for its whole run.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

#[test]
fn the_sub_steps_of_a_composition_share_one_compile() {
    let _alone = ONE_AT_A_TIME.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let system = DoubleSphericalPendulum::default();
    let problem = Problem { steps: 100, ..DoubleSphericalPendulum::paper_problem(10_000) };
    for reduced in [false, true] {
        let mut compiles = vec![];
        for composition in [Composition::KahanLi17, Composition::Suzuki5, Composition::Basic] {
            let before = native_compilations();
            let method = Method {
                reduced,
                composition,
                differentiation: Differentiation::Compiled,
                atlas: false,
                ..Method::default()
            };
            let summary = solve(&system, &problem, &method, &OutputOptions::default()).unwrap().summary;
            assert!(matches!(summary.derivatives, DerivativePath::Compiled { closed_form: None, .. }));
            compiles.push(native_compilations() - before);
        }
        // Two programs (residual; residual and Jacobian) for the first run, none after.
        assert_eq!(compiles, [2, 0, 0], "reduced {reduced}");
    }
}

/// The sub-steps that share the first one's trace (its programs with their own h as input) step as
/// dual numbers do at each sub-step size: a run of order 8 ends where the same run on dual numbers
/// ends, to round-off.
#[test]
fn the_sub_steps_sharing_one_trace_step_as_dual_numbers_do() {
    let _alone = ONE_AT_A_TIME.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let system = DoubleSphericalPendulum::default();
    let problem = Problem { steps: 200, ..DoubleSphericalPendulum::paper_problem(10_000) };
    for composition in [Composition::KahanLi17, Composition::Suzuki5] {
        let end = |differentiation| {
            let method = Method { composition, differentiation, atlas: false, ..Method::default() };
            solve(&system, &problem, &method, &OutputOptions::default()).unwrap().summary.final_q
        };
        let (compiled, dual) = (end(Differentiation::Compiled), end(Differentiation::Dual));
        let apart = compiled.iter().zip(&dual).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        eprintln!("{composition:?}: compiled against dual numbers {apart:.1e}");
        assert!(apart < 1e-11, "{composition:?}: {apart:e}");
    }
}
