//! Derivatives of a function of two blocks of n arguments by dual numbers ([`crate::ad`]), as each
//! dimension takes them: for [`Fixed`] dimensions in one pass (in column chunks above
//! [`CROSSOVER`]), for [`Dynamic`](super::Dynamic) ones in blocks of [`BLOCK`](super::BLOCK)
//! arguments ([`super::blocks`]).

use super::{Dim, Fixed};
use crate::ad::{Gradient, Mixed};
use crate::Scalar;
use nalgebra::{SMatrix, SVector};

/// Above this many coordinates the mixed block is computed in column chunks.
pub const CROSSOVER: usize = 12;
/// Columns of the mixed block per pass above [`CROSSOVER`].
pub const CHUNK: usize = 4;

/// A scalar function f(a, b) of two blocks of n arguments, generic over the scalar type.
pub trait PairFunction<Dm: Dim> {
    /// f(a, b).
    fn eval<D: Scalar>(&self, a: &Dm::Array<D>, b: &Dm::Array<D>) -> D;
}

/// f with its first derivatives and the mixed block at one point.
#[derive(Debug, Clone, PartialEq)]
pub struct MixedDerivatives<Dm: Dim> {
    /// f(a, b).
    pub value: f64,
    /// ∂f/∂a.
    pub da: Dm::Vector,
    /// ∂f/∂b.
    pub db: Dm::Vector,
    /// ∂²f/∂a_i∂b_j at (i, j).
    pub dadb: Dm::Matrix,
}

impl<const N: usize> Copy for MixedDerivatives<Fixed<N>> {}

/// f with its first derivatives at one point.
#[derive(Debug, Clone, PartialEq)]
pub struct FirstDerivatives<Dm: Dim> {
    /// f(a, b).
    pub value: f64,
    /// ∂f/∂a.
    pub da: Dm::Vector,
    /// ∂f/∂b.
    pub db: Dm::Vector,
}

impl<const N: usize> Copy for FirstDerivatives<Fixed<N>> {}

/// Value, ∂f/∂a, ∂f/∂b and ∂²f/∂a∂b at (a, b): for [`Fixed`] dimensions in one pass up to
/// [`CROSSOVER`] arguments and in column chunks above ([`mixed_single_pass`], [`mixed_chunked`]);
/// for [`Dynamic`](crate::dim::Dynamic) ones in blocks of [`BLOCK`](super::BLOCK) × [`BLOCK`](super::BLOCK) entries ([`mixed_blocks`](super::mixed_blocks)). Each entry is
/// the same arithmetic in every case, so all give the same numbers.
///
/// ```
/// use ddirac::dim::{mixed, PairFunction};
/// use ddirac::dim::{Dim, Fixed};
/// use num_dual::DualNum;
/// struct F;
/// impl PairFunction<Fixed<2>> for F {
///     fn eval<D: DualNum<Primitive = f64> + Copy>(&self, a: &[D; 2], b: &[D; 2]) -> D {
///         a[0] * b[1].sin() + a[1] * a[1] * b[0]
///     }
/// }
/// let d = mixed(Fixed, &F, &[1.0, 2.0], &[3.0, 0.5]);
/// assert!((d.value - (0.5f64.sin() + 12.0)).abs() < 1e-15);
/// assert!((d.dadb[(0, 1)] - 0.5f64.cos()).abs() < 1e-15);
/// assert_eq!(d.dadb[(1, 0)], 4.0);
/// ```
pub fn mixed<Dm: Dim, F: PairFunction<Dm>>(
    dim: Dm,
    f: &F,
    a: &Dm::Array<f64>,
    b: &Dm::Array<f64>,
) -> MixedDerivatives<Dm> {
    dim.mixed(f, a, b)
}

