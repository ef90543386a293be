//! Where the characters of a TOML string value are in the spec text, so that an error at a byte
//! range of the string (an expression's span) can be labelled in the file.
//!
//! A literal string (`'...'`, `'''...'''`) and a basic string without escapes (`"..."`, `"""..."""`)
//! hold their value verbatim after the opening delimiter (and, for multi-line strings, after a newline
//! right behind it): byte `i` of the value is byte `start + i` of the file. A string with escapes has no
//! such offset; [`value_offset`] then returns `None` and the caller labels the whole value.

use std::ops::Range;

/// The file offset of the first byte of the string `value`, written at `span` of `text`, when every
/// byte of the value appears verbatim and contiguously in the file.
pub fn value_offset(text: &str, span: &Range<usize>, value: &str) -> Option<usize> {
    let raw = text.get(span.clone())?;
    let delimiter = ["\"\"\"", "'''", "\"", "'"].into_iter().find(|d| raw.starts_with(d) && raw.ends_with(d))?;
    if raw.len() < 2 * delimiter.len() {
        return None;
    }
    let mut start = delimiter.len();
    if delimiter.len() == 3 {
        if raw[start..].starts_with("\r\n") {
            start += 2;
        } else if raw[start..].starts_with('\n') {
            start += 1;
        }
    }
    let body = raw.get(start..raw.len() - delimiter.len())?;
    (body == value).then_some(span.start + start)
}

/// The file range of the bytes `inner` of the string `value` written at `span`, or `None` when the
/// string is not verbatim in the file (see [`value_offset`]).
pub fn inner_range(text: &str, span: &Range<usize>, value: &str, inner: Range<usize>) -> Option<Range<usize>> {
    if inner.end > value.len() || inner.start > inner.end {
        return None;
    }
    value_offset(text, span, value).map(|offset| offset + inner.start..offset + inner.end)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn offset(text: &str, value: &str) -> Option<usize> {
        let start = text.find('=').unwrap() + 2;
        value_offset(text, &(start..text.trim_end().len()), value)
    }

    #[test]
    fn verbatim_strings_have_an_offset() {
        assert_eq!(offset("l = \"x_dot^2\"", "x_dot^2"), Some(5));
        assert_eq!(offset("l = 'x_dot^2'", "x_dot^2"), Some(5));
        assert_eq!(offset("l = \"\"\"\nx_dot^2\n\"\"\"", "x_dot^2\n"), Some(8));
        assert_eq!(offset("l = '''\r\nx_dot^2'''", "x_dot^2"), Some(9));
        assert_eq!(offset("l = \"\"", ""), Some(5));
    }

    #[test]
    fn strings_with_escapes_have_none() {
        assert_eq!(offset("l = \"a\\tb\"", "a\tb"), None);
        assert_eq!(offset("l = \"\"\"a \\\n   b\"\"\"", "a b"), None);
        assert_eq!(offset("l = \"\\u0078\"", "x"), None);
    }

    #[test]
    fn inner_ranges_are_shifted_by_the_offset() {
        let text = "l = \"0.5*m*x_dot^2\"";
        assert_eq!(inner_range(text, &(4..text.len()), "0.5*m*x_dot^2", 4..5), Some(9..10));
        assert_eq!(&text[9..10], "m");
        assert_eq!(inner_range(text, &(4..text.len()), "0.5*m*x_dot^2", 4..50), None);
    }
}
