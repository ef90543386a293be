//! The compiled derivatives of a pair function f(base, a, b) at a = 0: what one Newton iterate of a
//! step needs (see [`crate::ad::first_or_mixed`] for the same numbers by dual numbers).
//!
//! A step evaluates f = L_d(base + a, base + b) (or the reduced l̂) at a = 0 and the trial unknowns
//! b: the value, ∂f/∂a (the residual), ∂f/∂b (the next momenta) and, for a fresh Jacobian, the
//! mixed block ∂²f/∂a∂b. [`CompiledPair`] holds two programs, one without and one with the
//! mixed block, built once per run from a trace of f (native code with the `jit` feature).

use std::cell::RefCell;
use std::sync::Arc;

use nalgebra::{SMatrix, SVector};

use super::executable::Executable;
#[cfg(feature = "jit")]
use super::JitError;
use super::{pair_programs, MalformedProgram, NotCompiled, PairPrograms, Program, Traced};
use crate::ad::FirstDerivatives;
use crate::dim::Fixed;
use crate::RuntimeInput;

/// Why derivatives could not be compiled.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CompileError {
    /// The function could not be traced into a graph.
    #[error(transparent)]
    Trace(#[from] NotCompiled),
    /// The graph could not be turned into native code.
    #[error("native code: {0}")]
    Native(String),
    /// A program reads a register, input or output it does not have.
    #[error(transparent)]
    Malformed(#[from] MalformedProgram),
    /// The compiled derivatives disagree with dual numbers at the first point.
    #[error("compiled derivatives disagree with dual numbers at the first step ({what}: {compiled} vs {dual})")]
    Disagrees {
        /// Which output.
        what: &'static str,
        /// The compiled value.
        compiled: f64,
        /// The dual-number value.
        dual: f64,
    },
}

#[cfg(feature = "jit")]
impl From<JitError> for CompileError {
    fn from(e: JitError) -> Self {
        CompileError::Native(e.to_string())
    }
}

/// Compiled derivatives of f(base, a, b) at a = 0, for N coordinates: native code with the `jit`
/// feature, interpreted programs without it.
///
/// If the trace of f was guarded (f compares numbers, see [`super::trace`]), the programs hold only
/// where the guards do: [`CompiledPair::first_or_mixed`] answers `None` elsewhere.
pub struct CompiledPair<const N: usize> {
    first: Arc<Executable>,
    mixed: Arc<Executable>,
    /// The allowed signs of each guard ([`PairPrograms::guards`]).
    guards: Vec<u8>,
    /// Instruction counts of the two programs (without, with the mixed block).
    pub instructions: (usize, usize),
    /// The position among the inputs of the step size h, when it is a runtime input.
    step_input: Option<usize>,
    buffers: RefCell<Buffers>,
}

struct Buffers {
    inputs: Vec<f64>,
    outputs: Vec<f64>,
}

impl<const N: usize> std::fmt::Debug for CompiledPair<N> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CompiledPair").field("instructions", &self.instructions).finish()
    }
}

impl<const N: usize> CompiledPair<N> {
    /// Whether the trace had no guards: then its programs are those of a trace at any point.
    pub fn is_unguarded(&self) -> bool {
        self.guards.is_empty()
    }

    /// Traces `f` at (`base`, a = 0, `b`), differentiates it and compiles both programs.
    pub fn new<F>(f: F, base: &[f64; N], b: &[f64; N]) -> Result<Self, CompileError>
    where
        F: Fn(&[Traced; N], &[Traced; N], &[Traced; N]) -> Traced,
    {
        Self::from_programs(&pair_programs(f, base, b)?)
    }

    /// Compiles the programs of a pair function of N coordinates (from [`pair_programs`] or
    /// [`super::pair_programs_with_runtime_inputs`], whose runtime inputs take the values the trace
    /// recorded), or shares the native code of an earlier run with the same programs
    /// ([`super::native_compilations`] counts the compilations); programs with other numbers of
    /// inputs or outputs are an error.
    pub fn from_programs(programs: &PairPrograms) -> Result<Self, CompileError> {
        let PairPrograms { first, mixed, guards, runtime, .. } = programs;
        let shape = |p: &Program| (p.inputs, p.outputs.len());
        let (g, inputs) = (guards.len(), 2 * N + runtime.len());
        if shape(first) != (inputs, 1 + 2 * N + g) || shape(mixed) != (inputs, 1 + 2 * N + N * N + g) {
            return Err(CompileError::Native(format!(
                "the programs do not compute a pair function of {N} coordinates (inputs and outputs {:?} and {:?})",
                shape(first),
                shape(mixed)
            )));
        }
        let instructions = (first.instructions.len(), mixed.instructions.len());
        let step_input = runtime.iter().position(|(input, _)| *input == RuntimeInput::Step).map(|i| 2 * N + i);
        Ok(Self {
            first: super::cache::shared(first)?,
            mixed: super::cache::shared(mixed)?,
            guards: guards.clone(),
            instructions,
            step_input,
            buffers: RefCell::new(Buffers {
                inputs: [0.0; N].iter().chain(&[0.0; N]).copied().chain(runtime.iter().map(|(_, v)| *v)).collect(),
                outputs: vec![0.0; 1 + 2 * N + N * N + g],
            }),
        })
    }

