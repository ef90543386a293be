//! DOP853 (the `ode_solvers` crate, feature `dop853`) on the Euler–Lagrange vector field of a
//! system, the peer of the work-precision race ([`super::race`]). Without the feature, [`integrate`]
//! answers `None` (`bench/mod.rs` declares that stand-in).

use ddirac::mechanics::euler_lagrange::EulerLagrange;
use ddirac::mechanics::legendre;
use ddirac::System;
use ode_solvers::{DVector, Dop853, OutputType};

/// The field as `ode_solvers` asks for it.
struct Field<'f, 'a, S, const N: usize>(&'f EulerLagrange<'a, S, N>);

impl<S: System<N>, const N: usize> ode_solvers::System<f64, DVector<f64>> for Field<'_, '_, S, N> {
    fn system(&self, _t: f64, y: &DVector<f64>, dy: &mut DVector<f64>) {
        self.0.field(y.as_slice(), dy.as_mut_slice());
    }
}

/// DOP853 for `field` from y0 over `duration` with relative and absolute tolerance `tolerance`:
/// Hairer's parameters of step-size control (safety 0.9, factors 1/3 … 6), at most 10⁷ steps, every
/// accepted step kept (the last ends at T; the dense output's interpolation is not needed).
fn solver<F: ode_solvers::System<f64, DVector<f64>>>(
    field: F,
    y0: DVector<f64>,
    duration: f64,
    tolerance: f64,
) -> Dop853<f64, DVector<f64>, F> {
    let output = OutputType::Sparse;
    Dop853::from_param(
        field,
        0.0,
        duration,
        duration,
        y0,
        tolerance,
        tolerance,
        0.9,
        0.0,
        1.0 / 3.0,
        6.0,
        duration,
        0.0,
        10_000_000,
        1000,
        output,
    )
}

/// Whether this build has the peer.
pub const AVAILABLE: bool = true;

/// q(T) from (q0, p0) with relative and absolute tolerance `tolerance`, and with `energy` the largest
/// |H − H₀|/|H₀| over the accepted steps (NaN without); the field's derivatives compiled (traced at
/// the initial data) as the engine's are. Hairer's parameters of step-size control (safety 0.9,
/// factors 1/3 … 6), at most 10⁷ steps. Always `Some` in this build.
pub fn integrate<S: System<N>, const N: usize>(
    system: &S,
    q0: &[f64; N],
    p0: &[f64; N],
    duration: f64,
    tolerance: f64,
    energy: bool,
) -> Option<Result<(Vec<f64>, f64), miette::Report>> {
    Some(solve(system, q0, p0, duration, tolerance, energy))
}

fn solve<S: System<N>, const N: usize>(
    system: &S,
    q0: &[f64; N],
    p0: &[f64; N],
    duration: f64,
    tolerance: f64,
    energy: bool,
) -> Result<(Vec<f64>, f64), miette::Report> {
    let v0 = legendre::velocity(system, q0, p0).0;
    let field = EulerLagrange::new(system, true, q0, &v0);
    let y0 = DVector::from_iterator(2 * N, q0.iter().chain(&v0).copied());
    let mut solver = solver(Field(&field), y0, duration, tolerance);
    solver.integrate().map_err(|e| miette::miette!("DOP853 at tolerance {tolerance:e} failed: {e}"))?;
    let last = solver.y_out().last().ok_or_else(|| miette::miette!("DOP853 gave no output"))?;
    let q: Vec<f64> = last.iter().take(N).copied().collect();
    if q.iter().any(|x| !x.is_finite()) {
        return Err(miette::miette!("DOP853 at tolerance {tolerance:e} ended with a non-finite state"));
    }
    let mut largest = f64::NAN;
    if energy {
        let h0 = legendre::hamiltonian(system, q0, p0);
        largest = 0.0;
        for y in solver.y_out() {
            let q: [f64; N] = std::array::from_fn(|i| y[i]);
            let v: [f64; N] = std::array::from_fn(|i| y[N + i]);
            let h = legendre::hamiltonian(system, &q, &legendre::momentum(system, &q, &v));
            largest = largest.max(((h - h0) / h0).abs());
        }
    }
    Ok((q, largest))
}

/// Euler's equations of a heavy rigid body in (R, Π), as `ode_solvers` asks for them: Ṙ = R Ω̂,
/// Π̇ = Π × Ω + Γ × w with Ω = I⁻¹Π, Γ = Rᵀe3 (R's third row) and w = m g c; y = (R by rows, Π).
struct RigidField {
    inertia: [f64; 3],
    weight: [f64; 3],
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

impl ode_solvers::System<f64, DVector<f64>> for RigidField {
    fn system(&self, _t: f64, y: &DVector<f64>, dy: &mut DVector<f64>) {
        let pi = [y[9], y[10], y[11]];
        let omega = [0, 1, 2].map(|i| pi[i] / self.inertia[i]);
        for i in 0..3 {
            // Row i of R Ω̂ is (row i of R) × Ω.
            let row = cross([y[3 * i], y[3 * i + 1], y[3 * i + 2]], omega);
            dy.as_mut_slice()[3 * i..3 * i + 3].copy_from_slice(&row);
        }
        let spin = cross(pi, omega);
        let torque = cross([y[6], y[7], y[8]], self.weight);
        for i in 0..3 {
            dy[9 + i] = spin[i] + torque[i];
        }
    }
}

/// R(T) of a heavy rigid body with principal moments `inertia` and weight w = m g c from
/// (R0, Π0), tolerances and step-size control as [`integrate`]; with `energy` the largest
/// |H − H₀|/|H₀| over the accepted steps, H = ½⟨Π, I⁻¹Π⟩ + ⟨e3, R w⟩ (NaN without). Always `Some`.
pub fn integrate_rigid(
    inertia: [f64; 3],
    weight: [f64; 3],
    r0: [[f64; 3]; 3],
    pi0: [f64; 3],
    duration: f64,
    tolerance: f64,
    energy: bool,
) -> Option<Result<RigidEnd, miette::Report>> {
    let y0 = DVector::from_iterator(12, r0.iter().flatten().chain(&pi0).copied());
    let mut solver = solver(RigidField { inertia, weight }, y0, duration, tolerance);
    let solved = solver.integrate().map_err(|e| miette::miette!("DOP853 at tolerance {tolerance:e} failed: {e}"));
    Some(solved.and_then(|_| {
        let last = solver.y_out().last().ok_or_else(|| miette::miette!("DOP853 gave no output"))?;
        if last.iter().any(|x| !x.is_finite()) {
            return Err(miette::miette!("DOP853 at tolerance {tolerance:e} ended with a non-finite state"));
        }
        let h = |y: &DVector<f64>| {
            (0..3).map(|i| 0.5 * y[9 + i] * y[9 + i] / inertia[i] + y[6 + i] * weight[i]).sum::<f64>()
        };
        let mut largest = f64::NAN;
        if energy {
            let h0 = h(&solver.y_out()[0]);
            largest = solver.y_out().iter().map(|y| ((h(y) - h0) / h0).abs()).fold(0.0, f64::max);
        }
        let r = [0, 1, 2].map(|i| [0, 1, 2].map(|j| last[3 * i + j]));
        Ok(RigidEnd { r, energy_error: largest })
    }))
}

/// The end of a rigid body's DOP853 run.
pub struct RigidEnd {
    /// R(T).
    pub r: [[f64; 3]; 3],
    /// The largest relative energy error over the accepted steps (NaN when not asked).
    pub energy_error: f64,
}
