//! Spherical pendulum with its atlas of charts (paper §6), in coordinates q = (θ, φ): θ the azimuth
//! (the group coordinate: rotations about the vertical translate it), φ the polar angle from the
//! upward vertical (hanging rest at φ = π), as the double spherical pendulum's links (§7.2):
//!
//! ```text
//! L = ½ m l² (φ̇² + sin²φ θ̇²) − m g l cos φ
//! ```
//!
//! The chart is singular at the poles sin φ = 0, which a motion with a small angular momentum
//! p_θ = m l² sin²φ θ̇ passes closely: near them θ turns by about π in a few hundredths of a
//! second. The atlas adds two charts without that singularity, the horizontal position of the bob
//! (x, y) = (sin φ cos θ, sin φ sin θ) on the lower and on the upper hemisphere (good where
//! |cos φ| is large). The rotations about the vertical act on (x, y) linearly, not by translation,
//! so these charts have no group coordinate: there the steps are unreduced, and the momentum map
//! J = x p_y − y p_x is conserved because L_d (midpoint or trapezoid) is invariant under linear
//! symmetries (the discrete Noether theorem), to the Newton tolerance.

use num_dual::DualNum;

use crate::{Chart, Coordinate, Error, Scalar, System};

/// The spherical pendulum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphericalPendulum {
    /// Mass of the bob.
    pub m: f64,
    /// Length of the rod.
    pub l: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl Default for SphericalPendulum {
    fn default() -> Self {
        Self { m: 1.0, l: 1.0, g: 9.8 }
    }
}

/// The charts of the atlas after the main one: the lower cap (index 1) and the upper cap (index 2).
const CAPS: [(&str, f64); 2] = [("lower cap (x, y)", -1.0), ("upper cap (x, y)", 1.0)];

impl SphericalPendulum {
    /// The position of the bob on the unit sphere at q = (θ, φ) (z upward).
    ///
    /// ```
    /// use ddirac::systems::SphericalPendulum;
    /// let r = SphericalPendulum::default().unit_position(&[0.0, std::f64::consts::PI]);
    /// assert!((r[2] + 1.0).abs() < 1e-15);
    /// ```
    pub fn unit_position(&self, q: &[f64; 2]) -> [f64; 3] {
        let (s, c) = q[1].sin_cos();
        [s * q[0].cos(), s * q[0].sin(), c]
    }
}

impl super::Parameters for SphericalPendulum {
    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![("m", self.m), ("l", self.l), ("g", self.g)]
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), Error> {
        match name {
            "m" => self.m = super::positive(name, value)?,
            "l" => self.l = super::positive(name, value)?,
            "g" => self.g = super::finite(name, value)?,
            _ => return Err(super::unknown_parameter(name, self)),
        }
        Ok(())
    }
}

impl System<2> for SphericalPendulum {
    fn coordinates(&self) -> [Coordinate; 2] {
        [Coordinate::group("theta").angle(), Coordinate::shape("phi").angle()]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 2], v: &[D; 2]) -> D {
        let Self { m, l, g } = *self;
        let (s, c) = q[1].sin_cos();
        (v[1] * v[1] + s * s * v[0] * v[0]) * (0.5 * m * l * l) - c * (m * g * l)
    }

    fn charts(&self) -> Vec<Chart<2>> {
        CAPS.iter()
            .map(|(name, _)| Chart {
                name: (*name).into(),
                coordinates: [Coordinate::shape("x"), Coordinate::shape("y")],
            })
            .collect()
    }

    fn chart_to_main<D: Scalar>(&self, chart: usize, q: &[D; 2]) -> [D; 2] {
        let side = CAPS[chart - 1].1;
        let [x, y] = *q;
        let r2 = x * x + y * y;
        let z = (-r2 + 1.0).sqrt() * side;
        [y.atan2(x), r2.sqrt().atan2(z)]
    }

    fn main_to_chart<D: Scalar>(&self, _chart: usize, q: &[D; 2]) -> [D; 2] {
        let s = q[1].sin();
        [s * q[0].cos(), s * q[0].sin()]
    }

    fn chart_quality<D: DualNum<Primitive = f64> + Copy>(&self, chart: usize, q: &[D; 2]) -> D {
        match chart {
            0 => q[1].sin().abs(),
            _ => crate::chart::root_or_zero(-(q[0] * q[0] + q[1] * q[1]) + 1.0),
        }
    }
}
