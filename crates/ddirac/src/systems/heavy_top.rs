//! The heavy symmetric top in Euler angles q = (φ, θ, ψ): precession φ and spin ψ are cyclic
//! (G = T², two group angles), nutation θ is the shape coordinate.
//!
//! ```text
//! L = ½ I1 (θ̇² + φ̇² sin²θ) + ½ I3 (ψ̇ + φ̇ cos θ)² − M g l cos θ
//! ```
//!
//! The momentum map (p_φ, p_ψ) is conserved; with a fast spin ψ reaches hundreds of radians, where a
//! global chart would lose digits forming (ψ_{k+1} − ψ_k)/h.

use num_dual::DualNum;

use crate::{Coordinate, Error, System};

/// The heavy symmetric top.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeavyTop {
    /// Moment of inertia about a transverse axis through the pivot.
    pub i1: f64,
    /// Moment of inertia about the symmetry axis.
    pub i3: f64,
    /// M g l: mass × gravity × distance from the pivot to the centre of mass.
    pub mgl: f64,
}

impl Default for HeavyTop {
    fn default() -> Self {
        Self::default_parameters()
    }
}

impl HeavyTop {
    /// I1 = 1, I3 = 0.5, M g l = 1.
    pub fn default_parameters() -> Self {
        Self { i1: 1.0, i3: 0.5, mgl: 1.0 }
    }
}

impl super::Parameters for HeavyTop {
    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![("I1", self.i1), ("I3", self.i3), ("Mgl", self.mgl)]
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), Error> {
        match name {
            "I1" => self.i1 = super::positive(name, value)?,
            "I3" => self.i3 = super::positive(name, value)?,
            "Mgl" => self.mgl = super::finite(name, value)?,
            _ => return Err(super::unknown_parameter(name, self)),
        }
        Ok(())
    }
}

impl System<3> for HeavyTop {
    fn coordinates(&self) -> [Coordinate; 3] {
        [Coordinate::group("phi").angle(), Coordinate::shape("theta").angle(), Coordinate::group("psi").angle()]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 3], v: &[D; 3]) -> D {
        let (s, c) = q[1].sin_cos();
        let spin = v[2] + v[0] * c;
        (v[1] * v[1] + v[0] * v[0] * s * s) * (0.5 * self.i1) + spin * spin * (0.5 * self.i3) - c * self.mgl
    }
}
