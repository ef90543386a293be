//! A system on Q = SO(3) × S: an attitude R and shape coordinates s, with a Lagrangian in the body
//! angular velocity Ω = (RᵀṘ)^∨, the attitude and the shape.

use super::so3::Matrix3;
use crate::{Coordinate, Scalar};

/// The symmetry a rigid system declares: the subgroup of SO(3) acting on the attitude from the left
/// (R ↦ g R, a rotation of space) under which its Lagrangian is invariant.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Symmetry {
    /// No rotation of space leaves the Lagrangian invariant.
    None,
    /// Rotations of space about the vertical e3 (a heavy body in gravity −g e3): the vertical component
    /// e3 · R Π of the spatial angular momentum is conserved.
    Vertical,
    /// Every rotation of space (a free body, a satellite with internal rotors): the whole spatial
    /// angular momentum R Π is conserved, the Lagrangian does not depend on R,
    /// ℓ(R, Ω, s, ṡ) = ℓ(I, Ω, s, ṡ), and the motion reduces to (s, Ω, Π) (Euler–Poincaré /
    /// Lagrange–Poincaré) with R reconstructed.
    Rotations,
}

impl Symmetry {
    /// The name in specs and messages: `none`, `vertical`, `SO(3)`.
    pub fn name(self) -> &'static str {
        match self {
            Symmetry::None => "none",
            Symmetry::Vertical => "vertical",
            Symmetry::Rotations => "SO(3)",
        }
    }

    /// The components of the spatial angular momentum R Π the symmetry conserves (discrete Noether).
    pub fn conserved_components(self) -> &'static [usize] {
        match self {
            Symmetry::None => &[],
            Symmetry::Vertical => &[2],
            Symmetry::Rotations => &[0, 1, 2],
        }
    }
}

/// ℓ(R, Ω) = ½ ⟨Ω, 𝕀 Ω⟩ − ⟨e3, R w⟩ with 𝕀 = diag(`moments`) and w = `weight` (m g c for a body of mass
/// m in gravity −g e3 with its centre of mass at c in the body frame), and no shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipalAxes {
    /// The principal moments (I1, I2, I3), all positive.
    pub moments: [f64; 3],
    /// w = m g c: the potential is ⟨e3, R w⟩.
    pub weight: [f64; 3],
}

/// A system whose configuration is an attitude R ∈ SO(3) (body to space) and shape coordinates.
///
/// The Lagrangian is generic over the scalar, so that dual numbers give every derivative. A free
/// symmetric body:
///
/// ```
/// use ddirac::num_dual::DualNum;
/// use ddirac::rigid::{RigidSystem, Symmetry, so3::Matrix3};
/// struct Free;
/// impl RigidSystem for Free {
///     fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, _r: &Matrix3<D>, w: &[D; 3], _s: &[D], _v: &[D]) -> D {
///         (w[0] * w[0] + w[1] * w[1] + w[2] * w[2] * 2.0) * 0.5
///     }
///     fn symmetry(&self) -> Symmetry { Symmetry::Rotations }
/// }
/// assert_eq!(Free.lagrangian(&ddirac::rigid::so3::identity(), &[1.0, 0.0, 1.0], &[], &[]), 1.5);
/// ```
pub trait RigidSystem: Send + Sync {
    /// The shape coordinates s (none by default).
    fn shape(&self) -> Vec<Coordinate> {
        Vec::new()
    }

    /// ℓ(R, Ω, s, ṡ): R the attitude (rows of the matrix), Ω the body angular velocity, s and ṡ the
    /// shape coordinates and their velocities (as many as [`RigidSystem::shape`]).
    fn lagrangian<D: Scalar>(&self, r: &Matrix3<D>, omega: &[D; 3], s: &[D], v: &[D]) -> D;

    /// The rotations of space the Lagrangian is invariant under. The check tests it before a run.
    fn symmetry(&self) -> Symmetry;

    /// Where ℓ(R, Ω) = ½ ⟨Ω, 𝕀 Ω⟩ − ⟨e3, R w⟩ with 𝕀 = diag(I1, I2, I3) and no shape (a body in
    /// principal axes whose weight w = m g c pulls at its centre of mass c), the moments and w: the
    /// steps are then solved with their derivatives in closed form, on the stack, about two orders of
    /// magnitude faster than with dual numbers, to the same equations. A run tests the claim against
    /// [`RigidSystem::lagrangian`] and refuses a system whose Lagrangian differs. `None` (the default)
    /// differentiates the Lagrangian with dual numbers.
    fn principal_axes(&self) -> Option<PrincipalAxes> {
        None
    }
}

impl<S: RigidSystem> RigidSystem for &S {
    fn shape(&self) -> Vec<Coordinate> {
        (**self).shape()
    }

    fn lagrangian<D: Scalar>(&self, r: &Matrix3<D>, omega: &[D; 3], s: &[D], v: &[D]) -> D {
        (**self).lagrangian(r, omega, s, v)
    }

    fn symmetry(&self) -> Symmetry {
        (**self).symmetry()
    }

    fn principal_axes(&self) -> Option<PrincipalAxes> {
        (**self).principal_axes()
    }
}
