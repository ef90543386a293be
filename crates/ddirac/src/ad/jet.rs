//! The arithmetic and elementary functions shared by [`super::Gradient`] and [`super::Mixed`].
//!
//! A type provides five primitives — `constant`, `sum`, `scaled`, `product` and the chain rule
//! `chain(f(x), f'(x), f''(x))` — and [`dual_number!`] derives from them every operator and the
//! functions num-dual's [`num_dual::DualNum`] asks for. Formulas for f', f'' are the textbook ones.

/// Implements operators, num-traits and `DualNum` for `$t<A, B>` from its primitives.
macro_rules! dual_number {
    ($t:ident, $nderiv:expr) => {
        impl<const A: usize, const B: usize> std::ops::Add for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn add(self, o: Self) -> Self {
                self.sum(&o, 1.0)
            }
        }
        impl<const A: usize, const B: usize> std::ops::Sub for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn sub(self, o: Self) -> Self {
                self.sum(&o, -1.0)
            }
        }
        impl<const A: usize, const B: usize> std::ops::Mul for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn mul(self, o: Self) -> Self {
                self.product(&o)
            }
        }
        impl<const A: usize, const B: usize> std::ops::Div for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn div(self, o: Self) -> Self {
                self.product(&num_dual::DualNum::recip(&o))
            }
        }
        impl<const A: usize, const B: usize> std::ops::Rem for $t<A, B> {
            type Output = Self;
            /// x − y · trunc(x / y), the truncation held constant.
            #[inline(always)]
            fn rem(self, o: Self) -> Self {
                self.sum(&o, -(self.re / o.re).trunc())
            }
        }
        impl<const A: usize, const B: usize> std::ops::Neg for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                self.scaled(-1.0)
            }
        }
        impl<'r, const A: usize, const B: usize> std::ops::Add<&'r $t<A, B>> for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn add(self, o: &Self) -> Self {
                self + *o
            }
        }
        impl<'r, const A: usize, const B: usize> std::ops::Sub<&'r $t<A, B>> for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn sub(self, o: &Self) -> Self {
                self - *o
            }
        }
        impl<'r, const A: usize, const B: usize> std::ops::Mul<&'r $t<A, B>> for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn mul(self, o: &Self) -> Self {
                self * *o
            }
        }
        impl<'r, const A: usize, const B: usize> std::ops::Div<&'r $t<A, B>> for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn div(self, o: &Self) -> Self {
                self / *o
            }
        }
        impl<'r, const A: usize, const B: usize> std::ops::Rem<&'r $t<A, B>> for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn rem(self, o: &Self) -> Self {
                self % *o
            }
        }
        impl<const A: usize, const B: usize> std::ops::Add<f64> for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn add(mut self, c: f64) -> Self {
                self.re += c;
                self
            }
        }
        impl<const A: usize, const B: usize> std::ops::Sub<f64> for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn sub(mut self, c: f64) -> Self {
                self.re -= c;
                self
            }
        }
        impl<const A: usize, const B: usize> std::ops::Mul<f64> for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn mul(self, c: f64) -> Self {
                self.scaled(c)
            }
        }
        impl<const A: usize, const B: usize> std::ops::Div<f64> for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn div(self, c: f64) -> Self {
                self.scaled(c.recip())
            }
        }
        impl<const A: usize, const B: usize> std::ops::Rem<f64> for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn rem(mut self, c: f64) -> Self {
                self.re %= c;
                self
            }
        }
        impl<const A: usize, const B: usize> std::ops::AddAssign for $t<A, B> {
            #[inline(always)]
            fn add_assign(&mut self, o: Self) {
                *self = *self + o;
            }
        }
        impl<const A: usize, const B: usize> std::ops::SubAssign for $t<A, B> {
            #[inline(always)]
            fn sub_assign(&mut self, o: Self) {
                *self = *self - o;
            }
        }
        impl<const A: usize, const B: usize> std::ops::MulAssign for $t<A, B> {
            #[inline(always)]
            fn mul_assign(&mut self, o: Self) {
                *self = *self * o;
            }
        }
        impl<const A: usize, const B: usize> std::ops::DivAssign for $t<A, B> {
            #[inline(always)]
            fn div_assign(&mut self, o: Self) {
                *self = *self / o;
            }
        }
        impl<const A: usize, const B: usize> std::ops::RemAssign for $t<A, B> {
            #[inline(always)]
            fn rem_assign(&mut self, o: Self) {
                *self = *self % o;
            }
        }
        impl<const A: usize, const B: usize> std::ops::AddAssign<f64> for $t<A, B> {
            #[inline(always)]
            fn add_assign(&mut self, c: f64) {
                *self = *self + c;
            }
        }
        impl<const A: usize, const B: usize> std::ops::SubAssign<f64> for $t<A, B> {
            #[inline(always)]
            fn sub_assign(&mut self, c: f64) {
                *self = *self - c;
            }
        }
        impl<const A: usize, const B: usize> std::ops::MulAssign<f64> for $t<A, B> {
            #[inline(always)]
            fn mul_assign(&mut self, c: f64) {
                *self = *self * c;
            }
        }
        impl<const A: usize, const B: usize> std::ops::DivAssign<f64> for $t<A, B> {
            #[inline(always)]
            fn div_assign(&mut self, c: f64) {
                *self = *self / c;
            }
        }
        impl<const A: usize, const B: usize> std::ops::RemAssign<f64> for $t<A, B> {
            #[inline(always)]
            fn rem_assign(&mut self, c: f64) {
                *self = *self % c;
            }
        }
        impl<const A: usize, const B: usize> num_traits::Inv for $t<A, B> {
            type Output = Self;
            #[inline(always)]
            fn inv(self) -> Self {
                num_dual::DualNum::recip(&self)
            }
        }
        impl<const A: usize, const B: usize> std::iter::Sum for $t<A, B> {
            fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
                iter.fold(Self::constant(0.0), |s, x| s + x)
            }
        }
        impl<const A: usize, const B: usize> std::iter::Product for $t<A, B> {
            fn product<I: Iterator<Item = Self>>(iter: I) -> Self {
                iter.fold(Self::constant(1.0), |s, x| s * x)
            }
        }
        impl<const A: usize, const B: usize> From<f64> for $t<A, B> {
            #[inline(always)]
            fn from(re: f64) -> Self {
                Self::constant(re)
            }
        }
        impl<const A: usize, const B: usize> num_traits::FromPrimitive for $t<A, B> {
            fn from_i64(n: i64) -> Option<Self> {
                Some(Self::constant(n as f64))
            }
            fn from_u64(n: u64) -> Option<Self> {
                Some(Self::constant(n as f64))
            }
            fn from_f64(x: f64) -> Option<Self> {
                Some(Self::constant(x))
            }
        }
        impl<const A: usize, const B: usize> num_traits::Zero for $t<A, B> {
            fn zero() -> Self {
                Self::constant(0.0)
            }
            fn is_zero(&self) -> bool {
                self.re == 0.0
            }
        }
        impl<const A: usize, const B: usize> num_traits::One for $t<A, B> {
            fn one() -> Self {
                Self::constant(1.0)
            }
        }
        impl<const A: usize, const B: usize> num_traits::Num for $t<A, B> {
            type FromStrRadixErr = <f64 as num_traits::Num>::FromStrRadixErr;
            fn from_str_radix(s: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
                <f64 as num_traits::Num>::from_str_radix(s, radix).map(Self::constant)
            }
        }
        impl<const A: usize, const B: usize> num_traits::Signed for $t<A, B> {
            fn abs(&self) -> Self {
                if self.re < 0.0 {
                    -*self
                } else {
                    *self
                }
            }
            fn abs_sub(&self, o: &Self) -> Self {
                if self.re > o.re {
                    *self - *o
                } else {
                    Self::constant(0.0)
                }
            }
            fn signum(&self) -> Self {
                Self::constant(if self.re == 0.0 { 0.0 } else { self.re.signum() })
            }
            fn is_positive(&self) -> bool {
                self.re > 0.0
            }
            fn is_negative(&self) -> bool {
                self.re < 0.0
            }
        }
        /// Comparisons look at the value only, so code branches as it would on f64.
        impl<const A: usize, const B: usize> PartialEq for $t<A, B> {
            fn eq(&self, o: &Self) -> bool {
                self.re == o.re
            }
        }
        impl<const A: usize, const B: usize> PartialEq<f64> for $t<A, B> {
            fn eq(&self, o: &f64) -> bool {
                self.re == *o
            }
        }
        impl<const A: usize, const B: usize> PartialOrd for $t<A, B> {
            fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
                self.re.partial_cmp(&o.re)
            }
        }
        impl<const A: usize, const B: usize> PartialOrd<f64> for $t<A, B> {
            fn partial_cmp(&self, o: &f64) -> Option<std::cmp::Ordering> {
                self.re.partial_cmp(o)
            }
        }
        impl<const A: usize, const B: usize> std::fmt::Display for $t<A, B> {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                write!(f, "{} + {:?}εa + {:?}εb", self.re, self.a, self.b)
            }
        }
        impl<const A: usize, const B: usize> num_dual::DualStruct for $t<A, B> {
            type Real = f64;
            type Inner = f64;
            fn re(&self) -> f64 {
                self.re
            }
            fn from_inner(inner: &f64) -> Self {
                Self::constant(*inner)
            }
        }
        impl<const A: usize, const B: usize> num_dual::Mappable<Self> for $t<A, B> {
            type Output<O> = O;
            fn map_dual<G: Fn(Self) -> O, O>(self, g: G) -> O {
                g(self)
            }
        }
        impl<const A: usize, const B: usize> crate::Scalar for $t<A, B> {}
        impl<const A: usize, const B: usize> num_dual::DualNum for $t<A, B> {
            type Primitive = f64;
            const NDERIV: usize = $nderiv;
            type InnerDual = f64;

            fn from_re(re: f64) -> Self {
                Self::constant(re)
            }
            #[inline(always)]
            fn scale(self, factor: &f64) -> Self {
                self.scaled(*factor)
            }
            #[inline(always)]
            fn recip(&self) -> Self {
                let r = self.re.recip();
                self.chain(r, -r * r, 2.0 * r * r * r)
            }
            #[inline(always)]
            fn powi(&self, n: i32) -> Self {
                match n {
                    0 => Self::constant(1.0),
                    1 => *self,
                    2 => self.product(self),
                    _ if n.unsigned_abs() > 1024 => self.powf(n as f64),
                    _ => {
                        let x = self.re;
                        let p = x.powi(n - 2);
                        let nf = n as f64;
                        self.chain(p * x * x, nf * p * x, nf * (nf - 1.0) * p)
                    }
                }
            }
            #[inline(always)]
            fn powf(&self, n: f64) -> Self {
                if n == 0.0 {
                    Self::constant(1.0)
                } else if n == 1.0 {
                    *self
                } else if n == 2.0 {
                    self.product(self)
                } else {
                    let x = self.re;
                    let p = x.powf(n - 2.0);
                    self.chain(p * x * x, n * p * x, n * (n - 1.0) * p)
                }
            }
            #[inline(always)]
            fn sqrt(&self) -> Self {
                let s = self.re.sqrt();
                let d = 0.5 / s;
                self.chain(s, d, -0.5 * d / self.re)
            }
            #[inline(always)]
            fn cbrt(&self) -> Self {
                let c = self.re.cbrt();
                let d = c / (3.0 * self.re);
                self.chain(c, d, -2.0 * d / (3.0 * self.re))
            }
            #[inline(always)]
            fn exp(&self) -> Self {
                let e = self.re.exp();
                self.chain(e, e, e)
            }
            #[inline(always)]
            fn exp2(&self) -> Self {
                let e = self.re.exp2();
                let l = std::f64::consts::LN_2;
                self.chain(e, e * l, e * l * l)
            }
            #[inline(always)]
            fn exp_m1(&self) -> Self {
                let e = self.re.exp();
                self.chain(self.re.exp_m1(), e, e)
            }
            #[inline(always)]
            fn ln(&self) -> Self {
                let r = self.re.recip();
                self.chain(self.re.ln(), r, -r * r)
            }
            #[inline(always)]
            fn log(&self, base: f64) -> Self {
                let r = self.re.recip() / base.ln();
                self.chain(self.re.log(base), r, -r / self.re)
            }
            #[inline(always)]
            fn log2(&self) -> Self {
                self.log(2.0)
            }
            #[inline(always)]
            fn log10(&self) -> Self {
                self.log(10.0)
            }
            #[inline(always)]
            fn ln_1p(&self) -> Self {
                let r = (1.0 + self.re).recip();
                self.chain(self.re.ln_1p(), r, -r * r)
            }
            #[inline(always)]
            fn sin(&self) -> Self {
                let (s, c) = self.re.sin_cos();
                self.chain(s, c, -s)
            }
            #[inline(always)]
            fn cos(&self) -> Self {
                let (s, c) = self.re.sin_cos();
                self.chain(c, -s, -c)
            }
            #[inline(always)]
            fn sin_cos(&self) -> (Self, Self) {
                let (s, c) = self.re.sin_cos();
                (self.chain(s, c, -s), self.chain(c, -s, -c))
            }
            #[inline(always)]
            fn tan(&self) -> Self {
                let t = self.re.tan();
                let d = 1.0 + t * t;
                self.chain(t, d, 2.0 * t * d)
            }
            #[inline(always)]
            fn asin(&self) -> Self {
                let x = self.re;
                let r = (1.0 - x * x).recip();
                let d = r.sqrt();
                self.chain(x.asin(), d, x * d * r)
            }
            #[inline(always)]
            fn acos(&self) -> Self {
                let x = self.re;
                let r = (1.0 - x * x).recip();
                let d = -r.sqrt();
                self.chain(x.acos(), d, x * d * r)
            }
            #[inline(always)]
            fn atan(&self) -> Self {
                let x = self.re;
                let r = (1.0 + x * x).recip();
                self.chain(x.atan(), r, -2.0 * x * r * r)
            }
            #[inline(always)]
            fn atan2(&self, other: Self) -> Self {
                let mut res = (*self / other).atan();
                res.re = self.re.atan2(other.re);
                res
            }
            #[inline(always)]
            fn sinh(&self) -> Self {
                let (s, c) = (self.re.sinh(), self.re.cosh());
                self.chain(s, c, s)
            }
            #[inline(always)]
            fn cosh(&self) -> Self {
                let (s, c) = (self.re.sinh(), self.re.cosh());
                self.chain(c, s, c)
            }
            #[inline(always)]
            fn tanh(&self) -> Self {
                let t = self.re.tanh();
                let d = 1.0 - t * t;
                self.chain(t, d, -2.0 * t * d)
            }
            #[inline(always)]
            fn asinh(&self) -> Self {
                let x = self.re;
                let r = (1.0 + x * x).recip();
                let d = r.sqrt();
                self.chain(x.asinh(), d, -x * d * r)
            }
            #[inline(always)]
            fn acosh(&self) -> Self {
                let x = self.re;
                let r = (x * x - 1.0).recip();
                let d = r.sqrt();
                self.chain(x.acosh(), d, -x * d * r)
            }
            #[inline(always)]
            fn atanh(&self) -> Self {
                let x = self.re;
                let r = (1.0 - x * x).recip();
                self.chain(x.atanh(), r, 2.0 * x * r * r)
            }
            fn sph_j0(&self) -> Self {
                if self.re.abs() < f64::EPSILON {
                    Self::constant(1.0) - *self * *self / 6.0
                } else {
                    self.sin() / *self
                }
            }
            fn sph_j1(&self) -> Self {
                if self.re.abs() < f64::EPSILON {
                    *self / 3.0
                } else {
                    let (s, c) = self.sin_cos();
                    (s - *self * c) / (*self * *self)
                }
            }
            fn sph_j2(&self) -> Self {
                if self.re.abs() < f64::EPSILON {
                    *self * *self / 15.0
                } else {
                    let (s, c) = self.sin_cos();
                    let s2 = *self * *self;
                    ((s - *self * c) * 3.0 - s2 * s) / (s2 * *self)
                }
            }
        }
    };
}

pub(crate) use dual_number;
