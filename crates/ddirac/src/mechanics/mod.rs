//! Unreduced mechanics: discrete Lagrangians, the Legendre transform and the discrete
//! Lagrange–Dirac equations (paper §2.3); the continuous Euler–Lagrange field for explicit peers.

pub(crate) mod dirac;
pub mod discrete_lagrangian;
pub mod euler_lagrange;
pub mod lagrangian;
pub mod legendre;
pub mod rule;
