//! Lagrangians written as text: a small expression language, compiled once to a program of the
//! compiled IR and evaluated generically over the scalar (f64 or any num-dual number), so that
//! automatic differentiation gives every derivative exactly as for a Lagrangian written in Rust.
//!
//! # Language
//!
//! ```text
//! expression := term (("+" | "-") term)*
//! term       := unary (("*" | "/") unary)*
//! unary      := ("-" | "+") unary | power
//! power      := atom ("^" unary)?            right-associative: 2^3^2 = 2^(3^2)
//! atom       := number | name | name "(" arguments ")" | "(" expression ")"
//! ```
//!
//! `^` binds tighter than a sign, so `-x^2` is `-(x^2)`. A run of `+ -` (or of `* /`) is read in a
//! loop into one [`ExprKind::Chain`], so a sum of any length is one level of the tree; real nesting
//! (parentheses, signs, powers, calls) is limited to [`MAX_DEPTH`] levels. `**` is an error that
//! says to write `^`. Numbers take any usual notation (`1`, `1.5`, `.5`, `3.`, `1e-3`, `2.5E+4`);
//! names are `[A-Za-z_][A-Za-z0-9_]*`. The functions are `sin cos tan asin acos atan sinh cosh tanh
//! exp ln log sqrt abs` (one argument; `log` is the natural logarithm, like `ln`) and `atan2(y, x)
//! pow(x, y) min(a, b) max(a, b)` ([`FUNCTIONS`]); the constant is `pi` ([`CONSTANTS`]), and no
//! coordinate, parameter or definition may take its name. `x^n` (or `pow(x, n)`) with an integer constant
//! n, |n| ≤ 16, is the product of binary exponentiation (`x^2` is x·x, as in `powi`), with
//! 16 < |n| ≤ 1024 `powi`, with another constant exponent `powf` (`x^0.5` is `sqrt(x)`), and
//! otherwise `exp(n ln x)`.
//! `min`/`max` pick one argument by value (the first when they are equal) and carry that argument's
//! derivatives; compiled, they are one operation each, valid on both sides of the kink.
//!
//! # Compilation
//!
//! A [`Scope`] names the variables (in the order of the slice given to
//! [`CompiledExpression::eval`]), the constants (parameters) and the definitions (named expressions,
//! which may refer to one another, but not in a cycle). [`Scope::compile`] resolves names and lowers
//! the text into the graph of the compiled IR ([`crate::compiled`], the graph a trace of a Rust
//! Lagrangian builds, with the same operations): every subexpression that does not depend on a
//! variable is folded into an f64, identical subexpressions are merged (so each definition and each
//! repeated `sin(φ)` is computed once), and exact scalings by powers of two are merged. The result
//! is a [`crate::compiled::Program`] with two back ends: its interpreter
//! ([`crate::compiled::Interpreter`], which pairs `sin`/`cos` of one argument into one `sin_cos`,
//! keeps constant operands on the cheap scalar path of dual numbers and allocates registers by
//! linear scan) and native code. Definitions are lowered each after those it uses, in an order found
//! without recursion, so that a long chain of definitions needs no deep stack. Folding may change the
//! last bits of a result relative to a literal left-to-right evaluation.
//!
//! Every token and syntax node carries its byte [`Span`] in its source, and every error names the
//! source it belongs to ([`Origin`]: the Lagrangian, a definition, an exact solution), so that a
//! caller can point at the offending text in a spec file. An unknown name comes with the closest
//! known one, a name that differs only in case first (`K` → `k`).
//!
//! ```
//! use ddirac::expression::Scope;
//! let scope = Scope::new().variable("x").variable("x_dot").constant("m", 2.0).definition("v2", "x_dot^2");
//! let compiled = scope.compile_expression("0.5*m*v2 - cos(x)").unwrap();
//! assert!((compiled.eval(&[0.0f64, 3.0]) - 8.0).abs() < 1e-15);
//! ```
//!
//! [`ExpressionSystem`] turns a coordinate list, a Lagrangian, definitions and parameters into a
//! [`System`](crate::System).

mod ast;
mod atlas;
mod compile;
mod compiled_expression;
mod compiled_spec;
mod definitions;
mod erased;
mod error;
mod functions;
mod lagrangian;
mod lexer;
mod parser;
mod scope;
mod spec;
mod system;

pub use ast::{BinaryOp, Expr, ExprKind, UnaryOp};
pub use compiled_expression::CompiledExpression;
pub(crate) use compiled_spec::compile_rigid;
pub use compiled_spec::ATTITUDE_NAMES;
pub use error::{CycleStep, ExpressionError, Origin, SyntaxError};
pub use functions::{CONSTANTS, FUNCTIONS};
pub use lagrangian::ExpressionLagrangian;
pub use lexer::{tokenize, Token, TokenKind};
pub use parser::{parse, MAX_DEPTH};
pub use scope::Scope;
pub use spec::{ChartPart, ChartSpec, ExpressionSpec};
pub use system::ExpressionSystem;

/// A byte range `start..end` in a source text.
///
/// ```
/// use ddirac::expression::{parse, Span};
/// let expr = parse("1 + foo").unwrap();
/// assert_eq!(expr.span, Span::new(0, 7));
/// assert_eq!(&"1 + foo"[std::ops::Range::from(Span::new(4, 7))], "foo");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// First byte.
    pub start: usize,
    /// One past the last byte.
    pub end: usize,
}

impl Span {
    /// The range `start..end`.
    pub fn new(start: usize, end: usize) -> Self {
        Self { start, end }
    }

    /// The smallest span covering `self` and `other`.
    pub fn to(self, other: Span) -> Span {
        Span::new(self.start.min(other.start), self.end.max(other.end))
    }

    /// Number of bytes covered.
    pub fn len(&self) -> usize {
        self.end - self.start
    }

    /// Whether the span covers no byte (a position, e.g. the end of the input).
    pub fn is_empty(&self) -> bool {
        self.start == self.end
    }
}

impl From<Span> for std::ops::Range<usize> {
    fn from(span: Span) -> Self {
        span.start..span.end
    }
}

impl std::fmt::Display for Span {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}..{}", self.start, self.end)
    }
}
