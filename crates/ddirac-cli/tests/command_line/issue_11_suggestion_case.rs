//! Name suggestions ignored case: with parameters `k` and `r`, an unknown `K` got "did you mean `x`?"
//! (the first name one edit away). A name that differs only in case is now the suggestion, and
//! otherwise the closest name ignoring case comes first.

use crate::common;

use common::{assert_fails, check, TempDir};
use ddirac::expression::{ExpressionError, Scope};

fn suggestion(scope: &Scope, source: &str) -> Option<String> {
    match scope.compile_expression(source) {
        Err(ExpressionError::UnknownName { suggestion, .. } | ExpressionError::UnknownFunction { suggestion, .. }) => {
            suggestion
        }
        other => panic!("{source}: expected an unknown name, got {other:?}"),
    }
}

#[test]
fn a_name_in_another_case_is_suggested_first() {
    let scope =
        Scope::new().variable("x").variable("x_dot").constant("k", 1.0).constant("r", 2.0).constant("Mass", 3.0);
    assert_eq!(suggestion(&scope, "K*x").as_deref(), Some("k"));
    assert_eq!(suggestion(&scope, "X_DOT^2").as_deref(), Some("x_dot"));
    assert_eq!(suggestion(&scope, "mass*x").as_deref(), Some("Mass"));
    // Closest ignoring case, then with case: `MAS` is one edit from `Mass` once case is ignored.
    assert_eq!(suggestion(&scope, "MAS*x").as_deref(), Some("Mass"));
    assert_eq!(suggestion(&scope, "Sin(x)").as_deref(), Some("sin"));
    // Still nothing for a name far from every name.
    assert_eq!(suggestion(&scope, "omega*x"), None);
}

#[test]
fn the_spec_error_suggests_the_name_in_its_case() {
    let dir = TempDir::new("suggestion-case");
    let spec = dir.file(
        "spec.toml",
        r#"
[system]
shape = ["x"]
lagrangian = "0.5*x_dot^2 - 0.5*K*x^2"
[parameters]
k = 1.0
r = 2.0
[time]
steps = 10
step = 0.01
[initial]
q = [1.0]
p = [0.0]
"#,
    );
    assert_fails(&check(&spec, &[], &dir), &dir, &["unknown name `K` (did you mean `k`?)"]);
}
