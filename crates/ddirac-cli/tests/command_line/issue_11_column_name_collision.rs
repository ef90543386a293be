//! A coordinate named like another output column (`energy`, `discrete_energy`, `p_x` beside `x`,
//! `momentum_g` beside a group coordinate `g`) made two columns of trajectory.csv share a name, and
//! the energy figure plotted the coordinate. Such a spec is an error located at the coordinate's
//! name, whatever the output formats, and nothing is written. (`t` is refused by the expression
//! language already, as the name of time.)

use crate::common;

use std::process::Output;

use common::{assert_fails, ddirac, run, underlined, TempDir};

/// `ddirac run SPEC --out DIR/out --quiet --format FORMAT`.
fn run_as(spec: &str, format: &str, dir: &TempDir) -> Output {
    ddirac(&["run", spec, "--out", dir.out().to_str().unwrap(), "--quiet", "--format", format], &dir.0)
}

/// A free particle on a plane, `a` along the symmetry, with the names of its coordinates to fill in.
fn particle(dir: &TempDir, shape: &str, group: &str) -> String {
    let lagrangian = format!("0.5*({shape}_dot^2 + {group}_dot^2)");
    dir.file(
        "spec.toml",
        &format!(
            r#"
[system]
shape = ["{shape}"]
group = ["{group}"]
lagrangian = "{lagrangian}"
[time]
steps = 10
duration = 1.0
[initial]
q = [0.5, 0.0]
p = [1.0, 2.0]
"#
        ),
    )
}

#[test]
fn a_coordinate_named_like_a_column_of_its_own_is_refused_at_its_name() {
    for (name, column) in [
        ("energy", "the column `energy` (the Hamiltonian H)"),
        ("discrete_energy", "the column `discrete_energy` (L_d)"),
    ] {
        for format in ["csv", "npy", "csv,npy"] {
            let dir = TempDir::new(name);
            let spec = particle(&dir, name, "a");
            let output = run_as(&spec, format, &dir);
            let message = format!("the coordinate `{name}` has the name of another output column: {column}");
            let stderr = assert_fails(&output, &dir, &[&message]);
            assert_eq!(output.status.code(), Some(2), "{stderr}");
            assert_eq!(underlined(&stderr, "shape = "), [format!("\"{name}\"")], "{stderr}");
        }
    }
}

#[test]
fn a_coordinate_named_like_the_momentum_of_another_is_refused_at_both_names() {
    // `p_x` beside `x`: the coordinate p_x and the momentum of x would both be the column `p_x`.
    let dir = TempDir::new("p_x");
    let spec = particle(&dir, "x", "p_x");
    let output = run(&spec, &[], &dir);
    let stderr = assert_fails(
        &output,
        &dir,
        &["the coordinate `p_x` has the name of another output column: the momentum column of the coordinate `x`"],
    );
    assert_eq!(output.status.code(), Some(2));
    assert_eq!(underlined(&stderr, "group = "), ["\"p_x\""]);
    assert_eq!(underlined(&stderr, "shape = "), ["\"x\""]);

    // `momentum_a` beside the group coordinate `a`: the momentum map of `a` is the column `momentum_a`.
    let dir = TempDir::new("momentum");
    let spec = particle(&dir, "momentum_a", "a");
    let output = run_as(&spec, "npy", &dir);
    let stderr = assert_fails(&output, &dir, &["the momentum-map column of the group coordinate `a`"]);
    assert_eq!(underlined(&stderr, "shape = "), ["\"momentum_a\""]);
    assert_eq!(underlined(&stderr, "group = "), ["\"a\""]);
}

#[test]
fn check_refuses_the_spec_too_and_distinct_names_run() {
    let dir = TempDir::new("check");
    let spec = particle(&dir, "energy", "a");
    let output = common::check(&spec, &[], &dir);
    assert_eq!(output.status.code(), Some(2), "{}", String::from_utf8_lossy(&output.stderr));

    // Names that only look alike are fine: `p` and `energy_x` clash with nothing.
    let dir = TempDir::new("fine");
    let finished = common::succeed(&particle(&dir, "energy_x", "p"), &[], &dir);
    assert_eq!(finished.column("energy_x").len(), 11);
    let energy = finished.column("energy");
    assert!(energy.iter().all(|e| (e - 2.5).abs() < 1e-12), "H = (1² + 2²)/2 = 2.5: {energy:?}");
}
