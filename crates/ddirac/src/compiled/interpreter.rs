//! The interpreter back end of a [`Program`]: its one output evaluated over any [`crate::Scalar`]
//! (f64, dual numbers, a traced number), the other back end being native code ([`super::jit`]).
//!
//! [`Interpreter::new`] turns the program, whose instruction k writes register k, into steps over a
//! few reused registers:
//!
//! - an operation with a constant operand (x + c, x − c, c − x, x · c, x / c, c / x, xᶜ) takes the
//!   constant as an f64, on the cheap scalar path of dual numbers; other constants are loaded;
//! - `sin` and `cos` of one argument become one `sin_cos`;
//! - registers are allocated by linear scan, so that the register count is the largest number of
//!   values alive at once. A register is free again after the last step that reads it; a result takes
//!   the register of its first operand when that operand dies there (sums, differences, negations
//!   and scalar updates are then made in place, without copying the number), and otherwise the
//!   lowest free register.
//!
//! Each step calls the scalar's own operation, so on a [`super::Traced`] number the interpreter
//! replays the program's operations into the trace: min and max through [`crate::Scalar::min_of`]
//! and [`crate::Scalar::max_of`], which a trace records as operations. The indicator
//! [`Binary::Less`], the gate [`Binary::Gate`] and [`Unary::Signum`] (which only derivative programs
//! contain) are comparisons on a generic scalar.
//!
//! The registers live on the stack: an array of 16 or 64 scalars chosen by the register count, or a
//! `Vec` above 64, so that evaluation allocates nothing on the heap for all but very large programs.
//! The array is initialised with `std::array::from_fn`, which for a num-dual number writes its real
//! part and the "absent" tags of its derivative parts only: an array of 64 HyperDualSVec64<4, 4>
//! (about 14 KB) costs a few hundred stores, far less than one multiplication of such numbers, so no
//! uninitialised memory (and no `unsafe`) is needed. Two size classes keep small programs from
//! touching 14 KB of stack.

use std::collections::HashMap;

use super::program::{Binary, Instruction, Program, Unary};

/// An operation of one operand x and an f64 constant c.
#[derive(Debug, Clone, Copy, PartialEq)]
enum WithConstant {
    /// x + c
    Add,
    /// x − c
    Sub,
    /// c − x
    SubFrom,
    /// x · c
    Mul,
    /// x / c
    Div,
    /// c / x
    DivInto,
    /// xᶜ
    Powf,
}

impl WithConstant {
    #[inline(always)]
    fn apply<D: crate::Scalar>(self, x: D, c: f64) -> D {
        match self {
            WithConstant::Add => x + c,
            WithConstant::Sub => x - c,
            WithConstant::SubFrom => -x + c,
            WithConstant::Mul => x * c,
            WithConstant::Div => x / D::from(c),
            WithConstant::DivInto => D::from(c) / x,
            WithConstant::Powf => x.powf(c),
        }
    }
}

/// One step; operands and destinations are register indices.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Step {
    Load {
        dst: u32,
        input: u32,
    },
    Const {
        dst: u32,
        value: f64,
    },
    Unary {
        op: Unary,
        dst: u32,
        a: u32,
    },
    Binary {
        op: Binary,
        dst: u32,
        a: u32,
        b: u32,
    },
    Scalar {
        op: WithConstant,
        dst: u32,
        a: u32,
        c: f64,
    },
    /// r[dst] ∘= r[b], in place (`Add`, `Sub`).
    Update {
        op: Binary,
        dst: u32,
        b: u32,
    },
    /// r[dst] = r[dst] ∘ c, in place (`Add`, `Sub`, `SubFrom`, `Mul`).
    ScalarUpdate {
        op: WithConstant,
        dst: u32,
        c: f64,
    },
    Powi {
        dst: u32,
        a: u32,
        n: i32,
    },
    SinCos {
        sin: u32,
        cos: u32,
        a: u32,
    },
}

