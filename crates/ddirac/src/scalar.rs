//! The scalar the engine evaluates Lagrangians on.
//!
//! A Lagrangian is written against num-dual's [`DualNum`] and runs on every [`Scalar`]: `f64`, the
//! engine's own dual numbers ([`crate::ad`]), num-dual's numbers and the recording number of compiled
//! derivatives ([`crate::compiled::Traced`]). What `Scalar` adds is what tracing needs to keep a
//! number a *runtime input* of the compiled program instead of folding it in: the step size h of a
//! discrete Lagrangian and the parameters of a text Lagrangian. On every scalar but a traced one,
//! [`Scalar::runtime_input`] is `None` and the code computes with the plain `f64`, exactly as before.
//! `Scalar` also names the choices a trace records as operations rather than as guarded comparisons
//! ([`Scalar::min_of`], [`Scalar::max_of`]).
//!
//! A system implements [`crate::System::lagrangian`] for `D: DualNum<Primitive = f64> + Copy` (a
//! weaker bound than the trait's `D: Scalar`, which Rust accepts), so user code never names
//! `Scalar`.

use num_dual::DualNum;

/// A number whose value a traced program reads at run time rather than folding it in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RuntimeInput {
    /// The step size h of the discrete Lagrangian.
    Step,
    /// The k-th parameter of a text Lagrangian ([`crate::expression::ExpressionSpec::parameters`]).
    Parameter(usize),
}

/// A scalar a Lagrangian can be evaluated on (see the module documentation).
///
/// ```
/// use ddirac::{RuntimeInput, Scalar};
/// // Outside a trace every scalar computes with the plain value.
/// assert_eq!(<f64 as Scalar>::runtime_input(RuntimeInput::Step, 0.01), None);
/// ```
pub trait Scalar: DualNum<Primitive = f64> + Copy + Send + Sync {
    /// The number standing for `input` (whose value is `value`) in a trace that keeps it as an input
    /// of the compiled program; `None` on every other scalar, and in traces that fold it.
    #[inline(always)]
    fn runtime_input(_input: RuntimeInput, _value: f64) -> Option<Self> {
        None
    }

    /// min(self, other): `other` if it is smaller, else `self` (also when they are equal or `other`
    /// is NaN), with the derivatives of the one picked. A traced number records one operation
    /// ([`crate::compiled::Binary::Min`]) instead of a comparison, so the program holds on both sides.
    ///
    /// ```
    /// use ddirac::Scalar;
    /// assert_eq!(2.0f64.min_of(1.0), 1.0);
    /// assert!(0.0f64.min_of(-0.0).is_sign_positive()); // equal: the first
    /// assert_eq!(2.0f64.min_of(f64::NAN), 2.0);
    /// ```
    #[inline(always)]
    fn min_of(self, other: Self) -> Self {
        if other < self {
            other
        } else {
            self
        }
    }

    /// max(self, other): `other` if it is larger, else `self`; see [`Scalar::min_of`].
    ///
    /// ```
    /// use ddirac::Scalar;
    /// assert_eq!(1.0f64.max_of(2.0), 2.0);
    /// assert_eq!(2.0f64.max_of(f64::NAN), 2.0);
    /// ```
    #[inline(always)]
    fn max_of(self, other: Self) -> Self {
        if other > self {
            other
        } else {
            self
        }
    }
}

impl Scalar for f64 {}

/// num-dual's own numbers over `f64`.
macro_rules! num_dual_scalars {
    ($($t:ident<$($p:ident),*>),*) => {$(
        impl<$($p),*> Scalar for num_dual::$t<$($p),*> where Self: DualNum<Primitive = f64> + Copy + Send + Sync {}
    )*};
}

num_dual_scalars!(Dual<T>, Dual2<T>, Dual3<T>, HyperDual<T>, HyperHyperDual<T>, Real<T>);

impl<T: nalgebra::Scalar, D: nalgebra::Dim> Scalar for num_dual::DualVec<T, D>
where
    Self: DualNum<Primitive = f64> + Copy + Send + Sync,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<D>,
{
}

impl<T: nalgebra::Scalar, D: nalgebra::Dim> Scalar for num_dual::Dual2Vec<T, D>
where
    Self: DualNum<Primitive = f64> + Copy + Send + Sync,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<nalgebra::U1, D> + nalgebra::allocator::Allocator<D, D>,
{
}

impl<T: nalgebra::Scalar, M: nalgebra::Dim, N: nalgebra::Dim> Scalar for num_dual::HyperDualVec<T, M, N>
where
    Self: DualNum<Primitive = f64> + Copy + Send + Sync,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<M>
        + nalgebra::allocator::Allocator<nalgebra::U1, N>
        + nalgebra::allocator::Allocator<M, N>,
{
}
