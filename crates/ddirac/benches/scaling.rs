//! Scaling with the number of coordinates, on the chain of N pendula (`systems::PendulumChain`).
//!
//! - `chain_mixed/{single_pass,chunked,blocks}/N`: the mixed block of the midpoint L_d in one pass of
//!   `ad::Mixed<N, N>`, in column chunks of `ad::Mixed<N, CHUNK>` (their crossover sets
//!   `dim::CROSSOVER`), or in blocks of `ad::Mixed<BLOCK, BLOCK>` as in a dimension chosen at run time
//!   (`dim::Dynamic`, the arguments copied into arrays for the chain's Lagrangian);
//! - `chain_step/N`: time per step of a whole unreduced midpoint run (100 steps, h = 0.01).
//!
//! A single pass of `Mixed<N, N>` keeps N² + 2N + 1 numbers per intermediate value on the stack;
//! up to N = 32 that fits the main thread's stack, where criterion runs.
//!
//! `cargo bench -p ddirac --bench scaling -- --noplot`

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, measurement::WallTime, BenchmarkGroup, Criterion, Throughput};
use ddirac::dim::{mixed_blocks, mixed_chunked, mixed_single_pass, PairFunction};
use ddirac::dim::{Dynamic, Fixed};
use ddirac::systems::PendulumChain;
use ddirac::Scalar;
use ddirac::{integrate, DiscreteLagrangian, Method, OutputOptions, Rule};

struct Ld<'a, const N: usize>(DiscreteLagrangian<&'a PendulumChain<N>>, [f64; N]);

impl<const N: usize> PairFunction<Fixed<N>> for Ld<'_, N> {
    fn eval<D: Scalar>(&self, a: &[D; N], b: &[D; N]) -> D {
        self.0.eval_local(&self.1, a, b)
    }
}

impl<const N: usize> PairFunction<Dynamic> for Ld<'_, N> {
    fn eval<D: Scalar>(&self, a: &Vec<D>, b: &Vec<D>) -> D {
        let (a, b): (&[D; N], &[D; N]) = (a.as_slice().try_into().unwrap(), b.as_slice().try_into().unwrap());
        self.0.eval_local(&self.1, a, b)
    }
}

fn mixed<const N: usize>(group: &mut BenchmarkGroup<'_, WallTime>, single_pass: bool) {
    let chain = PendulumChain::<N>::default();
    let base: [f64; N] = std::array::from_fn(|i| 0.3 * (i as f64 * 0.7).sin());
    let f = Ld(DiscreteLagrangian::new(&chain, Rule::Midpoint, 0.01), base);
    let zero = [0.0; N];
    let dq: [f64; N] = std::array::from_fn(|i| 1e-3 * (1.0 + i as f64).cos());
    if single_pass {
        group.bench_function(format!("single_pass/{N}"), |b| {
            b.iter(|| mixed_single_pass(&f, black_box(&zero), black_box(&dq)))
        });
    }
    group.bench_function(format!("chunked/{N}"), |b| b.iter(|| mixed_chunked(&f, black_box(&zero), black_box(&dq))));
    let (zero, dq) = (zero.to_vec(), dq.to_vec());
    group.bench_function(format!("blocks/{N}"), |b| {
        b.iter(|| mixed_blocks(Dynamic(N), &f, black_box(&zero), black_box(&dq)))
    });
}

fn step<const N: usize>(group: &mut BenchmarkGroup<'_, WallTime>) {
    let chain = PendulumChain::<N>::default();
    let problem = PendulumChain::<N>::problem(100, 0.01);
    let method = Method { rule: Rule::Midpoint, ..Method::default() };
    let output = OutputOptions { every: 1_000_000, wrap_angles: false };
    group.throughput(Throughput::Elements(100));
    group.bench_function(format!("{N}"), |b| {
        b.iter(|| integrate(&chain, black_box(&problem), &method, &output, &mut |_| Ok(())).expect("the chain runs"))
    });
}

fn configured<'a>(c: &'a mut Criterion, name: &str) -> BenchmarkGroup<'a, WallTime> {
    let mut group = c.benchmark_group(name);
    group.sample_size(20).warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2));
    group
}

fn scaling(c: &mut Criterion) {
    let mut group = configured(c, "chain_mixed");
    mixed::<4>(&mut group, true);
    mixed::<8>(&mut group, true);
    mixed::<12>(&mut group, true);
    mixed::<16>(&mut group, true);
    mixed::<24>(&mut group, true);
    mixed::<32>(&mut group, true);
    mixed::<50>(&mut group, false);
    mixed::<100>(&mut group, false);
    group.finish();
    let mut group = configured(c, "chain_step");
    step::<2>(&mut group);
    step::<4>(&mut group);
    step::<8>(&mut group);
    step::<16>(&mut group);
    step::<32>(&mut group);
    step::<50>(&mut group);
    group.finish();
}

criterion_group!(benches, scaling);
criterion_main!(benches);
