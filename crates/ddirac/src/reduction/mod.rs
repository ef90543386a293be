//! Reduction by an abelian symmetry (paper §§2.2, 3–5): discrete connections, the invariance
//! hypothesis, the reduced Lagrangians, the trivialization λ̂_d of the momenta and the reduced (+) and
//! (−) equations with reconstruction.

pub mod connection;
pub mod invariance;
pub(crate) mod reduced;
pub mod reduced_lagrangian;
pub(crate) mod trivialization;
