//! `derivatives = "auto"` compiled every run of 5000 steps or more, whatever the size of the program:
//! a chain of 4000 definitions, each using the previous one twice, took 71 s to compile where dual
//! numbers take 2.8 s. Native code generation grows faster than the program (with the live ranges of
//! its values, which such a chain makes quadratic), so `auto` now estimates the cost of compiling
//! against what the run's steps would save, chooses dual numbers when compiling would not pay, and
//! says why in the summary. `derivatives = "compiled"` still compiles.
//!
//! The decision is asserted, not timed: a chain of 1000 definitions over 5000 steps (about 1 s to
//! compile, about 0.3 s of dual numbers) is far on the dual side of the estimate, and a small
//! program over the same steps far on the compiled side.

use crate::common;

use common::{succeed, TempDir};

/// A one-coordinate system with a chain of `n` definitions, each using the previous one twice;
/// `derivatives` as given.
fn chain(n: usize, derivatives: &str) -> String {
    let mut definitions = vec!["a1 = \"x + 0.001*x_dot\"".to_owned()];
    definitions.extend((2..=n).map(|k| format!("a{k} = \"a{p}*a{p} - a{p}\"", p = k - 1)));
    format!(
        "[system]\nshape = [\"x\"]\nlagrangian = \"0.5*x_dot^2 - 0.5*x^2 + 0.001*a{n}\"\n\
         [system.definitions]\n{}\n[parameters]\n[method]\nderivatives = \"{derivatives}\"\n\
         [time]\nsteps = 5000\nstep = 0.01\n[initial]\nq = [0.5]\np = [0.0]\n[output]\nevery = 5000\n",
        definitions.join("\n")
    )
}

fn derivatives(spec: &str, sets: &[&str], dir: &TempDir) -> String {
    let finished = succeed(spec, sets, dir);
    finished.summary["derivatives"].as_str().expect("`derivatives` is a string").to_owned()
}

#[test]
fn auto_chooses_dual_numbers_for_a_program_too_large_to_pay_and_says_why() {
    let dir = TempDir::new("auto-large");
    let spec = dir.file("chain.toml", &chain(1000, "auto"));
    let path = derivatives(&spec, &[], &dir);
    assert!(path.starts_with("dual numbers (not compiled: program of "), "{path}");
    assert!(path.contains("compiling would cost more than it saves over 5000 steps"), "{path}");
    // The same chain, compiled on request: the first steps check it against dual numbers.
    let compiled = derivatives(&spec, &["method.derivatives=\"compiled\"", "time.steps=5"], &dir);
    assert!(compiled.starts_with("compiled ("), "{compiled}");
}

#[test]
fn auto_still_compiles_a_small_program_over_the_same_steps() {
    let dir = TempDir::new("auto-small");
    let spec = dir.file("chain.toml", &chain(3, "auto"));
    let path = derivatives(&spec, &[], &dir);
    assert!(path.starts_with("compiled ("), "{path}");
}
