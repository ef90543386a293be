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
//! a 2 × 2 system with determinant a² + c² > 0, solved in closed form. μ is conserved, so a, c and
//! the inverse matrix are the same at every step of a run and are computed once. These are the numbers the
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
    /// What every step with conserved momentum `mu` shares: a = m/h, c = μ B0/2 and the inverse of
    /// the 2 × 2 matrix, computed once per run (as the engine's closed-form step holds its constant
    /// matrices), so that a step is multiplications and additions only.
    fn invariants(&self, mu: f64) -> Invariants {
        let half = 0.5 * self.b0;
        let a = self.m / self.h;
        let c = mu * half;
        let det = a * a + c * c;
        Invariants { half, a, mu, h_mu: self.h * mu, inv: [a / det, c / det], inv_a: 1.0 / a }
    }

    /// One step (q_k, θ_k, w_k, μ) ↦ (q_{k+1}, θ_{k+1}, w_{k+1}, μ).
    #[inline]
    pub fn step(&self, s: &ReducedState) -> ReducedState {
        self.invariants(s.mu).step(s)
    }

    /// Runs `steps` steps from `start` and returns the last state: the same steps as
    /// [`ChargedParticleStep::step`], with the invariants of the run computed once.
    pub fn run(&self, start: ReducedState, steps: usize) -> ReducedState {
        let invariants = self.invariants(start.mu);
        let mut s = start;
        for _ in 0..steps {
            s = invariants.step(&s);
        }
        s
    }
}

/// The quantities every step of a run shares.
#[derive(Debug, Clone, Copy)]
struct Invariants {
    half: f64,
    a: f64,
    mu: f64,
    h_mu: f64,
    /// The first row of the inverse of [[a, −c], [c, a]]: (a, c)/det; the second is (−c, a)/det.
    inv: [f64; 2],
    inv_a: f64,
}

impl Invariants {
    #[inline(always)]
    fn step(&self, s: &ReducedState) -> ReducedState {
        let Self { half, a, mu, h_mu, inv: [i1, i2], inv_a } = *self;
        let [q1, q2, q3] = s.q;
        // A(q_k)
        let (a1, a2) = (-half * q2, half * q1);
        let (r1, r2) = (s.w[0] - mu * a1, s.w[1] - mu * a2);
        let d1 = i1 * r1 + i2 * r2;
        let d2 = i1 * r2 - i2 * r1;
        let d3 = s.w[2] * inv_a;
        ReducedState {
            q: [q1 + d1, q2 + d2, q3 + d3],
            theta: s.theta + (h_mu - (a1 * d1 + a2 * d2)),
            w: [a * d1 + mu * a1, a * d2 + mu * a2, a * d3],
            mu,
        }
    }
}
