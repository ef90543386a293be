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
//!
//! # The atlas
//!
//! The main chart is singular where either bob is at a pole (sin φ_i = 0): there its azimuth θ_i,
//! and with it ϑ1 and ϑ2, is undefined. Two more charts cover those places, each keeping a group
//! coordinate that the rotation about the vertical translates (so reduced runs go on in them):
//!
//! - chart 1, *first bob near a pole*: (θ2, a1, b1, φ2). The group coordinate is the second bob's
//!   azimuth θ2 (the first bob's is what degenerates). The first bob's direction, seen in the frame
//!   turned by θ2 about the vertical, u = (sin φ1 cos α, sin φ1 sin α, cos φ1) with α = θ1 − θ2 =
//!   −2ϑ2, is written in spherical angles about the frame's horizontal y axis:
//!   u = (sin a1 cos b1, cos a1, sin a1 sin b1). Both vertical poles u = ±e_z are regular points
//!   (a1 = π/2, b1 = ±π/2); the chart is singular only at u = ±e_y. The rotation about the vertical
//!   moves θ2 and leaves u: translation of θ2 alone. Back: α = atan2(u_y, u_x), ϑ2 = −α/2,
//!   ϑ1 = θ2 − ϑ2, φ1 = atan2(√(u_x² + u_y²), u_z).
//! - chart 2, *second bob near a pole*: (θ1, φ1, a2, b2), the same with the bobs' roles exchanged:
//!   α = θ2 − θ1 = 2ϑ2, ϑ2 = α/2, ϑ1 = θ1 + ϑ2.
//!
//! - charts 3 to 6, *both bobs near a pole*: (x1, y1, x2, y2), the horizontal components of both
//!   bobs' directions, each on its lower or upper hemisphere (lower–lower, lower–upper, upper–lower,
//!   upper–upper). Near the configuration with both bobs on the vertical axis, which the rotation
//!   fixes, no chart has a group coordinate: the rotation acts on these charts linearly, so their
//!   steps are unreduced and conserve the momentum map by the discrete Noether theorem (L_d by the
//!   midpoint or trapezoid rule is invariant under linear symmetries), to the Newton tolerance.
//!
//! Each chart's measure is the smaller of its two sines (|sin φ1|, |sin φ2| in the main chart;
//! sin a1 and |sin φ2| in chart 1; |sin φ1| and sin a2 in chart 2), and in charts 3 to 6 the smaller
//! of the two |cos φ_i| (the hemispheres' edges are their singular set).
//!
//! The Lagrangian of charts 3 to 6 is written out in the bobs' unit vectors
//! ([`System::chart_lagrangian`]): the composition L ∘ Tφ through the spherical angles computes the
//! same function with about five times as many operations (a test holds the two together).

use num_dual::DualNum;

use crate::{Chart, Coordinate, Error, InitialMomentum, Problem, Scalar, System};

