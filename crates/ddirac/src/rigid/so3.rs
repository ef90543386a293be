//! The rotation group SO(3) and its Lie algebra so(3) ≅ ℝ³, with the Cayley retraction that the
//! discrete steps on the group use.
//!
//! Conventions (`docs/systems/rigid-body.md`): a rotation R maps body to space; the hat map
//! ξ̂ = [[0, −ξ3, ξ2], [ξ3, 0, −ξ1], [−ξ2, ξ1, 0]] (ξ̂ v = ξ × v) and vee its inverse; a step is
//! R_{k+1} = R_k F_k with F_k = cay(ζ_k), where
//!
//! ```text
//! cay(ζ) = (I − ζ̂/2)⁻¹ (I + ζ̂/2) = I + 4/(4 + |ζ|²) (ζ̂ + ζ̂²/2)        (Cayley)
//! cay⁻¹(F) = 2/(1 + tr F) · vee(F − Fᵀ)
//! dcay⁻¹_ζ = I − ζ̂/2 + ζ ζᵀ/4        (right trivialized: δF F⁻¹ = (dcay_ζ δζ)^)
//! ```
//!
//! The Cayley map is rational (no trigonometric function in a step), exactly orthogonal in exact
//! arithmetic, and symmetric, cay(−ζ) = cay(ζ)⁻¹, so that a symmetric discrete Lagrangian built on it
//! gives a symmetric method of order 2 (the base of the compositions of orders 4, 6, 8). It covers
//! every rotation by an angle below π, 2 arctan(|ζ|/2), which a step of a resolved motion never
//! approaches. The rotation by half of cay(ζ) about the same axis is cay(ζ / (1 + √(1 + |ζ|²/4)))
//! ([`half`]), the group midpoint of the step.

use num_dual::DualNum;

/// A 3 × 3 matrix as rows, over any scalar (`m[i][j]`: row i, column j).
pub type Matrix3<D> = [[D; 3]; 3];

/// The identity over any scalar.
pub fn identity<D: DualNum<Primitive = f64> + Copy>() -> Matrix3<D> {
    let (o, z) = (D::one(), D::zero());
    [[o, z, z], [z, o, z], [z, z, o]]
}

/// ξ̂, the skew matrix with ξ̂ v = ξ × v.
pub fn hat<D: DualNum<Primitive = f64> + Copy>(x: &[D; 3]) -> Matrix3<D> {
    let z = D::zero();
    [[z, -x[2], x[1]], [x[2], z, -x[0]], [-x[1], x[0], z]]
}

/// The vector of the skew part of m: vee((m − mᵀ)/2).
pub fn vee_skew(m: &Matrix3<f64>) -> [f64; 3] {
    [0.5 * (m[2][1] - m[1][2]), 0.5 * (m[0][2] - m[2][0]), 0.5 * (m[1][0] - m[0][1])]
}

/// a b.
pub fn mul<D: DualNum<Primitive = f64> + Copy>(a: &Matrix3<D>, b: &Matrix3<D>) -> Matrix3<D> {
    let mut c = [[D::zero(); 3]; 3];
    for (ci, ai) in c.iter_mut().zip(a) {
        for (j, cij) in ci.iter_mut().enumerate() {
            *cij = ai[0] * b[0][j] + ai[1] * b[1][j] + ai[2] * b[2][j];
        }
    }
    c
}

/// mᵀ.
pub fn transpose<D: DualNum<Primitive = f64> + Copy>(m: &Matrix3<D>) -> Matrix3<D> {
    let mut t = *m;
    for (i, row) in m.iter().enumerate() {
        for (j, &x) in row.iter().enumerate() {
            t[j][i] = x;
        }
    }
    t
}

/// m v.
pub fn apply<D: DualNum<Primitive = f64> + Copy>(m: &Matrix3<D>, v: &[D; 3]) -> [D; 3] {
    let row = |i: usize| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    [row(0), row(1), row(2)]
}

/// mᵀ v.
pub fn apply_transpose<D: DualNum<Primitive = f64> + Copy>(m: &Matrix3<D>, v: &[D; 3]) -> [D; 3] {
    let column = |j: usize| m[0][j] * v[0] + m[1][j] * v[1] + m[2][j] * v[2];
    [column(0), column(1), column(2)]
}

/// [f(0), f(1), f(2)], written out: `[0, 1, 2].map` is not always inlined in a step's inner loops.
#[inline(always)]
pub(crate) fn vector(f: impl Fn(usize) -> f64) -> [f64; 3] {
    [f(0), f(1), f(2)]
}

/// The matrix with the entries f(i, j), written out as [`vector`].
#[inline(always)]
pub(crate) fn matrix(f: impl Fn(usize, usize) -> f64) -> Matrix3<f64> {
    [vector(|j| f(0, j)), vector(|j| f(1, j)), vector(|j| f(2, j))]
}

