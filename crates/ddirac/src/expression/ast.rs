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
    /// A binary operation. The parser gives this for `^` and for a single `+ - * /`; two or more
    /// operations of one level in a row are a [`ExprKind::Chain`].
    Binary {
        /// The operator.
        op: BinaryOp,
        /// Left operand.
        lhs: Box<Expr>,
        /// Right operand.
        rhs: Box<Expr>,
    },
    /// A left-associative chain of two or more operations of one level (`+ -`, or `* /`), as the
    /// parser reads `a + b - c`: the value of `first`, combined with each operand in turn,
    /// ((a + b) − c). Keeping the operands of a chain side by side, rather than nested, keeps the depth
    /// of the tree independent of the length of a sum or a product.
    ///
    /// ```
    /// use ddirac::expression::{parse, BinaryOp, ExprKind};
    /// let expr = parse("a + b - c").unwrap();
    /// let ExprKind::Chain { first, rest } = &expr.kind else { panic!("a chain") };
    /// assert_eq!(first.to_string(), "a");
    /// assert_eq!(rest.iter().map(|(op, _)| *op).collect::<Vec<_>>(), [BinaryOp::Add, BinaryOp::Sub]);
    /// assert_eq!(expr.to_string(), "(a + b - c)");
    /// ```
    Chain {
        /// The first operand.
        first: Box<Expr>,
        /// Each further operator with its right operand, left to right.
        rest: Vec<(BinaryOp, Expr)>,
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
    /// The precedence level: 0 for `+ -`, 1 for `* /`, 2 for `^`.
    pub fn level(self) -> u8 {
        match self {
            BinaryOp::Add | BinaryOp::Sub => 0,
            BinaryOp::Mul | BinaryOp::Div => 1,
            BinaryOp::Pow => 2,
        }
    }

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

/// Prints the expression with every operation (every chain) in parentheses, so that parsing the text
/// gives back the same tree (up to spans). Numbers print in Rust's shortest round-trip notation; a
/// negative number prints as a sign applied to a positive one. A chain whose operators are not all of
/// one level `+ -` or `* /` (which the parser does not make) prints as nested operations.
///
/// ```
/// let expr = ddirac::expression::parse("-x^2 + atan2(y, 1.5e-3) - 2*x*y").unwrap();
/// assert_eq!(expr.to_string(), "((-(x ^ 2.0)) + atan2(y, 0.0015) - (2.0 * x * y))");
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
            ExprKind::Chain { first, rest } => {
                let level = rest.first().map(|(op, _)| op.level());
                let flat = level != Some(2) && rest.iter().all(|(op, _)| Some(op.level()) == level);
                let opening = if flat { 1 } else { rest.len() };
                write!(f, "{}{first}", "(".repeat(opening))?;
                for (op, operand) in rest {
                    write!(f, " {} {operand}{}", op.symbol(), if flat { "" } else { ")" })?;
                }
                if flat {
                    write!(f, ")")?;
                }
                Ok(())
            }
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
