//! `**`, the power operator of other languages, was reported as "unexpected `*`" with no hint. It is
//! now an error of its own that says to write `^`, at the two stars.

use crate::common;

use common::{assert_fails, check, underlined, TempDir};
use ddirac::expression::{parse, Span, SyntaxError};

const SPEC: &str = r#"
[system]
shape = ["x"]
lagrangian = "0.5*x_dot**2 - 0.5*k*x^2"
[parameters]
k = 1.0
[time]
steps = 10
step = 0.01
[initial]
q = [1.0]
p = [0.0]
"#;

#[test]
fn double_star_says_to_write_a_caret() {
    let error = parse("0.5*x_dot**2").unwrap_err();
    assert_eq!(error, SyntaxError::DoubleStar { span: Span::new(9, 11) });
    assert!(error.to_string().contains("write `^` for powers"), "{error}");
    // Stars apart are a product missing its operand, not a power.
    assert!(matches!(parse("x * * 2"), Err(SyntaxError::UnexpectedToken { .. })));
    assert_eq!(parse("x*2*y").unwrap().to_string(), "(x * 2.0 * y)");
}

#[test]
fn the_spec_error_points_at_the_stars_and_gives_the_hint() {
    let dir = TempDir::new("double-star");
    let spec = dir.file("spec.toml", SPEC);
    let stderr = assert_fails(&check(&spec, &[], &dir), &dir, &["in the Lagrangian", "write `^` for powers"]);
    assert_eq!(underlined(&stderr, "lagrangian = "), ["**"]);
}
