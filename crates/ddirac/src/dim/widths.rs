//! Derivatives in a dimension chosen at run time by dual numbers exactly as wide as n, for n up to
//! [`WIDEST`]: one small kernel per width, the passes a [`Fixed`](super::Fixed) dimension of the same
//! n makes (one pass up to [`CROSSOVER`], column chunks of [`CHUNK`] above), so that both give the
//! same numbers at the same cost of arithmetic. Wider systems take blocks ([`super::blocks`]).
//!
//! Blocks of [`BLOCK`](super::BLOCK) arguments at every n cost a system of 4 coordinates four times
//! the mixed entries it needs (64 per pass instead of 16): the width is what a dimension chosen at
//! run time must not give away at small n, and the kernels are all that is instantiated per width.

use super::{Dim, Dynamic, FirstDerivatives, MixedDerivatives, PairFunction, CHUNK, CROSSOVER};
use crate::ad::{Gradient, Mixed};
use nalgebra::{DMatrix, DVector};

/// The widest dual numbers of a kernel of its own; n above this takes blocks.
pub const WIDEST: usize = 16;

/// `$body` with the constant `$w` = n for n in 1 ..= [`WIDEST`], else `$other`.
macro_rules! by_width {
    ($n:expr, $w:ident => $body:expr, _ => $other:expr) => {
        $crate::dim::widths::by_width!(@arms $n, $w, $body, $other; 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16)
    };
    (@arms $n:expr, $w:ident, $body:expr, $other:expr; $($width:literal)*) => {
        match $n {
            $($width => {
                const $w: usize = $width;
                $body
            })*
            _ => $other,
        }
    };
}
pub(super) use by_width;

/// The arguments as an array of W, when there are W of them.
fn exactly<const W: usize>(values: &[f64]) -> Option<&[f64; W]> {
    values.try_into().ok()
}

/// [`super::mixed`] in `Dynamic(W)`: W × W mixed entries in one pass up to [`CROSSOVER`], else
/// ⌈W / CHUNK⌉ passes of CHUNK columns. `None` if a or b does not hold W values.
pub(super) fn mixed_width<F: PairFunction<Dynamic>, const W: usize>(
    f: &F,
    a: &[f64],
    b: &[f64],
) -> Option<MixedDerivatives<Dynamic>> {
    let (a, b) = (exactly::<W>(a)?, exactly::<W>(b)?);
    if W <= CROSSOVER {
        let (x, y) = Mixed::<W, W>::seed(a, b, 0);
        let r = f.eval::<Mixed<W, W>>(&x.to_vec(), &y.to_vec());
        return Some(MixedDerivatives {
            value: r.re,
            da: DVector::from_vec(r.a.to_vec()),
            db: DVector::from_vec(r.b.to_vec()),
            dadb: Dynamic(W).matrix(|i, j| r.ab[i][j]),
        });
    }
    let (mut value, mut da) = (0.0, DVector::<f64>::zeros(W));
    let (mut db, mut dadb) = (DVector::<f64>::zeros(W), DMatrix::<f64>::zeros(W, W));
    for start in (0..W).step_by(CHUNK) {
        let (x, y) = Mixed::<W, CHUNK>::seed(a, b, start);
        let r: Mixed<W, CHUNK> = f.eval::<Mixed<W, CHUNK>>(&x.to_vec(), &y.to_vec());
        if start == 0 {
            value = r.re;
            da = DVector::from_vec(r.a.to_vec());
        }
        for c in 0..CHUNK.min(W - start) {
            db[start + c] = r.b[c];
            for i in 0..W {
                dadb[(i, start + c)] = r.ab[i][c];
            }
        }
    }
    Some(MixedDerivatives { value, da, db, dadb })
}

/// [`super::first`] in `Dynamic(W)`: one pass. `None` if a or b does not hold W values.
pub(super) fn first_width<F: PairFunction<Dynamic>, const W: usize>(
    f: &F,
    a: &[f64],
    b: &[f64],
) -> Option<FirstDerivatives<Dynamic>> {
    let (a, b) = (exactly::<W>(a)?, exactly::<W>(b)?);
    let (x, y) = Gradient::<W, W>::seed(a, b);
    let r = f.eval::<Gradient<W, W>>(&x.to_vec(), &y.to_vec());
    Some(FirstDerivatives { value: r.re, da: DVector::from_vec(r.a.to_vec()), db: DVector::from_vec(r.b.to_vec()) })
}
