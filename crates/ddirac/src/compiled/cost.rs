//! Whether compiling a run's derivatives pays: the estimated time of preparing the programs of a
//! pair function (native code generation), against what the run would save on its steps.
//!
//! ```text
//! compile    = 0.5 ms + 0.6 µs · I + 22 ns · L   per program of I instructions and live ranges L
//! dual eval  = ops · (5 ns + 0.1 ns · flops(n))  ops operations of f, flops of one dual product
//! native     = 0.6 ns · I                        per evaluation of a program
//! step       = 1 Jacobian + 2 residuals, or 8 residuals when a Jacobian is kept across steps
//! pays       ⟺  compile < steps · (dual step − native step) + 10 ms
//! ```
//!
//! The tolerance of 10 ms, ten times what compiling a small system costs, keeps compiling wherever
//! little is at stake: there the estimate is less accurate than what it leaves out, the closed-form
//! step of linear step equations ([`super::LinearStep`]) and the cheaper Jacobians of compiled runs.
//!
//! Without the `jit` feature the programs run on their interpreter ([`Program::eval`]): nothing to
//! generate (compile = 0), about 3 ns per instruction (2.3 to 3.7 ns measured on the double spherical
//! pendulum's programs, where its dual numbers in Rust take 1.0 to 1.4 ns per instruction's worth), no
//! tolerance: interpreting pays only where it is estimated faster per step than dual numbers. The
//! constant is 4 ns, above the measurements, because the estimate of the dual numbers is that of the
//! expression language's, up to five times that of a Lagrangian written in Rust. A run whose step
//! equations have a closed form is interpreted whatever the estimate (see `scheme.rs`): one evaluation
//! per step instead of Newton's iterations, 3.7× faster than dual numbers on the charged particle.
//!
//! Cranelift's time grows faster than the program: most of it is register allocation, which grows
//! with the total length of the values' live ranges ([`Program::live_ranges`]). That total is
//! proportional to the program for derivative code of many short-lived values (a chain of pendula),
//! and to its square for a deep chain of definitions, whose reverse sweep keeps every forward value
//! alive: a chain of 3000 definitions of one coordinate has 54 000 instructions and 2·10⁸ in live
//! ranges, and takes 5 s to compile, where its dual numbers cost 0.1 ms per step.
//!
//! The constants were measured on the machine of BENCHMARKS.md ("Compiling only when it pays",
//! `cargo bench -p ddirac --bench compile_cost`); only their ratios matter. 5 ns per operation of
//! dual numbers is the expression language's interpreter (a Lagrangian written in Rust takes
//! under 1 ns); the flops are those of one product of [`crate::ad`]'s numbers: 4n + 1 for a
//! residual, 3n² + 4n + 1 for a Jacobian in one pass, ⌈n/4⌉ · (12n + 2(n + 4) + 1) in column chunks
//! above [`crate::dim::CROSSOVER`]. The estimate is within a factor of two of the measurements, and
//! leans towards compiling for Lagrangians written in Rust, whose dual numbers it overestimates.

use super::{PairPrograms, Program};
use crate::dim::{CHUNK, CROSSOVER};
use crate::newton::{dual_relative_cost, ACROSS_SOLVES};

/// Seconds of native code generation per program (the JIT module and the function around the code).
#[cfg(feature = "jit")]
const COMPILE_PER_PROGRAM: f64 = 0.5e-3;
/// Seconds of native code generation per instruction.
#[cfg(feature = "jit")]
const COMPILE_PER_INSTRUCTION: f64 = 0.6e-6;
/// Seconds of native code generation per instruction of live range (register allocation).
#[cfg(feature = "jit")]
const COMPILE_PER_LIVE: f64 = 22e-9;
/// The interpreter needs no code generation.
#[cfg(not(feature = "jit"))]
const COMPILE_PER_PROGRAM: f64 = 0.0;
/// The interpreter needs no code generation.
#[cfg(not(feature = "jit"))]
const COMPILE_PER_INSTRUCTION: f64 = 0.0;
/// The interpreter needs no code generation.
#[cfg(not(feature = "jit"))]
const COMPILE_PER_LIVE: f64 = 0.0;
/// Seconds per operation of a dual-number evaluation, besides its flops.
const DUAL_PER_OPERATION: f64 = 5e-9;
/// Seconds per flop of a dual-number operation.
const DUAL_PER_FLOP: f64 = 0.1e-9;
/// Seconds per instruction of a native program.
#[cfg(feature = "jit")]
const NATIVE_PER_INSTRUCTION: f64 = 0.6e-9;
/// Seconds per instruction of an interpreted program (see the module documentation).
#[cfg(not(feature = "jit"))]
const NATIVE_PER_INSTRUCTION: f64 = 4e-9;
/// Seconds that compiling may be estimated to lose and still be chosen.
#[cfg(feature = "jit")]
const TOLERANCE: f64 = 10e-3;
/// Without native code there is no compile time to misjudge: the interpreter must be faster.
#[cfg(not(feature = "jit"))]
const TOLERANCE: f64 = 0.0;
/// Residual evaluations per step when a Jacobian is kept across steps (chord corrections, 7.5 to 7.7
/// per step on chains of 10 to 50 pendula).
const RESIDUALS_KEPT: f64 = 8.0;

