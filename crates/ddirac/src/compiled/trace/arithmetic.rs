//! [`Traced`] as a scalar: its operators, the num-traits it needs and num-dual's [`DualNum`], each
//! operation recorded as one instruction of [`crate::compiled::program`] (or a few, for `log`).

use std::fmt;

use num_dual::DualNum;

use super::{record, Comparison, Traced, RECORDING};
use crate::compiled::program::{Binary, Unary};

/// Implements an operator for `Traced` with a `Traced`, `&Traced` or `f64` right-hand side, and its
/// assigning form.
macro_rules! operator {
    ($op:ident $method:ident $assign:ident $assign_method:ident, $traced:expr, $scalar:expr) => {
        impl std::ops::$op for Traced {
            type Output = Self;
            fn $method(self, o: Self) -> Self {
                ($traced)(self, o)
            }
        }
        impl std::ops::$op<&Traced> for Traced {
            type Output = Self;
            fn $method(self, o: &Self) -> Self {
                ($traced)(self, *o)
            }
        }
        impl std::ops::$op<f64> for Traced {
            type Output = Self;
            fn $method(self, c: f64) -> Self {
                ($scalar)(self, c)
            }
        }
        impl std::ops::$assign for Traced {
            fn $assign_method(&mut self, o: Self) {
                *self = ($traced)(*self, o);
            }
        }
        impl std::ops::$assign<f64> for Traced {
            fn $assign_method(&mut self, c: f64) {
                *self = ($scalar)(*self, c);
            }
        }
    };
}

/// x op c as x op (the constant c).
fn with_constant(op: Binary) -> impl Fn(Traced, f64) -> Traced {
    move |x, c| x.binary(op, Traced::constant(c))
}

operator!(Add add AddAssign add_assign, |x: Traced, y| x.binary(Binary::Add, y), with_constant(Binary::Add));
operator!(Sub sub SubAssign sub_assign, |x: Traced, y| x.binary(Binary::Sub, y), with_constant(Binary::Sub));
operator!(Mul mul MulAssign mul_assign, |x: Traced, y| x.binary(Binary::Mul, y), with_constant(Binary::Mul));
// x / c is x · (1/c), as the dual numbers of `crate::ad` compute it.
operator!(Div div DivAssign div_assign, |x: Traced, y| x.binary(Binary::Div, y), |x: Traced, c: f64| x
    .binary(Binary::Mul, Traced::constant(c.recip())));
operator!(Rem rem RemAssign rem_assign, Traced::remainder, |x: Traced, c| x.remainder(Traced::constant(c)));

impl std::ops::Neg for Traced {
    type Output = Self;
    fn neg(self) -> Self {
        self.unary(Unary::Neg)
    }
}

impl num_traits::Inv for Traced {
    type Output = Self;
    fn inv(self) -> Self {
        self.unary(Unary::Recip)
    }
}

impl std::iter::Sum for Traced {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::constant(0.0), |s, x| s + x)
    }
}

impl std::iter::Product for Traced {
    fn product<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::constant(1.0), |p, x| p * x)
    }
}

impl From<f64> for Traced {
    fn from(c: f64) -> Self {
        Self::constant(c)
    }
}

impl num_traits::FromPrimitive for Traced {
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

impl num_traits::Zero for Traced {
    fn zero() -> Self {
        Self::constant(0.0)
    }
    fn is_zero(&self) -> bool {
        self.compare(Self::constant(0.0), Comparison::Equal)
    }
}

impl num_traits::One for Traced {
    fn one() -> Self {
        Self::constant(1.0)
    }
}

impl num_traits::Num for Traced {
    type FromStrRadixErr = <f64 as num_traits::Num>::FromStrRadixErr;
    fn from_str_radix(s: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
        <f64 as num_traits::Num>::from_str_radix(s, radix).map(Self::constant)
    }
}

/// |x| and sign(x) are operations of the program; the predicates are guarded comparisons with zero.
impl num_traits::Signed for Traced {
    fn abs(&self) -> Self {
        self.unary(Unary::Abs)
    }
    fn abs_sub(&self, o: &Self) -> Self {
        if self > o {
            *self - *o
        } else {
            Self::constant(0.0)
        }
    }
    fn signum(&self) -> Self {
        self.unary(Unary::Signum)
    }
    fn is_positive(&self) -> bool {
        self.compare(Self::constant(0.0), Comparison::Greater)
    }
    fn is_negative(&self) -> bool {
        self.compare(Self::constant(0.0), Comparison::Less)
    }
}

/// Comparisons answer for the trace point and guard the answer (see the module documentation).
impl PartialEq for Traced {
    fn eq(&self, o: &Self) -> bool {
        self.compare(*o, Comparison::Equal)
    }
}

impl PartialEq<f64> for Traced {
    fn eq(&self, o: &f64) -> bool {
        self.compare(Self::constant(*o), Comparison::Equal)
    }
}

impl PartialOrd for Traced {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        self.ordering(*o)
    }
    fn lt(&self, o: &Self) -> bool {
        self.compare(*o, Comparison::Less)
    }
    fn le(&self, o: &Self) -> bool {
        self.compare(*o, Comparison::LessOrEqual)
    }
    fn gt(&self, o: &Self) -> bool {
        self.compare(*o, Comparison::Greater)
    }
    fn ge(&self, o: &Self) -> bool {
        self.compare(*o, Comparison::GreaterOrEqual)
    }
}