/// Value, ∂f/∂a and ∂f/∂b at (a, b): for [`Fixed`] dimensions in one pass, for [`Dynamic`](crate::dim::Dynamic) ones in
/// blocks of [`BLOCK`](super::BLOCK) arguments of each ([`first_blocks`](super::first_blocks)).
///
/// ```
/// use ddirac::dim::{first, PairFunction};
/// use ddirac::dim::{Dim, Fixed};
/// use num_dual::DualNum;
/// struct F;
/// impl PairFunction<Fixed<1>> for F {
///     fn eval<D: DualNum<Primitive = f64> + Copy>(&self, a: &[D; 1], b: &[D; 1]) -> D {
///         a[0] * a[0] * b[0].exp()
///     }
/// }
/// let d = first(Fixed, &F, &[3.0], &[0.0]);
/// assert_eq!((d.value, d.da[0], d.db[0]), (9.0, 6.0, 9.0));
/// ```
pub fn first<Dm: Dim, F: PairFunction<Dm>>(
    dim: Dm,
    f: &F,
    a: &Dm::Array<f64>,
    b: &Dm::Array<f64>,
) -> FirstDerivatives<Dm> {
    dim.first(f, a, b)
}

/// [`first`], or with `with_mixed` one pass of [`mixed`] and its mixed block: what a Newton
/// iterate needs with or without a fresh Jacobian.
pub fn first_or_mixed<Dm: Dim, F: PairFunction<Dm>>(
    dim: Dm,
    f: &F,
    a: &Dm::Array<f64>,
    b: &Dm::Array<f64>,
    with_mixed: bool,
) -> (FirstDerivatives<Dm>, Option<Dm::Matrix>) {
    if with_mixed {
        let d = mixed(dim, f, a, b);
        (FirstDerivatives { value: d.value, da: d.da, db: d.db }, Some(d.dadb))
    } else {
        (first(dim, f, a, b), None)
    }
}

/// [`first`] for a [`Fixed`] dimension: one pass.
pub fn first_single_pass<F: PairFunction<Fixed<N>>, const N: usize>(
    f: &F,
    a: &[f64; N],
    b: &[f64; N],
) -> FirstDerivatives<Fixed<N>> {
    let (x, y) = Gradient::<N, N>::seed(a, b);
    let r = f.eval::<Gradient<N, N>>(&x, &y);
    FirstDerivatives { value: r.re, da: SVector::from(r.a), db: SVector::from(r.b) }
}

/// [`mixed`] in one pass with all n × n mixed entries (what [`mixed`] does up to [`CROSSOVER`]).
#[inline(never)]
pub fn mixed_single_pass<F: PairFunction<Fixed<N>>, const N: usize>(
    f: &F,
    a: &[f64; N],
    b: &[f64; N],
) -> MixedDerivatives<Fixed<N>> {
    let (x, y) = Mixed::<N, N>::seed(a, b, 0);
    let r = f.eval::<Mixed<N, N>>(&x, &y);
    MixedDerivatives {
        value: r.re,
        da: SVector::from(r.a),
        db: SVector::from(r.b),
        dadb: SMatrix::from_fn(|i, j| r.ab[i][j]),
    }
}

/// [`mixed`] in ⌈n / CHUNK⌉ passes, each with the mixed entries of CHUNK columns (what [`mixed`]
/// does above [`CROSSOVER`]).
#[inline(never)]
pub fn mixed_chunked<F: PairFunction<Fixed<N>>, const N: usize>(
    f: &F,
    a: &[f64; N],
    b: &[f64; N],
) -> MixedDerivatives<Fixed<N>> {
    let mut out: MixedDerivatives<Fixed<N>> =
        MixedDerivatives { value: 0.0, da: SVector::zeros(), db: SVector::zeros(), dadb: SMatrix::zeros() };
    for start in (0..N).step_by(CHUNK) {
        let (x, y) = Mixed::<N, CHUNK>::seed(a, b, start);
        let r = f.eval::<Mixed<N, CHUNK>>(&x, &y);
        if start == 0 {
            out.value = r.re;
            out.da = SVector::from(r.a);
        }
        for c in 0..CHUNK.min(N - start) {
            out.db[start + c] = r.b[c];
            for i in 0..N {
                out.dadb[(i, start + c)] = r.ab[i][c];
            }
        }
    }
    out
}
