//! The compiled derivatives of a pair function f(base, a, b) at a = 0: what one Newton iterate of a
//! step needs (see [`crate::dim::first_or_mixed`] for the same numbers by dual numbers).
//!
//! A step evaluates f = L_d(base + a, base + b) (or the reduced l̂) at a = 0 and the trial unknowns
//! b: the value, ∂f/∂a (the residual), ∂f/∂b (the next momenta) and, for a fresh Jacobian, the
//! mixed block ∂²f/∂a∂b. [`CompiledPair`] holds two programs, one without and one with the
//! mixed block, built once per run from a trace of f (native code with the `jit` feature).

use std::cell::RefCell;
use std::sync::Arc;

use super::error::CompileError;
use super::executable::Executable;
use super::{pair_programs, PairPrograms, Program, Traced};
use crate::dim::Dim;
use crate::dim::FirstDerivatives;
use crate::RuntimeInput;

/// Compiled derivatives of f(base, a, b) at a = 0, for N coordinates: native code with the `jit`
/// feature, interpreted programs without it.
///
/// If the trace of f was guarded (f compares numbers, see [`super::trace`]), the programs hold only
/// where the guards do: [`CompiledPair::first_or_mixed`] answers `None` elsewhere.
pub struct CompiledPair<Dm: Dim> {
    dim: Dm,
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

impl<Dm: Dim> std::fmt::Debug for CompiledPair<Dm> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CompiledPair").field("instructions", &self.instructions).finish()
    }
}

impl<Dm: Dim> CompiledPair<Dm> {
    /// Whether the trace had no guards: then its programs are those of a trace at any point.
    pub fn is_unguarded(&self) -> bool {
        self.guards.is_empty()
    }

    /// Traces `f` at (`base`, a = 0, `b`), differentiates it and compiles both programs.
    pub fn new<F>(dim: Dm, f: F, base: &Dm::Array<f64>, b: &Dm::Array<f64>) -> Result<Self, CompileError>
    where
        F: Fn(&Dm::Array<Traced>, &Dm::Array<Traced>, &Dm::Array<Traced>) -> Traced,
    {
        Self::from_programs(dim, &pair_programs(dim, f, base, b)?)
    }

    /// Compiles the programs of a pair function of N coordinates (from [`pair_programs`] or
    /// [`super::pair_programs_with_runtime_inputs`], whose runtime inputs take the values the trace
    /// recorded), or shares the native code of an earlier run with the same programs
    /// ([`super::native_compilations`] counts the compilations); programs with other numbers of
    /// inputs or outputs are an error.
    pub fn from_programs(dim: Dm, programs: &PairPrograms) -> Result<Self, CompileError> {
        let n = dim.n();
        let PairPrograms { first, mixed, guards, runtime, .. } = programs;
        let shape = |p: &Program| (p.inputs, p.outputs.len());
        let (g, inputs) = (guards.len(), 2 * n + runtime.len());
        if shape(first) != (inputs, 1 + 2 * n + g) || shape(mixed) != (inputs, 1 + 2 * n + n * n + g) {
            return Err(CompileError::Native(format!(
                "the programs do not compute a pair function of {n} coordinates (inputs and outputs {:?} and {:?})",
                shape(first),
                shape(mixed)
            )));
        }
        let instructions = (first.instructions.len(), mixed.instructions.len());
        let step_input = runtime.iter().position(|(input, _)| *input == RuntimeInput::Step).map(|i| 2 * n + i);
        Ok(Self {
            dim,
            first: super::cache::shared(first)?,
            mixed: super::cache::shared(mixed)?,
            guards: guards.clone(),
            instructions,
            step_input,
            buffers: RefCell::new(Buffers {
                inputs: std::iter::repeat_n(0.0, 2 * n).chain(runtime.iter().map(|(_, v)| *v)).collect(),
                outputs: vec![0.0; 1 + 2 * n + n * n + g],
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
            dim: self.dim,
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
        base: &Dm::Array<f64>,
        b: &Dm::Array<f64>,
        with_mixed: bool,
    ) -> Option<(FirstDerivatives<Dm>, Option<Dm::Matrix>)> {
        let n = self.dim.n();
        let mut buffers = self.buffers.borrow_mut();
        let Buffers { inputs, outputs } = &mut *buffers;
        inputs[..n].copy_from_slice(base.as_ref());
        inputs[n..2 * n].copy_from_slice(b.as_ref());
        let program = if with_mixed { &self.mixed } else { &self.first };
        let outputs = &mut outputs[..program.outputs()];
        program.call(inputs, outputs);
        let signs = &outputs[outputs.len() - self.guards.len()..];
        if !PairPrograms::holds(&self.guards, signs) {
            return None;
        }
        let first = FirstDerivatives {
            value: outputs[0],
            da: self.dim.vector(|i| outputs[1 + i]),
            db: self.dim.vector(|i| outputs[1 + n + i]),
        };
        let mixed = with_mixed.then(|| self.dim.matrix(|i, j| outputs[1 + 2 * n + i * n + j]));
        Some((first, mixed))
    }

    /// The mixed block ∂²f/∂a∂b at (`base`, `b`), entry (i, j) handed to `entry` (no first
    /// derivatives built, nothing allocated); `false` where a guard of the trace fails.
    pub fn mixed_with(&self, base: &[f64], b: &[f64], mut entry: impl FnMut(usize, usize, f64)) -> bool {
        let n = self.dim.n();
        let mut buffers = self.buffers.borrow_mut();
        let Buffers { inputs, outputs } = &mut *buffers;
        inputs[..n].copy_from_slice(base);
        inputs[n..2 * n].copy_from_slice(b);
        let outputs = &mut outputs[..self.mixed.outputs()];
        self.mixed.call(inputs, outputs);
        if !PairPrograms::holds(&self.guards, &outputs[outputs.len() - self.guards.len()..]) {
            return false;
        }
        for i in 0..n {
            for j in 0..n {
                entry(i, j, outputs[1 + 2 * n + i * n + j]);
            }
        }
        true
    }

    /// Checks the compiled numbers against `dual` (the same derivatives by dual numbers) at one point:
    /// every entry within `tolerance` relative to the largest entry of its block.
    pub fn check_against(
        &self,
        base: &Dm::Array<f64>,
        b: &Dm::Array<f64>,
        dual: (FirstDerivatives<Dm>, Dm::Matrix),
        tolerance: f64,
    ) -> Result<(), CompileError> {
        let Some((c, cm)) = self.first_or_mixed(base, b, true) else {
            return Err(CompileError::Disagrees { what: "guards of the trace", compiled: f64::NAN, dual: 0.0 });
        };
        let cm = cm.unwrap_or_else(|| self.dim.matrix(|_, _| 0.0));
        let (d, dm) = dual;
        let blocks: [(&'static str, &[f64], &[f64]); 4] = [
            ("value", std::slice::from_ref(&c.value), std::slice::from_ref(&d.value)),
            ("∂f/∂a", Dm::entries(&c.da), Dm::entries(&d.da)),
            ("∂f/∂b", Dm::entries(&c.db), Dm::entries(&d.db)),
            ("∂²f/∂a∂b", Dm::matrix_entries(&cm), Dm::matrix_entries(&dm)),
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
