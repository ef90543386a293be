//! Finding 6: a singular potential was crossed silently: `0.5*x_dot^2 + 0.001/x` from x = 1 towards 0
//! stepped across x = 0, the energy jumped in one step and the run exited 0 without a word. A step
//! whose energy jumps far beyond the run's typical change must warn (or fail, if asked).

use crate::common;

use common::{assert_fails, run, stderr, succeed, summary, TempDir};

const SINGULAR: &str = r#"
[system]
shape = ["x"]
lagrangian = "0.5*x_dot^2 + 0.001/x"

[time]
step = 0.1
steps = 100

[initial]
q = [1.0]
v = [-0.87]
"#;

#[test]
fn stepping_over_a_singular_potential_warns_at_the_step() {
    let dir = TempDir::new("singular");
    let spec = dir.file("singular.toml", SINGULAR);
    let finished = succeed(&spec, &[], &dir);
    // The energy H of the rows: constant to 1e-4 before x = 0, a jump of more than 100 % across it.
    let (x, energy) = (finished.column("x"), finished.column("energy"));
    let crossing = x.iter().position(|&x| x < 0.0).expect("the run steps over x = 0");
    assert!((energy[crossing] - energy[0]).abs() > energy[0].abs(), "{energy:?}");
    let warnings = summary(&dir)["warnings"].as_array().unwrap().clone();
    // The crossing step's energy is implausible: it is taken again as sub-steps (issue 14), which
    // cannot avoid the singularity, and the jump is reported.
    let kinds: Vec<&str> = warnings.iter().map(|w| w["kind"].as_str().unwrap()).collect();
    assert_eq!(kinds, ["subdivided", "energy_jump"], "{warnings:?}");
    let jump = &warnings[1];
    // Reported at the step q_k → q_{k+1} that crosses: its row k is the last with x > 0.
    assert_eq!(jump["step"].as_u64(), Some(crossing as u64 - 1));
    let t = jump["t"].as_f64().unwrap();
    assert!((t - 0.1 * (crossing - 1) as f64).abs() < 1e-12, "{t}");
    let output = run(&spec, &[], &dir);
    assert_eq!(stderr(&output).matches("warning [energy_jump]").count(), 1, "{}", stderr(&output));

    // Made an error: a non-zero exit that names the step and the spec's time grid, and no output.
    let dir = TempDir::new("singular-error");
    let spec = dir.file("singular.toml", SINGULAR);
    let stderr = assert_fails(
        &run(&spec, &["method.on_energy_jump=\"error\""], &dir),
        &dir,
        &[
            &format!("step {} (t = {}, h = 0.1)", crossing - 1, ddirac::Time(0.1 * (crossing - 1) as f64)),
            "the energy jumped",
        ],
    );
    assert!(stderr.contains("this time grid"), "{stderr}");
}

#[test]
fn a_run_that_stays_away_from_the_singularity_has_no_warning() {
    let dir = TempDir::new("regular");
    let spec = dir.file("away.toml", SINGULAR);
    // Outward from x = 1 with positive energy: the particle escapes and never nears x = 0.
    let finished = succeed(&spec, &["initial.v=[0.87]"], &dir);
    assert!(finished.column("x").iter().all(|&x| x >= 1.0));
    assert_eq!(summary(&dir)["warnings"].as_array().map(Vec::len), Some(0));
}
