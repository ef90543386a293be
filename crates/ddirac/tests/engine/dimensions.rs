//! The engine's parts written over a dimension (`ddirac::dim`) give the same numbers, bit for bit,
//! whether the dimension is fixed when the engine is compiled or chosen at run time: Newton's method
//! and compiled derivatives here, the dual numbers in the library's `ad` tests.

use ddirac::compiled::{CompiledPair, Traced};
use ddirac::dim::{self, PairFunction};
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

/// f(base, a, b) = Σ_i sin(q_i − q_{i+1}) v_i² + ½ (Σ q_i)² with q = base + a, v = b − a: every
/// derivative block is full.
fn coupled<T: ddirac::Scalar>(base: &[T], a: &[T], b: &[T]) -> T {
    let n = base.len();
    let q = |i: usize| base[i] + a[i];
    let v = |i: usize| b[i] - a[i];
    let mut sum = T::from(0.0);
    let mut total = T::from(0.0);
    for i in 0..n {
        sum += (q(i) - q((i + 1) % n)).sin() * v(i) * v(i);
        total += q(i);
    }
    sum + total * total * 0.5
}

fn compiled_alike<const N: usize>() {
    let base: [f64; N] = std::array::from_fn(|i| 0.2 * i as f64 - 0.3);
    let b: [f64; N] = std::array::from_fn(|i| 0.05 * (i as f64 + 1.0).cos());
    let fixed = CompiledPair::new(
        Fixed::<N>,
        |base: &[Traced; N], a: &[Traced; N], b: &[Traced; N]| coupled(base, a, b),
        &base,
        &b,
    )
    .unwrap();
    let dynamic = CompiledPair::new(
        Dynamic(N),
        |base: &Vec<Traced>, a: &Vec<Traced>, b: &Vec<Traced>| coupled(base, a, b),
        &base.to_vec(),
        &b.to_vec(),
    )
    .unwrap();
    assert_eq!(fixed.instructions, dynamic.instructions, "n = {N}");
    // At another point than the trace's.
    let (base, b) = (base.map(|x| x + 0.1), b.map(|x| 1.5 * x));
    let (first, mixed) = fixed.first_or_mixed(&base, &b, true).unwrap();
    let (dyn_first, dyn_mixed) = dynamic.first_or_mixed(&base.to_vec(), &b.to_vec(), true).unwrap();
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(first.value.to_bits(), dyn_first.value.to_bits());
    assert_eq!(bits(first.da.as_slice()), bits(dyn_first.da.as_slice()));
    assert_eq!(bits(first.db.as_slice()), bits(dyn_first.db.as_slice()));
    assert_eq!(bits(mixed.unwrap().as_slice()), bits(dyn_mixed.unwrap().as_slice()));
    // And both are the derivatives: against dual numbers in the dynamic dimension.
    struct F<'a>(&'a [f64]);
    impl PairFunction<Dynamic> for F<'_> {
        fn eval<D: ddirac::Scalar>(&self, a: &Vec<D>, b: &Vec<D>) -> D {
            let base: Vec<D> = self.0.iter().map(|&x| D::from(x)).collect();
            coupled(&base, a, b)
        }
    }
    let dual = dim::mixed(Dynamic(N), &F(&base), &vec![0.0; N], &b.to_vec());
    dynamic
        .check_against(
            &base.to_vec(),
            &b.to_vec(),
            (dim::FirstDerivatives { value: dual.value, da: dual.da, db: dual.db }, dual.dadb),
            1e-12,
        )
        .unwrap();
}

#[test]
fn compiled_derivatives_are_alike_in_a_fixed_and_a_dynamic_dimension() {
    compiled_alike::<1>();
    compiled_alike::<5>();
    compiled_alike::<17>();
}
