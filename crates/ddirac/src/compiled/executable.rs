//! A program ready to run in a step: native code ([`super::NativeProgram`]) with the `jit` feature,
//! else the program itself, run by its interpreter [`Program::eval`].
//!
//! Both give the same numbers (the native code repeats the interpreter's operations, to the last
//! bit), so the feature changes speed only: native code costs about 0.6 ns per instruction and a
//! millisecond or more to generate, the interpreter about 4 ns per instruction and nothing to
//! prepare ([`super::CompileCost`] weighs either against dual numbers).

#[cfg(not(feature = "jit"))]
use std::cell::RefCell;

use super::{CompileError, Program};

/// A validated [`Program`], native or interpreted by the `jit` feature. `Send` and `Sync` either way.
pub(crate) struct Executable {
    outputs: usize,
    #[cfg(feature = "jit")]
    native: super::NativeProgram,
    #[cfg(not(feature = "jit"))]
    program: Program,
}

#[cfg(not(feature = "jit"))]
thread_local! {
    /// The interpreter's registers, shared by the programs a thread runs: they grow to the largest
    /// program at its first evaluation (a run's set-up), so that steps do not allocate.
    static REGISTERS: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

impl Executable {
    /// Checks `program` ([`Program::validate`]) and prepares it to run.
    pub(crate) fn new(program: &Program) -> Result<Self, CompileError> {
        program.validate()?;
        Ok(Self {
            outputs: program.outputs.len(),
            #[cfg(feature = "jit")]
            native: super::NativeProgram::compile(program)?,
            #[cfg(not(feature = "jit"))]
            program: program.clone(),
        })
    }

    /// How many numbers [`Executable::call`] writes.
    pub(crate) fn outputs(&self) -> usize {
        self.outputs
    }

    /// Evaluates the program: reads `inputs`, writes every entry of `outputs`.
    ///
    /// # Panics
    ///
    /// If the slices do not have the program's numbers of inputs and outputs (a programming error:
    /// the sizes come from the program, not from the user).
    #[inline]
    pub(crate) fn call(&self, inputs: &[f64], outputs: &mut [f64]) {
        #[cfg(feature = "jit")]
        self.native.call(inputs, outputs);
        #[cfg(not(feature = "jit"))]
        {
            assert_eq!(inputs.len(), self.program.inputs, "wrong number of inputs for a compiled program");
            assert_eq!(outputs.len(), self.outputs, "wrong number of outputs for a compiled program");
            REGISTERS.with_borrow_mut(|registers| self.program.eval(inputs, registers, outputs));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compiled::{Binary, Instruction, MalformedProgram, Unary};

    #[test]
    fn runs_a_program_as_its_interpreter_does() {
        let program = Program {
            inputs: 2,
            instructions: vec![
                Instruction::Input(0),
                Instruction::Input(1),
                Instruction::Unary(Unary::Sin, 0),
                Instruction::Binary(Binary::Mul, 2, 1),
                Instruction::Powi(3, -3),
            ],
            outputs: vec![4, 0, 3],
        };
        let executable = Executable::new(&program).unwrap();
        assert_eq!(executable.outputs(), 3);
        for inputs in [[0.7, -1.3], [0.0, 2.5], [-3.0, 1e-3]] {
            let mut expected = [0.0; 3];
            program.eval(&inputs, &mut Vec::new(), &mut expected);
            let mut actual = [f64::NAN; 3];
            executable.call(&inputs, &mut actual);
            assert_eq!(actual.map(f64::to_bits), expected.map(f64::to_bits), "at {inputs:?}");
        }
    }

    #[test]
    fn malformed_programs_are_refused_before_they_run() {
        let program = Program { inputs: 1, instructions: vec![Instruction::Input(0)], outputs: vec![0, 1] };
        let refused = MalformedProgram::UndefinedOutput { output: 1, register: 1, registers: 1 };
        assert!(matches!(Executable::new(&program), Err(CompileError::Malformed(e)) if e == refused));
    }

    #[test]
    fn executables_can_be_shared_between_threads() {
        fn send_sync<T: Send + Sync>() {}
        send_sync::<Executable>();
    }
}
