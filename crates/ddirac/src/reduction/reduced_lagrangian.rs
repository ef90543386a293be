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

use crate::dim::{Dim, Entry, Fixed};
use crate::mechanics::lagrangian::{Lagrangian, SystemIn};
use crate::Scalar;

use crate::{Connection, DiscreteLagrangian, Error, Input, Rule, Split, System};

/// A discrete Lagrangian L_d read in a trivialization Q = Σ × G through a linear connection: the reduced
/// Lagrangians l±, which the reduced schemes differentiate in the chart of each step. Their partials and
/// the reduced Dirac differentials built on them are transcribed independently in the `ddirac-oracle`
/// crate.
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
pub struct ReducedLagrangian<S> {
    /// L_d.
    pub ld: DiscreteLagrangian<S>,
    /// Shape and group coordinates.
    pub split: Split,
    /// The linear connection K = h_{d,Σ}.
    pub connection: Connection,
}

impl<S> ReducedLagrangian<S> {
    /// L_d of `system` by `rule` with step `step`, reduced with `connection`, whose size must match the
    /// system's shape and group coordinates.
    pub fn new<Dm: Dim>(system: S, rule: Rule, step: f64, connection: Connection) -> Result<Self, Error>
    where
        S: SystemIn<Dm>,
    {
        let split = Split::new(system.coordinates().as_ref());
        if (connection.n_x(), connection.n_g()) != (split.n_x(), split.n_g()) {
            return Err(Error::Invalid {
                what: Input::Connection,
                why: crate::Reason::Shape {
                    rows: connection.n_g(),
                    columns: connection.n_x(),
                    group: split.n_g(),
                    shape: split.n_x(),
                },
            });
        }
        Ok(Self { ld: DiscreteLagrangian::new(system, rule, step), split, connection })
    }

    /// l₊(x0, x1, γ) = L_d((x0, 0), (x1, γ + h_d^0(x0, x1))) (eq:reducedlagrangianlocal), generic over
    /// the scalar.
    pub fn lagrangian_plus<D, const N: usize>(&self, x0: &[D], x1: &[D], gamma: &[D]) -> Result<D, Error>
    where
        S: System<N>,
        D: Scalar,
    {
        self.check_sizes(&[("x0", x0.len(), true), ("x1", x1.len(), true), ("gamma", gamma.len(), false)])?;
        let zero = D::from(0.0);
        let (a, b) = (self.pack(x0, gamma, zero), self.pack(x1, &[], zero));
        Ok(self.l_plus_in_place::<Fixed<N>, D, f64>(&[0.0f64; N], a, b))
    }

    /// l₋(x0, γ, x1) = L_d((x0, γ + h_d^0(x1, x0)), (x1, 0)) (eq:reducedlagrangianlocalminus), generic
    /// over the scalar.
    pub fn lagrangian_minus<D, const N: usize>(&self, x0: &[D], gamma: &[D], x1: &[D]) -> Result<D, Error>
    where
        S: System<N>,
        D: Scalar,
    {
        self.check_sizes(&[("x0", x0.len(), true), ("x1", x1.len(), true), ("gamma", gamma.len(), false)])?;
        let zero = D::from(0.0);
        let (a, b) = (self.pack(x0, gamma, zero), self.pack(x1, &[], zero));
        Ok(self.l_minus_in_place::<Fixed<N>, D, f64>(&[0.0f64; N], a, b))
    }

    /// l₊ on packed blocks a = (x0 at the shape positions, γ at the group positions), b = (x1, ·), in
    /// the chart centred at `base` (x0 = base + a_x, x1 = base + b_x; the group entries of `base` are the
    /// chart's g = 0), see [`DiscreteLagrangian::eval_local`]; the group entries of b are not read. The
    /// blocks may be overwritten (no copies of dual numbers).
    pub(crate) fn l_plus_in_place<Dm, D, B>(&self, base: &Dm::Array<B>, mut a: Dm::Array<D>, mut b: Dm::Array<D>) -> D
    where
        Dm: Dim,
        S: Lagrangian<Dm>,
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy,
    {
        for (j, &gj) in self.split.group.iter().enumerate() {
            b[gj] = self.k_row(j, b.as_ref(), a.as_ref()).map_or(a[gj], |k| a[gj] + k);
            a[gj] = D::from(0.0);
        }
        self.ld.eval_in::<Dm, D, B>(base, &a, &b)
    }

    /// l₋ on packed blocks as for [`Self::l_plus_in_place`], in the chart centred at `base`.
    pub(crate) fn l_minus_in_place<Dm, D, B>(&self, base: &Dm::Array<B>, mut a: Dm::Array<D>, mut b: Dm::Array<D>) -> D
    where
        Dm: Dim,
        S: Lagrangian<Dm>,
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy,
    {
        for (j, &gj) in self.split.group.iter().enumerate() {
            a[gj] = self.k_row(j, a.as_ref(), b.as_ref()).map_or(a[gj], |k| a[gj] + k);
            b[gj] = D::from(0.0);
        }
        self.ld.eval_in::<Dm, D, B>(base, &a, &b)
    }

    /// Row j of K (u − v) = h_d^0(v, u) on the shape entries of packed blocks; `None` when row j of K
    /// is zero.
    fn k_row<D: Scalar>(&self, j: usize, u: &[D], v: &[D]) -> Option<D> {
        let shape = &self.split.shape;
        self.connection.row_apply(j, |i| u[shape[i]] - v[shape[i]])
    }

    /// Packs a shape vector and a group vector at the coordinates' positions (missing entries `zero`).
    fn pack<D: Copy, const N: usize>(&self, x: &[D], g: &[D], zero: D) -> [D; N] {
        let mut out = [zero; N];
        self.split.shape.iter().zip(x).for_each(|(&i, &v)| out[i] = v);
        self.split.group.iter().zip(g).for_each(|(&i, &v)| out[i] = v);
        out
    }

    fn check_sizes(&self, items: &[(&str, usize, bool)]) -> Result<(), Error> {
        for &(what, found, shape) in items {
            let expected = if shape { self.split.n_x() } else { self.split.n_g() };
            if found != expected {
                return Err(Error::Size { what: Input::Argument(what.into()), expected, found });
            }
        }
        Ok(())
    }
}