/// The estimated costs, in seconds, of compiling the programs of a pair function of `N` coordinates,
/// and of one step with dual numbers and with the native programs.
///
/// ```
/// use ddirac::compiled::{pair_programs, CompileCost, Traced};
/// use ddirac::dim::Fixed;
/// use num_dual::DualNum;
/// // A pendulum's L_d: a few dozen instructions, compiled in about a millisecond.
/// let ld = |base: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| {
///     let (q0, q1) = (base[0] + a[0], base[0] + b[0]);
///     (q1 - q0).powi(2) * 50.0 + ((q0 + q1) * 0.5).cos() * 0.1
/// };
/// let cost = CompileCost::estimate(1, &pair_programs(Fixed, ld, &[0.3], &[0.01]).unwrap());
/// assert!(cost.compile < 2e-3);
/// if cfg!(feature = "jit") {
///     assert!(cost.pays(5000));
///     // Its steps save a fraction of a microsecond each: they pay for compiling from about 10⁴ steps.
///     assert!(cost.compile > 5000.0 * (cost.dual_step - cost.native_step));
///     assert!(cost.compile < 20_000.0 * (cost.dual_step - cost.native_step));
/// } else {
///     // Nothing to compile: the interpreter pays if its steps are faster than dual numbers.
///     assert_eq!(cost.compile, 0.0);
///     assert_eq!(cost.pays(5000), cost.native_step < cost.dual_step);
/// }
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompileCost {
    /// Generating the native code of both programs (0 without the `jit` feature).
    pub compile: f64,
    /// A step's evaluations by dual numbers.
    pub dual_step: f64,
    /// The same evaluations by the native programs (interpreted, without the `jit` feature).
    pub native_step: f64,
    /// Instructions of both programs.
    pub instructions: usize,
}

impl CompileCost {
    /// The estimate for `programs` of a pair function of `coordinates` coordinates per block, against
    /// the dual numbers of a fixed dimension (see the module documentation).
    pub fn estimate(coordinates: usize, programs: &PairPrograms) -> Self {
        let PairPrograms { first, mixed, operations, .. } = programs;
        let n = coordinates as f64;
        let compile = |p: &Program| {
            COMPILE_PER_PROGRAM
                + COMPILE_PER_INSTRUCTION * p.instructions.len() as f64
                + COMPILE_PER_LIVE * p.live_ranges() as f64
        };
        let residual_flops = 4.0 * n + 1.0;
        let jacobian_flops = if coordinates <= CROSSOVER {
            3.0 * n * n + 4.0 * n + 1.0
        } else {
            let chunk = CHUNK as f64;
            coordinates.div_ceil(CHUNK) as f64 * (3.0 * chunk * n + 2.0 * (n + chunk) + 1.0)
        };
        let dual = |flops: f64| *operations as f64 * (DUAL_PER_OPERATION + DUAL_PER_FLOP * flops);
        let native = |p: &Program| NATIVE_PER_INSTRUCTION * p.instructions.len() as f64;
        let (dual_step, native_step) = if dual_relative_cost(coordinates) >= ACROSS_SOLVES {
            (RESIDUALS_KEPT * dual(residual_flops), RESIDUALS_KEPT * native(first))
        } else {
            (dual(jacobian_flops) + 2.0 * dual(residual_flops), native(mixed) + 2.0 * native(first))
        };
        Self {
            compile: compile(first) + compile(mixed),
            dual_step,
            native_step,
            instructions: first.instructions.len() + mixed.instructions.len(),
        }
    }

    /// Whether compiling pays over a run of `steps` steps: the steps save more than the compiling
    /// costs, give or take a tolerance of 10 ms; without `jit`, the interpreted steps are faster
    /// (see the module documentation).
    pub fn pays(&self, steps: usize) -> bool {
        self.compile < steps as f64 * (self.dual_step - self.native_step) + TOLERANCE
    }

    /// Why compiling does not pay over `steps` steps, for a run's summary; `None` if it pays.
    pub fn refusal(&self, steps: usize) -> Option<String> {
        let steps_f = steps as f64;
        let (compiled, dual) = (seconds(steps_f * self.native_step), seconds(steps_f * self.dual_step));
        (!self.pays(steps)).then(|| {
            let why = if cfg!(feature = "jit") {
                format!(
                    "compiling would cost more than it saves over {steps} steps (estimated {} to compile and \
                     {compiled} for the compiled steps, against {dual} with dual numbers)",
                    seconds(self.compile)
                )
            } else {
                format!(
                    "without native code (feature `jit`), interpreting it would be slower than dual numbers \
                     (estimated {compiled} for {steps} interpreted steps, against {dual})"
                )
            };
            format!("program of {} instructions: {why}", self.instructions)
        })
    }
}

/// A time for a message, to about two significant digits, in s from one second on, else in ms.
fn seconds(t: f64) -> String {
    let (value, unit) = if t >= 1.0 { (t, "s") } else { (t * 1e3, "ms") };
    let decimals = if value >= 10.0 {
        0
    } else if value >= 1.0 {
        1
    } else {
        2
    };
    format!("{value:.decimals$} {unit}")
}
