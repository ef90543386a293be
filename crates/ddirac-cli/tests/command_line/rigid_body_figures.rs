//! The figures of a rigid body's run: `output.plots = true` draws them into the run directory and
//! `ddirac plot DIR` draws the same set again; a trajectory without the attitude is refused.

use crate::common;

use std::collections::BTreeSet;
use std::path::Path;

use common::{ddirac, example, files_under, stderr, stdout, TempDir};

/// The figures of every rigid body's run.
const FIGURES: [&str; 3] = ["momentum_sphere", "body_axes", "rigid_invariants"];

/// The colours of the first three series (the palette of the figures).
const COLOURS: [[u8; 3]; 3] = [[31, 119, 180], [214, 39, 40], [44, 160, 44]];

/// A decoded PNG: width, height and its RGB pixels.
fn pixels(path: &Path) -> (u32, u32, Vec<[u8; 3]>) {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())));
    let mut reader = decoder.read_info().unwrap();
    let mut buffer = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buffer).unwrap();
    let samples = info.color_type.samples();
    let rgb = buffer[..info.buffer_size()].chunks_exact(samples).map(|p| [p[0], p[1], p[2]]).collect();
    (info.width, info.height, rgb)
}

/// Whether some pixel has colour `c` (to within the blending of anti-aliasing).
fn has_colour(rgb: &[[u8; 3]], c: [u8; 3]) -> bool {
    rgb.iter().filter(|p| p.iter().zip(c).all(|(&v, w)| v.abs_diff(w) <= 6)).count() > 200
}

/// The number of points of the longest `<polyline>` of an SVG.
fn longest_polyline(svg: &str) -> usize {
    svg.split("<polyline")
        .skip(1)
        .filter_map(|p| {
            p.split_once("points=\"")?.1.split_once('"').map(|(points, _)| points.split_whitespace().count())
        })
        .max()
        .unwrap_or(0)
}

/// The texts of an SVG.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| Some(t.split_once('>')?.1.split_once("</text>")?.0.trim().to_owned()))
        .collect()
}

/// The figure files in `dir`.
fn figure_files(dir: &Path) -> BTreeSet<String> {
    files_under(dir).into_iter().filter(|f| f.ends_with(".png") || f.ends_with(".svg")).collect()
}

/// Checks the PNG and SVG of `name` in `dir`: size, colours, long curves; returns the SVG's texts.
fn check_figure(dir: &Path, name: &str, height: u32, colours: &[[u8; 3]]) -> Vec<String> {
    let (width, h, rgb) = pixels(&dir.join(format!("{name}.png")));
    assert_eq!((width, h), (1200, height), "{name}.png");
    let distinct: BTreeSet<[u8; 3]> = rgb.iter().copied().collect();
    assert!(distinct.len() > 100, "{name}.png has only {} colours", distinct.len());
    for &c in colours {
        assert!(has_colour(&rgb, c), "{name}.png has no curve of colour {c:?}");
    }
    let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"), "{name}.svg is not an SVG");
    assert!(longest_polyline(&svg) >= 50, "{name}.svg has no long curve");
    texts(&svg)
}

