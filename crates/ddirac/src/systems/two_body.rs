//! Two bodies in the plane attracting each other with potential −k/|r|, in coordinates adapted to
//! translations: g = r1 (position of the first body), x = r = r2 − r1.
//!
//! ```text
//! L = ½ m1 |ṙ1|² + ½ m2 |ṙ1 + ṙ|² + k / |r|
//! ```
//!
//! G = ℝ² translates r1. The centre-of-mass connection, whose horizontal motions keep the centre of
//! mass fixed, is linear with K = h_{d,Σ} = −m2/(m1 + m2) · I ([`TwoBody::centre_of_mass_connection`]):
//! a system where the paper's maps h_{d,Q}, h_{d,Σ} and h_d^0 are all non-zero.

use num_dual::DualNum;

use crate::{Connection, Coordinate, Error, System};

/// Two bodies of masses `m1`, `m2` with attraction constant `k`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoBody {
    /// Mass of the first body.
    pub m1: f64,
    /// Mass of the second body.
    pub m2: f64,
    /// Attraction constant k (G m1 m2 for gravity).
    pub k: f64,
}

impl Default for TwoBody {
    fn default() -> Self {
        Self::default_parameters()
    }
}

impl TwoBody {
    /// m1 = 1, m2 = 0.5, k = 1.
    pub fn default_parameters() -> Self {
        Self { m1: 1.0, m2: 0.5, k: 1.0 }
    }

    /// K = −m2/(m1 + m2) · I, rows for (r1x, r1y), columns for (rx, ry); an error when it is not
    /// finite (m1 + m2 = 0).
    ///
    /// ```
    /// let k = ddirac::systems::TwoBody::default().centre_of_mass_connection().unwrap();
    /// assert_eq!(k.rows(), vec![vec![-1.0 / 3.0, 0.0], vec![0.0, -1.0 / 3.0]]);
    /// ```
    pub fn centre_of_mass_connection(&self) -> Result<Connection, Error> {
        let c = -self.m2 / (self.m1 + self.m2);
        Connection::new(&[vec![c, 0.0], vec![0.0, c]])
    }
}

impl super::Parameters for TwoBody {
    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![("m1", self.m1), ("m2", self.m2), ("k", self.k)]
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), Error> {
        match name {
            "m1" => self.m1 = super::positive(name, value)?,
            "m2" => self.m2 = super::positive(name, value)?,
            "k" => self.k = super::finite(name, value)?,
            _ => return Err(super::unknown_parameter(name, self)),
        }
        Ok(())
    }
}

impl System<4> for TwoBody {
    fn coordinates(&self) -> [Coordinate; 4] {
        [Coordinate::group("r1x"), Coordinate::group("r1y"), Coordinate::shape("rx"), Coordinate::shape("ry")]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 4], v: &[D; 4]) -> D {
        let (u, w) = (v[0] + v[2], v[1] + v[3]);
        let kinetic = (v[0] * v[0] + v[1] * v[1]) * (0.5 * self.m1) + (u * u + w * w) * (0.5 * self.m2);
        let distance = (q[2] * q[2] + q[3] * q[3]).sqrt();
        kinetic + distance.recip() * self.k
    }
}
