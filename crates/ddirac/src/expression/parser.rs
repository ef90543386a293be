//! A Pratt parser from tokens to the syntax tree.
//!
//! Binding powers, loosest first: `+ -` (left), `* /` (left), prefix `- +`, `^` (right). A sign binds
//! looser than `^`, so `-x^2` is `-(x^2)`, while `2^-x` is `2^(-x)`.

use super::ast::{BinaryOp, Expr, ExprKind, UnaryOp};
use super::lexer::{tokenize, Token, TokenKind};
use super::{Span, SyntaxError};

/// The deepest syntax tree accepted (levels of nesting, counting every operation), so that the
/// recursive passes over a tree stay far from the limits of the stack.
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
        let (mut lhs, mut depth) = self.prefix(nesting)?;
        loop {
            let op = match self.peek().map(|t| t.kind) {
                Some(TokenKind::Plus) => BinaryOp::Add,
                Some(TokenKind::Minus) => BinaryOp::Sub,
                Some(TokenKind::Star) => BinaryOp::Mul,
                Some(TokenKind::Slash) => BinaryOp::Div,
                Some(TokenKind::Caret) => BinaryOp::Pow,
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
            let (rhs, rhs_depth) = self.expression(right_power, nesting + 1)?;
            let span = lhs.span.to(rhs.span);
            let kind = ExprKind::Binary { op, lhs: Box::new(lhs), rhs: Box::new(rhs) };
            (lhs, depth) = Self::node(kind, span, depth.max(rhs_depth) + 1)?;
        }
        Ok((lhs, depth))
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
