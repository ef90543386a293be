//! The energy of every reported row inverts the Legendre transform (`legendre::velocity`: chord
//! Newton on ∂L/∂v(q, v) = p). At the round-off level the mismatch goes up and down at random, and
//! its test of progress (a decrease) then called for ∂²L/∂v² again and again: up to 40 iterations with
//! a fresh ∂²L/∂v² every other one, 196 evaluations of L (14 of ∂²L/∂v²) for a text chain of 50 links
//! where one ∂²L/∂v² and three gradients (16) do. Rows of large systems cost 40 times a step
//! (`ddirac run` of the text chain of 50, a row every step: 3.6 s, of which 0.09 s the steps). The
//! iteration now stops when the mismatch stops decreasing at the round-off level
//! (`legendre::ROUND_OFF`).

use crate::chain_text;

use std::cell::Cell;

use ddirac::expression::ExpressionSystem;
use ddirac::mechanics::legendre;
use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{Coordinate, Scalar, System};

/// A system that counts the evaluations of its Lagrangian.
struct Counting<S> {
    inner: S,
    calls: Cell<usize>,
}

impl<S: System<N>, const N: usize> System<N> for Counting<S> {
    fn coordinates(&self) -> [Coordinate; N] {
        self.inner.coordinates()
    }

    fn lagrangian<D: Scalar>(&self, q: &[D; N], v: &[D; N]) -> D {
        self.calls.set(self.calls.get() + 1);
        self.inner.lagrangian(q, v)
    }
}

/// The velocity recovered from p = ∂L/∂v(q, v), the evaluations of L it took, and the mismatch.
fn recovered<S: System<N>, const N: usize>(inner: S, q: [f64; N], v: [f64; N]) -> (f64, usize, f64) {
    let system = Counting { inner, calls: Cell::new(0) };
    let p = legendre::momentum(&system, &q, &v);
    system.calls.set(0);
    let (w, mismatch) = legendre::velocity(&system, &q, &p);
    let error = w.iter().zip(&v).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    let scale = p.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(mismatch <= 1e-13 * scale, "mismatch {mismatch:e} against ‖p‖ = {scale}");
    (error, system.calls.get(), mismatch)
}

#[test]
fn a_text_chain_of_50_inverts_its_legendre_transform_with_one_hessian() {
    let q: [f64; 50] = std::array::from_fn(|i| 0.5 * (std::f64::consts::PI * (i + 1) as f64 / 51.0).sin());
    let v: [f64; 50] = std::array::from_fn(|i| 0.3 * (i as f64 * 0.7).cos());
    let chain = ExpressionSystem::<50>::new(&chain_text::chain_spec(50)).unwrap();
    let (error, calls, mismatch) = recovered(chain, q, v);
    eprintln!("chain of 50: {calls} evaluations of L, velocity error {error:.1e}, mismatch {mismatch:.1e}");
    assert!(error < 1e-12, "{error:e}");
    // ∂²L/∂v² in ⌈50 / 4⌉ = 13 chunks, and three gradients.
    assert!(calls <= 16, "{calls} evaluations of L");
}

#[test]
fn the_double_spherical_pendulum_inverts_its_legendre_transform_to_round_off() {
    // Near a pole (sin φ1 = 0.01: ∂²L/∂v² ill-conditioned) and away from it.
    for phi1 in [0.01, 1.0] {
        let q = [0.3, phi1, 0.2, 1.3];
        let v = [0.4, -0.2, 0.7, 0.1];
        let (error, calls, _) = recovered(DoubleSphericalPendulum::default(), q, v);
        eprintln!("double spherical pendulum, φ1 = {phi1}: {calls} evaluations, velocity error {error:.1e}");
        assert!(error < 1e-8, "{error:e}");
        assert!(calls <= 8, "{calls} evaluations of L");
    }
}
