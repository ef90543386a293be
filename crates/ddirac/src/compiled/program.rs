//! Straight-line programs over `f64` registers: the compiled form of a Lagrangian's derivatives.
//!
//! Instruction k writes register k; operands name earlier registers. A [`Program`] has no branches,
//! so evaluating it costs exactly its instructions. [`Program::eval`] interprets it: the reference
//! for the native code of `jit` (feature `jit`), and the path of compiled derivatives without it.

/// A unary operation. [`Unary::apply`] is its one definition, shared by the interpreter and by the
/// native code, which calls it for every function that is not a single machine instruction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Unary {
    /// −x
    Neg,
    /// 1/x
    Recip,
    /// √x
    Sqrt,
    /// ∛x
    Cbrt,
    /// |x|
    Abs,
    /// sign of x (±1, or 0 at zero, NaN at NaN), piecewise constant
    Signum,
    /// eˣ
    Exp,
    /// eˣ − 1
    ExpM1,
    /// ln x
    Ln,
    /// ln(1 + x)
    Ln1p,
    /// sin x
    Sin,
    /// cos x
    Cos,
    /// tan x
    Tan,
    /// asin x
    Asin,
    /// acos x
    Acos,
    /// atan x
    Atan,
    /// sinh x
    Sinh,
    /// cosh x
    Cosh,
    /// tanh x
    Tanh,
    /// asinh x
    Asinh,
    /// acosh x
    Acosh,
    /// atanh x
    Atanh,
}

impl Unary {
    /// The operation on one number of any [`crate::Scalar`] type: f64 for constant folding and the
    /// native code's calls, dual numbers and traces for the interpreter.
    #[inline(always)]
    pub fn apply<D: crate::Scalar>(self, x: D) -> D {
        match self {
            Unary::Neg => -x,
            Unary::Recip => x.recip(),
            Unary::Sqrt => x.sqrt(),
            Unary::Cbrt => x.cbrt(),
            Unary::Abs => x.abs(),
            Unary::Signum => {
                if x == D::from(0.0) {
                    D::from(0.0)
                } else {
                    x.signum()
                }
            }
            Unary::Exp => x.exp(),
            Unary::ExpM1 => x.exp_m1(),
            Unary::Ln => x.ln(),
            Unary::Ln1p => x.ln_1p(),
            Unary::Sin => x.sin(),
            Unary::Cos => x.cos(),
            Unary::Tan => x.tan(),
            Unary::Asin => x.asin(),
            Unary::Acos => x.acos(),
            Unary::Atan => x.atan(),
            Unary::Sinh => x.sinh(),
            Unary::Cosh => x.cosh(),
            Unary::Tanh => x.tanh(),
            Unary::Asinh => x.asinh(),
            Unary::Acosh => x.acosh(),
            Unary::Atanh => x.atanh(),
        }
    }
}

/// A binary operation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Binary {
    /// x + y
    Add,
    /// x − y
    Sub,
    /// x · y
    Mul,
    /// x / y
    Div,
    /// xʸ
    Pow,
    /// atan2(x, y), the angle of the point (y, x)
    Atan2,
    /// min(x, y): y if y < x, else x (so x when they are equal or y is NaN)
    Min,
    /// max(x, y): y if y > x, else x (so x when they are equal or y is NaN)
    Max,
    /// 1 if x < y, else 0 (also when either is NaN): which operand `Min` or `Max` picks, piecewise
    /// constant
    Less,
    /// y where x ≠ 0, else 0: y gated by an indicator x. Unlike x · y, a gated-off y that is infinite
    /// or NaN gives 0, so the derivative of the branch `Min` or `Max` did not take cannot leak into the
    /// one it took.
    Gate,
}

impl Binary {
    /// The operation on two numbers of any [`crate::Scalar`] type; xʸ with a variable exponent is
    /// exp(y ln x) on dual numbers.
    #[inline(always)]
    pub fn apply<D: crate::Scalar>(self, x: D, y: D) -> D {
        match self {
            Binary::Add => x + y,
            Binary::Sub => x - y,
            Binary::Mul => x * y,
            Binary::Div => x / y,
            Binary::Pow => x.powd(y),
            Binary::Atan2 => x.atan2(y),
            Binary::Min => x.min_of(y),
            Binary::Max => x.max_of(y),
            Binary::Less => D::from(if x < y { 1.0 } else { 0.0 }),
            Binary::Gate => {
                if x != D::from(0.0) {
                    y
                } else {
                    D::from(0.0)
                }
            }
        }
    }
}

/// A register index.
pub type Register = u32;

/// One instruction; it writes the register of its own index.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Instruction {
    /// The i-th input.
    Input(u32),
    /// A constant, stored as its bits so that instructions can be hashed.
    Const(u64),
    /// f(x).
    Unary(Unary, Register),
    /// f(x, y).
    Binary(Binary, Register, Register),
    /// xⁿ for an integer n.
    Powi(Register, i32),
}

impl Instruction {
    /// The constant c.
    pub fn constant(c: f64) -> Self {
        Instruction::Const(c.to_bits())
    }

    /// The registers this instruction reads.
    pub fn operands(self) -> impl Iterator<Item = Register> {
        let (a, b) = match self {
            Instruction::Input(_) | Instruction::Const(_) => (None, None),
            Instruction::Unary(_, a) | Instruction::Powi(a, _) => (Some(a), None),
            Instruction::Binary(_, a, b) => (Some(a), Some(b)),
        };
        a.into_iter().chain(b)
    }

