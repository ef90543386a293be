//! # ddirac-oracle — the paper's formulas as printed
//!
//! Independent transcriptions of the printed formulas of *Discrete Dirac reduction of implicit
//! Lagrangian systems with abelian symmetry groups* (Rodríguez Abella & Leok), which the tests hold the
//! `ddirac` engine against. Nothing here runs an integration: each module states a formula in the
//! paper's own terms (the maps h_d, h_{d,Q}, h_{d,Σ}, h*_{d,Σ} of the connection evaluated as printed,
//! pairings formed on basis vectors), so that a trajectory computed by the engine can be checked
//! against it. Equation labels in the docs refer to the paper.
//!
//! | module | paper | what |
//! |---|---|---|
//! | [`pontryagin`] | §2.3.3, eqs. `lagrangepontryaginaction(minus)`, `Ed`, `Edminus`; §5 lemmas `reducedactionlocal(minus)` | Lagrange–Pontryagin actions S±, generalized energies E_d±, reduced e_d±, their gradients |
//! | [`trivialization`] | §3.1–3.2, eqs. `lambdadlocal` … `invadjointhatlambdadlocal` | trivializations λ_d, λ̃_d, λ̂_d, λ̌_d, inverses, adjoints |
//! | [`reduced_lagrangian`] | §4.3–4.4, eqs. `reducedlagrangianlocal(minus)` | partials of the engine's reduced Lagrangians l± (for the maps below) |
//! | [`dirac_structure`] | §3.4, props. `reduceddiractructurelocal(minus)`; §4.1 props. `reduceddiracdifferentiallocal(minus)`; eqs. `geometricequations(minus)` | reduced Dirac structures and Dirac differentials, lemmas `partialderivativesld(minus)`, the general-form reduced equations |
//!
//! The paper's (−) displays `geometricequationsminus`, `lagrangepontryaginactionminus`, `Edminus` and
//! `reducedactionlocalminus` carry a sign slip on every momentum term; [`dirac_structure::Signs`]
//! evaluates them as printed or corrected.
//!
//! Derivatives come from the engine's own dual numbers ([`ddirac::ad::Gradient`]), one pass per block
//! of arguments, so that the oracle and the engine share one automatic-differentiation path and differ
//! only in the formulas they transcribe.
//!
//! ```
//! use ddirac::Connection;
//! use ddirac_oracle::trivialization::{lambda_hat, SplitVector};
//! // Paper §7.1: the charged particle's p0 = (1, 0, 1, 1) with K = 0 trivializes to w0 = (1, 0, 1), μ0 = 1.
//! let t = lambda_hat(&Connection::zero(3, 1), &SplitVector::zeros(3, 1),
//!                    &SplitVector::new(vec![1.0, 0.0, 1.0], vec![1.0])).unwrap();
//! assert_eq!((t.w, t.mu), (vec![1.0, 0.0, 1.0], vec![1.0]));
//! ```
#![warn(missing_docs)]

pub mod dirac_structure;
mod gradient;
pub mod pontryagin;
pub mod reduced_lagrangian;
pub mod trivialization;
