//! Finding: with J₀ = 0 (the main example) the momentum map's drift was printed as a bare number
//! ("drift 6.3e-9") with no scale, and its figure was a random walk of unlabelled size, although the
//! momenta it is computed from are of size 10⁵. The drift is now also given relative to the larger of
//! ‖J₀‖∞ and the run's largest momentum (`momentum_map.scale` in summary.json), in the printed
//! summary and in the figure.

use crate::common;

use common::{example, succeed, TempDir};

#[test]
fn a_zero_momentum_map_is_measured_against_the_momenta() {
    let dir = TempDir::new("momentum-scale");
    // Unreduced, every step a row: the scale is the largest |p_i| of the rows, read back from the CSV.
    let run = succeed(
        &example("double_spherical_pendulum.toml"),
        &["method.reduced=false", "output.every=1", "time.steps=2000", "time.duration=20"],
        &dir,
    );
    let j = &run.summary["momentum_map"];
    assert_eq!(common::numbers(&j["initial"]), vec![0.0], "the main example starts with J₀ = 0");
    let largest = ["p_vartheta1", "p_phi1", "p_vartheta2", "p_phi2"]
        .iter()
        .flat_map(|name| run.column(name).iter().map(|p| p.abs()))
        .fold(0.0f64, f64::max);
    assert!(largest > 1e4, "the momenta are large: {largest}");
    let scale = j["scale"].as_f64().expect("a scale");
    assert!((scale - largest).abs() <= 1e-15 * largest, "scale {scale} vs the largest momentum {largest}");
    let drift = j["max_drift"].as_f64().unwrap();
    let relative = j["max_relative_drift"].as_f64().expect("a relative drift although J₀ = 0");
    assert!((relative - drift / scale).abs() <= 1e-15 * relative, "{relative:e} vs {:e}", drift / scale);
    // Kept to round-off of the momenta accumulated over the run and the Newton tolerance 1e-12 (the
    // glued steps where charts overlap, `ddirac::blend`: measured 5.9e-12).
    assert!(relative < 2e-11, "{relative:e}");
}

#[test]
fn a_nonzero_momentum_map_larger_than_the_momenta_is_its_own_scale() {
    // Kepler: J₀ = p_φ = 0.8 and |p_r| stays below it on this orbit, so the scale is J₀.
    let dir = TempDir::new("momentum-scale-kepler");
    let run = succeed(&example("kepler.toml"), &["output.every=1", "time.duration=8"], &dir);
    let largest_pr = run.column("p_r").iter().fold(0.0f64, |m, p| m.max(p.abs()));
    assert!(largest_pr < 0.8, "{largest_pr}");
    assert_eq!(run.summary["momentum_map"]["scale"].as_f64(), Some(0.8));
}

#[test]
fn the_printed_summary_says_what_the_drift_is_relative_to() {
    let dir = TempDir::new("momentum-scale-printed");
    let out = dir.out();
    let spec = example("double_spherical_pendulum.toml");
    let output = common::ddirac(
        &["run", &spec, "--out", out.to_str().unwrap(), "--set", "time.steps=100", "--set", "time.duration=1"],
        &dir.0,
    );
    assert!(output.status.success(), "{}", common::stderr(&output));
    let report = common::stdout(&output);
    let line = common::line(&report, "momentum map");
    assert!(line.contains("relative") && line.contains("the largest of |J_0| and the momenta"), "{line}");
}

#[test]
fn a_run_whose_momenta_are_all_zero_has_no_relative_drift_and_says_why() {
    // The charged particle at rest: every momentum stays 0, so there is nothing to measure against.
    let dir = TempDir::new("momentum-scale-zero");
    let out = dir.out();
    let spec = example("charged_particle.toml");
    let output = common::ddirac(
        &["run", &spec, "--out", out.to_str().unwrap(), "--set", "initial.p=[0.0, 0.0, 0.0, 0.0]"],
        &dir.0,
    );
    assert!(output.status.success(), "{}", common::stderr(&output));
    let summary = common::summary(&dir);
    let j = &summary["momentum_map"];
    assert_eq!(j["scale"].as_f64(), Some(0.0));
    assert_eq!(j["max_drift"].as_f64(), Some(0.0));
    assert!(j["max_relative_drift"].is_null());
    let report = common::stdout(&output);
    assert!(common::line(&report, "momentum map").contains("every momentum is 0"), "{report}");
}
