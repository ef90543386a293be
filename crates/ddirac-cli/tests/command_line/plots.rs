//! `ddirac plot DIR` and `output.plots = true`: which figures are written, that they are real PNG
//! and SVG files with their axis names, and the pendulum's own figures (paper §7.2).

use crate::common;

use common::{ddirac, TempDir};

use std::path::Path;
use std::process::Output;

const CHARGED_PARTICLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/charged_particle.toml");
const PENDULUM: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/double_spherical_pendulum.toml");

/// The figures of every run, and those only the double spherical pendulum has.
const RUN_FIGURES: [&str; 4] = ["coordinates", "energy_error", "momentum_map", "discrete_energy"];
const PENDULUM_FIGURES: [&str; 2] = ["phi1", "second_bob_path"];

fn succeed(args: &[&str], cwd: &Path) -> Output {
    let output = ddirac(args, cwd);
    assert!(output.status.success(), "ddirac {args:?}: {}", String::from_utf8_lossy(&output.stderr));
    output
}

/// Runs `spec` quietly into `dir.out()` with the given `--set` assignments.
fn run(spec: &str, sets: &[&str], dir: &TempDir) {
    let out = dir.out();
    let mut args = vec!["run", spec, "--out", out.to_str().unwrap(), "--quiet"];
    for s in sets {
        args.extend(["--set", s]);
    }
    succeed(&args, &dir.0);
}

/// Checks that `DIR/<name>.png` is a PNG and `DIR/<name>.svg` an SVG; returns the SVG text.
fn figure(dir: &Path, name: &str) -> String {
    let png = std::fs::read(dir.join(format!("{name}.png"))).unwrap_or_else(|e| panic!("{name}.png: {e}"));
    assert!(png.len() > 10_000, "{name}.png has only {} bytes", png.len());
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{name}.png is not a PNG");
    let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).unwrap_or_else(|e| panic!("{name}.svg: {e}"));
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"), "{name}.svg is not an SVG");
    svg
}

/// The texts of an SVG: what plotters writes between `<text …>` and `</text>`.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| Some(t.split_once('>')?.1.split_once("</text>")?.0.trim().to_owned()))
        .collect()
}

/// The numeric labels of the vertical axis: those that share one `x` position (the horizontal axis's
/// labels share one `y` instead).
fn y_tick_labels(svg: &str) -> Vec<String> {
    let labels: Vec<(String, String)> = svg
        .split("<text")
        .skip(1)
        .filter_map(|t| {
            let (attributes, rest) = t.split_once('>')?;
            let text = rest.split_once("</text>")?.0.trim().to_owned();
            let x = attributes.split_once("x=\"")?.1.split_once('"')?.0.to_owned();
            text.parse::<f64>().is_ok().then_some((x, text))
        })
        .collect();
    let count = |x: &String| labels.iter().filter(|(other, _)| other == x).count();
    let Some((axis, _)) = labels.iter().max_by_key(|(x, _)| count(x)) else { return vec![] };
    labels.iter().filter(|(x, _)| x == axis).map(|(_, text)| text.clone()).collect()
}

fn no_temporaries(dir: &Path) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!name.contains("partial"), "a temporary file is left: {name}");
    }
}

#[test]
fn plot_draws_the_figures_of_a_run_with_their_axis_names() {
    let dir = TempDir::new("charged");
    run(CHARGED_PARTICLE, &[], &dir);
    let out = dir.out();
    let output = succeed(&["plot", out.to_str().unwrap()], &dir.0);
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(stdout.contains("5 figures"), "{stdout}");

    let coordinates = texts(&figure(&out, "coordinates"));
    for name in ["q1", "q2", "q3", "theta", "t", "charged_particle: coordinates"] {
        assert!(coordinates.iter().any(|t| t == name), "no `{name}` in coordinates.svg: {coordinates:?}");
    }
    assert!(coordinates.iter().any(|t| t.contains("100 steps of h = 0.2")), "{coordinates:?}");
    let energy = texts(&figure(&out, "energy_error"));
    assert!(energy.iter().any(|t| t.starts_with("(H − H₀)/|H₀|")), "{energy:?}");
    let momentum = texts(&figure(&out, "momentum_map"));
    assert!(momentum.iter().any(|t| t == "J_theta − J_theta(0)"), "{momentum:?}");
    let discrete = texts(&figure(&out, "discrete_energy"));
    assert!(discrete.iter().any(|t| t.starts_with("L_d(q_k, q_k+1)")), "{discrete:?}");
    for name in PENDULUM_FIGURES {
        assert!(!out.join(format!("{name}.png")).exists(), "{name}.png drawn for the charged particle");
    }
    no_temporaries(&out);
}

#[test]
fn tick_labels_of_a_round_off_sized_error_are_short_and_distinct() {
    // The charged particle conserves H to round-off: the energy error axis is scaled by a power
    // of ten, named in the axis label, and its ticks are short numbers.
    let dir = TempDir::new("ticks");
    run(CHARGED_PARTICLE, &["output.plots=true"], &dir);
    let energy = texts(&figure(&dir.out(), "energy_error"));
    let label = energy.iter().find(|t| t.starts_with("(H − H₀)/|H₀|")).unwrap();
    assert!(label.contains("×10⁻"), "{label}");
    let ticks = y_tick_labels(&figure(&dir.out(), "energy_error"));
    assert!(ticks.len() >= 4, "{energy:?}");
    assert!(ticks.iter().all(|t| t.len() <= 5), "long tick labels: {ticks:?}");
    let mut distinct = ticks.clone();
    distinct.sort();
    distinct.dedup();
    assert_eq!(distinct.len(), ticks.len(), "repeated tick labels: {ticks:?}");
}

