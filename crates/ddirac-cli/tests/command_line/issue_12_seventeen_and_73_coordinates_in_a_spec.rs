//! Specs of 17, 73, 101 and 150 coordinates (issue 12: text systems of any number of coordinates) run
//! from the command line in a dimension chosen at run time: the trajectory has the spec's columns of
//! q and of p, the summary and `ddirac check` speak of the spec's coordinates, and the motion is the
//! midpoint rule's exact rotation of each oscillator.

use crate::common;

use common::{check, numbers, stdout, succeed, TempDir};

/// `n` uncoupled oscillators x0 … x{n−1} with ω_i = 1 + i/n, released from x_i = 1 at rest.
fn oscillators(n: usize) -> String {
    let names: Vec<String> = (0..n).map(|i| format!("\"x{i}\"")).collect();
    let terms: Vec<String> =
        (0..n).map(|i| format!("0.5*(x{i}_dot^2 - {}*x{i}^2)", (1.0 + i as f64 / n as f64).powi(2))).collect();
    let q: Vec<String> = (0..n).map(|i| format!("x{i} = 1.0")).collect();
    let p: Vec<String> = (0..n).map(|i| format!("x{i} = 0.0")).collect();
    format!(
        "[system]\nname = \"{n} oscillators\"\nshape = [{}]\nlagrangian = \"{}\"\n\n[method]\nrule = \"midpoint\"\n\n\
         [time]\nstep = 0.02\nsteps = 500\n\n[initial]\nq = {{ {} }}\np = {{ {} }}\n",
        names.join(", "),
        terms.join(" + "),
        q.join(", "),
        p.join(", ")
    )
}

#[test]
fn specs_of_17_and_73_coordinates_run_with_their_columns_and_the_exact_rotation() {
    for n in [17, 73] {
        seventeen_or_73(n);
    }
}

fn seventeen_or_73(n: usize) {
    let dir = TempDir::new(&format!("oscillators-{n}"));
    let spec = dir.file("oscillators.toml", &oscillators(n));
    let run = succeed(&spec, &[], &dir);
    let names: Vec<String> = (0..n).map(|i| format!("x{i}")).collect();
    assert_eq!(run.summary["coordinates"], serde_json::json!(names));
    assert_eq!(numbers(&run.summary["final"]["q"]).len(), n);
    assert_eq!(numbers(&run.summary["final"]["p"]).len(), n);
    let csv = std::fs::read_to_string(dir.out().join("trajectory.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(!header.contains("padding") && !header.contains(&format!("x{n}")), "{header}");
    let summary = std::fs::read_to_string(dir.out().join("summary.json")).unwrap();
    assert!(!summary.contains("padding"), "{summary}");
    for (i, x) in run.final_q().iter().enumerate() {
        let omega = 1.0 + i as f64 / n as f64;
        let rotation = (2.0 * 500.0 * (omega * 0.02 / 2.0).atan()).cos();
        assert!((x - rotation).abs() < 1e-11, "x{i}: {x} against {rotation}");
        assert_eq!(run.column(&format!("x{i}")).len(), 501);
    }

    let report = stdout(&check(&spec, &[], &dir));
    assert!(!report.contains("padding"), "{report}");
    assert!(report.contains(&format!("rank {n} of {n}")), "{report}");
}

#[test]
fn specs_of_101_and_150_coordinates_run_in_a_dynamic_dimension_with_the_exact_rotation() {
    for n in [101, 150] {
        seventeen_or_73(n);
    }
}
