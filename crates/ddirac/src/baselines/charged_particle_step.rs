//! The reduced (+) left-rule step of the charged particle, written out by hand (paper eq.
//! `reduceddiscreteequationsem`).
//!
//! With L = ½ m |q̇|² + ½ (A(q)·q̇ + θ̇)², A(q) = (B0/2)(−q2, q1, 0), the left-rectangle L_d and
//! K = 0, the reduced (+) equations read, for Δ = q_{k+1} − q_k and μ = μ_k = μ_{k+1},
//!
//! ```text
//! (m/h) Δ − μ (∇⟨A, Δ⟩ − A(q_k)) = w_k
//! w_{k+1} = (m/h) Δ + μ A(q_k)
//! θ_{k+1} − θ_k = h μ − ⟨A(q_k), Δ⟩
//! ```
//!
//! where ∇⟨A, Δ⟩ = (B0/2)(Δ2, −Δ1, 0) is the gradient of q ↦ ⟨A(q), Δ⟩. The first equation is
//! linear in Δ: with a = m/h and c = μ B0/2,
//!
//! ```text
//! ⎡ a  −c ⎤ ⎡Δ1⎤   ⎡w1 − μ A1(q_k)⎤
//! ⎣ c   a ⎦ ⎣Δ2⎦ = ⎣w2 − μ A2(q_k)⎦,      a Δ3 = w3,
//! ```
//!
//! a 2 × 2 system with determinant a² + c² > 0, solved in closed form. These are the numbers the
//! generic engine computes for [`ChargedParticle`](crate::systems::ChargedParticle) with
//! [`Rule::Left`](crate::Rule::Left), reduced, (+), by automatic differentiation and Newton's method.

/// The step map of a particle of mass `m` in the field B = (0, 0, `b0`) with step `h`.
///
/// ```
/// use ddirac::baselines::charged_particle_step::{ChargedParticleStep, ReducedState};
/// // Paper §7.1, N = 200 over T = 20: Table 1 gives ‖q(T) − q_N‖ = 0.01664.
/// let stepper = ChargedParticleStep { m: 1.0, b0: 1.0, h: 0.1 };
/// let start = ReducedState { q: [0.0; 3], theta: 0.0, w: [1.0, 0.0, 1.0], mu: 1.0 };
/// let end = stepper.run(start, 200);
/// let exact = [20f64.sin(), 20f64.cos() - 1.0, 20.0];
/// let error = (0..3).map(|i| (end.q[i] - exact[i]).powi(2)).sum::<f64>().sqrt();
/// assert!((error - 0.01664).abs() < 5e-6);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChargedParticleStep {
    /// Mass m.
    pub m: f64,
    /// Field strength B0.
    pub b0: f64,
    /// Step size h.
    pub h: f64,
}

/// A point (q, θ, w, μ) of the reduced phase space; w = p_q and μ = p_θ (K = 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReducedState {
    /// Position q ∈ ℝ³.
    pub q: [f64; 3],
    /// The group angle θ, continuous (not wrapped).
    pub theta: f64,
    /// Reduced momentum w ∈ (ℝ³)*.
    pub w: [f64; 3],
    /// Momentum map μ = p_θ (the charge), constant along the motion.
    pub mu: f64,
}

impl ChargedParticleStep {
    /// One step (q_k, θ_k, w_k, μ) ↦ (q_{k+1}, θ_{k+1}, w_{k+1}, μ).
    #[inline]
    pub fn step(&self, s: &ReducedState) -> ReducedState {
        let half = 0.5 * self.b0;
        let [q1, q2, q3] = s.q;
        let mu = s.mu;
        // A(q_k)
        let (a1, a2) = (-half * q2, half * q1);
        let a = self.m / self.h;
        let c = mu * half;
        let (r1, r2) = (s.w[0] - mu * a1, s.w[1] - mu * a2);
        let det = a * a + c * c;
        let d1 = (a * r1 + c * r2) / det;
        let d2 = (a * r2 - c * r1) / det;
        let d3 = s.w[2] / a;
        ReducedState {
            q: [q1 + d1, q2 + d2, q3 + d3],
            theta: s.theta + (self.h * mu - (a1 * d1 + a2 * d2)),
            w: [a * d1 + mu * a1, a * d2 + mu * a2, a * d3],
            mu,
        }
    }

    /// Runs `steps` steps from `start` and returns the last state.
    pub fn run(&self, start: ReducedState, steps: usize) -> ReducedState {
        let mut s = start;
        for _ in 0..steps {
            s = self.step(&s);
        }
        s
    }
}
