//! Tokens of the expression language, each with its byte span.

use super::{Span, SyntaxError};

/// What a token is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TokenKind {
    /// A number literal and its value.
    Number(f64),
    /// A name `[A-Za-z_][A-Za-z0-9_]*` (its text is the token's span in the source).
    Name,
    /// `+`
    Plus,
    /// `-`
    Minus,
    /// `*`
    Star,
    /// `/`
    Slash,
    /// `^`
    Caret,
    /// `(`
    LeftParen,
    /// `)`
    RightParen,
    /// `,`
    Comma,
}

/// A token and its byte span.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Token {
    /// What it is.
    pub kind: TokenKind,
    /// Where it is.
    pub span: Span,
}

impl Token {
    /// A description for error messages, e.g. "`)`" or "name `y`".
    pub(super) fn describe(&self, source: &str) -> String {
        let text = &source[self.span.start..self.span.end];
        match self.kind {
            TokenKind::Number(_) => format!("number `{text}`"),
            TokenKind::Name => format!("name `{text}`"),
            _ => format!("`{text}`"),
        }
    }
}

/// Splits `source` into tokens, skipping white space.
///
/// ```
/// use ddirac::expression::{tokenize, Span, TokenKind};
/// let tokens = tokenize("2.5e1*x_dot").unwrap();
/// assert_eq!(tokens[0].kind, TokenKind::Number(25.0));
/// assert_eq!(tokens[2].span, Span::new(6, 11));
/// assert!(tokenize("2 $ 3").is_err());
/// ```
pub fn tokenize(source: &str) -> Result<Vec<Token>, SyntaxError> {
    let bytes = source.as_bytes();
    let mut tokens = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let start = i;
        let b = bytes[i];
        let kind = match b {
            b' ' | b'\t' | b'\n' | b'\r' => {
                i += 1;
                continue;
            }
            b'0'..=b'9' | b'.' => {
                let (value, end) = number(source, start)?;
                i = end;
                TokenKind::Number(value)
            }
            b'A'..=b'Z' | b'a'..=b'z' | b'_' => {
                i += 1;
                while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                    i += 1;
                }
                TokenKind::Name
            }
            _ => {
                i += 1;
                match b {
                    b'+' => TokenKind::Plus,
                    b'-' => TokenKind::Minus,
                    b'*' => TokenKind::Star,
                    b'/' => TokenKind::Slash,
                    b'^' => TokenKind::Caret,
                    b'(' => TokenKind::LeftParen,
                    b')' => TokenKind::RightParen,
                    b',' => TokenKind::Comma,
                    _ => {
                        let found = source[start..].chars().next().unwrap_or('\u{fffd}');
                        let span = Span::new(start, start + found.len_utf8());
                        return Err(SyntaxError::UnexpectedCharacter { span, found });
                    }
                }
            }
        };
        tokens.push(Token { kind, span: Span::new(start, i) });
    }
    Ok(tokens)
}

/// Reads the number starting at `start`: digits, an optional fraction, an optional exponent.
fn number(source: &str, start: usize) -> Result<(f64, usize), SyntaxError> {
    let bytes = source.as_bytes();
    let digits = |mut i: usize| {
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            i += 1;
        }
        i
    };
    let mut i = digits(start);
    let integer_digits = i - start;
    if i < bytes.len() && bytes[i] == b'.' {
        let fraction = digits(i + 1);
        if integer_digits == 0 && fraction == i + 1 {
            return Err(SyntaxError::UnexpectedCharacter { span: Span::new(start, start + 1), found: '.' });
        }
        i = fraction;
    }
    if i < bytes.len() && (bytes[i] == b'e' || bytes[i] == b'E') {
        let mut j = i + 1;
        if j < bytes.len() && (bytes[j] == b'+' || bytes[j] == b'-') {
            j += 1;
        }
        let end = digits(j);
        if end == j {
            return Err(SyntaxError::MalformedNumber {
                span: Span::new(start, j),
                text: source[start..j].to_owned(),
                why: "expected digits after the exponent marker",
            });
        }
        i = end;
    }
    let text = &source[start..i];
    let malformed = |why| SyntaxError::MalformedNumber { span: Span::new(start, i), text: text.to_owned(), why };
    match text.parse::<f64>() {
        Ok(value) if value.is_finite() => Ok((value, i)),
        Ok(_) => Err(malformed("too large for a 64-bit float")),
        Err(_) => Err(malformed("not a decimal number")),
    }
}
