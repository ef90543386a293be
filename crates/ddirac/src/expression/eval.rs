//! The compiled program and its evaluation, generic over the scalar.
//!
//! The registers live on the stack: an array of 16 or 64 scalars chosen by the register count, or a
//! `Vec` above 64, so that evaluation allocates nothing on the heap for all but very large programs.
//! The array is initialised with `std::array::from_fn`, which for a num-dual number writes its real
//! part and the "absent" tags of its derivative parts only: an array of 64 HyperDualSVec64<4, 4>
//! (about 14 KB) costs a few hundred stores, far less than one multiplication of such numbers, so no
//! uninitialised memory (and no `unsafe`) is needed. Two size classes keep small programs from
//! touching 14 KB of stack.
//!
//! Copies of such numbers (224 bytes each) are a large part of the cost of an instruction, so sums,
//! differences and operations with a constant update their destination in place when it is their
//! first operand's register (see the register allocation in `emit`).

use super::functions::{Binary, Scalar, Unary};

/// One instruction; operands and destinations are register indices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Inst {
    Load {
        dst: u32,
        var: u32,
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
        op: Scalar,
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
    /// r[dst] = r[dst] ∘ c, in place (`Add`, `Mul`, `SubFrom`).
    ScalarUpdate {
        op: Scalar,
        dst: u32,
        c: f64,
    },
    SinCos {
        sin: u32,
        cos: u32,
        a: u32,
    },
}

/// Where the value of a program ends up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Result {
    Const(f64),
    Register(u32),
}

/// A compiled expression: a flat list of instructions over a small set of registers.
///
/// ```
/// use ddirac::expression::Scope;
/// use num_dual::first_derivative;
/// let program = Scope::new().variable("x").compile_expression("x^3 + sin(x)").unwrap();
/// let (value, derivative) = first_derivative(|x| program.eval(&[x]), 0.5);
/// assert!((value - (0.125 + 0.5f64.sin())).abs() < 1e-15);
/// assert!((derivative - (0.75 + 0.5f64.cos())).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    pub(super) instructions: Vec<Inst>,
    pub(super) registers: usize,
    pub(super) variables: usize,
    pub(super) result: Result,
}

impl Program {
    /// Number of variables `eval` expects.
    pub fn variables(&self) -> usize {
        self.variables
    }

    /// Number of registers the program uses.
    pub fn registers(&self) -> usize {
        self.registers
    }

    /// Number of instructions.
    pub fn instructions(&self) -> usize {
        self.instructions.len()
    }

    /// The value, if the expression depends on no variable.
    pub fn constant(&self) -> Option<f64> {
        match self.result {
            Result::Const(c) => Some(c),
            Result::Register(_) => None,
        }
    }

    /// The value at `vars` (in the order of the scope's variables).
    ///
    /// # Panics
    ///
    /// If `vars.len()` differs from [`Program::variables`].
    pub fn eval<D: crate::Scalar>(&self, vars: &[D]) -> D {
        assert_eq!(vars.len(), self.variables, "the program has {} variables", self.variables);
        self.eval_with(|i| vars[i])
    }

    /// The value with the i-th variable given by `load(i)`, called once for each variable the
    /// expression uses (i < [`Program::variables`]).
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
        for &inst in &self.instructions {
            match inst {
                Inst::Load { dst, var } => r[dst as usize] = load(var as usize),
                Inst::Const { dst, value } => r[dst as usize] = D::from(value),
                Inst::Unary { op, dst, a } => r[dst as usize] = op.apply(r[a as usize]),
                Inst::Binary { op, dst, a, b } => r[dst as usize] = op.apply(r[a as usize], &r[b as usize]),
                Inst::Scalar { op, dst, a, c } => r[dst as usize] = op.apply(r[a as usize], c),
                Inst::Update { op, dst, b } => {
                    let b = r[b as usize];
                    let x = &mut r[dst as usize];
                    match op {
                        Binary::Sub => *x -= b,
                        _ => *x += b,
                    }
                }
                Inst::ScalarUpdate { op, dst, c } => {
                    let x = &mut r[dst as usize];
                    match op {
                        Scalar::Add => *x += c,
                        Scalar::SubFrom => {
                            *x *= -1.0;
                            *x += c;
                        }
                        _ => *x *= c,
                    }
                }
                Inst::SinCos { sin, cos, a } => (r[sin as usize], r[cos as usize]) = r[a as usize].sin_cos(),
            }
        }
        match self.result {
            Result::Const(c) => D::from(c),
            Result::Register(register) => r[register as usize],
        }
    }
}