/// a × b.
pub fn cross<D: DualNum<Primitive = f64> + Copy>(a: &[D; 3], b: &[D; 3]) -> [D; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// ⟨a, b⟩.
pub fn dot<D: DualNum<Primitive = f64> + Copy>(a: &[D; 3], b: &[D; 3]) -> D {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// cay(ζ) = I + 4/(4 + |ζ|²) (ζ̂ + ζ̂²/2).
///
/// ```
/// use ddirac::rigid::so3::{cayley, cayley_inverse};
/// let f = cayley(&[0.3f64, -0.2, 0.5]);
/// let z = cayley_inverse(&f);
/// assert!((z[0] - 0.3).abs() < 1e-15 && (z[1] + 0.2).abs() < 1e-15 && (z[2] - 0.5).abs() < 1e-15);
/// ```
pub fn cayley<D: DualNum<Primitive = f64> + Copy>(z: &[D; 3]) -> Matrix3<D> {
    let c = D::from(4.0) / (D::from(4.0) + dot(z, z));
    let k = hat(z);
    let k2 = mul(&k, &k);
    let mut f = identity::<D>();
    for i in 0..3 {
        for j in 0..3 {
            f[i][j] += c * (k[i][j] + k2[i][j] * 0.5);
        }
    }
    f
}

/// cay⁻¹(F) = 2/(1 + tr F) · vee(F − Fᵀ) for a rotation F by less than π.
pub fn cayley_inverse(f: &Matrix3<f64>) -> [f64; 3] {
    let s = 4.0 / (1.0 + f[0][0] + f[1][1] + f[2][2]);
    vee_skew(f).map(|x| s * x)
}

/// dcay⁻¹_ζ = I − ζ̂/2 + ζ ζᵀ/4, the inverse of the right-trivialized derivative of the Cayley map.
///
/// ```
/// use ddirac::rigid::so3::{cayley, dcay_inverse, mul, transpose, vee_skew};
/// // δF F⁻¹ = (dcay_ζ δζ)^, so dcay⁻¹_ζ · vee(δF F⁻¹) gives δζ back.
/// let (z, dz, e) = ([0.4, -0.7, 0.2], [0.1, 0.3, -0.2], 1e-6);
/// let plus = cayley(&[0, 1, 2].map(|i| z[i] + e * dz[i]));
/// let minus = cayley(&[0, 1, 2].map(|i| z[i] - e * dz[i]));
/// let mut d = [[0.0; 3]; 3];
/// for i in 0..3 { for j in 0..3 { d[i][j] = (plus[i][j] - minus[i][j]) / (2.0 * e); } }
/// let w = vee_skew(&mul(&d, &transpose(&cayley(&z))));
/// let b = dcay_inverse(&z);
/// for i in 0..3 {
///     let back: f64 = (0..3).map(|j| b[i][j] * w[j]).sum();
///     assert!((back - dz[i]).abs() < 1e-9);
/// }
/// ```
pub fn dcay_inverse<D: DualNum<Primitive = f64> + Copy>(z: &[D; 3]) -> Matrix3<D> {
    let k = hat(z);
    let mut b = identity::<D>();
    for i in 0..3 {
        for j in 0..3 {
            b[i][j] += k[i][j] * (-0.5) + z[i] * z[j] * 0.25;
        }
    }
    b
}

/// The Lie algebra element of the rotation by half of cay(ζ) about the same axis:
/// ζ / (1 + √(1 + |ζ|²/4)), so that cay(half(ζ))² = cay(ζ).
pub fn half<D: DualNum<Primitive = f64> + Copy>(z: &[D; 3]) -> [D; 3] {
    let s = D::one() / (D::one() + (D::one() + dot(z, z) * 0.25).sqrt());
    [z[0] * s, z[1] * s, z[2] * s]
}

/// The largest entry of |RᵀR − I|: how far R is from orthogonal.
pub fn orthogonality_error(r: &Matrix3<f64>) -> f64 {
    let rtr = mul(&transpose(r), r);
    let mut worst = 0.0f64;
    for (i, row) in rtr.iter().enumerate() {
        for (j, &x) in row.iter().enumerate() {
            let target = if i == j { 1.0 } else { 0.0 };
            worst = worst.max((x - target).abs());
        }
    }
    worst
}

/// det R.
pub fn determinant(r: &Matrix3<f64>) -> f64 {
    dot(&r[0], &cross(&r[1], &r[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &Matrix3<f64>, b: &Matrix3<f64>, tol: f64) -> bool {
        (0..3).all(|i| (0..3).all(|j| (a[i][j] - b[i][j]).abs() <= tol))
    }

    /// The closed form against the definition (I − ζ̂/2)⁻¹ (I + ζ̂/2), inverted by nalgebra.
    #[test]
    fn the_closed_form_is_the_cayley_transform() {
        for z in [[0.3, -0.2, 0.5], [2.0, 1.0, -3.0], [1e-9, 0.0, 0.0]] {
            let k = nalgebra::Matrix3::new(0.0, -z[2], z[1], z[2], 0.0, -z[0], -z[1], z[0], 0.0);
            let i = nalgebra::Matrix3::identity();
            let f = (i - k * 0.5).try_inverse().unwrap() * (i + k * 0.5);
            let expected = [0, 1, 2].map(|r| [0, 1, 2].map(|c| f[(r, c)]));
            assert!(close(&cayley(&z), &expected, 1e-15), "{z:?}");
            assert!(orthogonality_error(&cayley(&z)) < 1e-15);
            assert!((determinant(&cayley(&z)) - 1.0).abs() < 1e-15);
        }
    }

    /// cay(−ζ) = cay(ζ)ᵀ (symmetry), cay(half(ζ))² = cay(ζ), and the rotation angle is 2 arctan(|ζ|/2).
    #[test]
    fn symmetric_with_an_exact_half() {
        let z = [0.8, -1.1, 0.4];
        let f = cayley(&z);
        assert!(close(&cayley(&z.map(|x: f64| -x)), &transpose(&f), 1e-15));
        let h = cayley(&half(&z));
        assert!(close(&mul(&h, &h), &f, 2e-15));
        let angle = ((f[0][0] + f[1][1] + f[2][2] - 1.0) / 2.0).acos();
        let norm = dot(&z, &z).sqrt();
        assert!((angle - 2.0 * (norm / 2.0).atan()).abs() < 1e-14);
    }

    #[test]
    fn a_reflection_is_not_a_rotation() {
        let r = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]];
        assert_eq!(orthogonality_error(&r), 0.0);
        assert_eq!(determinant(&r), -1.0);
    }
}
