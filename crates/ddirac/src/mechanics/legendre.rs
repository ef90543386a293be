//! The Legendre transform FL(q, v) = (q, ∂L/∂v) and the Hamiltonian H(q, p) = ⟨p, v⟩ − L(q, v).
//!
//! For a degenerate Lagrangian (∂²L/∂v² singular, e.g. L linear in the velocities) the velocity is
//! not determined by the momentum; [`velocity`] then returns one velocity compatible with it, and H
//! does not depend on the choice as long as p lies on the primary constraint p = ∂L/∂v.

use nalgebra::{SMatrix, SVector};
use num_dual::{gradient, hessian, DualNum};

use crate::System;

/// The momentum p = ∂L/∂v(q, v).
///
/// ```
/// use ddirac::{mechanics::legendre, systems::ChargedParticle};
/// let p = legendre::momentum(&ChargedParticle::default(), &[0.0; 4], &[1.0, 0.0, 1.0, 1.0]);
/// assert_eq!(p, [1.0, 0.0, 1.0, 1.0]);
/// ```
pub fn momentum<S: System<N>, const N: usize>(system: &S, q: &[f64; N], v: &[f64; N]) -> [f64; N] {
    let (_, p) = gradient(
        |v: SVector<_, N>| {
            let q = q.map(DualNum::from_re);
            system.lagrangian(&q, &v.into())
        },
        &SVector::from(*v),
    );
    p.into()
}

/// The rank of ∂²L/∂v² at (q, v), counting pivots above 10⁻¹⁰ of its largest entry; 0 when the
/// Lagrangian is linear in the velocities.
pub fn rank<S: System<N>, const N: usize>(system: &S, q: &[f64; N], v: &[f64; N]) -> usize {
    let hess = velocity_hessian(system, q, v).2;
    crate::linalg::solve(hess, SVector::zeros(), 1e-10).map_or(0, |(_, rank)| rank)
}

/// Whether the Legendre transform is regular at (q, v): ∂²L/∂v² has full rank.
pub fn is_regular<S: System<N>, const N: usize>(system: &S, q: &[f64; N], v: &[f64; N]) -> bool {
    rank(system, q, v) == N
}

fn velocity_hessian<S: System<N>, const N: usize>(
    system: &S,
    q: &[f64; N],
    v: &[f64; N],
) -> (f64, SVector<f64, N>, SMatrix<f64, N, N>) {
    hessian(
        |v: SVector<_, N>| {
            let q = q.map(DualNum::from_re);
            system.lagrangian(&q, &v.into())
        },
        &SVector::from(*v),
    )
}

/// A velocity v with ∂L/∂v(q, v) = p, by Newton's method on ∂L/∂v(q, v) = p; where ∂²L/∂v² is
/// singular the undetermined velocity components stay 0. Returns the velocity and the remaining
/// mismatch ‖∂L/∂v − p‖∞.
pub fn velocity<S: System<N>, const N: usize>(system: &S, q: &[f64; N], p: &[f64; N]) -> ([f64; N], f64) {
    let p = SVector::from(*p);
    let mut v = SVector::<f64, N>::zeros();
    let mut mismatch = f64::INFINITY;
    for _ in 0..20 {
        let (_, grad, hess) = velocity_hessian(system, q, &v.into());
        let r = grad - p;
        let new_mismatch = r.amax();
        if !new_mismatch.is_finite() || new_mismatch >= mismatch {
            break;
        }
        mismatch = new_mismatch;
        let Some((delta, _)) = crate::linalg::solve(hess, r, 1e-10) else { break };
        v -= delta;
        if delta.amax() <= 1e-15 * (1.0 + v.amax()) {
            mismatch = (velocity_hessian(system, q, &v.into()).1 - p).amax();
            break;
        }
    }
    (v.into(), mismatch)
}

/// The Hamiltonian H(q, p) = ⟨p, v⟩ − L(q, v) with v from [`velocity`].
///
/// ```
/// use ddirac::{mechanics::legendre, systems::ChargedParticle};
/// // Kaluza–Klein particle at rest in ℝ³ with p_θ = 1: H = ½ p_θ² = 0.5
/// let h = legendre::hamiltonian(&ChargedParticle::default(), &[0.0; 4], &[0.0, 0.0, 0.0, 1.0]);
/// assert!((h - 0.5).abs() < 1e-14);
/// ```
pub fn hamiltonian<S: System<N>, const N: usize>(system: &S, q: &[f64; N], p: &[f64; N]) -> f64 {
    let (v, _) = velocity(system, q, p);
    let pv: f64 = p.iter().zip(&v).map(|(a, b)| a * b).sum();
    pv - system.lagrangian(q, &v)
}
