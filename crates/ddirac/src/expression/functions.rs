//! The operations of a compiled program and the functions of the language, each evaluated generically
//! over the scalar. Constant folding evaluates the same code at f64, so a folded constant equals what
//! the program would compute.

/// The functions of the language, by name.
pub const FUNCTIONS: &[&str] = &[
    "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "exp", "ln", "log", "sqrt", "abs",
    "pow", "min", "max",
];

/// A function of the language.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Function {
    Unary(Unary),
    Binary(Binary),
}

impl Function {
    pub(super) fn named(name: &str) -> Option<Function> {
        use Function::{Binary as B, Unary as U};
        Some(match name {
            "sin" => U(Unary::Sin),
            "cos" => U(Unary::Cos),
            "tan" => U(Unary::Tan),
            "asin" => U(Unary::Asin),
            "acos" => U(Unary::Acos),
            "atan" => U(Unary::Atan),
            "sinh" => U(Unary::Sinh),
            "cosh" => U(Unary::Cosh),
            "tanh" => U(Unary::Tanh),
            "exp" => U(Unary::Exp),
            "ln" | "log" => U(Unary::Ln),
            "sqrt" => U(Unary::Sqrt),
            "abs" => U(Unary::Abs),
            "atan2" => B(Binary::Atan2),
            "pow" => B(Binary::Pow),
            "min" => B(Binary::Min),
            "max" => B(Binary::Max),
            _ => return None,
        })
    }

    pub(super) fn arity(self) -> usize {
        match self {
            Function::Unary(_) => 1,
            Function::Binary(_) => 2,
        }
    }
}

/// Operations of one operand.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Unary {
    Neg,
    Recip,
    Square,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Exp,
    Ln,
    Sqrt,
    Abs,
}

impl Unary {
    #[inline(always)]
    pub(super) fn apply<D: crate::Scalar>(self, x: D) -> D {
        match self {
            Unary::Neg => -x,
            Unary::Recip => x.recip(),
            Unary::Square => x * x,
            Unary::Sin => x.sin(),
            Unary::Cos => x.cos(),
            Unary::Tan => x.tan(),
            Unary::Asin => x.asin(),
            Unary::Acos => x.acos(),
            Unary::Atan => x.atan(),
            Unary::Sinh => x.sinh(),
            Unary::Cosh => x.cosh(),
            Unary::Tanh => x.tanh(),
            Unary::Exp => x.exp(),
            Unary::Ln => x.ln(),
            Unary::Sqrt => x.sqrt(),
            Unary::Abs => x.abs(),
        }
    }
}

/// Operations of two operands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Binary {
    Add,
    Sub,
    Mul,
    Div,
    /// x^y = exp(y ln x) for a non-constant exponent.
    Pow,
    /// atan2(y, x).
    Atan2,
    /// The smaller operand (the first when equal).
    Min,
    /// The larger operand (the first when equal).
    Max,
}

impl Binary {
    #[inline(always)]
    pub(super) fn apply<D: crate::Scalar>(self, a: D, b: &D) -> D {
        match self {
            Binary::Add => a + b,
            Binary::Sub => a - b,
            Binary::Mul => a * b,
            Binary::Div => a / b,
            Binary::Pow => a.powd(*b),
            Binary::Atan2 => a.atan2(*b),
            Binary::Min => {
                if *b < a {
                    *b
                } else {
                    a
                }
            }
            Binary::Max => {
                if *b > a {
                    *b
                } else {
                    a
                }
            }
        }
    }
}

/// Operations of one operand and an f64 constant c, on the cheap scalar path of the dual numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Scalar {
    /// x + c
    Add,
    /// x · c
    Mul,
    /// c − x
    SubFrom,
    /// c / x
    DivInto,
    /// x^c with an integer c (`powi`)
    Powi,
    /// x^c (`powf`)
    Powf,
}

impl Scalar {
    #[inline(always)]
    pub(super) fn apply<D: crate::Scalar>(self, x: D, c: f64) -> D {
        match self {
            Scalar::Add => x + c,
            Scalar::Mul => x * c,
            Scalar::SubFrom => -x + c,
            Scalar::DivInto => x.recip() * c,
            Scalar::Powi => x.powi(c as i32),
            Scalar::Powf => x.powf(c),
        }
    }
}
