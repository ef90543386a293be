//! Discrete Lagrangians L_d(q0, q1) from a continuous Lagrangian by a quadrature rule with step h
//! (paper §7: `left` for the charged particle, `midpoint` for the double spherical pendulum).
//!
//! | rule      | L_d(q0, q1)                                  |
//! |-----------|----------------------------------------------|
//! | left      | h L(q0, (q1 − q0)/h)                         |
//! | right     | h L(q1, (q1 − q0)/h)                         |
//! | midpoint  | h L((q0 + q1)/2, (q1 − q0)/h)                |
//! | trapezoid | h/2 [L(q0, (q1 − q0)/h) + L(q1, (q1 − q0)/h)] |
//!
//! Evaluation is *chart-local*: L_d is evaluated at q0 = base + δ0, q1 = base + δ1, so that the
//! velocity (δ1 − δ0)/h is formed from small offsets and never loses digits to a large base value
//! (paper §6, retraction-compatible charts).

use crate::dim::{Dim, Entry, Fixed};
use crate::mechanics::lagrangian::Lagrangian;
use crate::Scalar;
use nalgebra::{SMatrix, SVector};

use crate::dim::{self, PairFunction};

pub use super::rule::Rule;
use crate::{RuntimeInput, System};

/// L_d of a system for a rule and a step size.
///
/// ```
/// use ddirac::{DiscreteLagrangian, Rule, systems::ChargedParticle};
/// let system = ChargedParticle::default();
/// let ld = DiscreteLagrangian::new(&system, Rule::Left, 0.1);
/// // Free flight along z: L_d = h · ½ m (Δz/h)²
/// let value = ld.value(&[0.0; 4], &[0.0, 0.0, 0.1, 0.0]);
/// assert!((value - 0.05).abs() < 1e-15);
/// ```
#[derive(Debug)]
pub struct DiscreteLagrangian<S> {
    /// The continuous system.
    pub system: S,
    /// The quadrature rule.
    pub rule: Rule,
    /// The step size h.
    pub step: f64,
}

/// L_d with its first derivatives and the mixed second derivative D1D2 L_d (an n × n matrix whose
/// entry (i, j) is ∂²L_d/∂q0_i ∂q1_j).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Derivatives<const N: usize> {
    /// L_d(q0, q1).
    pub value: f64,
    /// D1 L_d.
    pub d1: SVector<f64, N>,
    /// D2 L_d.
    pub d2: SVector<f64, N>,
    /// D1 D2 L_d.
    pub d1d2: SMatrix<f64, N, N>,
}

impl<S> DiscreteLagrangian<S> {
    /// Couples a system with a rule and a step size.
    pub fn new(system: S, rule: Rule, step: f64) -> Self {
        Self { system, rule, step }
    }

    /// L_d(base + δ0, base + δ1), generic over the scalar. The base is usually plain numbers; it may be
    /// of the scalar type itself when it is a variable too (tracing, [`crate::compiled`]).
    pub fn eval_local<D, B, const N: usize>(&self, base: &[B; N], d0: &[D; N], d1: &[D; N]) -> D
    where
        S: System<N>,
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy,
    {
        self.eval_in::<Fixed<N>, D, B>(base, d0, d1)
    }

    /// [`DiscreteLagrangian::eval_local`] in any dimension ([`Dim`]): the system is a [`Lagrangian`]
    /// in it.
    pub fn eval_in<Dm, D, B>(&self, base: &Dm::Array<B>, d0: &Dm::Array<D>, d1: &Dm::Array<D>) -> D
    where
        Dm: Dim,
        S: Lagrangian<Dm>,
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy,
    {
        if let Some(glued) = self.system.discrete(self.rule, self.step, base, d0, d1) {
            return glued;
        }
        by_rule::<Dm, D, B>(self.rule, self.step, base, d0, d1, |q, v| self.system.lagrangian(q, v))
    }

    /// L_d(q0, q1), generic over the scalar, in the global chart.
    pub fn eval<D, const N: usize>(&self, q0: &[D; N], q1: &[D; N]) -> D
    where
        S: System<N>,
        D: Scalar,
    {
        self.eval_local(&[0.0f64; N], q0, q1)
    }

    /// L_d(q0, q1) in floating point.
    pub fn value<const N: usize>(&self, q0: &[f64; N], q1: &[f64; N]) -> f64
    where
        S: System<N>,
    {
        self.value_in::<Fixed<N>>(q0, q1)
    }

    /// [`DiscreteLagrangian::value`] in any dimension.
    pub fn value_in<Dm: Dim>(&self, q0: &Dm::Array<f64>, q1: &Dm::Array<f64>) -> f64
    where
        S: Lagrangian<Dm>,
    {
        let dim = Dm::of(q0);
        let d1 = dim.array(|i| q1[i] - q0[i]);
        self.eval_in::<Dm, f64, f64>(q0, &dim.array(|_| 0.0), &d1)
    }

