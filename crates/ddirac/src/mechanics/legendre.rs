//! The Legendre transform FL(q, v) = (q, ∂L/∂v) and the Hamiltonian H(q, p) = ⟨p, v⟩ − L(q, v).
//!
//! For a degenerate Lagrangian (∂²L/∂v² singular, e.g. L linear in the velocities) the velocity is
//! not determined by the momentum; [`velocity`] then returns one velocity compatible with it, and H
//! does not depend on the choice as long as p lies on the primary constraint p = ∂L/∂v.

use crate::dim::{Dim, Fixed};
use crate::mechanics::lagrangian::Lagrangian;
use crate::Scalar;
use nalgebra::{SMatrix, SVector};

use crate::dim::{self, PairFunction};
use crate::linalg::Factorization;
use crate::System;

/// L(q, v + a + b) as a function of (a, b): at a = b = 0 its a-gradient is ∂L/∂v and its mixed
/// block is ∂²L/∂v², so the dual numbers of [`crate::ad`] give both.
struct AtVelocity<'a, S, Dm: Dim> {
    system: &'a S,
    q: &'a Dm::Array<f64>,
    v: &'a Dm::Array<f64>,
}

impl<S: Lagrangian<Dm>, Dm: Dim> PairFunction<Dm> for AtVelocity<'_, S, Dm> {
    fn eval<D: Scalar>(&self, a: &Dm::Array<D>, b: &Dm::Array<D>) -> D {
        let q = Dm::of(a).array(|i| D::from(self.q[i]));
        let mut v = a.clone();
        for ((v, b), v0) in v.as_mut().iter_mut().zip(b.as_ref()).zip(self.v.as_ref()) {
            *v = *v + *b + *v0;
        }
        Lagrangian::<Dm>::lagrangian(self.system, &q, &v)
    }
}

/// The momentum p = ∂L/∂v(q, v).
///
/// ```
/// use ddirac::{mechanics::legendre, systems::ChargedParticle};
/// let p = legendre::momentum(&ChargedParticle::default(), &[0.0; 4], &[1.0, 0.0, 1.0, 1.0]);
/// assert_eq!(p, [1.0, 0.0, 1.0, 1.0]);
/// ```
pub fn momentum<S: System<N>, const N: usize>(system: &S, q: &[f64; N], v: &[f64; N]) -> [f64; N] {
    momentum_in(Fixed, system, q, v)
}

/// [`momentum`] in any dimension.
pub(crate) fn momentum_in<Dm: Dim, S: Lagrangian<Dm>>(
    dim: Dm,
    system: &S,
    q: &Dm::Array<f64>,
    v: &Dm::Array<f64>,
) -> Dm::Array<f64> {
    let da = velocity_gradient(dim, system, q, v);
    dim.array(|i| da[i])
}

/// ∂L/∂v(q, v) as a vector: what [`momentum_in`] gives, and what the inversion compares with p.
fn velocity_gradient<Dm: Dim, S: Lagrangian<Dm>>(
    dim: Dm,
    system: &S,
    q: &Dm::Array<f64>,
    v: &Dm::Array<f64>,
) -> Dm::Vector {
    let zero = dim.array(|_| 0.0);
    dim::first(dim, &AtVelocity { system, q, v }, &zero, &zero).da
}

/// The rank of ∂²L/∂v² at (q, v), counting pivots above 10⁻¹⁰ of its largest entry; 0 when the
/// Lagrangian is linear in the velocities.
pub fn rank<S: System<N>, const N: usize>(system: &S, q: &[f64; N], v: &[f64; N]) -> usize {
    rank_in(Fixed, system, q, v)
}

/// [`rank`] in any dimension.
pub(crate) fn rank_in<Dm: Dim, S: Lagrangian<Dm>>(
    dim: Dm,
    system: &S,
    q: &Dm::Array<f64>,
    v: &Dm::Array<f64>,
) -> usize {
    let hess = velocity_hessian_in(dim, system, q, v).2;
    crate::linalg::solve(dim, &hess, &dim.zeros(), 1e-10).map_or(0, |(_, rank)| rank)
}

/// Whether the Legendre transform is regular at (q, v): ∂²L/∂v² has full rank.
pub fn is_regular<S: System<N>, const N: usize>(system: &S, q: &[f64; N], v: &[f64; N]) -> bool {
    rank(system, q, v) == N
}

