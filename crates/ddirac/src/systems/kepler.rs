//! The Kepler problem in polar coordinates, q = (r, φ), with φ a cyclic angle (G = S¹).
//!
//! ```text
//! L = ½ m (ṙ² + r² φ̇²) + k / r
//! ```
//!
//! The momentum map is the angular momentum ℓ = p_φ = m r² φ̇. Bound orbits (energy E < 0) have the
//! exact solution of [`System::exact_solution`]: semi-major axis a = −k/(2E), eccentricity
//! e = √(1 + 2Eℓ²/(m k²)), mean motion n = √(k/(m a³)), r = a (1 − e cos 𝓔) with Kepler's equation
//! 𝓔 − e sin 𝓔 = M0 + n t, and φ − φ0 the change of true anomaly (signed by ℓ).

use num_dual::DualNum;

use crate::{Coordinate, Error, System};

/// A body of mass `m` attracted to the origin with potential −k/r.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kepler {
    /// Mass m.
    pub m: f64,
    /// Attraction constant k.
    pub k: f64,
}

impl Default for Kepler {
    fn default() -> Self {
        Self::default_parameters()
    }
}

impl Kepler {
    /// m = 1, k = 1.
    pub fn default_parameters() -> Self {
        Self { m: 1.0, k: 1.0 }
    }

    /// Eccentric anomaly from the mean anomaly, solving Kepler's equation 𝓔 − e sin 𝓔 = M by Newton.
    fn eccentric_anomaly(mean: f64, e: f64) -> f64 {
        let mut big_e = if e < 0.8 { mean } else { mean + e.copysign(mean.sin()) };
        for _ in 0..50 {
            let step = (big_e - e * big_e.sin() - mean) / (1.0 - e * big_e.cos());
            big_e -= step;
            if step.abs() <= 1e-15 * (1.0 + big_e.abs()) {
                break;
            }
        }
        big_e
    }

    /// True anomaly as a continuous function of the eccentric anomaly.
    fn true_anomaly(big_e: f64, e: f64) -> f64 {
        let beta = e / (1.0 + (1.0 - e * e).sqrt());
        big_e + 2.0 * (beta * big_e.sin()).atan2(1.0 - beta * big_e.cos())
    }
}

impl super::Parameters for Kepler {
    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![("m", self.m), ("k", self.k)]
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), Error> {
        match name {
            "m" => self.m = super::positive(name, value)?,
            "k" => self.k = super::positive(name, value)?,
            _ => return Err(super::unknown_parameter(name, self)),
        }
        Ok(())
    }
}

impl System<2> for Kepler {
    fn coordinates(&self) -> [Coordinate; 2] {
        [Coordinate::shape("r"), Coordinate::group("phi").angle()]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 2], v: &[D; 2]) -> D {
        let r = q[0];
        (v[0] * v[0] + r * r * v[1] * v[1]) * (0.5 * self.m) + r.recip() * self.k
    }

    /// The bound orbit through (q0, p0); `None` for unbound or degenerate (ℓ = 0) motion.
    ///
    /// ```
    /// use ddirac::{System, systems::Kepler};
    /// // Circular orbit of radius 1: φ = t.
    /// let q = Kepler::default().exact_solution(&[1.0, 0.0], &[0.0, 1.0], 2.0).unwrap();
    /// assert!((q[0].unwrap() - 1.0).abs() < 1e-12 && (q[1].unwrap() - 2.0).abs() < 1e-12);
    /// ```
    fn exact_solution(&self, q0: &[f64; 2], p0: &[f64; 2], t: f64) -> Option<[Option<f64>; 2]> {
        let (m, k) = (self.m, self.k);
        let (r0, ell) = (q0[0], p0[1]);
        let rdot = p0[0] / m;
        let energy = 0.5 * m * rdot * rdot + ell * ell / (2.0 * m * r0 * r0) - k / r0;
        if !(energy < 0.0 && r0 > 0.0 && ell != 0.0) {
            return None;
        }
        let a = -k / (2.0 * energy);
        let e = (1.0 + 2.0 * energy * ell * ell / (m * k * k)).max(0.0).sqrt();
        let n = (k / (m * a.powi(3))).sqrt();
        let e0 = if e < 1e-12 {
            0.0
        } else {
            let (cos_e, sin_e) = ((1.0 - r0 / a) / e, r0 * rdot / (e * (k * a / m).sqrt()));
            sin_e.atan2(cos_e)
        };
        let mean = e0 - e * e0.sin() + n * t;
        let big_e = Self::eccentric_anomaly(mean, e);
        let r = a * (1.0 - e * big_e.cos());
        let phi = q0[1] + ell.signum() * (Self::true_anomaly(big_e, e) - Self::true_anomaly(e0, e));
        Some([Some(r), Some(phi)])
    }
}
