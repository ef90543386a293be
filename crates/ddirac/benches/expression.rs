//! The double spherical pendulum's discrete Lagrangian derivatives (`DiscreteLagrangian::derivatives`,
//! midpoint rule, h = 0.01, at the paper's q0 and a small increment) for the Lagrangian written in Rust
//! and for the same Lagrangian given as text, side by side in one group; and the compilation of that
//! text.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use ddirac::expression::{ExpressionSpec, ExpressionSystem};
use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{Coordinate, DiscreteLagrangian, Rule};

/// The Lagrangian of the module doc of `ddirac::systems::double_spherical_pendulum`, with
/// θ1 = ϑ1 − ϑ2 and θ2 = ϑ1 + ϑ2.
fn spec() -> ExpressionSpec {
    let string = |s: &str| s.to_owned();
    let cross = "phi1_dot*phi2_dot*sin(phi1)*sin(phi2) + phi1_dot*phi2_dot*cos(phi1)*cos(phi2)*cos(theta1 - theta2) \
                 + phi1_dot*theta2_dot*sin(phi2)*sin(theta1 - theta2)*cos(phi1) \
                 - phi2_dot*theta1_dot*sin(phi1)*sin(theta1 - theta2)*cos(phi2) \
                 + theta1_dot*theta2_dot*sin(phi1)*sin(phi2)*cos(theta1 - theta2)";
    let t2 = format!(
        "0.5*m2*(l1^2*phi1_dot^2 + l2^2*phi2_dot^2 + l1^2*theta1_dot^2*sin(phi1)^2 \
         + l2^2*theta2_dot^2*sin(phi2)^2 + 2*l1*l2*({cross}))"
    );
    ExpressionSpec {
        coordinates: vec![
            Coordinate::group("vartheta1").angle(),
            Coordinate::shape("phi1").angle(),
            Coordinate::shape("vartheta2").angle(),
            Coordinate::shape("phi2").angle(),
        ],
        lagrangian: string(
            "0.5*l1^2*m1*(phi1_dot^2 + theta1_dot^2*sin(phi1)^2) + T2 \
             - g*m1*l1*cos(phi1) - g*m2*(l1*cos(phi1) + l2*cos(phi2))",
        ),
        definitions: vec![
            (string("theta1"), string("vartheta1 - vartheta2")),
            (string("theta2"), string("vartheta1 + vartheta2")),
            (string("theta1_dot"), string("vartheta1_dot - vartheta2_dot")),
            (string("theta2_dot"), string("vartheta1_dot + vartheta2_dot")),
            (string("T2"), t2),
        ],
        parameters: [("m1", 20.0), ("m2", 35.0), ("l1", 500.0), ("l2", 800.0), ("g", 9.8)]
            .map(|(n, v)| (string(n), v))
            .to_vec(),
        exact_solution: vec![],
    }
}

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