/// How near to singular the Legendre map is at (q, v): the smallest pivot of ∂²L/∂v² (full pivoting)
/// over its largest, 0 where it is singular, and the coordinate of the smallest pivot, along whose
/// velocity the momentum stops determining the motion. The spherical pendulum's ∂²L/∂v² =
/// m l² diag(1, sin²θ) gives sin²θ and the azimuth: its chart is singular at the poles θ = 0, π.
///
/// ```
/// use ddirac::{Coordinate, System, mechanics::legendre};
/// use ddirac::num_dual::DualNum;
/// struct Sphere;
/// impl System<2> for Sphere {
///     fn coordinates(&self) -> [Coordinate; 2] {
///         [Coordinate::shape("theta").angle(), Coordinate::group("phi").angle()]
///     }
///     fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 2], v: &[D; 2]) -> D {
///         (v[0] * v[0] + q[0].sin().powi(2) * v[1] * v[1]) * 0.5
///     }
/// }
/// let (ratio, along) = legendre::conditioning(&Sphere, &[0.01, 0.0], &[0.0, 0.0]);
/// assert!((ratio - 0.01f64.sin().powi(2)).abs() < 1e-15 && along == 1);
/// ```
pub fn conditioning<S: System<N>, const N: usize>(system: &S, q: &[f64; N], v: &[f64; N]) -> (f64, usize) {
    conditioning_in(Fixed, system, q, v)
}

/// [`conditioning`] in any dimension.
pub(crate) fn conditioning_in<Dm: Dim, S: Lagrangian<Dm>>(
    dim: Dm,
    system: &S,
    q: &Dm::Array<f64>,
    v: &Dm::Array<f64>,
) -> (f64, usize) {
    let hess = velocity_hessian_in(dim, system, q, v).2;
    Factorization::new(dim, &hess, 0.0).map_or((0.0, 0), |lu| lu.smallest_pivot())
}

pub(crate) fn velocity_hessian<S: System<N>, const N: usize>(
    system: &S,
    q: &[f64; N],
    v: &[f64; N],
) -> (f64, SVector<f64, N>, SMatrix<f64, N, N>) {
    velocity_hessian_in(Fixed, system, q, v)
}

/// [`velocity_hessian`] in any dimension.
pub(crate) fn velocity_hessian_in<Dm: Dim, S: Lagrangian<Dm>>(
    dim: Dm,
    system: &S,
    q: &Dm::Array<f64>,
    v: &Dm::Array<f64>,
) -> (f64, Dm::Vector, Dm::Matrix) {
    let zero = dim.array(|_| 0.0);
    let d = dim::mixed(dim, &AtVelocity { system, q, v }, &zero, &zero);
    (d.value, d.da, d.dadb)
}

/// Where the mismatch ‖∂L/∂v − p‖∞ of [`velocity`] counts as round-off, relative to ‖p‖∞ + ‖∂²L/∂v²‖ ‖v‖∞:
/// about 450 ε, what sums of a few hundred terms leave (a chain of 50 links: 24 ε).
pub const ROUND_OFF: f64 = 1e-13;

/// A velocity v with ∂L/∂v(q, v) = p, by chord Newton on ∂L/∂v(q, v) = p from v = 0 (∂²L/∂v² is
/// evaluated at the first iterate and again only where the mismatch stops decreasing; one
/// correction is exact for a Lagrangian quadratic in v). The iteration ends when a correction is
/// below round-off, or when the mismatch stops decreasing at the round-off level of ∂L/∂v
/// ([`ROUND_OFF`] of ‖p‖∞ + ‖∂²L/∂v²‖ ‖v‖∞) or after a correction made with ∂²L/∂v² of the iterate
/// it started from: the iterate before is returned. Where ∂²L/∂v² is singular the
/// undetermined velocity components stay 0. Returns the velocity and the remaining mismatch
/// ‖∂L/∂v − p‖∞.
pub fn velocity<S: System<N>, const N: usize>(system: &S, q: &[f64; N], p: &[f64; N]) -> ([f64; N], f64) {
    velocity_in(Fixed, system, q, p)
}

