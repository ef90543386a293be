//! The dual numbers ([`crate::ad`]) and each dimension's way of running them, against num-dual's
//! `partial_hessian` on functions that use every operation.

use crate::ad::Mixed;
use crate::Scalar;
use nalgebra::SVector;
use num_dual::{partial_hessian, HyperDualSVec64};

use super::*;

/// Uses every arithmetic operator and elementary function on values where all are defined.
struct Everything;

impl PairFunction<Fixed<3>> for Everything {
    fn eval<D: Scalar>(&self, a: &[D; 3], b: &[D; 3]) -> D {
        let (x, y, z) = (a[0], a[1], a[2]);
        let (u, v, w) = (b[0], b[1], b[2]);
        let t1 = x * u + y / v - z * 2.0 + w / 3.0 + (x - w) * (y + u);
        let t2 = (x * v).sin() + (y * w).cos() + (z + u).tan() * 0.1;
        let (s, c) = (x - u).sin_cos();
        let t3 = s * c + (x * x + v * v).sqrt() + (y * u).exp() * 0.01 + (z * z + w + 1.0).ln();
        let t4 = (x * 0.3).asin() + (u * 0.2).acos() + (y * w).atan() + y.atan2(u + 2.0);
        let t5 = (x * v).sinh() * 0.1 + (z * u).cosh() * 0.1 + (y * w).tanh();
        let t6 = (x * u).asinh() + (v + 2.0).acosh() + (w * 0.4).atanh();
        let t7 = (x + 2.0).powi(3) + (u + 2.0).powi(-2) + (y + 2.0).powf(2.5) + (v + 2.0).cbrt();
        let t8 = (x * w).exp2() * 0.1 + (u + 2.0).log(3.0) + (v + 2.0).log2() + (w + 2.0).log10();
        let t9 = (x * v).ln_1p() + (y * u).exp_m1() + (z - w).recip() + (x * u).sph_j0() + (y * v).sph_j1();
        let t10 = (z * w).sph_j2()
            + (x + u).abs()
            + (y - w) * (z + v).signum()
            + (x * x + 0.5).powd(u + 1.0)
            + x.mul_add(u, v);
        t1 + t2 + t3 + t4 + t5 + t6 + t7 + t8 + t9 + t10
    }
}

fn reference<F: PairFunction<Fixed<N>>, const N: usize>(
    f: &F,
    a: &[f64; N],
    b: &[f64; N],
) -> MixedDerivatives<Fixed<N>> {
    let (value, da, db, dadb) = partial_hessian(
        |(x, y): (SVector<HyperDualSVec64<N, N>, N>, SVector<HyperDualSVec64<N, N>, N>)| f.eval(&x.into(), &y.into()),
        (&SVector::from(*a), &SVector::from(*b)),
    );
    MixedDerivatives { value, da, db, dadb }
}

fn close(x: f64, y: f64) -> bool {
    (x - y).abs() <= 1e-13 * (1.0 + x.abs().max(y.abs()))
}

fn assert_same<const N: usize>(got: &MixedDerivatives<Fixed<N>>, want: &MixedDerivatives<Fixed<N>>) {
    assert!(close(got.value, want.value), "value {} vs {}", got.value, want.value);
    for i in 0..N {
        assert!(close(got.da[i], want.da[i]), "da[{i}] {} vs {}", got.da[i], want.da[i]);
        assert!(close(got.db[i], want.db[i]), "db[{i}] {} vs {}", got.db[i], want.db[i]);
        for j in 0..N {
            assert!(
                close(got.dadb[(i, j)], want.dadb[(i, j)]),
                "dadb[{i},{j}] {} vs {}",
                got.dadb[(i, j)],
                want.dadb[(i, j)]
            );
        }
    }
}

const POINTS: [([f64; 3], [f64; 3]); 3] =
    [([0.3, 0.7, -0.4], [0.5, 1.1, 0.2]), ([-0.6, 0.2, 0.9], [1.3, -0.5, 0.6]), ([1.1, -0.8, 0.35], [-0.7, 0.9, -0.3])];

#[test]
fn mixed_and_first_agree_with_num_dual() {
    for (a, b) in POINTS {
        let want = reference(&Everything, &a, &b);
        assert_same(&mixed(Fixed, &Everything, &a, &b), &want);
        let g = first(Fixed, &Everything, &a, &b);
        assert_same(&MixedDerivatives { value: g.value, da: g.da, db: g.db, dadb: want.dadb }, &want);
    }
}

/// A chain of couplings between many arguments, so that every entry of the mixed block is nonzero.
struct Coupled;

impl<Dm: Dim> PairFunction<Dm> for Coupled {
    fn eval<D: Scalar>(&self, a: &Dm::Array<D>, b: &Dm::Array<D>) -> D {
        let (a, b) = (a.as_ref(), b.as_ref());
        let n = a.len();
        let mut sa = D::from(0.0);
        let mut sb = D::from(0.0);
        let mut acc = D::from(0.0);
        for i in 0..n {
            sa += a[i] * (i as f64 + 1.0);
            sb += b[i] * (0.5 + i as f64 * 0.1);
            acc += (a[i] - b[(i + 1) % n]).sin() * b[i];
        }
        acc + (sa * 0.1).sin() * (sb * 0.2).cos() + sa * sb * sb * 0.01
    }
}

