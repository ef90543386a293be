//! The discrete reduced Lagrangians (paper §4.3–4.4).
//!
//! L̂_{d+} ∘ λ_d = L_d and L̂_{d−} ∘ λ̃_d = L_d
//! are G-invariant; in the quotient they are the reduced Lagrangians ([`ReducedLagrangian`])
//!
//! ```text
//! l₊(x0, x1, γ) = L_d((x0, 0), (x1, γ + h_d^0(x0, x1)))       eq:reducedlagrangianlocal
//! l₋(x0, γ, x1) = L_d((x0, γ + h_d^0(x1, x0)), (x1, 0))       eq:reducedlagrangianlocalminus
//! ```
//!
//! with γ the group argument (g1 of the paper for l₊, g0 for l₋).
//!

use num_dual::DualNum;

use crate::mechanics::pontryagin::block_gradient;
use crate::reduction::trivialization::SplitVector;
use crate::{Connection, DiscreteLagrangian, Error, Input, Rule, Split, System};

/// The value and partial derivatives of a reduced Lagrangian l± at one point.
#[derive(Debug, Clone, PartialEq)]
pub struct ReducedPartials {
    /// l±.
    pub value: f64,
    /// ∂l/∂x0.
    pub x0: Vec<f64>,
    /// ∂l/∂x1.
    pub x1: Vec<f64>,
    /// ∂l/∂γ: ∂l₊/∂g1 for (+), ∂l₋/∂g0 for (−).
    pub gamma: Vec<f64>,
}

/// A discrete Lagrangian L_d read in a trivialization Q = Σ × G through a linear connection: the reduced
/// Lagrangians l± and their derivatives. The reduced Dirac differentials and equations built on it are in
/// [`crate::reduction::dirac_structure`].
///
/// ```
/// use ddirac::{reduction::reduced_lagrangian::ReducedLagrangian, systems::ChargedParticle, Connection, Rule};
/// let system = ChargedParticle::default();
/// let reduction = ReducedLagrangian::new(&system, Rule::Left, 0.2, Connection::zero(3, 1)).unwrap();
/// // l₊(0, (0, 0, 0.2), 0.2) = L_d((0, 0), ((0, 0, 0.2), 0.2)) = ½ (0.2² + 0.2²) / 0.2
/// let l: f64 = reduction.lagrangian_plus(&[0.0; 3], &[0.0, 0.0, 0.2], &[0.2]).unwrap();
/// assert!((l - 0.2).abs() < 1e-15);
/// ```
#[derive(Debug)]
pub struct ReducedLagrangian<'a, S> {
    /// L_d.
    pub ld: DiscreteLagrangian<'a, S>,
    /// Shape and group coordinates.
    pub split: Split,
    /// The linear connection K = h_{d,Σ}.
    pub connection: Connection,
}

