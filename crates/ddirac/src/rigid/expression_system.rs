//! A rigid system whose Lagrangian is text: ℓ(R, Ω, s, ṡ) as an expression in the entries `R11` …
//! `R33` of the attitude (body to space), the body angular velocity `Omega1` … `Omega3`, the shape
//! coordinates and their velocities `<name>_dot`, the parameters and the definitions
//! ([`crate::expression`]'s language), with the symmetry it declares (tested before a run).

use super::so3::Matrix3;
use super::system::{RigidSystem, Symmetry};
use crate::expression::{compile_rigid, CompiledExpression, ExpressionError, ExpressionSpec};
use crate::{Coordinate, Scalar};

/// A rigid system of text: a satellite with a rotor about its third axis, say.
///
/// ```
/// use ddirac::expression::ExpressionSpec;
/// use ddirac::rigid::{RigidExpressionSystem, RigidSystem, Symmetry};
/// use ddirac::Coordinate;
/// let spec = ExpressionSpec {
///     coordinates: vec![Coordinate::shape("a").angle()],
///     lagrangian: "0.5*(J1*Omega1^2 + J2*Omega2^2 + J3*Omega3^2) + 0.5*K*(Omega3 + a_dot)^2".into(),
///     parameters: vec![("J1".into(), 1.0), ("J2".into(), 2.0), ("J3".into(), 3.0), ("K".into(), 0.1)],
///     ..ExpressionSpec::default()
/// };
/// let satellite = RigidExpressionSystem::new(&spec, Symmetry::Rotations).unwrap();
/// let identity = ddirac::rigid::so3::identity();
/// assert_eq!(satellite.lagrangian(&identity, &[0.0, 0.0, 1.0], &[0.0], &[1.0]), 0.5 * 3.0 + 0.5 * 0.1 * 4.0);
/// assert_eq!(satellite.shape()[0].name, "a");
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct RigidExpressionSystem {
    shape: Vec<Coordinate>,
    lagrangian: CompiledExpression,
    symmetry: Symmetry,
}

impl RigidExpressionSystem {
    /// Compiles the spec: its coordinates are the shape coordinates (none for a body alone); exact
    /// solutions and charts are not taken (refused with [`ExpressionError::Unsupported`]).
    pub fn new(spec: &ExpressionSpec, symmetry: Symmetry) -> Result<Self, ExpressionError> {
        if !spec.exact_solution.is_empty() || !spec.charts.is_empty() || spec.quality.is_some() {
            return Err(ExpressionError::Unsupported {
                what: "exact solutions and atlases of charts for a rigid body (its attitude needs no chart)".into(),
            });
        }
        Ok(Self { shape: spec.coordinates.clone(), lagrangian: compile_rigid(spec)?, symmetry })
    }
}

impl RigidSystem for RigidExpressionSystem {
    fn shape(&self) -> Vec<Coordinate> {
        self.shape.clone()
    }

    fn lagrangian<D: Scalar>(&self, r: &Matrix3<D>, omega: &[D; 3], s: &[D], v: &[D]) -> D {
        let n = self.shape.len();
        self.lagrangian.eval_with(|i| match i {
            0..=8 => r[i / 3][i % 3],
            9..=11 => omega[i - 9],
            _ if i < 12 + n => s[i - 12],
            _ => v[i - 12 - n],
        })
    }

    fn symmetry(&self) -> Symmetry {
        self.symmetry
    }
}
