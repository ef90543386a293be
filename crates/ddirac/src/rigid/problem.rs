//! A rigid system's problem: the step, the number of steps and the initial data (R0, Π0 or Ω0, s0, p0
//! or ṡ0), validated before a run.

use super::so3::{self, Matrix3};
use crate::{Error, Input, Reason};

/// How far R0 may be from a rotation: |RᵀR − I| and |det R − 1| at most this.
pub const ROTATION_TOLERANCE: f64 = 1e-12;

/// The initial velocities or momenta of a rigid system.
#[derive(Debug, Clone, PartialEq)]
pub enum RigidInitial {
    /// The body angular momentum Π0 and the shape momenta p0.
    Momentum {
        /// Π0.
        pi: [f64; 3],
        /// p0, one per shape coordinate.
        p: Vec<f64>,
    },
    /// The body angular velocity Ω0 and the shape velocities ṡ0; the momenta are their Legendre
    /// transform.
    Velocity {
        /// Ω0.
        omega: [f64; 3],
        /// ṡ0, one per shape coordinate.
        v: Vec<f64>,
    },
}

/// Step, number of steps and initial data of a rigid system.
///
/// ```
/// use ddirac::rigid::{RigidInitial, RigidProblem};
/// let problem = RigidProblem::new(0.01, 100, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
///     RigidInitial::Velocity { omega: [0.0, 1.0, 0.1], v: vec![] });
/// assert!(problem.validate(0).is_ok());
/// let tilted = RigidProblem { r0: [[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], ..problem };
/// assert!(tilted.validate(0).unwrap_err().to_string().starts_with("invalid initial attitude R: not a rotation"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct RigidProblem {
    /// The step h.
    pub step: f64,
    /// The number of steps N.
    pub steps: usize,
    /// R0 (body to space), rows.
    pub r0: Matrix3<f64>,
    /// The initial shape s0, one per shape coordinate.
    pub s0: Vec<f64>,
    /// The initial momenta or velocities.
    pub initial: RigidInitial,
}

impl RigidProblem {
    /// A problem without shape coordinates beyond those `initial` names (s0 = 0 for each).
    pub fn new(step: f64, steps: usize, r0: Matrix3<f64>, initial: RigidInitial) -> Self {
        let n = match &initial {
            RigidInitial::Momentum { p, .. } => p.len(),
            RigidInitial::Velocity { v, .. } => v.len(),
        };
        Self { step, steps, r0, s0: vec![0.0; n], initial }
    }

    /// Refuses a step that is not positive and finite, non-finite data, vectors of another size than
    /// the `shape` coordinates, and an R0 that is not a rotation to [`ROTATION_TOLERANCE`].
    pub fn validate(&self, shape: usize) -> Result<(), Error> {
        if !(self.step.is_finite() && self.step > 0.0) {
            return Err(Error::Invalid { what: Input::Step, why: Reason::NotPositiveFinite { value: self.step } });
        }
        if self.steps == 0 {
            return Err(Error::Invalid { what: Input::Steps, why: Reason::Zero });
        }
        finite(Input::InitialAttitude, self.r0.iter().flatten())?;
        let orthogonality = so3::orthogonality_error(&self.r0);
        let determinant = so3::determinant(&self.r0);
        if !(orthogonality <= ROTATION_TOLERANCE && (determinant - 1.0).abs() <= ROTATION_TOLERANCE) {
            let why = Reason::NotARotation { orthogonality, determinant, tolerance: ROTATION_TOLERANCE };
            return Err(Error::Invalid { what: Input::InitialAttitude, why });
        }
        sized(Input::InitialConfiguration, &self.s0, shape)?;
        match &self.initial {
            RigidInitial::Momentum { pi, p } => {
                finite(Input::InitialAngularMomentum, pi)?;
                sized(Input::InitialMomentum, p, shape)
            }
            RigidInitial::Velocity { omega, v } => {
                finite(Input::InitialAngularVelocity, omega)?;
                sized(Input::InitialVelocity, v, shape)
            }
        }
    }
}

fn finite<'a>(what: Input, values: impl IntoIterator<Item = &'a f64>) -> Result<(), Error> {
    match values.into_iter().enumerate().find(|(_, x)| !x.is_finite()) {
        Some((entry, &value)) => Err(Error::NonFinite { what, entry: Some(entry), value }),
        None => Ok(()),
    }
}

fn sized(what: Input, values: &[f64], expected: usize) -> Result<(), Error> {
    if values.len() != expected {
        return Err(Error::Size { what, expected, found: values.len() });
    }
    finite(what, values)
}