#[test]
fn chunked_equals_single_pass() {
    const N: usize = 15;
    let a: [f64; N] = std::array::from_fn(|i| 0.1 * i as f64 - 0.4);
    let b: [f64; N] = std::array::from_fn(|i| 0.3 - 0.05 * i as f64);
    const { assert!(N > CROSSOVER && !N.is_multiple_of(CHUNK), "covers a partial last chunk") };
    let single = mixed_single_pass(&Coupled, &a, &b);
    let chunked = mixed_chunked(&Coupled, &a, &b);
    assert_same(&chunked, &single);
    assert_same(&single, &reference(&Coupled, &a, &b));
    assert!(single.dadb.iter().all(|x| *x != 0.0));
}

fn same_bits(x: &[f64], y: &[f64]) -> bool {
    x.len() == y.len() && x.iter().zip(y).all(|(a, b)| a.to_bits() == b.to_bits())
}

fn assert_bits_equal<const N: usize>(
    fixed: &MixedDerivatives<Fixed<N>>,
    dynamic: &MixedDerivatives<Dynamic>,
    how: &str,
) {
    assert_eq!(fixed.value.to_bits(), dynamic.value.to_bits(), "n = {N}, {how}");
    assert!(same_bits(fixed.da.as_slice(), dynamic.da.as_slice()), "n = {N}, {how}: ∂f/∂a");
    assert!(same_bits(fixed.db.as_slice(), dynamic.db.as_slice()), "n = {N}, {how}: ∂f/∂b");
    assert!(same_bits(fixed.dadb.as_slice(), dynamic.dadb.as_slice()), "n = {N}, {how}: ∂²f/∂a∂b");
}

/// A dynamic dimension's derivatives (kernels as wide as n up to [`WIDEST`], blocks above) and
/// blocks at every n, against the fixed dimension's, bit for bit.
fn dynamic_equals_fixed<const N: usize>() {
    let a: [f64; N] = std::array::from_fn(|i| 0.1 * i as f64 - 0.4);
    let b: [f64; N] = std::array::from_fn(|i| 0.3 - 0.05 * i as f64);
    let (av, bv) = (a.to_vec(), b.to_vec());
    let fixed = mixed(Fixed, &Coupled, &a, &b);
    assert_bits_equal(&fixed, &mixed(Dynamic(N), &Coupled, &av, &bv), "as the dimension takes them");
    assert_bits_equal(&fixed, &mixed_blocks(Dynamic(N), &Coupled, &av, &bv), "blocks");
    let (fixed, dynamic) = (first(Fixed, &Coupled, &a, &b), first(Dynamic(N), &Coupled, &av, &bv));
    let blocks = first_blocks(Dynamic(N), &Coupled, &av, &bv);
    for d in [&dynamic, &blocks] {
        assert_eq!(fixed.value.to_bits(), d.value.to_bits(), "n = {N}");
        assert!(same_bits(fixed.da.as_slice(), d.da.as_slice()), "n = {N}: first ∂f/∂a");
        assert!(same_bits(fixed.db.as_slice(), d.db.as_slice()), "n = {N}: first ∂f/∂b");
    }
}

#[test]
fn a_dynamic_dimension_equals_a_fixed_one_bit_for_bit() {
    // Kernels of one pass and of column chunks (13, 16: above CROSSOVER, a partial last chunk at 13);
    // blocks: one block, a full block, several with a partial last one, and above WIDEST.
    dynamic_equals_fixed::<1>();
    dynamic_equals_fixed::<4>();
    dynamic_equals_fixed::<BLOCK>();
    dynamic_equals_fixed::<11>();
    dynamic_equals_fixed::<12>();
    dynamic_equals_fixed::<13>();
    dynamic_equals_fixed::<WIDEST>();
    dynamic_equals_fixed::<21>();
    let a: [f64; 21] = std::array::from_fn(|i| 0.1 * i as f64 - 0.4);
    let b: [f64; 21] = std::array::from_fn(|i| 0.3 - 0.05 * i as f64);
    assert_same(&mixed(Fixed, &Coupled, &a, &b), &reference(&Coupled, &a, &b));
}

#[test]
fn a_width_kernel_refuses_arguments_of_another_length() {
    let (a, b) = (vec![0.1, 0.2, 0.3], vec![0.4, 0.5, 0.6]);
    assert!(widths::mixed_width::<Coupled, 2>(&Coupled, &a, &b).is_none());
    assert!(widths::first_width::<Coupled, 4>(&Coupled, &a, &b).is_none());
    assert!(widths::mixed_width::<Coupled, 3>(&Coupled, &a, &b[..2]).is_none());
    assert!(widths::mixed_width::<Coupled, 3>(&Coupled, &a, &b).is_some());
}

#[test]
fn comparisons_and_conversions_use_the_value() {
    let (a, _) = Mixed::<2, 2>::seed(&[1.5, -2.0], &[0.0, 0.0], 0);
    assert!(a[0] > a[1] && a[0] > 1.0 && a[1] < -1.0);
    assert_eq!(num_traits::Signed::abs(&a[1]).a, [0.0, -1.0]);
    assert_eq!((a[0] % 1.0).re, 0.5);
    let total: Mixed<2, 2> = a.iter().copied().sum();
    assert_eq!((total.re, total.a), (-0.5, [1.0, 1.0]));
}