/// The hemispheres of the charts with both bobs near a pole (charts 3 to 6): their names and
/// whether each bob's is the lower one.
const CAPS: [(&str, bool, bool); 4] = [
    ("lower, lower", true, true),
    ("lower, upper", true, false),
    ("upper, lower", false, true),
    ("upper, upper", false, false),
];

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

    fn charts(&self) -> Vec<Chart<4>> {
        let angle = |name: &str| Coordinate::shape(name).angle();
        let caps = CAPS.iter().map(|(name, _, _)| Chart {
            name: format!("both bobs near a pole ({name})"),
            coordinates: ["x1", "y1", "x2", "y2"].map(Coordinate::shape),
        });
        let mut charts = vec![
            Chart {
                name: "first bob near a pole".into(),
                coordinates: [Coordinate::group("theta2").angle(), angle("a1"), angle("b1"), angle("phi2")],
            },
            Chart {
                name: "second bob near a pole".into(),
                coordinates: [Coordinate::group("theta1").angle(), angle("phi1"), angle("a2"), angle("b2")],
            },
        ];
        charts.extend(caps);
        charts
    }

    fn chart_to_main<D: Scalar>(&self, chart: usize, q: &[D; 4]) -> [D; 4] {
        // The bob near its pole: (a, b) → its polar angle φ and its azimuth α relative to the other.
        let polar = |a: D, b: D| {
            let (sa, ca) = a.sin_cos();
            let (ux, uy, uz) = (sa * b.cos(), ca, sa * b.sin());
            ((ux * ux + uy * uy).sqrt().atan2(uz), uy.atan2(ux))
        };
        if chart >= 3 {
            let (_, lower1, lower2) = CAPS[chart - 3];
            let cap = |x: D, y: D, lower: bool| {
                let r2 = x * x + y * y;
                let z = (-r2 + 1.0).sqrt();
                (y.atan2(x), r2.sqrt().atan2(if lower { -z } else { z }))
            };
            let ((theta1, phi1), (theta2, phi2)) = (cap(q[0], q[1], lower1), cap(q[2], q[3], lower2));
            return [(theta1 + theta2) * 0.5, phi1, (theta2 - theta1) * 0.5, phi2];
        }
        if chart == 1 {
            let (phi1, alpha) = polar(q[1], q[2]);
            let vartheta2 = alpha * -0.5;
            [q[0] - vartheta2, phi1, vartheta2, q[3]]
        } else {
            let (phi2, alpha) = polar(q[2], q[3]);
            let vartheta2 = alpha * 0.5;
            [q[0] + vartheta2, q[1], vartheta2, phi2]
        }
    }

    fn main_to_chart<D: Scalar>(&self, chart: usize, q: &[D; 4]) -> [D; 4] {
        // The direction of a bob at polar angle φ and azimuth α relative to the other → (a, b).
        let about_y = |phi: D, alpha: D| {
            let (s, c) = phi.sin_cos();
            let (ux, uy, uz) = (s * alpha.cos(), s * alpha.sin(), c);
            ((ux * ux + uz * uz).sqrt().atan2(uy), uz.atan2(ux))
        };
        let (vartheta1, vartheta2) = (q[0], q[2]);
        if chart >= 3 {
            let (theta1, theta2) = (vartheta1 - vartheta2, vartheta1 + vartheta2);
            let (s1, s2) = (q[1].sin(), q[3].sin());
            return [s1 * theta1.cos(), s1 * theta1.sin(), s2 * theta2.cos(), s2 * theta2.sin()];
        }
        if chart == 1 {
            let (a1, b1) = about_y(q[1], vartheta2 * -2.0);
            [vartheta1 + vartheta2, a1, b1, q[3]]
        } else {
            let (a2, b2) = about_y(q[3], vartheta2 * 2.0);
            [vartheta1 - vartheta2, q[1], a2, b2]
        }
    }

    fn chart_lagrangian<D: Scalar>(&self, chart: usize, q: &[D; 4], v: &[D; 4]) -> Option<D> {
        // Charts 3 to 6: the bobs' directions u = (x, y, z), z = ∓√(1 − x² − y²) on the lower or upper
        // hemisphere (z = cos φ), u̇ = (ẋ, ẏ, −(x ẋ + y ẏ)/z); the paper's L is
        // ½ m1 l1² |u̇1|² + ½ m2 |l1 u̇1 + l2 u̇2|² − g m1 l1 z1 − g m2 (l1 z1 + l2 z2). The composition
        // through the spherical angles costs about five times as many operations.
        let (_, lower1, lower2) = *CAPS.get(chart.checked_sub(3)?)?;
        let Self { m1, m2, l1, l2, g } = *self;
        let bob = |x: D, y: D, vx: D, vy: D, lower: bool| {
            let w = (-(x * x + y * y) + 1.0).sqrt();
            let z = if lower { -w } else { w };
            (z, [vx, vy, -(x * vx + y * vy) / z])
        };
        let (z1, u1) = bob(q[0], q[1], v[0], v[1], lower1);
        let (z2, u2) = bob(q[2], q[3], v[2], v[3], lower2);
        let dot = |a: &[D; 3], b: &[D; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let kinetic = dot(&u1, &u1) * (0.5 * (m1 + m2) * l1 * l1)
            + dot(&u2, &u2) * (0.5 * m2 * l2 * l2)
            + dot(&u1, &u2) * (m2 * l1 * l2);
        Some(kinetic - z1 * (g * (m1 + m2) * l1) - z2 * (g * m2 * l2))
    }

    fn chart_quality<D: Scalar>(&self, chart: usize, q: &[D; 4]) -> D {
        let edge = |x: D, y: D| crate::chart::root_or_zero(-(x * x + y * y) + 1.0);
        let (first, second) = match chart {
            0 | 1 => (q[1].sin().abs(), q[3].sin().abs()),
            2 => (q[1].sin().abs(), q[2].sin().abs()),
            _ => (edge(q[0], q[1]), edge(q[2], q[3])),
        };
        first.min_of(second)
    }

    fn nearest_in_main(&self, q: [f64; 4], near: &[f64; 4], _kinds: &[crate::CoordinateKind; 4]) -> [f64; 4] {
        // ϑ1 ± π with ϑ2 ∓ π is one point (θ1 moved by a turn): move θ1 = ϑ1 − ϑ2 and θ2 = ϑ1 + ϑ2 by
        // whole turns instead of ϑ1 and ϑ2.
        let azimuths = |q: &[f64; 4]| [q[0] - q[2], q[1], q[0] + q[2], q[3]];
        let kinds = [crate::CoordinateKind::Angle; 4];
        let [theta1, phi1, theta2, phi2] = crate::chart::nearest_turns(azimuths(&q), &azimuths(near), &kinds);
        [0.5 * (theta1 + theta2), phi1, 0.5 * (theta2 - theta1), phi2]
    }
}
