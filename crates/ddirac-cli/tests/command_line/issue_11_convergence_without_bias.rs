//! `ddirac convergence` for a system without an exact solution measured the errors against the
//! finest listed run: the finest row had no error, the row before it was reported 25 % too small
//! with an observed order of 2.32 for a second-order method, and the figure drew a slope line from
//! rows where the observed order was not settled.
//!
//! The harmonic oscillator L = ½ẋ² − ½x² is written here without `[system.exact]`, so the command
//! cannot know x(T) = cos T; the test does. The midpoint rule on this linear system is the implicit
//! midpoint rule, a rotation by 2 atan(h/2) per step, so x_N = cos(2N atan(h/2)) from x0 = 1, p0 = 0:
//! the true error of each row is known in closed form.

use crate::common;

use common::{ddirac, TempDir};

const OSCILLATOR: &str = r#"
[system]
name = "harmonic oscillator"
shape = ["x"]
lagrangian = "0.5*x_dot^2 - 0.5*x^2"

[method]
rule = "midpoint"

[time]
duration = 10.0
steps = 100

[initial]
q = [1.0]
p = [0.0]
"#;

const T: f64 = 10.0;

/// x_N of the implicit midpoint rule with N steps over T, from x0 = 1, p0 = 0.
fn midpoint_x(n: u64) -> f64 {
    let h = T / n as f64;
    (2.0 * n as f64 * (0.5 * h).atan()).cos()
}

/// A row of convergence.csv.
#[derive(Debug)]
struct Row {
    steps: u64,
    error: Option<f64>,
    order: Option<f64>,
    reference: Option<String>,
}

/// The rows of convergence.csv, its columns found by name.
fn table(dir: &TempDir) -> Vec<Row> {
    let text = std::fs::read_to_string(dir.out().join("convergence.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name);
    lines
        .map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            let field = |name: &str| column(name).and_then(|i| f.get(i)).filter(|v| !v.is_empty()).copied();
            Row {
                steps: field("steps").unwrap().parse().unwrap(),
                error: field("error").map(|v| v.parse().unwrap()),
                order: field("order").map(|v| v.parse().unwrap()),
                reference: field("reference").map(str::to_owned),
            }
        })
        .collect()
}

fn convergence(spec: &str, steps: &str, dir: &TempDir) -> (String, String) {
    let out = dir.out();
    let output = ddirac(&["convergence", spec, "--steps", steps, "--out", out.to_str().unwrap()], &dir.0);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let svg = std::fs::read_to_string(out.join("convergence.svg")).unwrap();
    (String::from_utf8(output.stdout).unwrap(), svg)
}

/// The text of the SVG that starts with `start` (the legend entry of a slope line: "slope 2 (…)").
fn legend<'a>(svg: &'a str, start: &str) -> Option<&'a str> {
    svg.lines().map(str::trim).find(|l| l.starts_with(start))
}

#[test]
fn every_row_s_error_is_within_ten_percent_of_the_true_error_and_the_order_is_two() {
    let dir = TempDir::new("oscillator");
    let spec = dir.file("oscillator.toml", OSCILLATOR);
    // The closed form x_N is the command's own trajectory: an ordinary run gives it.
    let out = dir.0.join("run");
    let run = ddirac(&["run", &spec, "--quiet", "--out", out.to_str().unwrap(), "--set", "time.steps=400"], &dir.0);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["reference_error"], serde_json::Value::Null, "the spec declares no exact solution");
    let x = summary["final"]["q"][0].as_f64().unwrap();
    assert!((x - midpoint_x(400)).abs() < 1e-12, "x_400 = {x}, closed form {}", midpoint_x(400));

    let (stdout, svg) = convergence(&spec, "50,100,200,400", &dir);
    let rows = table(&dir);
    assert_eq!(rows.iter().map(|r| r.steps).collect::<Vec<_>>(), [50, 100, 200, 400]);
    let mut wrong = vec![];
    for row in &rows {
        let truth = (midpoint_x(row.steps) - T.cos()).abs();
        match row.error {
            Some(error) if ((error - truth) / truth).abs() < 0.1 => {}
            Some(error) => wrong.push(format!(
                "N = {}: reported {error:.4e}, true error {truth:.4e} ({:+.0} %)",
                row.steps,
                100.0 * (error - truth) / truth
            )),
            None => wrong.push(format!("N = {}: no error reported, true error {truth:.4e}", row.steps)),
        }
        if row.steps > 50 && !row.order.is_some_and(|p| (p - 2.0).abs() < 0.1) {
            wrong.push(format!("N = {}: observed order {:?}, the method's is 2", row.steps, row.order));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));

    // The method is stated in the table, the text and the figure.
    assert!(rows.iter().all(|r| r.reference.as_deref() == Some("reference run N=3200")), "{rows:?}");
    assert!(stdout.contains("against a reference run of the same method with N = 3200 steps"), "{stdout}");
    assert!(stdout.contains("stable at"), "{stdout}");
    assert!(svg.contains("reference run"), "the figure does not say what the errors are measured against");
    let slope = legend(&svg, "slope ").expect("no slope line where the order is stable");
    assert!(slope.starts_with("slope 2 (observed"), "{slope}");
}

#[test]
fn no_slope_line_where_the_observed_order_is_not_stable() {
    // Charged particle with N = 4, 6, 10, 50: observed orders 0.80, −0.57, 1.16, far from settled.
    let dir = TempDir::new("unsettled");
    let (stdout, svg) = convergence(&common::example("charged_particle.toml"), "4,6,10,50", &dir);
    let slope = legend(&svg, "slope ");
    assert!(slope.is_none(), "a slope line drawn from rows whose order is not stable: {slope:?}");
    assert!(stdout.contains("not stable"), "{stdout}");
    assert!(svg.contains("not stable"), "the figure does not say that the order is not stable");
}