    /// L_d, D1 L_d, D2 L_d and D1 D2 L_d at (base + δ0, base + δ1), by automatic differentiation
    /// ([`dim::mixed`]).
    pub fn derivatives_local<const N: usize>(
        &self,
        base: &[f64; N],
        d0: &SVector<f64, N>,
        d1: &SVector<f64, N>,
    ) -> Derivatives<N>
    where
        S: System<N>,
    {
        let d = dim::mixed(Fixed, &Local { ld: self, base }, &(*d0).into(), &(*d1).into());
        Derivatives { value: d.value, d1: d.da, d2: d.db, d1d2: d.dadb }
    }

    /// L_d, D1 L_d and D2 L_d at (base + δ0, base + δ1), without the mixed block ([`dim::first`]).
    pub fn first_derivatives_local<const N: usize>(
        &self,
        base: &[f64; N],
        d0: &SVector<f64, N>,
        d1: &SVector<f64, N>,
    ) -> dim::FirstDerivatives<Fixed<N>>
    where
        S: System<N>,
    {
        self.first_derivatives_in(base, &(*d0).into(), &(*d1).into())
    }

    /// [`DiscreteLagrangian::first_derivatives_local`] in any dimension, the offsets as arrays.
    pub fn first_derivatives_in<Dm: Dim>(
        &self,
        base: &Dm::Array<f64>,
        d0: &Dm::Array<f64>,
        d1: &Dm::Array<f64>,
    ) -> dim::FirstDerivatives<Dm>
    where
        S: Lagrangian<Dm>,
    {
        dim::first(Dm::of(base), &Local { ld: self, base }, d0, d1)
    }

    /// L_d, D1 L_d, D2 L_d and D1 D2 L_d at (q0, q1).
    pub fn derivatives<const N: usize>(&self, q0: &[f64; N], q1: &[f64; N]) -> Derivatives<N>
    where
        S: System<N>,
    {
        let d1 = SVector::from(std::array::from_fn(|i| q1[i] - q0[i]));
        self.derivatives_local(q0, &SVector::zeros(), &d1)
    }
}

/// L_d(base + δ0, base + δ1) as a function of the offsets (δ0, δ1).
struct Local<'l, S, Dm: Dim> {
    ld: &'l DiscreteLagrangian<S>,
    base: &'l Dm::Array<f64>,
}

impl<S: Lagrangian<Dm>, Dm: Dim> PairFunction<Dm> for Local<'_, S, Dm> {
    fn eval<D: Scalar>(&self, a: &Dm::Array<D>, b: &Dm::Array<D>) -> D {
        self.ld.eval_in::<Dm, D, f64>(self.base, a, b)
    }
}

/// L_d of `rule` and step `h` at q0 = base + d0, q1 = base + d1 for the Lagrangian `l` (the table of
/// the module documentation), on any scalar; h is a runtime input of a trace that keeps it.
pub(crate) fn by_rule<Dm, D, B>(
    rule: Rule,
    h: f64,
    base: &Dm::Array<B>,
    d0: &Dm::Array<D>,
    d1: &Dm::Array<D>,
    l: impl Fn(&Dm::Array<D>, &Dm::Array<D>) -> D,
) -> D
where
    Dm: Dim,
    D: Scalar + std::ops::Add<B, Output = D>,
    B: Entry + Copy,
{
    // In a trace that keeps it as an input, h is a number of the program; otherwise a constant.
    let step = D::runtime_input(RuntimeInput::Step, h);
    let reciprocal = step.map(|h| h.recip());
    let over_h = |x: D| match reciprocal {
        Some(r) => x * r,
        None => x * h.recip(),
    };
    let times_h = |x: D, weight: f64| match step {
        Some(h) => x * (h * weight),
        None => x * (weight * h),
    };
    let mut v = d1.clone();
    for (v, d0) in v.as_mut().iter_mut().zip(d0.as_ref()) {
        *v = over_h(*v - *d0);
    }
    let at = |weight0: f64, weight1: f64| -> Dm::Array<D> {
        let mut q = d0.clone();
        for ((q, d1), base) in q.as_mut().iter_mut().zip(d1.as_ref()).zip(base.as_ref()) {
            *q = *q * weight0 + *d1 * weight1 + *base;
        }
        q
    };
    let l = |q: &Dm::Array<D>| l(q, &v);
    match rule {
        Rule::Left => times_h(l(&at(1.0, 0.0)), 1.0),
        Rule::Right => times_h(l(&at(0.0, 1.0)), 1.0),
        Rule::Midpoint => times_h(l(&at(0.5, 0.5)), 1.0),
        Rule::Trapezoid => times_h(l(&at(1.0, 0.0)) + l(&at(0.0, 1.0)), 0.5),
    }
}
