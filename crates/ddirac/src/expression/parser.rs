//! A Pratt parser from tokens to the syntax tree.
//!
//! Binding powers, loosest first: `+ -` (left), `* /` (left), prefix `- +`, `^` (right). A sign binds
//! looser than `^`, so `-x^2` is `-(x^2)`, while `2^-x` is `2^(-x)`.
//!
//! Operations of one left-associative level in a row are read in a loop into one
//! [`ExprKind::Chain`], so a sum of a hundred thousand terms is as shallow as a sum of two: neither
//! the parser nor any pass over the tree recurses once per term. Recursion follows only real nesting
//! (parentheses, signs, powers, calls, a product inside a sum), which [`MAX_DEPTH`] bounds.

use super::ast::{BinaryOp, Expr, ExprKind, UnaryOp};
use super::lexer::{tokenize, Token, TokenKind};
use super::{Span, SyntaxError};

/// The deepest syntax tree accepted (levels of nesting: parentheses, signs, powers, calls, and one
/// level for each chain of operations, however long), so that the recursive passes over a tree stay
/// far from the limits of the stack.
pub const MAX_DEPTH: usize = 1000;

const PREFIX_POWER: u8 = 5;

const EXPRESSION: &str = "an expression (a number, a name, a function call, `(` or a sign)";

/// Parses one expression.
///
/// ```
/// use ddirac::expression::{parse, ExprKind, Span};
/// let expr = parse("-x^2").unwrap();
/// assert_eq!(expr.to_string(), "(-(x ^ 2.0))");
/// let error = parse("(x").unwrap_err();
/// assert_eq!(error.span(), Span::new(2, 2));
/// ```
pub fn parse(source: &str) -> Result<Expr, SyntaxError> {
    let tokens = tokenize(source)?;
    if tokens.is_empty() {
        return Err(SyntaxError::Empty { span: Span::new(0, source.len()) });
    }
    let mut parser = Parser { source, tokens, position: 0 };
    let (expr, _) = parser.expression(0, 0)?;
    match parser.peek() {
        Some(token) => Err(SyntaxError::TrailingInput { span: token.span, found: token.describe(source) }),
        None => Ok(expr),
    }
}

struct Parser<'s> {
    source: &'s str,
    tokens: Vec<Token>,
    position: usize,
}

/// A node and the depth of the tree below it.
type Parsed = (Expr, usize);

