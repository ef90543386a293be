//! The numbers the paper prints, one test per table row (paper §7.1, Table 1), for the reduced (+),
//! reduced (−) and unreduced integrators alike.

use ddirac::systems::{ChargedParticle, TABLE_1};
use ddirac::{solve, Method, OutputOptions, Rule, Variant};

fn error(steps: usize, reduced: bool, variant: Variant) -> f64 {
    let method = Method { rule: Rule::Left, variant, reduced, ..Method::default() };
    let problem = ChargedParticle::paper_problem(steps);
    let solution =
        solve(&ChargedParticle::default(), &problem, &method, &OutputOptions { every: steps, wrap_angles: false })
            .expect("the paper's run succeeds");
    solution.summary.reference_error.expect("the charged particle has an exact solution")
}

/// The printed value has `digits` significant digits; the computed one must round to it.
fn assert_matches_printed(computed: f64, printed: f64, digits: i32) {
    let unit = 10f64.powi(printed.abs().log10().floor() as i32 - digits + 1);
    assert!(
        (computed - printed).abs() <= 0.5 * unit,
        "computed {computed:.8} does not round to the printed {printed} ({digits} significant digits)"
    );
}

fn check_row(row: usize) {
    let (steps, printed) = TABLE_1[row];
    for (reduced, variant) in
        [(false, Variant::Plus), (false, Variant::Minus), (true, Variant::Plus), (true, Variant::Minus)]
    {
        let computed = error(steps, reduced, variant);
        let digits = if printed >= 1.0 { 5 } else { 4 };
        assert_matches_printed(computed, printed, digits);
        eprintln!("N = {steps}, reduced = {reduced}, {variant:?}: {computed:.8}");
    }
}

#[test]
fn table_1_n_10() {
    check_row(0);
}

#[test]
fn table_1_n_50() {
    check_row(1);
}

#[test]
fn table_1_n_100() {
    check_row(2);
}

#[test]
fn table_1_n_200() {
    check_row(3);
}
