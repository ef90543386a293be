//! The sub-steps of a composition share their compiled programs: the step size is a runtime input of
//! the programs (issue 12), so the 17 sub-steps of Kahan–Li's order 8, of 9 distinct sizes γh, compile
//! the two programs of the double spherical pendulum once, and another composition of the same run
//! compiles nothing. (A compiled closed-form step folds h into its constants, so each distinct size
//! has its own; the pendulum's steps are not linear and have none.) The counts are of this test
//! process only, which runs this one test (the compiled programs are cached in the process: another
//! test compiling the same programs first, on any thread, changes the count).

use ddirac::compiled::native_compilations;
use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{solve, Composition, DerivativePath, Differentiation, Method, OutputOptions, Problem};

#[test]
fn the_sub_steps_of_a_composition_share_one_compile() {
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
