//! The engine's parts written over a dimension (`ddirac::dim`) give the same numbers, bit for bit,
//! whether the dimension is fixed when the engine is compiled or chosen at run time.

use ddirac::dim::{Dim, Dynamic, Fixed};
use ddirac::newton::{self, KeptJacobian};
use ddirac::NewtonOptions;
use nalgebra::{DMatrix, DVector, SMatrix, SVector};

/// r_i(z) = z_i³ + Σ_j a_ij z_j − c_i with a diagonally dominant: a root near 0 for each c.
fn residual(dim: impl Dim, z: &[f64], c: f64) -> (Vec<f64>, Vec<f64>) {
    let n = dim.n();
    let a = |i: usize, j: usize| if i == j { 4.0 + i as f64 * 0.1 } else { 1.0 / (1.0 + (i + 2 * j) as f64) };
    let r = (0..n).map(|i| z[i].powi(3) + (0..n).map(|j| a(i, j) * z[j]).sum::<f64>() - c * (i as f64 + 1.0).sin());
    let jac = (0..n * n).map(|k| {
        let (i, j) = (k / n, k % n);
        a(i, j) + if i == j { 3.0 * z[i] * z[i] } else { 0.0 }
    });
    (r.collect(), jac.collect())
}

fn fixed<const N: usize>(c: f64, chord: bool) -> (Vec<Vec<f64>>, Vec<newton::NewtonStats>) {
    let options = NewtonOptions { reuse_jacobian: chord, ..NewtonOptions::default() };
    let mut kept = KeptJacobian::with_relative_cost(8);
    let (mut roots, mut stats) = (Vec::new(), Vec::new());
    let mut z = SVector::<f64, N>::zeros();
    for k in 0..3 {
        let s = newton::solve_with(&mut z, 1.0, &options, &mut kept, |z, with_jacobian| {
            let (r, j) = residual(Fixed::<N>, z.as_slice(), c + k as f64);
            (SVector::from_column_slice(&r), with_jacobian.then(|| SMatrix::from_row_slice(&j)))
        })
        .unwrap();
        roots.push(z.as_slice().to_vec());
        stats.push(s);
    }
    (roots, stats)
}

fn dynamic(n: usize, c: f64, chord: bool) -> (Vec<Vec<f64>>, Vec<newton::NewtonStats>) {
    let options = NewtonOptions { reuse_jacobian: chord, ..NewtonOptions::default() };
    let mut kept = KeptJacobian::with_relative_cost(8);
    let (mut roots, mut stats) = (Vec::new(), Vec::new());
    let mut z = DVector::<f64>::zeros(n);
    for k in 0..3 {
        let s = newton::solve_with(&mut z, 1.0, &options, &mut kept, |z, with_jacobian| {
            let (r, j) = residual(Dynamic(n), z.as_slice(), c + k as f64);
            (DVector::from_column_slice(&r), with_jacobian.then(|| DMatrix::from_row_slice(n, n, &j)))
        })
        .unwrap();
        roots.push(z.as_slice().to_vec());
        stats.push(s);
    }
    (roots, stats)
}

fn assert_alike<const N: usize>() {
    for chord in [false, true] {
        let (roots, stats) = fixed::<N>(0.7, chord);
        let (dyn_roots, dyn_stats) = dynamic(N, 0.7, chord);
        assert_eq!(stats, dyn_stats, "n = {N}, chord {chord}");
        for (k, (z, w)) in roots.iter().zip(&dyn_roots).enumerate() {
            let same = z.iter().zip(w).all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "n = {N}, chord {chord}, solve {k}: {z:?} against {w:?}");
            // And a root: the residual at it is at round-off.
            let r = residual(Fixed::<N>, z, 0.7 + k as f64).0;
            assert!(r.iter().all(|x| x.abs() < 1e-12), "n = {N}, solve {k}: residual {r:?}");
        }
        if chord {
            // The kept Jacobian served the later solves: fewer Jacobians than solves.
            assert!(stats.iter().map(|s| s.jacobians).sum::<usize>() < 3, "{stats:?}");
        }
    }
}

#[test]
fn newton_solves_alike_in_a_fixed_and_a_dynamic_dimension() {
    assert_alike::<1>();
    assert_alike::<6>();
    assert_alike::<23>();
}

#[test]
fn newton_reports_a_singular_jacobian_in_a_dynamic_dimension() {
    let mut z = DVector::<f64>::from_element(3, 1.0);
    let failure = newton::solve(&mut z, 1.0, &NewtonOptions::default(), |z| {
        (z.map(|x| x * x + 1.0), DMatrix::from_element(3, 3, 2.0 * z[0]))
    })
    .unwrap_err();
    assert_eq!(failure.reason, newton::FailureReason::SingularJacobian);
}