/// Where the value ends up.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Output {
    Const(f64),
    Register(u32),
}

/// What an instruction computes, with constant operands folded into the scalar forms; operands are
/// instruction indices.
#[derive(Debug, Clone, Copy)]
enum Form {
    Load(u32),
    Const(f64),
    Unary(Unary, u32),
    Binary(Binary, u32, u32),
    Scalar(WithConstant, u32, f64),
    Powi(u32, i32),
}

impl Form {
    fn of(instruction: Instruction, constant: impl Fn(u32) -> Option<f64>) -> Form {
        match instruction {
            Instruction::Input(i) => Form::Load(i),
            Instruction::Const(bits) => Form::Const(f64::from_bits(bits)),
            Instruction::Unary(op, a) => Form::Unary(op, a),
            Instruction::Powi(a, n) => Form::Powi(a, n),
            Instruction::Binary(op, a, b) => {
                let scalar = match (op, constant(a), constant(b)) {
                    (_, Some(_), Some(_)) => None,
                    (Binary::Add, None, Some(c)) => Some((WithConstant::Add, a, c)),
                    (Binary::Add, Some(c), None) => Some((WithConstant::Add, b, c)),
                    (Binary::Sub, None, Some(c)) => Some((WithConstant::Sub, a, c)),
                    (Binary::Sub, Some(c), None) => Some((WithConstant::SubFrom, b, c)),
                    (Binary::Mul, None, Some(c)) => Some((WithConstant::Mul, a, c)),
                    (Binary::Mul, Some(c), None) => Some((WithConstant::Mul, b, c)),
                    (Binary::Div, None, Some(c)) => Some((WithConstant::Div, a, c)),
                    (Binary::Div, Some(c), None) => Some((WithConstant::DivInto, b, c)),
                    (Binary::Pow, None, Some(c)) => Some((WithConstant::Powf, a, c)),
                    _ => None,
                };
                match scalar {
                    Some((op, x, c)) => Form::Scalar(op, x, c),
                    None => Form::Binary(op, a, b),
                }
            }
        }
    }

    /// The instructions this form reads.
    fn operands(self) -> impl Iterator<Item = u32> {
        let (a, b) = match self {
            Form::Load(_) | Form::Const(_) => (None, None),
            Form::Unary(_, a) | Form::Scalar(_, a, _) | Form::Powi(a, _) => (Some(a), None),
            Form::Binary(_, a, b) => (Some(a), Some(b)),
        };
        a.into_iter().chain(b)
    }
}

/// A program's one output as steps over reused registers, evaluated generically over the scalar.
///
/// ```
/// use ddirac::compiled::{Binary, Instruction, Interpreter, Program, Unary};
/// use num_dual::first_derivative;
/// // x · sin x + 2
/// let program = Program {
///     inputs: 1,
///     instructions: vec![
///         Instruction::Input(0),
///         Instruction::Unary(Unary::Sin, 0),
///         Instruction::Binary(Binary::Mul, 0, 1),
///         Instruction::constant(2.0),
///         Instruction::Binary(Binary::Add, 2, 3),
///     ],
///     outputs: vec![4],
/// };
/// let interpreter = Interpreter::new(&program);
/// let (value, derivative) = first_derivative(|x| interpreter.eval_with(|_| x), 0.5);
/// assert_eq!(value, 0.5 * 0.5f64.sin() + 2.0);
/// assert!((derivative - (0.5f64.sin() + 0.5 * 0.5f64.cos())).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Interpreter {
    steps: Vec<Step>,
    registers: usize,
    inputs: usize,
    output: Output,
}

