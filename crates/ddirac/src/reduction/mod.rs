//! Reduction by an abelian symmetry (paper §§2.2, 3–5): discrete connections, the invariance
//! hypothesis and the reduced (+) and (−) equations with reconstruction.

pub mod connection;
pub mod dirac_structure;
pub mod invariance;
pub(crate) mod reduced;
pub mod reduced_lagrangian;
pub mod trivialization;
