//! Derivatives in a dimension chosen at run time, by dual numbers of a fixed width.
//!
//! Dual numbers as wide as n would live on the heap and allocate at every operation. Instead, f is
//! evaluated once per pair of blocks of [`BLOCK`] arguments of a and of b, on [`Mixed<BLOCK, BLOCK>`]
//! numbers seeded along those blocks (the other arguments constant): each pass gives the value, the
//! entries of ∂f/∂a and ∂f/∂b of its blocks and a BLOCK × BLOCK tile of ∂²f/∂a∂b. The work is that of
//! one pass with n-wide numbers (⌈n/B⌉² passes of B² mixed entries each), and every entry comes from
//! the same arithmetic as in a single pass, so the numbers are the same.

use super::{Dim, Dynamic, FirstDerivatives, MixedDerivatives, PairFunction};
use crate::ad::{Gradient, Mixed};

/// Arguments of a and of b per pass.
pub const BLOCK: usize = 8;

/// The blocks' first arguments: 0, BLOCK, 2 BLOCK, … below n (one block for n = 0, so that f is
/// evaluated).
fn starts(n: usize) -> impl Iterator<Item = usize> + Clone {
    (0..n.max(1)).step_by(BLOCK)
}

/// `values` as constant dual numbers: the arguments of every pass, whose blocks [`Seeds::along`]
/// seeds in turn (one allocation per call, not one per pass).
struct Seeds<T> {
    values: Vec<T>,
}

impl<T> Seeds<T> {
    fn new(values: &[f64], constant: impl Fn(f64) -> T) -> Self {
        Self { values: values.iter().map(|&v| constant(v)).collect() }
    }

    /// The values with those of `start .. start + BLOCK` along the directions `seed` sets to 1, for
    /// `pass`; the seeds are taken back to 0 after it (every pass sees constants elsewhere).
    fn along<R>(
        &mut self,
        start: usize,
        seed: impl Fn(&mut T, usize) -> &mut f64,
        pass: impl FnOnce(&Vec<T>) -> R,
    ) -> R {
        let end = (start + BLOCK).min(self.values.len());
        for j in start..end {
            *seed(&mut self.values[j], j - start) = 1.0;
        }
        let r = pass(&self.values);
        for j in start..end {
            *seed(&mut self.values[j], j - start) = 0.0;
        }
        r
    }
}

/// [`super::mixed`] in a [`Dynamic`] dimension: ⌈n/BLOCK⌉² passes.
///
/// ```
/// use ddirac::dim::{mixed, PairFunction};
/// use ddirac::dim::{Dim, Dynamic};
/// use num_dual::DualNum;
/// /// f = Σ a_i b_{i+1} sin(b_i): entries of the mixed block in many blocks.
/// struct F;
/// impl PairFunction<Dynamic> for F {
///     fn eval<D: DualNum<Primitive = f64> + Copy>(&self, a: &Vec<D>, b: &Vec<D>) -> D {
///         (0..a.len() - 1).fold(D::from(0.0), |s, i| s + a[i] * b[i + 1] * b[i].sin())
///     }
/// }
/// let n = 20;
/// let (a, b): (Vec<f64>, Vec<f64>) = ((0..n).map(|i| i as f64).collect(), vec![0.5; n]);
/// let d = mixed(Dynamic(n), &F, &a, &b);
/// assert_eq!(d.dadb[(17, 18)], 0.5f64.sin());
/// assert_eq!(d.dadb[(17, 17)], 0.5 * 0.5f64.cos());
/// assert!((d.db[18] - (17.0 * 0.5f64.sin() + 18.0 * 0.5 * 0.5f64.cos())).abs() < 1e-14);
/// ```
pub fn mixed_blocks<F: PairFunction<Dynamic>>(dim: Dynamic, f: &F, a: &[f64], b: &[f64]) -> MixedDerivatives<Dynamic> {
    let n = dim.n();
    let mut out: MixedDerivatives<Dynamic> =
        MixedDerivatives { value: 0.0, da: dim.zeros(), db: dim.zeros(), dadb: dim.matrix(|_, _| 0.0) };
    type M = Mixed<BLOCK, BLOCK>;
    let (mut x, mut y) = (Seeds::new(a, M::constant), Seeds::new(b, M::constant));
    for row in starts(n) {
        for column in starts(n) {
            let r = x.along(row, |x, c| &mut x.a[c], |x| y.along(column, |y, c| &mut y.b[c], |y| f.eval::<M>(x, y)));
            let (rows, columns) = (BLOCK.min(n - row.min(n)), BLOCK.min(n - column.min(n)));
            if column == 0 {
                out.value = r.re;
                for i in 0..rows {
                    out.da[row + i] = r.a[i];
                }
            }
            if row == 0 {
                for j in 0..columns {
                    out.db[column + j] = r.b[j];
                }
            }
            for i in 0..rows {
                for j in 0..columns {
                    out.dadb[(row + i, column + j)] = r.ab[i][j];
                }
            }
        }
    }
    out
}

/// [`super::first`] in a [`Dynamic`] dimension: ⌈n/BLOCK⌉ passes, each along a block of a and the
/// same block of b.
pub fn first_blocks<F: PairFunction<Dynamic>>(dim: Dynamic, f: &F, a: &[f64], b: &[f64]) -> FirstDerivatives<Dynamic> {
    let n = dim.n();
    let mut out: FirstDerivatives<Dynamic> = FirstDerivatives { value: 0.0, da: dim.zeros(), db: dim.zeros() };
    type G = Gradient<BLOCK, BLOCK>;
    let (mut x, mut y) = (Seeds::new(a, G::constant), Seeds::new(b, G::constant));
    for start in starts(n) {
        let r = x.along(start, |x, c| &mut x.a[c], |x| y.along(start, |y, c| &mut y.b[c], |y| f.eval::<G>(x, y)));
        if start == 0 {
            out.value = r.re;
        }
        for i in 0..BLOCK.min(n - start.min(n)) {
            out.da[start + i] = r.a[i];
            out.db[start + i] = r.b[i];
        }
    }
    out
}
