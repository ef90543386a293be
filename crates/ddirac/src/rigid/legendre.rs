//! The Legendre transform of a rigid system: Π = ∂ℓ/∂Ω, p = ∂ℓ/∂ṡ, its inverse by Newton's method,
//! and the energy E = ⟨Π, Ω⟩ + ⟨p, ṡ⟩ − ℓ.

use nalgebra::DVector;

use super::so3::Matrix3;
use super::system::RigidSystem;
use crate::dim::{mixed, Dim, Dynamic, PairFunction};
use crate::newton::{self, NewtonOptions};
use crate::Scalar;

/// ℓ at a fixed attitude and shape as a function of the velocities w = (Ω, ṡ) = w_a + w_b, so that the
/// mixed block of [`mixed`] is the Hessian ∂²ℓ/∂w².
struct Velocities<'s, S> {
    system: &'s S,
    r: &'s Matrix3<f64>,
    s: &'s [f64],
}

impl<S: RigidSystem> PairFunction<Dynamic> for Velocities<'_, S> {
    fn eval<D: Scalar>(&self, a: &Vec<D>, b: &Vec<D>) -> D {
        let w: Vec<D> = a.iter().zip(b).map(|(&x, &y)| x + y).collect();
        let r = self.r.map(|row| row.map(D::from));
        let s: Vec<D> = self.s.iter().map(|&x| D::from(x)).collect();
        self.system.lagrangian(&r, &[w[0], w[1], w[2]], &s, &w[3..])
    }
}

/// (Π, p) = ∂ℓ/∂(Ω, ṡ) at (R, Ω, s, ṡ), and ℓ there.
pub(crate) fn momenta<S: RigidSystem>(
    system: &S,
    r: &Matrix3<f64>,
    omega: &[f64; 3],
    s: &[f64],
    v: &[f64],
) -> (f64, [f64; 3], Vec<f64>) {
    let f = Velocities { system, r, s };
    let dim = Dynamic(3 + s.len());
    let w = dim.array(|i| if i < 3 { omega[i] } else { v[i - 3] });
    let zero = dim.array(|_| 0.0);
    let d = crate::dim::first(dim, &f, &w, &zero);
    (d.value, [d.da[0], d.da[1], d.da[2]], d.da.as_slice()[3..].to_vec())
}

/// The velocities (Ω, ṡ) with ∂ℓ/∂(Ω, ṡ) = (Π, p) at (R, s), by Newton's method from `guess`; `None`
/// where the Hessian ∂²ℓ/∂(Ω, ṡ)² is singular (a degenerate Lagrangian) or Newton's method fails.
pub(crate) fn velocities<S: RigidSystem>(
    system: &S,
    r: &Matrix3<f64>,
    pi: &[f64; 3],
    s: &[f64],
    p: &[f64],
    guess: &[f64],
) -> Option<DVector<f64>> {
    let f = Velocities { system, r, s };
    let dim = Dynamic(3 + s.len());
    let target = dim.vector(|i| if i < 3 { pi[i] } else { p[i - 3] });
    let scale = target.amax();
    let mut w = DVector::from_column_slice(guess);
    let zero = dim.array(|_| 0.0);
    newton::solve(&mut w, scale, &NewtonOptions::default(), |w| {
        let d = mixed(dim, &f, &w.as_slice().to_vec(), &zero);
        (d.da - &target, d.dadb)
    })
    .ok()?;
    Some(w)
}

/// E = ⟨Π, Ω⟩ + ⟨p, ṡ⟩ − ℓ(R, Ω, s, ṡ) at the velocities `w` = (Ω, ṡ) of (Π, p).
pub(crate) fn energy<S: RigidSystem>(system: &S, r: &Matrix3<f64>, s: &[f64], w: &DVector<f64>) -> f64 {
    let omega = [w[0], w[1], w[2]];
    let (l, pi, p) = momenta(system, r, &omega, s, &w.as_slice()[3..]);
    let pv: f64 = p.iter().zip(&w.as_slice()[3..]).map(|(a, b)| a * b).sum();
    pi[0] * omega[0] + pi[1] * omega[1] + pi[2] * omega[2] + pv - l
}