impl Interpreter {
    /// The interpreter of `program`'s one output.
    ///
    /// # Panics
    ///
    /// If the program has another number of outputs than one, or an instruction reads a register
    /// that is not before it.
    pub fn new(program: &Program) -> Self {
        assert_eq!(program.outputs.len(), 1, "the interpreter evaluates programs of one output");
        let constant = |r: u32| match program.instructions[r as usize] {
            Instruction::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        };
        let forms: Vec<Form> = program.instructions.iter().map(|&i| Form::of(i, constant)).collect();
        let output = program.outputs[0] as usize;
        if let Form::Const(c) = forms[output] {
            return Self { steps: Vec::new(), registers: 0, inputs: program.inputs, output: Output::Const(c) };
        }
        let n = forms.len();
        let mut live = vec![false; n];
        live[output] = true;
        for i in (0..=output).rev() {
            if live[i] {
                forms[i].operands().for_each(|o| live[o as usize] = true);
            }
        }

        // sin and cos of one argument: both are computed at the first of the two positions.
        let mut partner: Vec<Option<usize>> = vec![None; n];
        let mut sines = HashMap::new();
        for (i, form) in forms.iter().enumerate().filter(|(i, _)| live[*i]) {
            if let Form::Unary(Unary::Sin, a) = form {
                sines.insert(*a, i);
            }
        }
        for (i, form) in forms.iter().enumerate().filter(|(i, _)| live[*i]) {
            if let Form::Unary(Unary::Cos, a) = form {
                if let Some(&s) = sines.get(a) {
                    (partner[s], partner[i]) = (Some(i), Some(s));
                }
            }
        }
        let position = |i: usize| partner[i].map_or(i, |p| p.min(i));

        let mut last_use = vec![0usize; n];
        for i in (0..n).filter(|&i| live[i]) {
            forms[i].operands().for_each(|o| last_use[o as usize] = last_use[o as usize].max(position(i)));
        }
        last_use[output] = usize::MAX;

        let mut allocator = Allocator::default();
        let mut register = vec![0u32; n];
        let mut steps = Vec::new();
        for i in (0..n).filter(|&i| live[i]) {
            if position(i) != i {
                continue;
            }
            let mut operands: Vec<u32> = forms[i].operands().collect();
            if matches!(forms[i], Form::Binary(Binary::Add | Binary::Mul, ..))
                && last_use[operands[0] as usize] != i
                && last_use[operands[1] as usize] == i
            {
                operands.swap(0, 1);
            }
            let read: Vec<u32> = operands.iter().map(|&o| register[o as usize]).collect();
            let mut freed = Vec::with_capacity(2);
            for &o in &operands {
                if last_use[o as usize] == i && !freed.contains(&o) {
                    allocator.free(register[o as usize]);
                    freed.push(o);
                }
            }
            // A result overwrites its first operand's register when that operand dies here, so that
            // updates can be made in place.
            let dst = allocator.take(freed.first().filter(|&&o| o == operands[0]).map(|&o| register[o as usize]));
            register[i] = dst;
            let in_place = read.first() == Some(&dst);
            steps.push(match forms[i] {
                Form::Load(input) => Step::Load { dst, input },
                Form::Const(value) => Step::Const { dst, value },
                Form::Unary(op @ (Unary::Sin | Unary::Cos), _) if partner[i].is_some() => {
                    let second = allocator.take(None);
                    register[partner[i].unwrap_or(i)] = second;
                    let (sin, cos) = if op == Unary::Sin { (dst, second) } else { (second, dst) };
                    Step::SinCos { sin, cos, a: read[0] }
                }
                Form::Unary(Unary::Neg, _) if in_place => Step::ScalarUpdate { op: WithConstant::Mul, dst, c: -1.0 },
                Form::Unary(op, _) => Step::Unary { op, dst, a: read[0] },
                Form::Binary(op @ (Binary::Add | Binary::Sub), _, _) if in_place => {
                    Step::Update { op, dst, b: read[1] }
                }
                Form::Binary(op, _, _) => Step::Binary { op, dst, a: read[0], b: read[1] },
                Form::Scalar(
                    op @ (WithConstant::Add | WithConstant::Sub | WithConstant::SubFrom | WithConstant::Mul),
                    _,
                    c,
                ) if in_place => Step::ScalarUpdate { op, dst, c },
                Form::Scalar(op, _, c) => Step::Scalar { op, dst, a: read[0], c },
                Form::Powi(_, n) => Step::Powi { dst, a: read[0], n },
            });
        }
        Self {
            steps,
            registers: allocator.in_use.len(),
            inputs: program.inputs,
            output: Output::Register(register[output]),
        }
    }

