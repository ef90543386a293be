//! With `output.wrap_angles = true` an angle jumps from π to −π where it wraps, and the figures
//! joined the two samples with a line across the whole panel that the angle never travelled. A jump
//! of more than π between consecutive samples of an angle must start a new piece of line.
//!
//! The double spherical pendulum's four coordinates are angles; from the example's initial data
//! ϑ₂ wraps within 20 time units. The test counts the wraps in the trajectory itself and finds the
//! pieces of line in the SVG figure of the coordinates.

use crate::common;

use common::{example, TempDir};

/// The colour of the first series of a panel.
const DATA: &str = r##"stroke="#1F77B4""##;

/// The pendulum for 2000 steps of h = 0.01, figures drawn, angles wrapped or not.
fn pendulum(wrap: bool, dir: &TempDir) {
    let wrap = format!("output.wrap_angles={wrap}");
    let sets = ["time.steps=2000", "time.duration=20", "output.plots=true", wrap.as_str()];
    let output = common::run(&example("double_spherical_pendulum.toml"), &sets, dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
}

/// How often each coordinate of the trajectory jumps by more than π between rows.
fn wraps(dir: &TempDir) -> Vec<usize> {
    let csv = std::fs::read_to_string(dir.out().join("trajectory.csv")).unwrap();
    let rows: Vec<Vec<f64>> =
        csv.lines().skip(1).map(|l| l.split(',').skip(1).take(4).map(|v| v.parse().unwrap()).collect()).collect();
    (0..4).map(|i| rows.windows(2).filter(|w| (w[1][i] - w[0][i]).abs() > std::f64::consts::PI).count()).collect()
}

/// The data lines of an SVG figure, as lists of points in pixels.
fn data_lines(svg: &str) -> Vec<Vec<(f64, f64)>> {
    svg.lines()
        .filter(|l| l.contains("<polyline") && l.contains(DATA))
        .map(|l| {
            let points = l.split("points=\"").nth(1).unwrap().split('"').next().unwrap();
            points
                .split_whitespace()
                .map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect()
        })
        .collect()
}

/// The largest vertical step between consecutive points of a line, in pixels.
fn largest_step(line: &[(f64, f64)]) -> f64 {
    line.windows(2).map(|w| (w[1].1 - w[0].1).abs()).fold(0.0, f64::max)
}

#[test]
fn a_wrapped_angle_is_drawn_in_pieces_that_never_cross_the_panel() {
    let dir = TempDir::new("wrapped");
    pendulum(true, &dir);
    let wraps = wraps(&dir);
    let total: usize = wraps.iter().sum();
    assert!(total >= 1, "the run was chosen for ϑ₂ to wrap; wraps per coordinate {wraps:?}");

    let svg = std::fs::read_to_string(dir.out().join("coordinates.svg")).unwrap();
    let lines = data_lines(&svg);
    assert_eq!(lines.len(), 4 + total, "one line per coordinate and one more per wrap ({wraps:?})");
    // A panel is 320 pixels high: a line joining π to −π spans most of it. Between two samples
    // 0.01 apart the pendulum moves a few pixels at most.
    for line in &lines {
        let step = largest_step(line);
        assert!(step < 80.0, "a line jumps {step} pixels between consecutive points");
    }
    // The pieces of a wrap meet the panel's edges: both ends of a wrap are at ±π, on the same time.
    let wrapped: Vec<&Vec<(f64, f64)>> = lines.iter().filter(|l| l.len() > 1).collect();
    for pair in wrapped.windows(2) {
        let (end, start) = (pair[0].last().unwrap(), pair[1][0]);
        if (end.0 - start.0).abs() <= 1.0 {
            assert!((end.1 - start.1).abs() > 150.0, "a piece ends at {end:?}, the next starts at {start:?}");
        }
    }
}

#[test]
fn a_continuous_angle_is_drawn_in_one_piece() {
    let dir = TempDir::new("continuous");
    pendulum(false, &dir);
    assert_eq!(wraps(&dir), [0, 0, 0, 0], "unwrapped angles do not jump");
    let svg = std::fs::read_to_string(dir.out().join("coordinates.svg")).unwrap();
    let lines = data_lines(&svg);
    assert_eq!(lines.len(), 4, "one line per coordinate");
    for line in &lines {
        assert!(largest_step(line) < 80.0);
    }
}
