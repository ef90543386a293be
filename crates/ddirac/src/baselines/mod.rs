//! Hand-written integrators of the charged particle of paper §7.1, kept as yardsticks for the
//! generic engine ([`crate::integrate`]): benchmarks and `ddirac bench` compare its
//! time per step and its error against them.
//!
//! - [`boris`]: the Boris pusher of plasma physics, a different second-order method for the same
//!   Lorentz motion m q̈ = e q̇ × B.
//! - [`charged_particle_step`]: the reduced (+) left-rule scheme of paper eq.
//!   `reduceddiscreteequationsem` written out by hand. It computes the same numbers as the engine
//!   with [`ChargedParticle`](crate::systems::ChargedParticle), [`Rule::Left`](crate::Rule::Left),
//!   reduced, (+), without automatic differentiation or Newton's method: the step equations are
//!   linear in the increment.
//!
//! Both take the field B = (0, 0, B0) and run allocation-free loops. They validate nothing: they
//! exist to be timed, and non-finite input simply propagates to the result.

pub mod boris;
pub mod charged_particle_step;
