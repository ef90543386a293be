//! Cost of the derivative blocks of one L_d evaluation, by scalar type: the double spherical
//! pendulum's midpoint L_d (h = 0.01) at the paper's q0 and a small increment, n = 4.
//!
//! - `num_dual_hyperdual`: num-dual's `partial_hessian` with `HyperDualSVec64<4, 4>` (value, D1, D2,
//!   D1D2 L_d);
//! - `mixed`: the same blocks with [`ddirac::ad::Mixed`] (what a Newton step with a fresh Jacobian uses);
//! - `first`: value, D1 and D2 only, with [`ddirac::ad::Gradient`] (what a residual check uses);
//! - `value`: L_d in f64, the arithmetic floor.
//!
//! `cargo bench -p ddirac --bench derivatives -- --noplot`

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{DiscreteLagrangian, Rule};
use nalgebra::SVector;
use num_dual::{partial_hessian, HyperDualSVec64};

fn derivatives(c: &mut Criterion) {
    let system = DoubleSphericalPendulum::default();
    let ld = DiscreteLagrangian::new(&system, Rule::Midpoint, 0.01);
    let base = [0.0, 2.25, 2.0, 3.0];
    let zero = SVector::<f64, 4>::zeros();
    let dq = SVector::from([0.001, 0.001, 0.0005, 0.002]);
    let mut group = c.benchmark_group("double_spherical_pendulum/ld_derivatives");
    group.bench_function("num_dual_hyperdual", |b| {
        b.iter(|| {
            partial_hessian(
                |(x, y): (SVector<HyperDualSVec64<4, 4>, 4>, SVector<HyperDualSVec64<4, 4>, 4>)| {
                    ld.eval_local(black_box(&base), &x.into(), &y.into())
                },
                (black_box(&zero), black_box(&dq)),
            )
        })
    });
    group.bench_function("mixed", |b| {
        b.iter(|| ld.derivatives_local(black_box(&base), black_box(&zero), black_box(&dq)))
    });
    group.bench_function("first", |b| {
        b.iter(|| ld.first_derivatives_local(black_box(&base), black_box(&zero), black_box(&dq)))
    });
    let q1: [f64; 4] = std::array::from_fn(|i| base[i] + dq[i]);
    group.bench_function("value", |b| b.iter(|| ld.value(black_box(&base), black_box(&q1))));
    group.finish();
}

criterion_group!(benches, derivatives);
criterion_main!(benches);