impl PartialOrd<f64> for Traced {
    fn partial_cmp(&self, o: &f64) -> Option<std::cmp::Ordering> {
        self.ordering(Self::constant(*o))
    }
    fn lt(&self, o: &f64) -> bool {
        self.compare(Self::constant(*o), Comparison::Less)
    }
    fn le(&self, o: &f64) -> bool {
        self.compare(Self::constant(*o), Comparison::LessOrEqual)
    }
    fn gt(&self, o: &f64) -> bool {
        self.compare(Self::constant(*o), Comparison::Greater)
    }
    fn ge(&self, o: &f64) -> bool {
        self.compare(Self::constant(*o), Comparison::GreaterOrEqual)
    }
}

/// A constant shows its value, any other number its node (`%7`).
impl fmt::Display for Traced {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let constant = RECORDING.with_borrow(|r| {
            (r.trace == self.trace && (self.node as usize) < r.graph.len())
                .then(|| r.graph.constant_of(self.node))
                .flatten()
        });
        match constant {
            Some(c) => write!(f, "{c}"),
            None => write!(f, "%{}", self.node),
        }
    }
}

impl num_dual::DualStruct for Traced {
    type Real = f64;
    type Inner = f64;
    fn re(&self) -> f64 {
        self.inspect("re")
    }
    fn from_inner(inner: &f64) -> Self {
        Self::constant(*inner)
    }
}

impl num_dual::Mappable<Self> for Traced {
    type Output<O> = O;
    fn map_dual<G: Fn(Self) -> O, O>(self, g: G) -> O {
        g(self)
    }
}

impl DualNum for Traced {
    type Primitive = f64;
    const NDERIV: usize = 0;
    type InnerDual = f64;

    fn from_re(re: f64) -> Self {
        Self::constant(re)
    }
    fn scale(self, factor: &f64) -> Self {
        self * *factor
    }
    fn recip(&self) -> Self {
        self.unary(Unary::Recip)
    }
    fn powi(&self, n: i32) -> Self {
        record([*self], |g, [x]| g.powi(x, n))
    }
    fn powf(&self, n: f64) -> Self {
        self.binary(Binary::Pow, Self::constant(n))
    }
    fn powd(&self, exponent: Self) -> Self {
        self.binary(Binary::Pow, exponent)
    }
    fn sqrt(&self) -> Self {
        self.unary(Unary::Sqrt)
    }
    fn cbrt(&self) -> Self {
        self.unary(Unary::Cbrt)
    }
    fn exp(&self) -> Self {
        self.unary(Unary::Exp)
    }
    /// 2ˣ as a power of the constant 2.
    fn exp2(&self) -> Self {
        Self::constant(2.0).binary(Binary::Pow, *self)
    }
    fn exp_m1(&self) -> Self {
        self.unary(Unary::ExpM1)
    }
    fn ln(&self) -> Self {
        self.unary(Unary::Ln)
    }
    /// ln x / ln base, as `f64::log` computes it.
    fn log(&self, base: f64) -> Self {
        self.ln().binary(Binary::Div, Self::constant(base.ln()))
    }
    fn log2(&self) -> Self {
        self.log(2.0)
    }
    fn log10(&self) -> Self {
        self.log(10.0)
    }
    fn ln_1p(&self) -> Self {
        self.unary(Unary::Ln1p)
    }
    fn sin(&self) -> Self {
        self.unary(Unary::Sin)
    }
    fn cos(&self) -> Self {
        self.unary(Unary::Cos)
    }
    fn tan(&self) -> Self {
        self.unary(Unary::Tan)
    }
    fn sin_cos(&self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    fn asin(&self) -> Self {
        self.unary(Unary::Asin)
    }
    fn acos(&self) -> Self {
        self.unary(Unary::Acos)
    }
    fn atan(&self) -> Self {
        self.unary(Unary::Atan)
    }
    fn atan2(&self, other: Self) -> Self {
        self.binary(Binary::Atan2, other)
    }
    fn sinh(&self) -> Self {
        self.unary(Unary::Sinh)
    }
    fn cosh(&self) -> Self {
        self.unary(Unary::Cosh)
    }
    fn tanh(&self) -> Self {
        self.unary(Unary::Tanh)
    }
    fn asinh(&self) -> Self {
        self.unary(Unary::Asinh)
    }
    fn acosh(&self) -> Self {
        self.unary(Unary::Acosh)
    }
    fn atanh(&self) -> Self {
        self.unary(Unary::Atanh)
    }
    fn sph_j0(&self) -> Self {
        Self::unsupported([*self], "sph_j0", |[x]| DualNum::sph_j0(&x))
    }
    fn sph_j1(&self) -> Self {
        Self::unsupported([*self], "sph_j1", |[x]| DualNum::sph_j1(&x))
    }
    fn sph_j2(&self) -> Self {
        Self::unsupported([*self], "sph_j2", |[x]| DualNum::sph_j2(&x))
    }
    fn mul_add(&self, a: Self, b: Self) -> Self {
        *self * a + b
    }
}
