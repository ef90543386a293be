//! The derivative of `min`/`max` through the branch not taken, under compiled derivatives.
//!
//! min(a, √x) with a picked has ∂/∂x = 0 for every x ≥ 0, and dual numbers give 0 at x = 0 too.
//! The compiled programs gated the adjoint of √x by the indicator and then multiplied it by
//! ∂√x/∂x = ∞ at x = 0: 0 · ∞ = NaN, so a run that reached x = 0 failed with a non-finite residual
//! where dual numbers went on.

use ddirac::compiled::{pair_programs, Traced};
use ddirac::dim::Fixed;
use ddirac::Scalar;

/// f(base, a, b) = min(−1, √(base + a)) + b²/2: the constant is always picked.
fn f<D: Scalar>(base: &[D; 1], a: &[D; 1], b: &[D; 1]) -> D {
    let root = (base[0] + a[0]).sqrt();
    D::from(-1.0).min_of(root) + b[0] * b[0] * 0.5
}

#[test]
fn the_untaken_square_root_of_min_gives_a_zero_derivative_at_zero_not_nan() {
    let traced = |base: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| f(base, a, b);
    let programs = pair_programs(Fixed, traced, &[1.0], &[0.5]).expect("the function compiles at x = 1");
    let (mut first, mut mixed) = ([0.0; 3], [0.0; 4]);
    for x in [0.0, 1e-300, 0.25, 4.0] {
        programs.first.eval(&[x, 0.5], &mut Vec::new(), &mut first);
        programs.mixed.eval(&[x, 0.5], &mut Vec::new(), &mut mixed);
        // f = −1 + b²/2, ∂f/∂a = 0, ∂f/∂b = b, ∂²f/∂a∂b = 0.
        assert_eq!(first, [-0.875, 0.0, 0.5], "first derivatives at x = {x}");
        assert_eq!(mixed, [-0.875, 0.0, 0.5, 0.0], "mixed block at x = {x}");
    }
}
