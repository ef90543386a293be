//! Charged particle in a constant magnetic field, in Kaluza–Klein form (paper §7.1).
//!
//! Q = ℝ³ × S¹ with q = (q1, q2, q3, θ); the symmetry shifts θ.
//!
//! ```text
//! L = ½ m |q̇|² + ½ (A(q)·q̇ + θ̇)²,   A(q) = (B0/2) (−q2, q1, 0)
//! ```
//!
//! The conserved p_θ = A·q̇ + θ̇ is the charge e; q follows the Lorentz law m q̈ = e q̇ × B with
//! B = (0, 0, B0), whose exact solution is [`System::exact_solution`]. The paper integrates it with the
//! left-rectangle L_d, m = 1, B0 = 1, T = 20, q0 = 0, θ0 = 0, w0 = (1, 0, 1), μ0 = 1; its Table 1 is
//! [`TABLE_1`].

use num_dual::DualNum;

use crate::{Coordinate, Error, InitialMomentum, Problem, System};

/// Paper Table 1: number of steps N over T = 20 and the error ‖q(T) − q_N‖.
pub const TABLE_1: [(usize, f64); 4] = [(10, 1.6781), (50, 0.25971), (100, 0.06626), (200, 0.01664)];

/// The charged particle with mass `m` in the field B = (0, 0, `b0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChargedParticle {
    /// Mass m.
    pub m: f64,
    /// Field strength B0.
    pub b0: f64,
}

impl Default for ChargedParticle {
    fn default() -> Self {
        Self::default_parameters()
    }
}

impl ChargedParticle {
    /// The paper's parameters: m = 1, B0 = 1.
    pub fn default_parameters() -> Self {
        Self { m: 1.0, b0: 1.0 }
    }

    /// The paper's problem with N steps over T = 20: q0 = 0, p0 = (1, 0, 1, 1).
    ///
    /// ```
    /// let problem = ddirac::systems::ChargedParticle::paper_problem(100);
    /// assert_eq!(problem.step, 0.2);
    /// ```
    pub fn paper_problem(steps: usize) -> Problem {
        Problem::new(20.0 / steps as f64, steps, vec![0.0; 4], InitialMomentum::Momentum(vec![1.0, 0.0, 1.0, 1.0]))
    }

    fn potential<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 4]) -> [D; 3] {
        let half = 0.5 * self.b0;
        [-q[1] * half, q[0] * half, D::from(0.0)]
    }
}

impl super::Parameters for ChargedParticle {
    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![("m", self.m), ("B0", self.b0)]
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), Error> {
        match name {
            "m" => self.m = super::positive(name, value)?,
            "B0" => self.b0 = super::finite(name, value)?,
            _ => return Err(super::unknown_parameter(name, self)),
        }
        Ok(())
    }
}

impl System<4> for ChargedParticle {
    fn coordinates(&self) -> [Coordinate; 4] {
        [Coordinate::shape("q1"), Coordinate::shape("q2"), Coordinate::shape("q3"), Coordinate::group("theta").angle()]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 4], v: &[D; 4]) -> D {
        let a = self.potential(q);
        let kinetic = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * (0.5 * self.m);
        let coupling = a[0] * v[0] + a[1] * v[1] + a[2] * v[2] + v[3];
        kinetic + coupling * coupling * 0.5
    }

    /// Helical motion: z uniform, (q1, q2) on a circle at the cyclotron frequency ω = e B0 / m with
    /// e = p_θ. θ is not given.
    fn exact_solution(&self, q0: &[f64; 4], p0: &[f64; 4], t: f64) -> Option<[Option<f64>; 4]> {
        let e = p0[3];
        let a = self.potential(q0);
        let v: [f64; 3] = std::array::from_fn(|i| (p0[i] - e * a[i]) / self.m);
        let omega = e * self.b0 / self.m;
        let (x, y) = if omega.abs() < 1e-300 {
            (q0[0] + v[0] * t, q0[1] + v[1] * t)
        } else {
            let (s, c) = (omega * t).sin_cos();
            (q0[0] + (v[0] * s - v[1] * c + v[1]) / omega, q0[1] + (v[1] * s + v[0] * c - v[0]) / omega)
        };
        Some([Some(x), Some(y), Some(q0[2] + v[2] * t), None])
    }
}