    /// Number of inputs the program reads.
    pub fn inputs(&self) -> usize {
        self.inputs
    }

    /// Number of registers the steps use.
    pub fn registers(&self) -> usize {
        self.registers
    }

    /// Number of steps.
    pub fn steps(&self) -> usize {
        self.steps.len()
    }

    /// The value, if the output is a constant.
    pub fn constant(&self) -> Option<f64> {
        match self.output {
            Output::Const(c) => Some(c),
            Output::Register(_) => None,
        }
    }

    /// The value with the i-th input given by `load(i)`, called once for each input the output
    /// reads (i < [`Interpreter::inputs`]).
    #[inline]
    pub fn eval_with<D: crate::Scalar>(&self, load: impl Fn(usize) -> D) -> D {
        let zero = |_| D::from(0.0);
        match self.registers {
            0 => self.run(&mut [], load),
            1..=16 => self.run(&mut std::array::from_fn::<D, 16, _>(zero), load),
            17..=64 => self.run(&mut std::array::from_fn::<D, 64, _>(zero), load),
            _ => self.run(&mut vec![D::from(0.0); self.registers], load),
        }
    }

    fn run<D: crate::Scalar>(&self, r: &mut [D], load: impl Fn(usize) -> D) -> D {
        for &step in &self.steps {
            match step {
                Step::Load { dst, input } => r[dst as usize] = load(input as usize),
                Step::Const { dst, value } => r[dst as usize] = D::from(value),
                Step::Unary { op, dst, a } => r[dst as usize] = op.apply(r[a as usize]),
                Step::Binary { op, dst, a, b } => r[dst as usize] = op.apply(r[a as usize], r[b as usize]),
                Step::Scalar { op, dst, a, c } => r[dst as usize] = op.apply(r[a as usize], c),
                Step::Update { op, dst, b } => {
                    let b = r[b as usize];
                    let x = &mut r[dst as usize];
                    match op {
                        Binary::Sub => *x -= b,
                        _ => *x += b,
                    }
                }
                Step::ScalarUpdate { op, dst, c } => {
                    let x = &mut r[dst as usize];
                    match op {
                        WithConstant::Add => *x += c,
                        WithConstant::Sub => *x -= c,
                        WithConstant::SubFrom => {
                            *x *= -1.0;
                            *x += c;
                        }
                        _ => *x *= c,
                    }
                }
                Step::Powi { dst, a, n } => r[dst as usize] = r[a as usize].powi(n),
                Step::SinCos { sin, cos, a } => (r[sin as usize], r[cos as usize]) = r[a as usize].sin_cos(),
            }
        }
        match self.output {
            Output::Const(c) => D::from(c),
            Output::Register(register) => r[register as usize],
        }
    }
}

/// Registers in use.
#[derive(Default)]
struct Allocator {
    in_use: Vec<bool>,
}

impl Allocator {
    /// Takes `preferred` if it is free, else the lowest free register.
    fn take(&mut self, preferred: Option<u32>) -> u32 {
        if let Some(r) = preferred.filter(|&r| !self.in_use[r as usize]) {
            self.in_use[r as usize] = true;
            return r;
        }
        match self.in_use.iter().position(|used| !used) {
            Some(r) => {
                self.in_use[r] = true;
                r as u32
            }
            None => {
                self.in_use.push(true);
                (self.in_use.len() - 1) as u32
            }
        }
    }

    fn free(&mut self, register: u32) {
        self.in_use[register as usize] = false;
    }
}
