//! The Lagrangian L(q, v) as the engine evaluates it: in a dimension ([`crate::dim::Dim`]) fixed when
//! the engine is compiled or chosen at run time.
//!
//! Every [`System`] is a Lagrangian in its fixed dimension ([`Fixed<N>`]); a system whose number of
//! coordinates is chosen at run time is one in [`crate::dim::Dynamic`]. The parts of the engine
//! written over a dimension (the discrete Lagrangian, the unreduced scheme) take any.

use crate::dim::{Dim, Fixed};
use crate::{Scalar, System};

/// L(q, v) on arrays of a dimension, generic over the scalar.
pub trait Lagrangian<Dm: Dim> {
    /// L(q, v).
    fn lagrangian<D: Scalar>(&self, q: &Dm::Array<D>, v: &Dm::Array<D>) -> D;
}

impl<S: System<N>, const N: usize> Lagrangian<Fixed<N>> for S {
    #[inline(always)]
    fn lagrangian<D: Scalar>(&self, q: &[D; N], v: &[D; N]) -> D {
        System::lagrangian(self, q, v)
    }
}
