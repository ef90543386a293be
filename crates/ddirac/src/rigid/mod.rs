//! Rigid bodies: systems on Q = SO(3) × S, an attitude R (body to space) and shape coordinates s,
//! advanced on the group and reduced by the nonabelian group SO(3).
//!
//! A [`RigidSystem`] writes its Lagrangian ℓ(R, Ω, s, ṡ) in the body angular velocity Ω = (RᵀṘ)^∨
//! and declares its [`Symmetry`]; a [`RigidProblem`] gives the step, the number of steps and the
//! initial data (R0, Π0 or Ω0, s0, p0 or ṡ0); the [`crate::Method`] of the abelian engine chooses the
//! rule, the composition, reduced or unreduced equations and Newton's options. A step
//! (`step.rs`) solves the discrete Hamilton–Pontryagin equations on the group for ζ_k, the Cayley
//! coordinates of R_k⁻¹R_{k+1} ([`so3`]), and the next shape; the attitude is never in a chart, so no
//! attitude is singular (Euler angles are at θ = 0), and RᵀR = I holds to round-off over any run.
//!
//! ```text
//! Π_k     = (dcay⁻¹_{ζ_k})ᵀ ∂L_d/∂ζ_k − ∂L_d/∂η_k          p_k     = −∂L_d/∂s_k
//! Π_{k+1} = cay(ζ_k)ᵀ (dcay⁻¹_{ζ_k})ᵀ ∂L_d/∂ζ_k             p_{k+1} = ∂L_d/∂s_{k+1}
//! R_{k+1} = R_k cay(ζ_k)
//! ```
//!
//! The discrete Noether theorem holds for every rotation of space leaving ℓ invariant: R Π is kept
//! to round-off for a free body, e3 · R Π for a heavy body. With `method.reduced = true` a system
//! invariant under every rotation runs the reduced (Lagrange–Poincaré / Euler–Poincaré) equations on
//! (s, ζ, Π), which keep the Casimir |Π| to round-off, and reconstructs R; one invariant only under
//! the vertical rotations is refused ([`crate::Error::NotReducible`]). The rules and compositions are
//! those of the abelian engine: midpoint (the group midpoint) and trapezoid are symmetric, of order 2,
//! and compose to orders 4, 6 and 8.
//!
//! ```
//! use ddirac::rigid::{solve_rigid, RigidInitial, RigidProblem};
//! use ddirac::systems::RigidBody;
//! use ddirac::Method;
//! // A free asymmetric body spinning near its intermediate axis.
//! let body = RigidBody::free(1.0, 2.0, 3.0);
//! let problem = RigidProblem::new(0.01, 500, ddirac::rigid::so3::identity(),
//!     RigidInitial::Velocity { omega: [0.01, 1.0, 0.01], v: vec![] });
//! let run = solve_rigid(&body, problem, &Method::default(), 100).unwrap();
//! assert!(run.summary.momentum_map.max_relative_drift.unwrap() < 1e-13);
//! assert!(run.summary.casimir.max_relative_drift < 1e-13);
//! assert!(run.summary.orthogonality < 1e-14);
//! assert_eq!(run.rows.len(), 6);
//! ```

mod discrete_lagrangian;
mod expression_system;
mod invariance;
mod legendre;
mod principal_axes;
mod problem;
pub mod so3;
mod step;
mod stepper;
mod system;

pub use expression_system::RigidExpressionSystem;
pub use invariance::{test_symmetry, INVARIANCE_TOLERANCE};
pub use problem::{RigidInitial, RigidProblem, ROTATION_TOLERANCE};
pub use stepper::{Casimir, RigidRow, RigidStepper, RigidSummary};
pub use system::{PrincipalAxes, RigidSystem, Symmetry};

use crate::{Error, Method};

/// A rigid system's trajectory kept in memory: the reported rows and the summary.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidSolution {
    /// Rows 0, every, 2·every, …, and the last.
    pub rows: Vec<RigidRow>,
    /// The run's summary.
    pub summary: RigidSummary,
}

/// Runs a rigid system's problem, streaming every `every`-th row (and the last) to `observer`.
pub fn integrate_rigid<S: RigidSystem>(
    system: &S,
    problem: RigidProblem,
    method: &Method,
    every: usize,
    mut observer: impl FnMut(&RigidRow),
) -> Result<RigidSummary, Error> {
    if every == 0 {
        return Err(Error::Invalid { what: crate::Input::Every, why: crate::Reason::Zero });
    }
    let mut stepper = RigidStepper::new(system, problem, method)?;
    observer(&stepper.row());
    while !stepper.is_finished() {
        stepper.step()?;
        if stepper.k() % every == 0 || stepper.is_finished() {
            observer(&stepper.row());
        }
    }
    Ok(stepper.summary())
}

/// [`integrate_rigid`] keeping the rows.
pub fn solve_rigid<S: RigidSystem>(
    system: &S,
    problem: RigidProblem,
    method: &Method,
    every: usize,
) -> Result<RigidSolution, Error> {
    let mut rows = Vec::new();
    let summary = integrate_rigid(system, problem, method, every, |row| rows.push(row.clone()))?;
    Ok(RigidSolution { rows, summary })
}
