//! The estimate by which `derivatives = "auto"` decides whether compiling pays
//! (`ddirac::compiled::CompileCost`), against measurements: for the midpoint L_d of a chain of n
//! definitions of one coordinate (each using the previous one twice, the shape that makes native
//! code generation grow as the square of the program) and of chains of pendula (many short-lived
//! values), the instructions and live ranges of both programs, the estimated and measured time of
//! compiling them, and the estimated and measured time of one step's evaluations (a Jacobian and two
//! residuals, or eight residuals when a Jacobian is kept across steps) by dual numbers and by the
//! native programs.
//!
//! `cargo bench -p ddirac --bench compile_cost` (about a minute; times are medians of 5 batches).

use std::hint::black_box;
use std::time::Instant;

use ddirac::compiled::{pair_programs, CompileCost, NativeProgram, Program, Traced};
use ddirac::dim::Fixed;
use ddirac::dim::{self, PairFunction};
use ddirac::expression::{ExpressionSpec, ExpressionSystem};
use ddirac::newton::{dual_relative_cost, ACROSS_SOLVES};
use ddirac::systems::PendulumChain;
use ddirac::Scalar;
use ddirac::{Coordinate, DiscreteLagrangian, Rule, System};

const STEP: f64 = 0.01;

struct Ld<S, const N: usize>(DiscreteLagrangian<S>, [f64; N]);

impl<S: System<N>, const N: usize> PairFunction<Fixed<N>> for Ld<S, N> {
    fn eval<D: Scalar>(&self, a: &[D; N], b: &[D; N]) -> D {
        self.0.eval_local(&self.1, a, b)
    }
}

fn median(mut samples: Vec<f64>) -> f64 {
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}

/// Seconds per call of `f`: the median of 5 batches of about 20 ms.
fn per_call(mut f: impl FnMut()) -> f64 {
    let start = Instant::now();
    f();
    let reps = (0.02 / start.elapsed().as_secs_f64().max(1e-9)).clamp(1.0, 1e6) as usize;
    median(
        (0..5)
            .map(|_| {
                let start = Instant::now();
                (0..reps).for_each(|_| f());
                start.elapsed().as_secs_f64() / reps as f64
            })
            .collect(),
    )
}

fn compile_seconds(program: &Program) -> f64 {
    let times = if program.instructions.len() > 20_000 { 1 } else { 3 };
    median(
        (0..times)
            .map(|_| {
                let start = Instant::now();
                black_box(NativeProgram::compile(program).expect("the host has native code"));
                start.elapsed().as_secs_f64()
            })
            .collect(),
    )
}

fn row<S: System<N>, const N: usize>(name: &str, system: &S, base: [f64; N]) {
    let z = [1e-3; N];
    let ld = DiscreteLagrangian::new(system, Rule::Midpoint, STEP);
    let traced = |base: &[Traced; N], a: &[Traced; N], b: &[Traced; N]| ld.eval_local(base, a, b);
    let programs = pair_programs(Fixed, traced, &base, &z).expect("the Lagrangian traces");
    let estimate = CompileCost::estimate(N, &programs);
    let (first, mixed) = (&programs.first, &programs.mixed);
    let compile = compile_seconds(first) + compile_seconds(mixed);

    let inputs: Vec<f64> = base.iter().chain(&z).copied().collect();
    let call = |program: &Program| {
        let native = NativeProgram::compile(program).expect("the host has native code");
        let mut outputs = vec![0.0; program.outputs.len()];
        per_call(|| native.call(black_box(&inputs), &mut outputs))
    };
    let (native_residual, native_jacobian) = (call(first), call(mixed));
    let f = Ld(ld, base);
    let dual_residual = per_call(|| {
        black_box(dim::first_or_mixed(Fixed, &f, &[0.0; N], black_box(&z), false));
    });
    let dual_jacobian = per_call(|| {
        black_box(dim::first_or_mixed(Fixed, &f, &[0.0; N], black_box(&z), true));
    });
    let kept = dual_relative_cost(N) >= ACROSS_SOLVES;
    let step = |residual: f64, jacobian: f64| if kept { 8.0 * residual } else { jacobian + 2.0 * residual };
    println!(
        "{name:>13} {N:>3} {:>7} {:>7} {:>10.2e} {:>10.3} {:>10.3} {:>9.1} {:>9.1} {:>9.2} {:>9.2}",
        programs.operations,
        first.instructions.len() + mixed.instructions.len(),
        (first.live_ranges() + mixed.live_ranges()) as f64,
        estimate.compile * 1e3,
        compile * 1e3,
        estimate.dual_step * 1e6,
        step(dual_residual, dual_jacobian) * 1e6,
        estimate.native_step * 1e6,
        step(native_residual, native_jacobian) * 1e6,
    );
}

/// One coordinate x; a1 = x + 0.001·ẋ, a_k = a_{k−1}² − a_{k−1}; L = ½ẋ² − ½x² + 0.001·a_n.
fn definitions(n: usize) -> ExpressionSystem<1> {
    let mut definitions = vec![("a1".to_owned(), "x + 0.001*x_dot".to_owned())];
    definitions.extend((2..=n).map(|k| (format!("a{k}"), format!("a{p}*a{p} - a{p}", p = k - 1))));
    let spec = ExpressionSpec {
        coordinates: vec![Coordinate::shape("x")],
        lagrangian: format!("0.5*x_dot^2 - 0.5*x^2 + 0.001*a{n}"),
        definitions,
        ..ExpressionSpec::default()
    };
    ExpressionSystem::<1>::new(&spec).expect("the chain compiles")
}

fn pendula<const N: usize>() {
    let base: [f64; N] = std::array::from_fn(|i| 0.3 * ((i + 1) as f64).sin());
    row(&format!("pendula {N}"), &PendulumChain::<N>::default(), base);
}

fn main() {
    println!(
        "{:>13} {:>3} {:>7} {:>7} {:>10} {:>10} {:>10} {:>9} {:>9} {:>9} {:>9}",
        "system", "n", "ops", "instr", "live", "compile ms", "measured", "dual µs", "measured", "native µs", "measured"
    );
    for n in [100, 250, 500, 1000, 2000, 3000] {
        row(&format!("{n} defs"), &definitions(n), [0.5]);
    }
    pendula::<4>();
    pendula::<8>();
    pendula::<16>();
    pendula::<32>();
    pendula::<50>();
}
