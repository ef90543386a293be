//! Unreduced mechanics: discrete Lagrangians, the Legendre transform and the discrete
//! Lagrange–Dirac equations (paper §2.3).

pub(crate) mod dirac;
pub mod discrete_lagrangian;
pub mod legendre;