    /// The same programs with the step size h set to `step`, when h is a runtime input of them: what
    /// a trace of the same function with step `step` would give, without tracing again (the
    /// sub-steps of a composition). `None` where h is a constant of the programs.
    pub fn with_step(&self, step: f64) -> Option<Self> {
        let slot = self.step_input?;
        let buffers = self.buffers.borrow();
        let mut inputs = buffers.inputs.clone();
        inputs[slot] = step;
        Some(Self {
            first: Arc::clone(&self.first),
            mixed: Arc::clone(&self.mixed),
            guards: self.guards.clone(),
            instructions: self.instructions,
            step_input: self.step_input,
            buffers: RefCell::new(Buffers { inputs, outputs: buffers.outputs.clone() }),
        })
    }

    /// Value, ∂f/∂a and ∂f/∂b at (`base`, 0, `b`), and with `with_mixed` the block ∂²f/∂a∂b; `None`
    /// where a guard of the trace does not hold (the programs are another branch's there).
    pub fn first_or_mixed(
        &self,
        base: &[f64; N],
        b: &[f64; N],
        with_mixed: bool,
    ) -> Option<(FirstDerivatives<Fixed<N>>, Option<SMatrix<f64, N, N>>)> {
        let mut buffers = self.buffers.borrow_mut();
        let Buffers { inputs, outputs } = &mut *buffers;
        inputs[..N].copy_from_slice(base);
        inputs[N..2 * N].copy_from_slice(b);
        let program = if with_mixed { &self.mixed } else { &self.first };
        let outputs = &mut outputs[..program.outputs()];
        program.call(inputs, outputs);
        let signs = &outputs[outputs.len() - self.guards.len()..];
        if !PairPrograms::holds(&self.guards, signs) {
            return None;
        }
        let first = FirstDerivatives {
            value: outputs[0],
            da: SVector::from_fn(|i, _| outputs[1 + i]),
            db: SVector::from_fn(|i, _| outputs[1 + N + i]),
        };
        let mixed = with_mixed.then(|| SMatrix::from_fn(|i, j| outputs[1 + 2 * N + i * N + j]));
        Some((first, mixed))
    }

    /// Checks the compiled numbers against `dual` (the same derivatives by dual numbers) at one point:
    /// every entry within `tolerance` relative to the largest entry of its block.
    pub fn check_against(
        &self,
        base: &[f64; N],
        b: &[f64; N],
        dual: (FirstDerivatives<Fixed<N>>, SMatrix<f64, N, N>),
        tolerance: f64,
    ) -> Result<(), CompileError> {
        let Some((c, cm)) = self.first_or_mixed(base, b, true) else {
            return Err(CompileError::Disagrees { what: "guards of the trace", compiled: f64::NAN, dual: 0.0 });
        };
        let cm = cm.unwrap_or_else(SMatrix::zeros);
        let (d, dm) = dual;
        let blocks: [(&'static str, &[f64], &[f64]); 4] = [
            ("value", std::slice::from_ref(&c.value), std::slice::from_ref(&d.value)),
            ("∂f/∂a", c.da.as_slice(), d.da.as_slice()),
            ("∂f/∂b", c.db.as_slice(), d.db.as_slice()),
            ("∂²f/∂a∂b", cm.as_slice(), dm.as_slice()),
        ];
        for (what, compiled, dual) in blocks {
            let scale = dual.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            if let Some((&compiled, &dual)) =
                compiled.iter().zip(dual).find(|(c, d)| (*c - *d).is_nan() || (*c - *d).abs() > tolerance * scale)
            {
                return Err(CompileError::Disagrees { what, compiled, dual });
            }
        }
        Ok(())
    }
}
