//! The syntax tree of an expression: every node carries the byte span of its source text.

use std::fmt;

use super::Span;

/// A node of the syntax tree.
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    /// What the node is.
    pub kind: ExprKind,
    /// Its source text.
    pub span: Span,
}

/// The kinds of syntax node.
#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    /// A number literal.
    Number(f64),
    /// A variable, constant or definition, by name.
    Name(String),
    /// A sign applied to an operand.
    Unary {
        /// `-` or `+`.
        op: UnaryOp,
        /// The operand.
        operand: Box<Expr>,
    },
    /// A binary operation.
    Binary {
        /// The operator.
        op: BinaryOp,
        /// Left operand.
        lhs: Box<Expr>,
        /// Right operand.
        rhs: Box<Expr>,
    },
    /// A function call.
    Call {
        /// The function name.
        name: String,
        /// The span of the name alone.
        name_span: Span,
        /// The arguments.
        args: Vec<Expr>,
    },
}

/// Prefix operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum UnaryOp {
    /// `-x`
    Neg,
    /// `+x`
    Plus,
}

/// Infix operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BinaryOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^` (right-associative)
    Pow,
}

impl BinaryOp {
    /// The operator's symbol.
    pub fn symbol(self) -> char {
        match self {
            BinaryOp::Add => '+',
            BinaryOp::Sub => '-',
            BinaryOp::Mul => '*',
            BinaryOp::Div => '/',
            BinaryOp::Pow => '^',
        }
    }
}

/// Prints the expression with every operation in parentheses, so that parsing the text gives back the
/// same tree (up to spans). Numbers print in Rust's shortest round-trip notation; a negative number
/// prints as a sign applied to a positive one.
///
/// ```
/// let expr = ddirac::expression::parse("-x^2 + atan2(y, 1.5e-3)").unwrap();
/// assert_eq!(expr.to_string(), "((-(x ^ 2.0)) + atan2(y, 0.0015))");
/// ```
impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            ExprKind::Number(value) if *value < 0.0 => write!(f, "(-{:?})", -value),
            ExprKind::Number(value) => write!(f, "{value:?}"),
            ExprKind::Name(name) => write!(f, "{name}"),
            ExprKind::Unary { op: UnaryOp::Neg, operand } => write!(f, "(-{operand})"),
            ExprKind::Unary { op: UnaryOp::Plus, operand } => write!(f, "(+{operand})"),
            ExprKind::Binary { op, lhs, rhs } => write!(f, "({lhs} {} {rhs})", op.symbol()),
            ExprKind::Call { name, args, .. } => {
                write!(f, "{name}(")?;
                for (i, arg) in args.iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    write!(f, "{arg}")?;
                }
                write!(f, ")")
            }
        }
    }
}
