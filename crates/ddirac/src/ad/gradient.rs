//! First-order dual numbers in two blocks of directions: f, ∂f/∂a, ∂f/∂b.

use super::jet::dual_number;

/// A value with its derivatives along A directions of block a and B directions of block b.
///
/// ```
/// use ddirac::ad::Gradient;
/// use num_dual::DualNum;
/// let (a, b) = Gradient::<1, 1>::seed(&[2.0], &[0.0]);
/// let f = a[0] * a[0] * b[0].cos();
/// assert_eq!((f.re, f.a[0], f.b[0]), (4.0, 4.0, 0.0));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Gradient<const A: usize, const B: usize> {
    /// f.
    pub re: f64,
    /// ∂f/∂a.
    pub a: [f64; A],
    /// ∂f/∂b.
    pub b: [f64; B],
}

impl<const A: usize, const B: usize> Gradient<A, B> {
    /// A constant.
    #[inline(always)]
    pub fn constant(re: f64) -> Self {
        Self { re, a: [0.0; A], b: [0.0; B] }
    }

    /// The independent variables a and b at the given values.
    pub fn seed(a: &[f64; A], b: &[f64; B]) -> ([Self; A], [Self; B]) {
        let mut x = [Self::constant(0.0); A];
        for (i, v) in x.iter_mut().enumerate() {
            v.re = a[i];
            v.a[i] = 1.0;
        }
        let mut y = [Self::constant(0.0); B];
        for (j, v) in y.iter_mut().enumerate() {
            v.re = b[j];
            v.b[j] = 1.0;
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
        }
        for j in 0..B {
            r.b[j] = self.b[j] * o.re + self.re * o.b[j];
        }
        r
    }

    /// f(self) from f, f′ (f″ is not needed at first order).
    #[inline(always)]
    fn chain(&self, f0: f64, f1: f64, _f2: f64) -> Self {
        let mut r = *self;
        r.re = f0;
        for i in 0..A {
            r.a[i] *= f1;
        }
        for j in 0..B {
            r.b[j] *= f1;
        }
        r
    }
}

dual_number!(Gradient, 1);