/// [`velocity`] in any dimension.
pub(crate) fn velocity_in<Dm: Dim, S: Lagrangian<Dm>>(
    dim: Dm,
    system: &S,
    q: &Dm::Array<f64>,
    p: &Dm::Array<f64>,
) -> (Dm::Array<f64>, f64) {
    let array = |v: &Dm::Vector| dim.array(|i| v[i]);
    let mismatch_at = |grad: &Dm::Vector| dim.vector(|i| grad[i] - p[i]);
    let p_scale = p.as_ref().iter().fold(0.0, |m: f64, x| x.abs().max(m));
    let mut v = dim.zeros();
    let mut previous = v.clone();
    let mut mismatch = f64::INFINITY;
    let mut lu: Option<Factorization<Dm>> = None;
    // Whether ∂²L/∂v² was evaluated at this iterate, and whether the correction that led to it used
    // one evaluated at the iterate it started from.
    let (mut fresh, mut fresh_correction) = (false, false);
    for _ in 0..40 {
        let grad = if lu.is_none() {
            let (_, grad, hess) = velocity_hessian_in(dim, system, q, &array(&v));
            (lu, fresh) = (Factorization::new(dim, &hess, 1e-10), true);
            grad
        } else {
            velocity_gradient(dim, system, q, &array(&v))
        };
        let r = mismatch_at(&grad);
        let new_mismatch = Dm::amax(&r);
        if !new_mismatch.is_finite() || new_mismatch >= mismatch {
            let scale = p_scale + lu.as_ref().map_or(0.0, Factorization::scale) * Dm::amax(&previous);
            if fresh || fresh_correction || mismatch <= ROUND_OFF * scale {
                // Nothing left to gain (a fresh ∂²L/∂v² would only move v within round-off): the
                // best iterate is the one before.
                v = previous;
                break;
            }
            // The kept ∂²L/∂v² no longer serves: evaluate it here and go on from this iterate.
            (lu, mismatch) = (None, f64::INFINITY);
            continue;
        }
        mismatch = new_mismatch;
        let Some(delta) = lu.as_ref().map(|lu| lu.solve(&r)) else { break };
        previous = v.clone();
        v -= &delta;
        (fresh_correction, fresh) = (fresh, false);
        if Dm::amax(&delta) <= 1e-15 * (1.0 + Dm::amax(&v)) {
            mismatch = Dm::amax(&mismatch_at(&velocity_gradient(dim, system, q, &array(&v))));
            break;
        }
    }
    (array(&v), mismatch)
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
    hamiltonian_in(Fixed, system, q, p)
}

/// [`hamiltonian`] in any dimension.
pub(crate) fn hamiltonian_in<Dm: Dim, S: Lagrangian<Dm>>(
    dim: Dm,
    system: &S,
    q: &Dm::Array<f64>,
    p: &Dm::Array<f64>,
) -> f64 {
    let (v, _) = velocity_in(dim, system, q, p);
    let pv: f64 = p.as_ref().iter().zip(v.as_ref()).map(|(a, b)| a * b).sum();
    pv - system.lagrangian(q, &v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dim::Dynamic;
    use crate::scheme::testing::AsDynamic;
    use crate::systems::{DoubleSphericalPendulum, PendulumChain};

    fn bits(x: &[f64]) -> Vec<u64> {
        x.iter().map(|v| v.to_bits()).collect()
    }

    fn alike<S: System<N> + Clone, const N: usize>(system: &S, q: [f64; N], v: [f64; N]) {
        let dynamic = AsDynamic::<_, N>(system.clone());
        let (qd, vd) = (q.to_vec(), v.to_vec());
        assert_eq!(bits(&momentum(system, &q, &v)), bits(&momentum_in(Dynamic(N), &dynamic, &qd, &vd)));
        let (l, grad, hess) = velocity_hessian(system, &q, &v);
        let (dl, dgrad, dhess) = velocity_hessian_in(Dynamic(N), &dynamic, &qd, &vd);
        assert_eq!(
            (l.to_bits(), bits(grad.as_slice()), bits(hess.as_slice())),
            (dl.to_bits(), bits(dgrad.as_slice()), bits(dhess.as_slice()))
        );
        // The Legendre inversion from the momentum at v: the same iterates, back to v.
        let p = momentum(system, &q, &v);
        let (w, mismatch) = velocity(system, &q, &p);
        let (dw, dmismatch) = velocity_in(Dynamic(N), &dynamic, &qd, &p.to_vec());
        assert_eq!((bits(&w), mismatch.to_bits()), (bits(&dw), dmismatch.to_bits()));
        assert!(w.iter().zip(&v).all(|(a, b)| (a - b).abs() < 1e-12), "{w:?} against {v:?}");
    }

    #[test]
    fn the_legendre_transform_is_alike_in_a_fixed_and_a_dynamic_dimension() {
        alike(&PendulumChain::<5>::default(), [0.3, -0.2, 0.5, 0.1, 0.7], [0.4, 0.1, -0.3, 0.2, 0.05]);
        alike(&DoubleSphericalPendulum::default(), [0.2, 0.7, -0.4, 1.1], [0.3, -0.1, 0.2, 0.4]);
    }
}
