//! The partial derivatives of the reduced Lagrangians (paper §4.3–4.4)
//!
//! ```text
//! l₊(x0, x1, γ) = L_d((x0, 0), (x1, γ + h_d^0(x0, x1)))       eq:reducedlagrangianlocal
//! l₋(x0, γ, x1) = L_d((x0, γ + h_d^0(x1, x0)), (x1, 0))       eq:reducedlagrangianlocalminus
//! ```
//!
//! as the engine evaluates them ([`ReducedLagrangian::lagrangian_plus`], `…_minus`), differentiated by
//! automatic differentiation: the maps of [`crate::dirac_structure`] and the reduced energies of
//! [`crate::pontryagin`] are built on them. D1 L_d and D2 L_d of the unreduced L_d come from the
//! engine's [`ddirac::DiscreteLagrangian::derivatives`].

use ddirac::reduction::reduced_lagrangian::ReducedLagrangian;
use ddirac::Scalar;
use ddirac::{Error, Input, System};

use crate::gradient::block_gradient;
use crate::trivialization::SplitVector;

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

/// l₊ and its partials at (x0, x1, γ).
///
/// ```
/// use ddirac::{reduction::reduced_lagrangian::ReducedLagrangian, systems::ChargedParticle, Connection, Rule};
/// use ddirac_oracle::reduced_lagrangian::partials_plus;
/// let system = ChargedParticle::default();
/// let reduction = ReducedLagrangian::new(&system, Rule::Left, 0.2, Connection::zero(3, 1)).unwrap();
/// // l₊ = ½ (|x1 − x0|² + γ²) / h at x0 = 0, x1 = (0, 0, 0.2), γ = 0.2 (no field on the z axis)
/// let l = partials_plus(&reduction, &[0.0; 3], &[0.0, 0.0, 0.2], &[0.2]).unwrap();
/// assert!((l.value - 0.2).abs() < 1e-15 && (l.x1[2] - 1.0).abs() < 1e-15 && (l.gamma[0] - 1.0).abs() < 1e-15);
/// ```
pub fn partials_plus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    x0: &[f64],
    x1: &[f64],
    gamma: &[f64],
) -> Result<ReducedPartials, Error> {
    check_sizes(reduction, x0, x1, gamma)?;
    let blocks = [pack(reduction, x0, gamma, 0.0), pack(reduction, x1, &[], 0.0)];
    let derivatives = block_gradient(&blocks, |[a, b]| l_plus(reduction, a, b))?;
    Ok(unpack_partials(reduction, derivatives))
}

/// l₋ and its partials at (x0, γ, x1).
pub fn partials_minus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    x0: &[f64],
    gamma: &[f64],
    x1: &[f64],
) -> Result<ReducedPartials, Error> {
    check_sizes(reduction, x0, x1, gamma)?;
    let blocks = [pack(reduction, x0, gamma, 0.0), pack(reduction, x1, &[], 0.0)];
    let derivatives = block_gradient(&blocks, |[a, b]| l_minus(reduction, a, b))?;
    Ok(unpack_partials(reduction, derivatives))
}

/// (D1 L_d, D2 L_d)(q0, q1) of the unreduced L_d ([`ddirac::DiscreteLagrangian::derivatives`]).
pub fn ld_partials<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    q0: &SplitVector,
    q1: &SplitVector,
) -> Result<(SplitVector, SplitVector), Error> {
    let full = |q: &SplitVector| -> Result<[f64; N], Error> {
        let v = q.to_full(&reduction.split)?;
        v.as_slice().try_into().map_err(|_| Error::Size {
            what: Input::Argument("q".into()),
            expected: N,
            found: v.len(),
        })
    };
    let d = reduction.ld.derivatives(&full(q0)?, &full(q1)?);
    Ok((
        SplitVector::from_full(&reduction.split, d.d1.as_slice())?,
        SplitVector::from_full(&reduction.split, d.d2.as_slice())?,
    ))
}

/// l₊ on packed blocks a = (x0 at the shape positions, γ at the group positions), b = (x1, ·); the
/// group entries of b are not read.
pub(crate) fn l_plus<S, D, const N: usize>(reduction: &ReducedLagrangian<S>, a: &[D; N], b: &[D; N]) -> Result<D, Error>
where
    S: System<N>,
    D: Scalar,
{
    let split = &reduction.split;
    reduction.lagrangian_plus(&split.x(a), &split.x(b), &split.g(a))
}

/// l₋ on packed blocks a = (x0 at the shape positions, γ at the group positions), b = (x1, ·); the
/// group entries of b are not read.
pub(crate) fn l_minus<S, D, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    a: &[D; N],
    b: &[D; N],
) -> Result<D, Error>
where
    S: System<N>,
    D: Scalar,
{
    let split = &reduction.split;
    reduction.lagrangian_minus(&split.x(a), &split.g(a), &split.x(b))
}

/// A shape vector and a group vector at the coordinates' positions (missing entries `zero`).
pub(crate) fn pack<S, D: Copy, const N: usize>(reduction: &ReducedLagrangian<S>, x: &[D], g: &[D], zero: D) -> [D; N] {
    let mut out = [zero; N];
    reduction.split.shape.iter().zip(x).for_each(|(&i, &v)| out[i] = v);
    reduction.split.group.iter().zip(g).for_each(|(&i, &v)| out[i] = v);
    out
}

/// Checks that x0 and x1 have one entry per shape coordinate and γ one per group coordinate.
fn check_sizes<S>(reduction: &ReducedLagrangian<S>, x0: &[f64], x1: &[f64], gamma: &[f64]) -> Result<(), Error> {
    let (n_x, n_g) = (reduction.split.n_x(), reduction.split.n_g());
    for (what, found, expected) in [("x0", x0.len(), n_x), ("x1", x1.len(), n_x), ("gamma", gamma.len(), n_g)] {
        if found != expected {
            return Err(Error::Size { what: Input::Argument(what.into()), expected, found });
        }
    }
    Ok(())
}

fn unpack_partials<S, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    (value, [da, db]): (f64, [[f64; N]; 2]),
) -> ReducedPartials {
    let split = &reduction.split;
    ReducedPartials { value, x0: split.x(&da), x1: split.x(&db), gamma: split.g(&da) }
}
