//! Hyper-dual numbers in two blocks of directions: f, ∂f/∂a, ∂f/∂b and ∂²f/∂a∂b.
//!
//! With ε_a² = ε_b² = 0 and ε_a ε_b kept, (x + x_a ε_a + x_b ε_b + x_ab ε_a ε_b)(y + …) carries the
//! product rule for the mixed term: (xy)_ab = x_ab y + x_a ⊗ y_b + y_a ⊗ x_b + x y_ab, and a function
//! f(x) gives f(x)_ab = f′(x) x_ab + f″(x) x_a ⊗ x_b.

use super::jet::dual_number;

/// A value with its derivatives along block a (A directions), block b (B directions) and the mixed
/// second derivatives between them.
///
/// ```
/// use ddirac::ad::Mixed;
/// let (a, b) = Mixed::<1, 1>::seed(&[3.0], &[2.0], 0);
/// let f = a[0] * a[0] * b[0];
/// assert_eq!((f.re, f.a[0], f.b[0], f.ab[0][0]), (18.0, 12.0, 9.0, 6.0));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Mixed<const A: usize, const B: usize> {
    /// f.
    pub re: f64,
    /// ∂f/∂a.
    pub a: [f64; A],
    /// ∂f/∂b.
    pub b: [f64; B],
    /// ∂²f/∂a_i∂b_j at `ab[i][j]`.
    pub ab: [[f64; B]; A],
}

impl<const A: usize, const B: usize> Mixed<A, B> {
    /// A constant.
    #[inline(always)]
    pub fn constant(re: f64) -> Self {
        Self { re, a: [0.0; A], b: [0.0; B], ab: [[0.0; B]; A] }
    }

    /// The independent variables: every entry of `a` along its own a-direction, and the entries
    /// `first_column .. first_column + B` of `b` along the b-directions (the others constant).
    pub fn seed<const N: usize>(a: &[f64; A], b: &[f64; N], first_column: usize) -> ([Self; A], [Self; N]) {
        let mut x = [Self::constant(0.0); A];
        for (i, v) in x.iter_mut().enumerate() {
            v.re = a[i];
            v.a[i] = 1.0;
        }
        let mut y = [Self::constant(0.0); N];
        for (j, v) in y.iter_mut().enumerate() {
            v.re = b[j];
            if let Some(c) = j.checked_sub(first_column).filter(|&c| c < B) {
                v.b[c] = 1.0;
            }
        }
        (x, y)
    }

    /// self + s · o.
    #[inline(always)]
    fn sum(&self, o: &Self, s: f64) -> Self {
        let mut r = *self;
        r.re += s * o.re;
        for i in 0..A {
            r.a[i] += s * o.a[i];
            for j in 0..B {
                r.ab[i][j] += s * o.ab[i][j];
            }
        }
        for j in 0..B {
            r.b[j] += s * o.b[j];
        }
        r
    }

    #[inline(always)]
    fn scaled(&self, s: f64) -> Self {
        self.chain(s * self.re, s, 0.0)
    }

    #[inline(always)]
    fn product(&self, o: &Self) -> Self {
        let mut r = *self;
        r.re = self.re * o.re;
        for i in 0..A {
            r.a[i] = self.a[i] * o.re + self.re * o.a[i];
            for j in 0..B {
                r.ab[i][j] = self.ab[i][j] * o.re + self.re * o.ab[i][j] + self.a[i] * o.b[j] + o.a[i] * self.b[j];
            }
        }
        for j in 0..B {
            r.b[j] = self.b[j] * o.re + self.re * o.b[j];
        }
        r
    }

    /// f(self) from f, f′ and f″ at the value.
    #[inline(always)]
    fn chain(&self, f0: f64, f1: f64, f2: f64) -> Self {
        let mut r = *self;
        r.re = f0;
        for i in 0..A {
            r.a[i] = f1 * self.a[i];
            let ai = f2 * self.a[i];
            for j in 0..B {
                r.ab[i][j] = f1 * self.ab[i][j] + ai * self.b[j];
            }
        }
        for j in 0..B {
            r.b[j] = f1 * self.b[j];
        }
        r
    }
}

dual_number!(Mixed, 2);
