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
    // Every accepted step is kept (the last ends at T; the dense output's interpolation is not needed).
    let output = OutputType::Sparse;
    let mut solver = Dop853::from_param(
        Field(&field),
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
    );
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
