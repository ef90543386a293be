//! Double spherical pendulum (paper §7.2), in the paper's coordinates q = (ϑ1, φ1, ϑ2, φ2).
//!
//! With spherical angles (θ_i, φ_i) of each link (φ from the upward vertical, so the hanging rest is
//! φ = π), the paper's Lagrangian is
//!
//! ```text
//! L = ½ l1² m1 (φ̇1² + θ̇1² sin²φ1) + T2 − g m1 l1 cos φ1 − g m2 (l1 cos φ1 + l2 cos φ2)
//! T2 = ½ m2 (l1² φ̇1² + l2² φ̇2² + l1² θ̇1² sin²φ1 + l2² θ̇2² sin²φ2
//!      + 2 l1 l2 (φ̇1 φ̇2 sin φ1 sin φ2 + φ̇1 φ̇2 cos φ1 cos φ2 cos(θ1 − θ2)
//!      + φ̇1 θ̇2 sin φ2 sin(θ1 − θ2) cos φ1 − φ̇2 θ̇1 sin φ1 sin(θ1 − θ2) cos φ2
//!      + θ̇1 θ̇2 sin φ1 sin φ2 cos(θ1 − θ2)))
//! ```
//!
//! and the change ϑ1 = (θ1 + θ2)/2, ϑ2 = (θ2 − θ1)/2 makes the rotation about the vertical a
//! translation of ϑ1 alone: g = ϑ1, x = (φ1, ϑ2, φ2). The paper integrates it with the midpoint L_d,
//! m1 = 20, m2 = 35, l1 = 500, l2 = 800, g = 9.8, T = 100, N = 10⁴, q0 = (0, 9/4, 2, 3),
//! p0 = (μ0; w0) = (0, 0, 1, 1) ([`DoubleSphericalPendulum::paper_problem`]), and reports the reduced
//! run about 75 % faster than the unreduced one. The run passes within |sin φ| ≈ 2·10⁻³ of the lower
//! pole, where the chart is singular; that passage amplifies round-off about 10⁵×.

use num_dual::DualNum;

use crate::{Coordinate, Error, InitialMomentum, Problem, System};

/// The double spherical pendulum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoubleSphericalPendulum {
    /// Mass of the first bob.
    pub m1: f64,
    /// Mass of the second bob.
    pub m2: f64,
    /// Length of the first link.
    pub l1: f64,
    /// Length of the second link.
    pub l2: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl Default for DoubleSphericalPendulum {
    fn default() -> Self {
        Self::default_parameters()
    }
}

impl DoubleSphericalPendulum {
    /// The paper's parameters.
    pub fn default_parameters() -> Self {
        Self { m1: 20.0, m2: 35.0, l1: 500.0, l2: 800.0, g: 9.8 }
    }

    /// The paper's initial data with N steps over T = 100 (the paper uses N = 10⁴).
    pub fn paper_problem(steps: usize) -> Problem {
        Problem::new(
            100.0 / steps as f64,
            steps,
            vec![0.0, 2.25, 2.0, 3.0],
            InitialMomentum::Momentum(vec![0.0, 0.0, 1.0, 1.0]),
        )
    }

    /// Cartesian position of the second bob, relative to the pivot, at q = (ϑ1, φ1, ϑ2, φ2).
    ///
    /// ```
    /// use ddirac::systems::DoubleSphericalPendulum;
    /// let p = DoubleSphericalPendulum::default().second_bob(&[0.0, std::f64::consts::PI, 0.0, std::f64::consts::PI]);
    /// assert!((p[2] + 1300.0).abs() < 1e-9);
    /// ```
    pub fn second_bob(&self, q: &[f64; 4]) -> [f64; 3] {
        let (theta1, theta2) = (q[0] - q[2], q[0] + q[2]);
        let r =
            |l: f64, theta: f64, phi: f64| [l * phi.sin() * theta.cos(), l * phi.sin() * theta.sin(), l * phi.cos()];
        let (a, b) = (r(self.l1, theta1, q[1]), r(self.l2, theta2, q[3]));
        [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
    }
}

impl super::Parameters for DoubleSphericalPendulum {
    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![("m1", self.m1), ("m2", self.m2), ("l1", self.l1), ("l2", self.l2), ("g", self.g)]
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), Error> {
        match name {
            "m1" => self.m1 = super::positive(name, value)?,
            "m2" => self.m2 = super::positive(name, value)?,
            "l1" => self.l1 = super::positive(name, value)?,
            "l2" => self.l2 = super::positive(name, value)?,
            "g" => self.g = super::finite(name, value)?,
            _ => return Err(super::unknown_parameter(name, self)),
        }
        Ok(())
    }
}

impl System<4> for DoubleSphericalPendulum {
    fn coordinates(&self) -> [Coordinate; 4] {
        [
            Coordinate::group("vartheta1").angle(),
            Coordinate::shape("phi1").angle(),
            Coordinate::shape("vartheta2").angle(),
            Coordinate::shape("phi2").angle(),
        ]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 4], v: &[D; 4]) -> D {
        let Self { m1, m2, l1, l2, g } = *self;
        let (phi1, phi2) = (q[1], q[3]);
        // θ1 − θ2 = −2 ϑ2; θ̇1 = ϑ̇1 − ϑ̇2, θ̇2 = ϑ̇1 + ϑ̇2
        let dtheta = q[2] * -2.0;
        let (th1, ph1, th2, ph2) = (v[0] - v[2], v[1], v[0] + v[2], v[3]);
        let (s1, c1) = phi1.sin_cos();
        let (s2, c2) = phi2.sin_cos();
        let (sd, cd) = dtheta.sin_cos();
        let t1 = (ph1 * ph1 + th1 * th1 * s1 * s1) * (0.5 * l1 * l1 * m1);
        let cross = ph1 * ph2 * s1 * s2 + ph1 * ph2 * c1 * c2 * cd + ph1 * th2 * s2 * sd * c1
            - ph2 * th1 * s1 * sd * c2
            + th1 * th2 * s1 * s2 * cd;
        let t2 = (ph1 * ph1 * (l1 * l1)
            + ph2 * ph2 * (l2 * l2)
            + th1 * th1 * s1 * s1 * (l1 * l1)
            + th2 * th2 * s2 * s2 * (l2 * l2)
            + cross * (2.0 * l1 * l2))
            * (0.5 * m2);
        t1 + t2 - c1 * (g * m1 * l1) - (c1 * l1 + c2 * l2) * (g * m2)
    }
}