#[test]
fn output_plots_draws_the_paper_figures_of_the_pendulum() {
    let dir = TempDir::new("pendulum");
    run(PENDULUM, &["time.steps=500", "time.duration=5", "output.every=1", "output.plots=true"], &dir);
    let out = dir.out();
    for name in RUN_FIGURES.iter().chain(&PENDULUM_FIGURES) {
        figure(&out, name);
    }
    let phi1 = texts(&figure(&out, "phi1"));
    assert!(phi1.iter().any(|t| t == "φ₁"), "{phi1:?}");
    let path = texts(&figure(&out, "second_bob_path"));
    for name in ["x", "y", "double_spherical_pendulum: second mass, projection on the (x, y) plane"] {
        assert!(path.iter().any(|t| t == name), "no `{name}` in second_bob_path.svg: {path:?}");
    }
    no_temporaries(&out);
}

#[test]
fn the_path_of_the_second_mass_is_drawn_where_the_trajectory_puts_it() {
    // x = l1 sin φ1 cos θ1 + l2 sin φ2 cos θ2, y likewise with sin, θ1 = ϑ1 − ϑ2, θ2 = ϑ1 + ϑ2, from
    // the trajectory file; the axes of the figure must span that path.
    let dir = TempDir::new("path");
    run(PENDULUM, &["time.steps=3000", "time.duration=30", "output.plots=true"], &dir);
    let csv = std::fs::read_to_string(dir.out().join("trajectory.csv")).unwrap();
    let (l1, l2) = (500.0, 800.0);
    let (mut x_range, mut y_range) = ((f64::INFINITY, f64::NEG_INFINITY), (f64::INFINITY, f64::NEG_INFINITY));
    for line in csv.lines().skip(1) {
        let q: Vec<f64> = line.split(',').skip(1).take(4).map(|v| v.parse().unwrap()).collect();
        let (t1, t2) = (q[0] - q[2], q[0] + q[2]);
        let x = l1 * q[1].sin() * t1.cos() + l2 * q[3].sin() * t2.cos();
        let y = l1 * q[1].sin() * t1.sin() + l2 * q[3].sin() * t2.sin();
        x_range = (x_range.0.min(x), x_range.1.max(x));
        y_range = (y_range.0.min(y), y_range.1.max(y));
    }
    let svg = figure(&dir.out(), "second_bob_path");
    // x tick labels are centred under their tick, y tick labels end at theirs.
    let ticks = |anchor: &str| -> Vec<f64> {
        anchored(&svg).into_iter().filter(|(a, _)| a == anchor).filter_map(|(_, t)| t.parse().ok()).collect()
    };
    assert!(x_range.1 - x_range.0 > 10.0, "the second mass did not move: {x_range:?}");
    for (axis, values, (lo, hi)) in [("x", ticks("middle"), x_range), ("y", ticks("end"), y_range)] {
        assert!(values.len() >= 3, "{axis}: {values:?}");
        let spacing = values[1] - values[0];
        let (first, last) = (values[0], values[values.len() - 1]);
        // The axis spans the path, and its outermost ticks lie within one spacing of its ends.
        assert!(first - spacing <= lo && last + spacing >= hi, "{axis} ticks {values:?} miss the path {lo}..{hi}");
    }
}

/// The texts of an SVG with their `text-anchor`.
fn anchored(svg: &str) -> Vec<(String, String)> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let (attributes, rest) = t.split_once('>')?;
            let anchor = attributes.split("text-anchor=\"").nth(1)?.split('"').next()?.to_owned();
            Some((anchor, rest.split_once("</text>")?.0.trim().to_owned()))
        })
        .collect()
}

#[test]
fn long_runs_are_thinned_so_that_the_svg_stays_small() {
    let dir = TempDir::new("long");
    run(CHARGED_PARTICLE, &["time.steps=40000", "output.plots=true"], &dir);
    let svg = figure(&dir.out(), "coordinates");
    // 40 001 rows per curve would make a file of several megabytes.
    assert!(svg.len() < 800_000, "coordinates.svg has {} bytes", svg.len());
}

#[test]
fn figures_can_be_drawn_from_npy_columns() {
    let dir = TempDir::new("npy");
    let out = dir.out();
    succeed(&["run", CHARGED_PARTICLE, "--out", out.to_str().unwrap(), "--quiet", "--format", "npy"], &dir.0);
    assert!(!out.join("trajectory.csv").exists());
    succeed(&["plot", out.to_str().unwrap(), "--quiet"], &dir.0);
    let coordinates = texts(&figure(&out, "coordinates"));
    assert!(coordinates.iter().any(|t| t == "theta"), "{coordinates:?}");
    figure(&out, "momentum_map");
}

#[test]
fn plot_refuses_a_directory_that_is_not_a_run() {
    let dir = TempDir::new("empty");
    let output = ddirac(&["plot", dir.0.to_str().unwrap()], &dir.0);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("summary.json") && stderr.contains("ddirac run"), "{stderr}");
    let written: Vec<_> = std::fs::read_dir(&dir.0).unwrap().collect();
    assert!(written.is_empty(), "files were written into a directory that is not a run");
}
