//! The Boris pusher for a charged particle in the constant magnetic field B = (0, 0, B0).
//!
//! The Lorentz law m q̈ = e q̇ × B is integrated with a staggered velocity v_{k+1/2} (leapfrog):
//!
//! ```text
//! t = (e B / m) (h/2),   s = 2 t / (1 + |t|²)
//! v′ = v_{k−1/2} + v_{k−1/2} × t
//! v_{k+1/2} = v_{k−1/2} + v′ × s
//! x_{k+1} = x_k + h v_{k+1/2}
//! ```
//!
//! (no electric field, so the two half kicks of the general pusher vanish). The rotation preserves
//! |v| exactly in exact arithmetic and turns v by 2 arctan(|t|) = ω h + O(h³) about B, with
//! ω = e B0 / m: the method is second order. The staggered velocity starts from v_{−1/2}, obtained by
//! rotating v0 back half a step with the same formula for the step −h/2.
//!
//! With B along z only the (x, y) components rotate, so the cross products are written out for
//! t = (0, 0, t_z).

/// A particle of charge `e` and mass `m` in the field B = (0, 0, `b0`).
///
/// ```
/// use ddirac::baselines::boris::Boris;
/// // The paper's particle (§7.1): q(t) = (sin t, cos t − 1, t).
/// let end = Boris { e: 1.0, m: 1.0, b0: 1.0 }.run(0.01, 2000, [0.0; 3], [1.0, 0.0, 1.0]);
/// let exact = [20f64.sin(), 20f64.cos() - 1.0, 20.0];
/// let error = (0..3).map(|i| (end.position[i] - exact[i]).powi(2)).sum::<f64>().sqrt();
/// assert!(error < 1e-3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Boris {
    /// Charge e.
    pub e: f64,
    /// Mass m.
    pub m: f64,
    /// Field strength B0.
    pub b0: f64,
}

/// Where a Boris run ends: the position x_N and the last staggered velocity v_{N−1/2}.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BorisEnd {
    /// x_N, the position at t = N h.
    pub position: [f64; 3],
    /// v_{N−1/2}, the velocity of the last drift.
    pub velocity: [f64; 3],
}

impl Boris {
    /// t_z = (e B0 / m)(h/2) and s_z = 2 t_z / (1 + t_z²) for a step `h`.
    fn rotation(&self, h: f64) -> (f64, f64) {
        let t = self.e * self.b0 / self.m * (0.5 * h);
        (t, 2.0 * t / (1.0 + t * t))
    }

    /// The Boris rotation of `v` about z with parameters (t, s).
    #[inline(always)]
    fn rotate(v: [f64; 3], (t, s): (f64, f64)) -> [f64; 3] {
        // v′ = v + v × t with t = (0, 0, t): v × t = (v_y t, −v_x t, 0)
        let (px, py) = (v[0] + v[1] * t, v[1] - v[0] * t);
        // v⁺ = v + v′ × s
        [v[0] + py * s, v[1] - px * s, v[2]]
    }

    /// Runs `steps` steps of size `h` from position `x0` and velocity `v0` at t = 0.
    pub fn run(&self, h: f64, steps: usize, x0: [f64; 3], v0: [f64; 3]) -> BorisEnd {
        let mut v = Self::rotate(v0, self.rotation(-0.5 * h));
        let mut x = x0;
        let rotation = self.rotation(h);
        for _ in 0..steps {
            v = Self::rotate(v, rotation);
            for (xi, vi) in x.iter_mut().zip(&v) {
                *xi += h * vi;
            }
        }
        BorisEnd { position: x, velocity: v }
    }
}