    /// The instruction's value, given the inputs and the registers before it.
    #[inline]
    pub fn apply(self, inputs: &[f64], registers: &[f64]) -> f64 {
        match self {
            Instruction::Input(i) => inputs[i as usize],
            Instruction::Const(bits) => f64::from_bits(bits),
            Instruction::Unary(op, a) => op.apply(registers[a as usize]),
            Instruction::Binary(op, a, b) => op.apply(registers[a as usize], registers[b as usize]),
            Instruction::Powi(a, n) => registers[a as usize].powi(n),
        }
    }
}

/// Why a [`Program`] cannot run: it reads a register, input or output that does not exist.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum MalformedProgram {
    /// An instruction reads a register that no earlier instruction writes.
    #[error("malformed program: instruction {instruction} reads register {register}, which is not written before it")]
    UndefinedRegister {
        /// The reading instruction.
        instruction: usize,
        /// The register it reads.
        register: Register,
    },
    /// An instruction reads an input the program does not have.
    #[error("malformed program: instruction {instruction} reads input {input}, but the program has {inputs} inputs")]
    UndefinedInput {
        /// The reading instruction.
        instruction: usize,
        /// The input it reads.
        input: u32,
        /// How many inputs the program has.
        inputs: usize,
    },
    /// An output names a register the program does not have.
    #[error("malformed program: output {output} reads register {register}, but the program has {registers} registers")]
    UndefinedOutput {
        /// The output.
        output: usize,
        /// The register it names.
        register: Register,
        /// How many registers (instructions) the program has.
        registers: usize,
    },
}

/// A straight-line program: `inputs` numbers in, one register per instruction, `outputs` read from
/// registers.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Program {
    /// How many inputs the program reads.
    pub inputs: usize,
    /// The instructions in evaluation order.
    pub instructions: Vec<Instruction>,
    /// The registers holding the outputs, in order.
    pub outputs: Vec<Register>,
}

impl Program {
    /// Interprets the program: reads `inputs`, writes `outputs`, uses `registers` as scratch space.
    ///
    /// The caller sizes the slices: `inputs.len() == self.inputs`, `outputs.len() == self.outputs.len()`.
    pub fn eval(&self, inputs: &[f64], registers: &mut Vec<f64>, outputs: &mut [f64]) {
        debug_assert_eq!(inputs.len(), self.inputs);
        debug_assert_eq!(outputs.len(), self.outputs.len());
        registers.clear();
        for &instruction in &self.instructions {
            let value = instruction.apply(inputs, registers);
            registers.push(value);
        }
        for (out, &r) in outputs.iter_mut().zip(&self.outputs) {
            *out = registers[r as usize];
        }
    }

    /// Checks that every operand, input and output exists, so that neither [`Program::eval`] nor
    /// native code generation can fail on the program's account.
    ///
    /// ```
    /// use ddirac::compiled::{Binary, Instruction, MalformedProgram, Program};
    /// let forward = Program {
    ///     inputs: 1,
    ///     instructions: vec![Instruction::Input(0), Instruction::Binary(Binary::Add, 0, 1)],
    ///     outputs: vec![1],
    /// };
    /// assert_eq!(forward.validate(), Err(MalformedProgram::UndefinedRegister { instruction: 1, register: 1 }));
    /// ```
    pub fn validate(&self) -> Result<(), MalformedProgram> {
        for (instruction, &op) in self.instructions.iter().enumerate() {
            if let Instruction::Input(input) = op {
                if input as usize >= self.inputs {
                    return Err(MalformedProgram::UndefinedInput { instruction, input, inputs: self.inputs });
                }
            }
            if let Some(register) = op.operands().find(|&r| r as usize >= instruction) {
                return Err(MalformedProgram::UndefinedRegister { instruction, register });
            }
        }
        let registers = self.instructions.len();
        match self.outputs.iter().position(|&r| r as usize >= registers) {
            Some(output) => {
                Err(MalformedProgram::UndefinedOutput { output, register: self.outputs[output], registers })
            }
            None => Ok(()),
        }
    }

    /// The total length of the values' live ranges: for each instruction, how many instructions
    /// later its value is last read (0 for a value that is only an output, stored when computed).
    /// Register allocation, most of the time of compiling a long program to native code, grows with
    /// it ([`super::CompileCost`]).
    ///
    /// ```
    /// use ddirac::compiled::{Binary, Instruction, Program};
    /// // x, y, x·y, (x·y) + x: x lives 3 instructions, y 1, x·y 1.
    /// let program = Program {
    ///     inputs: 2,
    ///     instructions: vec![
    ///         Instruction::Input(0),
    ///         Instruction::Input(1),
    ///         Instruction::Binary(Binary::Mul, 0, 1),
    ///         Instruction::Binary(Binary::Add, 2, 0),
    ///     ],
    ///     outputs: vec![3],
    /// };
    /// assert_eq!(program.live_ranges(), 5);
    /// ```
    pub fn live_ranges(&self) -> u64 {
        let mut last_read: Vec<usize> = (0..self.instructions.len()).collect();
        for (k, instruction) in self.instructions.iter().enumerate() {
            for operand in instruction.operands() {
                if let Some(last) = last_read.get_mut(operand as usize) {
                    *last = k;
                }
            }
        }
        last_read.iter().enumerate().map(|(k, &last)| last.saturating_sub(k) as u64).sum()
    }
}
