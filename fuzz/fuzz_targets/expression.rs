//! The expression language on arbitrary text: it must never panic.
//!
//! The input's first line is a Lagrangian; up to three more lines are the definitions `d0`, `d1`,
//! `d2` (which may use one another, cycles included). Checked on every input:
//! - tokenizing and parsing end in a tree or a syntax error whose span lies on character boundaries
//!   of the text;
//! - a parsed tree prints to text that parses back to the same tree (unless the printed text, which
//!   parenthesises every operation, nests too deeply);
//! - compiling against a scope of variables, constants, definitions and a reserved name ends in a
//!   program or an error whose span lies in the text it names;
//! - a program evaluates with f64, with first-derivative duals and with second-derivative duals
//!   (any value, NaN included, is fine; a folded constant is the value).

#![no_main]

use ddirac::expression::{parse, tokenize, ExpressionError, Origin, Scope, Span, SyntaxError};
use libfuzzer_sys::fuzz_target;
use num_dual::{hessian, Dual2SVec64, Dual64};

const DEFINITIONS: [&str; 3] = ["d0", "d1", "d2"];

fn check_span(text: &str, span: Span) {
    assert!(span.start <= span.end && span.end <= text.len(), "span {span} outside {} bytes", text.len());
    assert!(text.is_char_boundary(span.start) && text.is_char_boundary(span.end), "span {span} splits a character");
}

fn check_round_trip(source: &str) {
    let Ok(expr) = parse(source) else { return };
    check_span(source, expr.span);
    let printed = expr.to_string();
    match parse(&printed) {
        Ok(again) => assert_eq!(again.to_string(), printed, "the printed tree of {source:?} reads back differently"),
        Err(SyntaxError::TooDeep { .. }) => {}
        Err(e) => panic!("the printed tree {printed:?} of {source:?} does not parse: {e}"),
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let mut lines = text.split('\n');
    let lagrangian = lines.next().unwrap_or("");
    let definitions: Vec<&str> = lines.take(DEFINITIONS.len()).collect();

    match tokenize(lagrangian) {
        Ok(tokens) => tokens.iter().for_each(|t| check_span(lagrangian, t.span)),
        Err(e) => check_span(lagrangian, e.span()),
    }
    if let Err(e) = parse(lagrangian) {
        check_span(lagrangian, e.span());
        let _ = e.to_string();
    }
    check_round_trip(lagrangian);

    let mut scope = Scope::new()
        .variable("x")
        .variable("y")
        .variable("x_dot")
        .constant("m", 2.0)
        .constant("g", 9.81)
        .unavailable("t", "time does not enter a Lagrangian here");
    for (name, source) in DEFINITIONS.iter().zip(&definitions) {
        scope = scope.definition(name, source);
    }
    match scope.compile(Origin::Lagrangian, lagrangian) {
        Ok(program) => {
            assert_eq!(program.variables(), 3);
            let at: [f64; 3] = [0.3, -1.2, 0.7];
            let value = program.eval(&at);
            if let Some(c) = program.constant() {
                assert!(c.to_bits() == value.to_bits() || (c.is_nan() && value.is_nan()));
            }
            let _ = program.eval(&at.map(Dual64::from_re));
            let point = nalgebra::SVector::from(at);
            let _ = hessian(|v: nalgebra::SVector<Dual2SVec64<3>, 3>| program.eval(&[v[0], v[1], v[2]]), &point);
        }
        Err(error) => {
            let _ = error.to_string();
            let source = match error.origin() {
                Some(Origin::Lagrangian) => Some(lagrangian),
                Some(Origin::Definition(name)) => DEFINITIONS.iter().position(|d| d == name).map(|i| definitions[i]),
                other => panic!("an error from an unexpected source {other:?}: {error}"),
            };
            if let (Some(source), Some(span)) = (source, error.span()) {
                // A cycle reported with no reference has the empty span at 0.
                if !matches!(error, ExpressionError::Cycle { .. }) || !span.is_empty() {
                    check_span(source, span);
                }
            }
        }
    }
});
