//! A rigid body about a fixed point (or its centre of mass) in uniform gravity −g e3:
//!
//! ```text
//! ℓ(R, Ω) = ½ (I1 Ω1² + I2 Ω2² + I3 Ω3²) − m g ⟨e3, R c⟩
//! ```
//!
//! with principal moments I1, I2, I3 about the fixed point and the centre of mass c (in the body frame,
//! measured from the fixed point). With m |c| = 0 it is the free body, invariant under every rotation
//! of space (spatial angular momentum R Π and |Π| conserved; reducible by SO(3)); otherwise a heavy
//! top, invariant under rotations about the vertical (e3 · R Π conserved). Euler's equations
//! Π̇ = Π × Ω + m g (Γ × c), Γ = Rᵀ e3, Ṙ = R Ω̂ are its motion.

use crate::rigid::so3::Matrix3;
use crate::rigid::{PrincipalAxes, RigidSystem, Symmetry};
use crate::{Error, Scalar};

/// The rigid body `rigid_body`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody {
    /// Principal moments of inertia (I1, I2, I3).
    pub inertia: [f64; 3],
    /// The mass m.
    pub m: f64,
    /// Gravity g.
    pub g: f64,
    /// The centre of mass c in the body frame.
    pub c: [f64; 3],
}

impl Default for RigidBody {
    fn default() -> Self {
        Self::default_parameters()
    }
}

impl RigidBody {
    /// An asymmetric heavy top: I1 = 1, I2 = 2, I3 = 3, m = 1, g = 9.81, c = (0, 0, 0.1).
    pub fn default_parameters() -> Self {
        Self { inertia: [1.0, 2.0, 3.0], m: 1.0, g: 9.81, c: [0.0, 0.0, 0.1] }
    }

    /// The free body with principal moments I1, I2, I3.
    pub fn free(i1: f64, i2: f64, i3: f64) -> Self {
        Self { inertia: [i1, i2, i3], m: 0.0, g: 0.0, c: [0.0; 3] }
    }

    /// Whether gravity acts on it: m g |c| ≠ 0.
    pub fn is_heavy(&self) -> bool {
        self.m * self.g * (self.c[0].abs() + self.c[1].abs() + self.c[2].abs()) != 0.0
    }
}

impl super::Parameters for RigidBody {
    fn parameters(&self) -> Vec<(&'static str, f64)> {
        let [i1, i2, i3] = self.inertia;
        let [c1, c2, c3] = self.c;
        vec![("I1", i1), ("I2", i2), ("I3", i3), ("m", self.m), ("g", self.g), ("c1", c1), ("c2", c2), ("c3", c3)]
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), Error> {
        match name {
            "I1" => self.inertia[0] = super::positive(name, value)?,
            "I2" => self.inertia[1] = super::positive(name, value)?,
            "I3" => self.inertia[2] = super::positive(name, value)?,
            "m" => self.m = super::finite(name, value)?,
            "g" => self.g = super::finite(name, value)?,
            "c1" => self.c[0] = super::finite(name, value)?,
            "c2" => self.c[1] = super::finite(name, value)?,
            "c3" => self.c[2] = super::finite(name, value)?,
            _ => return Err(super::unknown_parameter(name, self)),
        }
        Ok(())
    }
}

impl RigidSystem for RigidBody {
    fn lagrangian<D: Scalar>(&self, r: &Matrix3<D>, omega: &[D; 3], _s: &[D], _v: &[D]) -> D {
        let [i1, i2, i3] = self.inertia;
        let kinetic = (omega[0] * omega[0] * i1 + omega[1] * omega[1] * i2 + omega[2] * omega[2] * i3) * 0.5;
        if !self.is_heavy() {
            return kinetic;
        }
        // ⟨e3, R c⟩ = the third row of R times c.
        let height = r[2][0] * self.c[0] + r[2][1] * self.c[1] + r[2][2] * self.c[2];
        kinetic - height * (self.m * self.g)
    }

    fn principal_axes(&self) -> Option<PrincipalAxes> {
        let weight = if self.is_heavy() { self.c.map(|c| self.m * self.g * c) } else { [0.0; 3] };
        Some(PrincipalAxes { moments: self.inertia, weight })
    }

    fn symmetry(&self) -> Symmetry {
        if self.is_heavy() {
            Symmetry::Vertical
        } else {
            Symmetry::Rotations
        }
    }
}
