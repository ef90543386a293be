//! `--set method.reduced=False` was read as the string "False" (it is not a TOML value), and the
//! report showed `reduced = "False"` as if the user had quoted it. A value that is a boolean or a
//! number spelt the way other languages spell them is refused with its TOML spelling.

use crate::common;

use common::{assert_fails, example, TempDir};

fn refused(set: &str, needles: &[&str]) -> String {
    let dir = TempDir::new("set");
    let output = common::run(&example("charged_particle.toml"), &[set], &dir);
    let stderr = assert_fails(&output, &dir, needles);
    assert!(!stderr.contains("invalid type: string"), "the value was taken as a string:\n{stderr}");
    stderr
}

#[test]
fn a_capitalised_boolean_gets_the_toml_spelling() {
    refused("method.reduced=False", &["`False` is not a TOML value", "booleans are `true`/`false`"]);
    refused("method.reduced=TRUE", &["`TRUE` is not a TOML value", "booleans are `true`/`false`"]);
}

#[test]
fn numbers_spelt_otherwise_get_the_toml_spelling() {
    refused("parameters.m=NaN", &["`NaN` is not a TOML value", "`nan`"]);
    refused("parameters.m=Inf", &["`Inf` is not a TOML value", "`inf`"]);
    refused("parameters.B0=-Infinity", &["`-Infinity` is not a TOML value", "`-inf`"]);
    refused("parameters.m=1.", &["`1.` is not a TOML value", "`1.0`"]);
}

#[test]
fn check_gives_the_same_hint() {
    let dir = TempDir::new("check");
    let output = common::check(&example("charged_particle.toml"), &["method.reduced=False"], &dir);
    assert_fails(&output, &dir, &["booleans are `true`/`false`"]);
}

#[test]
fn toml_values_and_bare_words_are_still_accepted() {
    let dir = TempDir::new("accepted");
    let sets = ["method.reduced=false", "method.rule=midpoint", "time.steps=10"];
    let finished = common::succeed(&example("charged_particle.toml"), &sets, &dir);
    assert_eq!(finished.summary["method"]["reduced"], false);
    assert_eq!(finished.summary["method"]["rule"], "midpoint");
}
