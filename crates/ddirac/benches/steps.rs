//! Time per step of the generic engine ([`ddirac::integrate`]) and of the hand-written baselines.
//!
//! Every benchmark runs about 1000 steps per iteration and declares them as its throughput
//! (`Throughput::Elements`), so criterion reports steps per second; time per step is the iteration
//! time divided by the number of steps. Engine runs report only the first and the last rows
//! (`every` = 10⁶) to an observer that does nothing; the per-run setup (Legendre transform of the
//! initial data, invariance check, summary) is included and spread over the steps.
//!
//! - charged particle (paper §7.1, h = 0.02, N = 1000 over T = 20): left and midpoint rules,
//!   reduced/unreduced × (+)/(−), the specialised reduced (+) left step and the Boris pusher;
//! - double spherical pendulum (paper §7.2, h = 0.01): its first 1000 steps, midpoint,
//!   reduced/unreduced × (+)/(−);
//! - Kepler (eccentric orbit, h = 0.01) and heavy top (fast spin, h = 10⁻³): midpoint,
//!   reduced and unreduced (+).
//!
//! The unreduced (+) and (−) equations are the same map (see `mechanics::dirac`), so their two
//! timings show the noise of the measurement.
//!
//! `cargo bench -p ddirac --bench steps -- --noplot`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, measurement::WallTime, BenchmarkGroup, Criterion, Throughput};
use ddirac::baselines::boris::Boris;
use ddirac::baselines::charged_particle_step::{ChargedParticleStep, ReducedState};
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, HeavyTop, Kepler};
use ddirac::{integrate, InitialMomentum, Method, OutputOptions, Problem, Rule, System, Variant};

const STEPS: usize = 1000;

/// Reduced/unreduced and (+)/(−) of a rule, named `rule/reduced/plus` and so on.
fn methods(rule: Rule, variants: &[(bool, Variant)]) -> Vec<(String, Method)> {
    variants
        .iter()
        .map(|&(reduced, variant)| {
            let name = format!("{}/{}/{}", rule.name(), if reduced { "reduced" } else { "unreduced" }, variant.name());
            (name, Method { rule, variant, reduced, ..Method::default() })
        })
        .collect()
}

const ALL: [(bool, Variant); 4] =
    [(true, Variant::Plus), (true, Variant::Minus), (false, Variant::Plus), (false, Variant::Minus)];
const PLUS: [(bool, Variant); 2] = [(true, Variant::Plus), (false, Variant::Plus)];

fn group<'a>(c: &'a mut Criterion, name: &str) -> BenchmarkGroup<'a, WallTime> {
    let mut group = c.benchmark_group(name);
    group.sample_size(20).warm_up_time(Duration::from_secs(1)).measurement_time(Duration::from_secs(3));
    group.throughput(Throughput::Elements(STEPS as u64));
    group
}

fn engine<S: System<N>, const N: usize>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    system: &S,
    problem: &Problem,
    methods: &[(String, Method)],
) {
    assert_eq!(problem.steps, STEPS);
    let output = OutputOptions { every: 1_000_000, wrap_angles: false };
    for (name, method) in methods {
        group.bench_function(name.as_str(), |b| {
            b.iter(|| {
                integrate(black_box(system), black_box(problem), method, &output, &mut |_| Ok(()))
                    .expect("the run succeeds")
            })
        });
    }
}

fn charged_particle(c: &mut Criterion) {
    let mut g = group(c, "charged_particle");
    let system = ChargedParticle::default();
    let problem = ChargedParticle::paper_problem(STEPS);
    let mut all = methods(Rule::Left, &ALL);
    all.extend(methods(Rule::Midpoint, &ALL[..3]));
    engine(&mut g, &system, &problem, &all);
    let stepper = ChargedParticleStep { m: 1.0, b0: 1.0, h: problem.step };
    let start = ReducedState { q: [0.0; 3], theta: 0.0, w: [1.0, 0.0, 1.0], mu: 1.0 };
    g.bench_function("left/specialised_step", |b| b.iter(|| black_box(&stepper).run(black_box(start), STEPS)));
    let boris = Boris { e: 1.0, m: 1.0, b0: 1.0 };
    g.bench_function("boris", |b| {
        b.iter(|| {
            black_box(&boris).run(black_box(problem.step), STEPS, black_box([0.0; 3]), black_box([1.0, 0.0, 1.0]))
        })
    });
    g.finish();
}

fn double_spherical_pendulum(c: &mut Criterion) {
    let mut g = group(c, "double_spherical_pendulum");
    // The paper's problem (h = 0.01), first 1000 steps.
    let problem = Problem { steps: STEPS, ..DoubleSphericalPendulum::paper_problem(10_000) };
    engine(&mut g, &DoubleSphericalPendulum::default(), &problem, &methods(Rule::Midpoint, &ALL));
    g.finish();
}

fn kepler(c: &mut Criterion) {
    let mut g = group(c, "kepler");
    // An eccentric bound orbit (e ≈ 0.45).
    let problem = Problem::new(0.01, STEPS, vec![1.0, 0.3], InitialMomentum::Momentum(vec![0.2, 1.2]));
    engine(&mut g, &Kepler::default(), &problem, &methods(Rule::Midpoint, &PLUS));
    g.finish();
}

fn heavy_top(c: &mut Criterion) {
    let mut g = group(c, "heavy_top");
    // Fast spin ψ̇ ≈ 30.
    let problem = Problem::new(1e-3, STEPS, vec![0.0, 0.6, 0.0], InitialMomentum::Velocity(vec![0.4, 0.0, 30.0]));
    engine(&mut g, &HeavyTop::default(), &problem, &methods(Rule::Midpoint, &PLUS));
    g.finish();
}

criterion_group!(benches, charged_particle, double_spherical_pendulum, kepler, heavy_top);
criterion_main!(benches);