impl Parser<'_> {
    fn peek(&self) -> Option<Token> {
        self.tokens.get(self.position).copied()
    }

    fn next(&mut self) -> Option<Token> {
        let token = self.peek();
        self.position += token.is_some() as usize;
        token
    }

    fn end(&self) -> Span {
        Span::new(self.source.len(), self.source.len())
    }

    fn unexpected(&self, token: Option<Token>, expected: &str) -> SyntaxError {
        let (span, found) = match token {
            Some(token) => (token.span, token.describe(self.source)),
            None => (self.end(), "end of expression".to_owned()),
        };
        SyntaxError::UnexpectedToken { span, found, expected: expected.to_owned() }
    }

    fn node(kind: ExprKind, span: Span, depth: usize) -> Result<Parsed, SyntaxError> {
        if depth > MAX_DEPTH {
            return Err(SyntaxError::TooDeep { span, limit: MAX_DEPTH });
        }
        Ok((Expr { kind, span }, depth))
    }

    /// An expression whose operators all bind at least as tightly as `min_power`.
    fn expression(&mut self, min_power: u8, nesting: usize) -> Result<Parsed, SyntaxError> {
        if nesting > MAX_DEPTH {
            return Err(SyntaxError::TooDeep { span: self.peek().map_or(self.end(), |t| t.span), limit: MAX_DEPTH });
        }
        let (first, first_depth) = self.prefix(nesting)?;
        // The operations read so far at the level of the last operator: `lhs` is their value.
        let mut chain = Chain { first, depth: first_depth, rest: Vec::new() };
        while let Some(token) = self.peek() {
            let op = match token.kind {
                TokenKind::Plus => BinaryOp::Add,
                TokenKind::Minus => BinaryOp::Sub,
                TokenKind::Star => BinaryOp::Mul,
                TokenKind::Slash => BinaryOp::Div,
                TokenKind::Caret => BinaryOp::Pow,
                _ => break,
            };
            let (left_power, right_power) = match op {
                BinaryOp::Add | BinaryOp::Sub => (1, 2),
                BinaryOp::Mul | BinaryOp::Div => (3, 4),
                BinaryOp::Pow => (7, 6),
            };
            if left_power < min_power {
                break;
            }
            self.next();
            if op == BinaryOp::Mul {
                self.double_star(token)?;
            }
            let (rhs, rhs_depth) = self.expression(right_power, nesting + 1)?;
            let continues =
                chain.rest.last().is_some_and(|(last, _)| last.level() == op.level() && op != BinaryOp::Pow);
            if !continues && !chain.rest.is_empty() {
                let (lhs, depth) = chain.finish()?;
                chain = Chain { first: lhs, depth, rest: Vec::new() };
            }
            chain.depth = chain.depth.max(rhs_depth);
            chain.rest.push((op, rhs));
        }
        chain.finish()
    }

    /// The error for `**` (a power in other languages) at the first `*`, if the next token is a `*`
    /// right after it.
    fn double_star(&self, star: Token) -> Result<(), SyntaxError> {
        match self.peek() {
            Some(next) if next.kind == TokenKind::Star && next.span.start == star.span.end => {
                Err(SyntaxError::DoubleStar { span: star.span.to(next.span) })
            }
            _ => Ok(()),
        }
    }

    fn prefix(&mut self, nesting: usize) -> Result<Parsed, SyntaxError> {
        let token = self.next();
        let Some(token) = token else { return Err(self.unexpected(None, EXPRESSION)) };
        match token.kind {
            TokenKind::Number(value) => Self::node(ExprKind::Number(value), token.span, 1),
            TokenKind::Name => {
                let name = self.source[token.span.start..token.span.end].to_owned();
                match self.peek() {
                    Some(open) if open.kind == TokenKind::LeftParen => {
                        self.next();
                        self.call(name, token.span, open.span, nesting)
                    }
                    _ => Self::node(ExprKind::Name(name), token.span, 1),
                }
            }
            TokenKind::Minus | TokenKind::Plus => {
                let op = if token.kind == TokenKind::Minus { UnaryOp::Neg } else { UnaryOp::Plus };
                let (operand, depth) = self.expression(PREFIX_POWER, nesting + 1)?;
                let span = token.span.to(operand.span);
                Self::node(ExprKind::Unary { op, operand: Box::new(operand) }, span, depth + 1)
            }
            TokenKind::LeftParen => {
                let (mut inner, depth) = self.expression(0, nesting + 1)?;
                let close = self.close(token.span, "`)` or an operator")?;
                inner.span = token.span.to(close);
                Ok((inner, depth))
            }
            _ => Err(self.unexpected(Some(token), EXPRESSION)),
        }
    }

    /// The arguments of a call, after its `(`.
    fn call(&mut self, name: String, name_span: Span, open: Span, nesting: usize) -> Result<Parsed, SyntaxError> {
        let mut args = Vec::new();
        let mut depth = 0;
        if self.peek().map(|t| t.kind) != Some(TokenKind::RightParen) {
            loop {
                let (arg, arg_depth) = self.expression(0, nesting + 1)?;
                depth = depth.max(arg_depth);
                args.push(arg);
                if self.peek().map(|t| t.kind) == Some(TokenKind::Comma) {
                    self.next();
                } else {
                    break;
                }
            }
        }
        let close = self.close(open, "`,`, `)` or an operator")?;
        Self::node(ExprKind::Call { name, name_span, args }, name_span.to(close), depth + 1)
    }

    /// Consumes the `)` matching the `(` at `open`.
    fn close(&mut self, open: Span, expected: &str) -> Result<Span, SyntaxError> {
        match self.next() {
            Some(token) if token.kind == TokenKind::RightParen => Ok(token.span),
            None => Err(SyntaxError::MissingParen { span: self.end(), open }),
            other => Err(self.unexpected(other, expected)),
        }
    }
}

/// Operations of one level being read: `first`, then each operator with its right operand.
struct Chain {
    first: Expr,
    /// The depth of the deepest operand.
    depth: usize,
    rest: Vec<(BinaryOp, Expr)>,
}

impl Chain {
    /// The node of the chain: `first` alone, one [`ExprKind::Binary`] operation, or an
    /// [`ExprKind::Chain`].
    fn finish(mut self) -> Result<Parsed, SyntaxError> {
        let Some((_, last)) = self.rest.last() else { return Ok((self.first, self.depth)) };
        let span = self.first.span.to(last.span);
        let kind = if self.rest.len() == 1 {
            let (op, rhs) = self.rest.pop().expect("one operation");
            ExprKind::Binary { op, lhs: Box::new(self.first), rhs: Box::new(rhs) }
        } else {
            ExprKind::Chain { first: Box::new(self.first), rest: self.rest }
        };
        Parser::node(kind, span, self.depth + 1)
    }
}
