//! The Euler–Lagrange equations of a system as a first-order vector field on (q, v), for explicit
//! integrators to compare with (the benchmarks' Runge–Kutta peer):
//!
//! ```text
//! M(q, v) v̇ = ∂L/∂q − (∂²L/∂v∂q) v,      M = ∂²L/∂v²,      q̇ = v
//! ```
//!
//! (L without explicit time dependence; M must be invertible, so degenerate Lagrangians have no such
//! field). Its derivatives come from the engine's own machinery: compiled programs of the two pair
//! functions (q, a, v) ↦ L(q + a, v) (∂L/∂q, ∂L/∂v, ∂²L/∂q∂v) and (q, a, v) ↦ L(q, v + a) (∂²L/∂v²)
//! where the Lagrangian can be traced, dual numbers otherwise.

use nalgebra::{SMatrix, SVector};

use crate::compiled::{CompiledPair, Traced};
use crate::dim::Fixed;
use crate::dim::{self, PairFunction};
use crate::{Scalar, System};

/// The Euler–Lagrange vector field of a system, with its derivatives compiled or by dual numbers.
pub struct EulerLagrange<'a, S, const N: usize> {
    system: &'a S,
    compiled: Option<(CompiledPair<Fixed<N>>, CompiledPair<Fixed<N>>)>,
}

/// (a, b) ↦ L(q + a, b) at a fixed q.
struct PositionVelocity<'a, S, const N: usize> {
    system: &'a S,
    q: [f64; N],
}

impl<S: System<N>, const N: usize> PairFunction<Fixed<N>> for PositionVelocity<'_, S, N> {
    fn eval<D: Scalar>(&self, a: &[D; N], b: &[D; N]) -> D {
        self.system.lagrangian(&std::array::from_fn(|i| a[i] + self.q[i]), b)
    }
}

/// (a, b) ↦ L(q, b + a) at a fixed q.
struct VelocityVelocity<'a, S, const N: usize> {
    system: &'a S,
    q: [f64; N],
}

impl<S: System<N>, const N: usize> PairFunction<Fixed<N>> for VelocityVelocity<'_, S, N> {
    fn eval<D: Scalar>(&self, a: &[D; N], b: &[D; N]) -> D {
        let q = self.q.map(D::from);
        self.system.lagrangian(&q, &std::array::from_fn(|i| b[i] + a[i]))
    }
}

impl<'a, S: System<N>, const N: usize> EulerLagrange<'a, S, N> {
    /// The field of `system`; with `compile`, its derivatives traced at (`q`, `v`) and compiled
    /// (dual numbers when the Lagrangian cannot be traced there).
    pub fn new(system: &'a S, compile: bool, q: &[f64; N], v: &[f64; N]) -> Self {
        let compiled = compile
            .then(|| {
                let pv = CompiledPair::new(
                    Fixed,
                    |base: &[Traced; N], a: &[Traced; N], b: &[Traced; N]| {
                        system.lagrangian(&std::array::from_fn(|i| a[i] + base[i]), b)
                    },
                    q,
                    v,
                );
                let vv = CompiledPair::new(
                    Fixed,
                    |base: &[Traced; N], a: &[Traced; N], b: &[Traced; N]| {
                        system.lagrangian(base, &std::array::from_fn(|i| b[i] + a[i]))
                    },
                    q,
                    v,
                );
                pv.ok().zip(vv.ok())
            })
            .flatten();
        Self { system, compiled }
    }

    /// Whether the derivatives are compiled.
    pub fn is_compiled(&self) -> bool {
        self.compiled.is_some()
    }

    /// The acceleration v̇ at (q, v); `None` where M is singular.
    pub fn acceleration(&self, q: &[f64; N], v: &[f64; N]) -> Option<[f64; N]> {
        let compiled = self.compiled.as_ref().and_then(|(pv, vv)| {
            let (first, mixed) = pv.first_or_mixed(q, v, true)?;
            let (_, mass) = vv.first_or_mixed(q, v, true)?;
            Some((first.da, mixed?, mass?))
        });
        let (dl_dq, dq_dv, mass): (SVector<f64, N>, SMatrix<f64, N, N>, SMatrix<f64, N, N>) = match compiled {
            Some(parts) => parts,
            None => {
                let pv = dim::mixed(Fixed, &PositionVelocity { system: self.system, q: *q }, &[0.0; N], v);
                let vv = dim::mixed(Fixed, &VelocityVelocity { system: self.system, q: *q }, &[0.0; N], v);
                (pv.da, pv.dadb, vv.dadb)
            }
        };
        let rhs = dl_dq - dq_dv.transpose() * SVector::from(*v);
        let (solution, rank) = crate::linalg::solve(Fixed::<N>, &mass, &rhs, 1e-14)?;
        (rank == N).then(|| solution.into())
    }

    /// The field ẏ = (v, v̇) at y = (q, v), written into `dy`; NaN where M is singular.
    pub fn field(&self, y: &[f64], dy: &mut [f64]) {
        let q: [f64; N] = std::array::from_fn(|i| y[i]);
        let v: [f64; N] = std::array::from_fn(|i| y[N + i]);
        let a = self.acceleration(&q, &v).unwrap_or([f64::NAN; N]);
        dy[..N].copy_from_slice(&v);
        dy[N..2 * N].copy_from_slice(&a);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::systems::{DoubleSphericalPendulum, Kepler};

    /// Kepler in polar coordinates: r̈ = r φ̇² − k/(m r²), φ̈ = −2 ṙ φ̇ / r, by hand; compiled and dual
    /// numbers agree with it.
    #[test]
    fn kepler_accelerations_are_those_written_by_hand() {
        let system = Kepler::default();
        let (q, v) = ([1.3, 0.4], [0.2, 0.7]);
        let expected = [q[0] * v[1] * v[1] - 1.0 / (q[0] * q[0]), -2.0 * v[0] * v[1] / q[0]];
        for compile in [false, true] {
            let field = EulerLagrange::new(&system, compile, &q, &v);
            assert_eq!(field.is_compiled(), compile);
            let a = field.acceleration(&q, &v).unwrap();
            assert!((a[0] - expected[0]).abs() < 1e-14 && (a[1] - expected[1]).abs() < 1e-14, "{a:?}");
        }
    }

    /// The compiled field of the double spherical pendulum equals the field by dual numbers.
    #[test]
    fn compiled_and_dual_fields_agree() {
        let system = DoubleSphericalPendulum::default();
        let (q, v) = ([0.1, 2.25, 2.0, 3.0], [1e-3, -2e-3, 5e-4, 1e-3]);
        let compiled = EulerLagrange::new(&system, true, &q, &v);
        let dual = EulerLagrange::new(&system, false, &q, &v);
        let (a, b) = (compiled.acceleration(&q, &v).unwrap(), dual.acceleration(&q, &v).unwrap());
        let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= 1e-12 * scale), "{a:?} against {b:?}");
    }
}