#[test]
fn a_rigid_body_run_draws_its_figures_and_plot_draws_them_again() {
    let dir = TempDir::new("rigid-figures");
    let out = dir.out();
    let spec = example("dzhanibekov.toml");
    let args =
        ["run", &spec, "--out", out.to_str().unwrap(), "--set", "time.duration=12", "--set", "output.plots=true"];
    let output = ddirac(&args, &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(common::line(&stdout(&output), "figures").contains("3 (PNG and SVG)"), "{}", stdout(&output));

    let expected: BTreeSet<String> = FIGURES.iter().flat_map(|f| [format!("{f}.png"), format!("{f}.svg")]).collect();
    assert_eq!(figure_files(&out), expected);
    let sphere = check_figure(&out, "momentum_sphere", 990, &COLOURS[..1]);
    assert!(sphere.iter().any(|t| t.starts_with("rigid_body: body angular momentum Π on the sphere")), "{sphere:?}");
    assert!(sphere.iter().any(|t| t.starts_with("I = (1, 2, 3), free body; 1200 steps of h = 0.01")), "{sphere:?}");
    assert!(sphere.iter().any(|t| t == "separatrix through ±e₂"), "{sphere:?}");
    let axes = check_figure(&out, "body_axes", 990, &COLOURS);
    assert!(axes.iter().any(|t| t.starts_with("R e₂, body axis 2")), "{axes:?}");
    let invariants = check_figure(&out, "rigid_invariants", 1050, &COLOURS);
    for label in ["(E − E₀)/|E₀|", "J_x − J_x(0)", "J_z − J_z(0)", "|Π|/|Π₀| − 1"] {
        assert!(invariants.iter().any(|t| t.starts_with(label)), "no `{label}`: {invariants:?}");
    }

    // `ddirac plot` on the same directory writes the same files.
    for f in &expected {
        std::fs::remove_file(out.join(f)).unwrap();
    }
    let output = ddirac(&["plot", out.to_str().unwrap()], &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stdout(&output).contains("3 figures"), "{}", stdout(&output));
    assert_eq!(figure_files(&out), expected);
    check_figure(&out, "momentum_sphere", 990, &COLOURS[..1]);
}

#[test]
fn a_heavy_body_has_no_energy_levels_and_conserves_the_vertical_momentum_only() {
    let dir = TempDir::new("heavy-figures");
    let sets = ["time.duration=1", "output.plots=true"];
    let output = common::run(&example("heavy_top_upright.toml"), &sets, &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    let sphere = check_figure(&dir.out(), "momentum_sphere", 990, &COLOURS[..1]);
    assert!(sphere.iter().any(|t| t.contains("Π/|Π|") && t.contains("no energy levels")), "{sphere:?}");
    assert!(!sphere.iter().any(|t| t.starts_with("separatrix")), "{sphere:?}");
    let invariants = check_figure(&dir.out(), "rigid_invariants", 90 + 2 * 320, &COLOURS[..1]);
    assert!(invariants.iter().any(|t| t == "J_z − J_z(0)"), "{invariants:?}");
    assert!(!invariants.iter().any(|t| t == "J_x − J_x(0)" || t.starts_with("|Π|")), "{invariants:?}");
}

/// A rigid system written as text (examples/satellite_rotors.toml) draws the same figures, named after
/// it, without the energy levels of the built-in body (its energy is not ½ Σ Πᵢ²/Iᵢ): the run with
/// `output.plots = true` failed with exit 4 ("no list of `coordinates`") before.
#[test]
fn a_rigid_system_written_as_text_draws_its_figures() {
    let dir = TempDir::new("text-rigid-figures");
    // Rotor 2 at rest: the body tumbles, and Π draws a long curve.
    let sets = ["time.duration=12", "initial.v.a2=0.0", "output.plots=true"];
    let output = common::run(&example("satellite_rotors.toml"), &sets, &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    let out = dir.out();
    let sphere = check_figure(&out, "momentum_sphere", 990, &COLOURS[..1]);
    assert!(sphere.iter().any(|t| t.starts_with("satellite with three rotors: body angular momentum Π")), "{sphere:?}");
    assert!(!sphere.iter().any(|t| t.starts_with("separatrix") || t.starts_with("levels")), "{sphere:?}");
    let axes = check_figure(&out, "body_axes", 990, &COLOURS);
    assert!(axes.iter().any(|t| t == "R e₂, body axis 2"), "{axes:?}");
    let invariants = check_figure(&out, "rigid_invariants", 1050, &COLOURS);
    assert!(invariants.iter().any(|t| t.starts_with("satellite with three rotors: drift")), "{invariants:?}");
    for f in figure_files(&out) {
        std::fs::remove_file(out.join(f)).unwrap();
    }
    let output = ddirac(&["plot", out.to_str().unwrap()], &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(figure_files(&out).len(), 6);
}

#[test]
fn plot_refuses_a_rigid_body_trajectory_without_the_attitude() {
    let dir = TempDir::new("rigid-no-attitude");
    let output = common::run(&example("dzhanibekov.toml"), &["time.duration=1"], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    let out = dir.out();
    let path = out.join("trajectory.csv");
    let csv = std::fs::read_to_string(&path).unwrap();
    // Keep every column but R11 … R33.
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let keep: Vec<usize> = (0..header.len()).filter(|&i| !header[i].starts_with('R')).collect();
    let stripped: String = csv
        .lines()
        .map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            keep.iter().map(|&i| fields[i]).collect::<Vec<_>>().join(",") + "\n"
        })
        .collect();
    std::fs::write(&path, stripped).unwrap();

    let output = ddirac(&["plot", out.to_str().unwrap()], &dir.0);
    assert!(!output.status.success(), "plot succeeded: {}", stdout(&output));
    let message = stderr(&output);
    for needle in ["trajectory.csv", "no column `R11`", "R11 … R33"] {
        assert!(message.contains(needle), "no `{needle}` in:\n{message}");
    }
    assert!(figure_files(&out).is_empty(), "figures drawn: {:?}", figure_files(&out));
}
