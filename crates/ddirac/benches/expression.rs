//! The double spherical pendulum's discrete Lagrangian derivatives (`DiscreteLagrangian::derivatives`,
//! midpoint rule, h = 0.01, at the paper's q0 and a small increment) for the Lagrangian written in Rust
//! and for the same Lagrangian given as text, side by side in one group; and the compilation of that
//! text.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use ddirac::expression::ExpressionSystem;
use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{DiscreteLagrangian, Rule};

#[path = "../tests/common/pendulum_text.rs"]
mod pendulum_text;
use pendulum_text::double_spherical_pendulum_spec as spec;

fn derivatives(c: &mut Criterion) {
    let rust = DoubleSphericalPendulum::default();
    let text = ExpressionSystem::<4>::new(&spec()).expect("the spec compiles");
    let q0 = [0.0, 2.25, 2.0, 3.0];
    let q1 = [0.001, 2.251, 2.0005, 3.002];
    let mut group = c.benchmark_group("double_spherical_pendulum/derivatives");
    group.bench_function("rust", |b| {
        let ld = DiscreteLagrangian::new(&rust, Rule::Midpoint, 0.01);
        b.iter(|| ld.derivatives(black_box(&q0), black_box(&q1)))
    });
    group.bench_function("expression", |b| {
        let ld = DiscreteLagrangian::new(&text, Rule::Midpoint, 0.01);
        b.iter(|| ld.derivatives(black_box(&q0), black_box(&q1)))
    });
    group.finish();
}

fn compile(c: &mut Criterion) {
    let spec = spec();
    c.bench_function("double_spherical_pendulum/compile", |b| {
        b.iter(|| ExpressionSystem::<4>::new(black_box(&spec)).expect("the spec compiles"))
    });
}

criterion_group!(benches, derivatives, compile);
criterion_main!(benches);