impl<'a, S> ReducedLagrangian<'a, S> {
    /// L_d of `system` by `rule` with step `step`, reduced with `connection`, whose size must match the
    /// system's shape and group coordinates.
    pub fn new<const N: usize>(system: &'a S, rule: Rule, step: f64, connection: Connection) -> Result<Self, Error>
    where
        S: System<N>,
    {
        let split = Split::new(&system.coordinates());
        if (connection.n_x(), connection.n_g()) != (split.n_x(), split.n_g()) {
            return Err(Error::Invalid {
                what: Input::Connection,
                why: format!(
                    "K is {}×{}, the system has {} group and {} shape coordinates",
                    connection.n_g(),
                    connection.n_x(),
                    split.n_g(),
                    split.n_x()
                ),
            });
        }
        Ok(Self { ld: DiscreteLagrangian::new(system, rule, step), split, connection })
    }

    /// l₊(x0, x1, γ) = L_d((x0, 0), (x1, γ + h_d^0(x0, x1))) (eq:reducedlagrangianlocal), generic over
    /// the scalar.
    pub fn lagrangian_plus<D, const N: usize>(&self, x0: &[D], x1: &[D], gamma: &[D]) -> Result<D, Error>
    where
        S: System<N>,
        D: DualNum<Primitive = f64> + Copy,
    {
        self.check_sizes(&[("x0", x0.len(), true), ("x1", x1.len(), true), ("gamma", gamma.len(), false)])?;
        let zero = D::from(0.0);
        let (a, b) = (self.pack(x0, gamma, zero), self.pack(x1, &[], zero));
        Ok(self.l_plus(&a, &b))
    }

    /// l₋(x0, γ, x1) = L_d((x0, γ + h_d^0(x1, x0)), (x1, 0)) (eq:reducedlagrangianlocalminus), generic
    /// over the scalar.
    pub fn lagrangian_minus<D, const N: usize>(&self, x0: &[D], gamma: &[D], x1: &[D]) -> Result<D, Error>
    where
        S: System<N>,
        D: DualNum<Primitive = f64> + Copy,
    {
        self.check_sizes(&[("x0", x0.len(), true), ("x1", x1.len(), true), ("gamma", gamma.len(), false)])?;
        let zero = D::from(0.0);
        let (a, b) = (self.pack(x0, gamma, zero), self.pack(x1, &[], zero));
        Ok(self.l_minus(&a, &b))
    }

    /// l₊ and its partials at (x0, x1, γ), by automatic differentiation.
    pub fn partials_plus<const N: usize>(&self, x0: &[f64], x1: &[f64], gamma: &[f64]) -> Result<ReducedPartials, Error>
    where
        S: System<N>,
    {
        self.check_sizes(&[("x0", x0.len(), true), ("x1", x1.len(), true), ("gamma", gamma.len(), false)])?;
        let blocks = [self.pack(x0, gamma, 0.0), self.pack(x1, &[], 0.0)];
        Ok(self.unpack_partials(block_gradient(&blocks, |[a, b]| self.l_plus(a, b))))
    }

    /// l₋ and its partials at (x0, γ, x1), by automatic differentiation.
    pub fn partials_minus<const N: usize>(
        &self,
        x0: &[f64],
        gamma: &[f64],
        x1: &[f64],
    ) -> Result<ReducedPartials, Error>
    where
        S: System<N>,
    {
        self.check_sizes(&[("x0", x0.len(), true), ("x1", x1.len(), true), ("gamma", gamma.len(), false)])?;
        let blocks = [self.pack(x0, gamma, 0.0), self.pack(x1, &[], 0.0)];
        Ok(self.unpack_partials(block_gradient(&blocks, |[a, b]| self.l_minus(a, b))))
    }

    /// (D1 L_d, D2 L_d)(q0, q1) by automatic differentiation ([`DiscreteLagrangian::derivatives`]).
    pub fn ld_partials<const N: usize>(
        &self,
        q0: &SplitVector,
        q1: &SplitVector,
    ) -> Result<(SplitVector, SplitVector), Error>
    where
        S: System<N>,
    {
        let full = |q: &SplitVector| -> Result<[f64; N], Error> {
            let v = q.to_full(&self.split)?;
            v.as_slice().try_into().map_err(|_| Error::Size {
                what: Input::Argument("q".into()),
                expected: N,
                found: v.len(),
            })
        };
        let d = self.ld.derivatives(&full(q0)?, &full(q1)?);
        Ok((
            SplitVector::from_full(&self.split, d.d1.as_slice())?,
            SplitVector::from_full(&self.split, d.d2.as_slice())?,
        ))
    }

    /// l₊ on packed blocks a = (x0 at the shape positions, γ at the group positions), b = (x1, ·);
    /// the group entries of b are not read.
    pub(crate) fn l_plus<D, const N: usize>(&self, a: &[D; N], b: &[D; N]) -> D
    where
        S: System<N>,
        D: DualNum<Primitive = f64> + Copy,
    {
        self.l_plus_in_place(&[0.0f64; N], *a, *b)
    }

    /// l₋ on packed blocks a = (x0 at the shape positions, γ at the group positions), b = (x1, ·);
    /// the group entries of b are not read.
    pub(crate) fn l_minus<D, const N: usize>(&self, a: &[D; N], b: &[D; N]) -> D
    where
        S: System<N>,
        D: DualNum<Primitive = f64> + Copy,
    {
        self.l_minus_in_place(&[0.0f64; N], *a, *b)
    }

    /// [`Self::l_plus`] in the chart centred at `base` (x0 = base + a_x, x1 = base + b_x; the group
    /// entries of `base` are the chart's g = 0), see [`DiscreteLagrangian::eval_local`], on blocks it may
    /// overwrite (no copies of dual numbers).
    pub(crate) fn l_plus_in_place<D, B, const N: usize>(&self, base: &[B; N], mut a: [D; N], mut b: [D; N]) -> D
    where
        S: System<N>,
        D: DualNum<Primitive = f64> + Copy + std::ops::Add<B, Output = D>,
        B: Copy,
    {
        for (j, &gj) in self.split.group.iter().enumerate() {
            b[gj] = self.k_row(j, &b, &a).map_or(a[gj], |k| a[gj] + k);
            a[gj] = D::from(0.0);
        }
        self.ld.eval_local(base, &a, &b)
    }

    /// [`Self::l_minus`] in the chart centred at `base`, on blocks it may overwrite.
    pub(crate) fn l_minus_in_place<D, B, const N: usize>(&self, base: &[B; N], mut a: [D; N], mut b: [D; N]) -> D
    where
        S: System<N>,
        D: DualNum<Primitive = f64> + Copy + std::ops::Add<B, Output = D>,
        B: Copy,
    {
        for (j, &gj) in self.split.group.iter().enumerate() {
            a[gj] = self.k_row(j, &a, &b).map_or(a[gj], |k| a[gj] + k);
            b[gj] = D::from(0.0);
        }
        self.ld.eval_local(base, &a, &b)
    }

    /// Row j of K (u − v) = h_d^0(v, u) on the shape entries of packed blocks; `None` when row j of K
    /// is zero.
    pub(crate) fn k_row<D: DualNum<Primitive = f64> + Copy, const N: usize>(
        &self,
        j: usize,
        u: &[D; N],
        v: &[D; N],
    ) -> Option<D> {
        let mut acc: Option<D> = None;
        for (i, &si) in self.split.shape.iter().enumerate() {
            let kji = self.connection.entry(j, i);
            if kji != 0.0 {
                let term = (u[si] - v[si]) * kji;
                acc = Some(acc.map_or(term, |s| s + term));
            }
        }
        acc
    }

    /// Packs a shape vector and a group vector at the coordinates' positions (missing entries `zero`).
    pub(crate) fn pack<D: Copy, const N: usize>(&self, x: &[D], g: &[D], zero: D) -> [D; N] {
        let mut out = [zero; N];
        self.split.shape.iter().zip(x).for_each(|(&i, &v)| out[i] = v);
        self.split.group.iter().zip(g).for_each(|(&i, &v)| out[i] = v);
        out
    }

    fn unpack_partials<const N: usize>(&self, (value, [da, db]): (f64, [[f64; N]; 2])) -> ReducedPartials {
        ReducedPartials { value, x0: self.split.x(&da), x1: self.split.x(&db), gamma: self.split.g(&da) }
    }

    pub(crate) fn check_sizes(&self, items: &[(&str, usize, bool)]) -> Result<(), Error> {
        for &(what, found, shape) in items {
            let expected = if shape { self.split.n_x() } else { self.split.n_g() };
            if found != expected {
                return Err(Error::Size { what: Input::Argument(what.into()), expected, found });
            }
        }
        Ok(())
    }
}
