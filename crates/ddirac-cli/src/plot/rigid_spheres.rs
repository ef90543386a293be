//! The two sphere figures of a rigid body's run: `momentum_sphere` (Π in the body frame, with the
//! level curves of the energy on |Π| = |Π₀|) and `body_axes` (R e₁, R e₂, R e₃ in space).

use std::f64::consts::TAU;

use plotters::style::{RGBColor, BLACK};

use super::figure::PALETTE;
use super::rigid_data::{RigidData, RigidSummary};
use super::sphere::{dot, unit, Curve, Mark, SphereFigure, Stroke, Vec3, View};

/// The oblique view: azimuth and elevation (radians) of the viewer, the third axis upward.
const AZIMUTH: f64 = 0.61;
const ELEVATION: f64 = 0.44;

/// The angle (radians) between the direction a free body's axes are seen from and its angular momentum.
const TILT: f64 = 0.6;

/// Points per level curve.
const LEVEL_POINTS: usize = 240;
/// Level curves on each side of the separatrix.
const LEVELS_PER_SIDE: usize = 3;

const SUBSCRIPTS: [&str; 3] = ["₁", "₂", "₃"];

/// The oblique view, turned so that the side with `signs` (each ±1) faces the viewer.
fn oblique(signs: Vec3) -> View {
    let (a, e) = (AZIMUTH, ELEVATION);
    let toward = [signs[0] * e.cos() * a.cos(), signs[1] * e.cos() * a.sin(), signs[2] * e.sin()];
    View::new(toward, [0.0, 0.0, 1.0])
}

/// +1 or −1 as `x` is clearly negative or not.
fn sign(x: f64) -> f64 {
    if x < -0.1 {
        -1.0
    } else {
        1.0
    }
}

/// The six points ±eᵢ, labelled `names[i]` and `−names[i]`.
fn axis_marks(names: [String; 3]) -> Vec<Mark> {
    let mut marks = vec![];
    for (i, name) in names.into_iter().enumerate() {
        for s in [1.0, -1.0] {
            let mut at = [0.0; 3];
            at[i] = s;
            let label = if s > 0.0 { name.clone() } else { format!("−{name}") };
            marks.push(Mark { at, label: Some(label), legend: None, color: BLACK, radius: 3.0, hollow: false });
        }
    }
    marks
}

/// A dot at the start and a ring at the end of `path`.
fn ends(path: &[Vec3], color: RGBColor) -> Vec<Mark> {
    let mark = |at: Vec3, hollow| Mark { at, label: None, legend: None, color, radius: 6.0, hollow };
    path.first().map(|&p| mark(p, false)).into_iter().chain(path.last().map(|&p| mark(p, true))).collect()
}

fn note(frame: &str, view: &View) -> String {
    let d = view.toward.map(|x| format!("{x:.2}"));
    format!("seen from ({}, {}, {}) in the {frame}; dots: start, rings: end", d[0], d[1], d[2])
}

/// Π in the body frame on the sphere |Π| = |Π₀|, with the level curves of the energy; Π/|Π| alone
/// for a heavy body.
pub fn momentum_sphere(summary: &RigidSummary, data: &RigidData) -> SphereFigure {
    let view = oblique(data.mean.map(sign));
    let path = data.pi.clone().finish();
    let color = PALETTE[0];
    let mut curves = vec![];
    let name = &summary.name;
    let title = if summary.heavy {
        curves.push(Curve { name: Some("Π/|Π|".into()), points: path.clone(), color, stroke: Stroke::Path });
        if summary.inertia.is_some() {
            format!("{name}: Π/|Π| in the body frame (heavy body: no energy levels)")
        } else {
            format!("{name}: Π/|Π| in the body frame")
        }
    } else {
        let mut named = [false; 2];
        for (points, separatrix, middle) in summary.inertia.map(energy_levels).unwrap_or_default() {
            let (stroke, name) = if separatrix {
                (Stroke::Separatrix, format!("separatrix through ±e{}", SUBSCRIPTS[middle]))
            } else {
                (Stroke::Level, "levels of the energy ½ Σ Πᵢ²/Iᵢ".to_owned())
            };
            let first = !std::mem::replace(&mut named[usize::from(separatrix)], true);
            curves.push(Curve { name: first.then_some(name), points, color: BLACK, stroke });
        }
        curves.push(Curve { name: Some("Π(t)/|Π₀|".into()), points: path.clone(), color, stroke: Stroke::Path });
        let size = data.pi0.iter().map(|x| x * x).sum::<f64>().sqrt();
        format!("{name}: body angular momentum Π on the sphere |Π| = {size:.4}")
    };
    let mut marks = axis_marks(SUBSCRIPTS.map(|s| format!("e{s}")));
    marks.extend(ends(&path, color));
    let note = Some(note("body frame", &view));
    SphereFigure {
        name: "momentum_sphere".into(),
        title,
        subtitle: Some(summary.description.clone()),
        view,
        curves,
        marks,
        note,
    }
}

/// The tips of the body's axes in space, R e₁, R e₂, R e₃.
pub fn body_axes(summary: &RigidSummary, data: &RigidData) -> SphereFigure {
    let free = summary.symmetry == "SO(3)" && data.momentum0.iter().any(|&x| x != 0.0);
    // A free body's axes turn about its angular momentum J, fixed in space: seen from near J.
    let view = if free {
        let j = unit(data.momentum0);
        let z = if j[2].abs() < 0.9 { [0.0, 0.0, 1.0] } else { [1.0, 0.0, 0.0] };
        let w = unit(std::array::from_fn(|i| z[i] - dot(z, j) * j[i]));
        let (c, s) = (TILT.cos(), TILT.sin());
        View::new(std::array::from_fn(|i| c * j[i] + s * w[i]), z)
    } else {
        oblique([1.0; 3])
    };
    let mut marks = axis_marks(["x", "y", "z"].map(str::to_owned));
    let mut curves = vec![];
    for (i, axis) in data.axes.iter().enumerate() {
        let points = axis.clone().finish();
        let name = match summary.inertia {
            Some(inertia) => format!("R e{0}, body axis {1} (I{0} = {2})", SUBSCRIPTS[i], i + 1, inertia[i]),
            None => format!("R e{0}, body axis {1}", SUBSCRIPTS[i], i + 1),
        };
        marks.extend(ends(&points, PALETTE[i]));
        curves.push(Curve { name: Some(name), points, color: PALETTE[i], stroke: Stroke::Path });
    }
    if free {
        let legend = Some("R Π, the angular momentum in space".to_owned());
        let at = unit(data.momentum0);
        marks.push(Mark { at, label: None, legend, color: PALETTE[3], radius: 7.0, hollow: false });
    }
    let title = format!("{}: the body's axes in space, the columns of R", summary.name);
    let note = Some(note("space frame", &view));
    SphereFigure {
        name: "body_axes".into(),
        title,
        subtitle: Some(summary.description.clone()),
        view,
        curves,
        marks,
        note,
    }
}

/// Level curves of the energy ½ Σ Πᵢ²/Iᵢ on the unit sphere, as (points, whether the separatrix,
/// the index of the middle axis): with aᵢ = 1/Iᵢ and k = Σ aᵢ Πᵢ², the levels of k between the
/// middle and the largest a circle the axis of the largest, those between the smallest and the middle
/// the axis of the smallest, and the level k = a_middle is two great circles through ±e_middle.
/// None when all moments are equal.
fn energy_levels(inertia: [f64; 3]) -> Vec<(Vec<Vec3>, bool, usize)> {
    let a = inertia.map(|i| 1.0 / i);
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &j| a[j].total_cmp(&a[i]));
    let [hi, mid, lo] = order;
    let (big, middle, small) = (a[hi], a[mid], a[lo]);
    let spread = big - small;
    let mut curves = vec![];
    if spread.is_nan() || spread <= 1e-9 * big {
        return curves;
    }
    // A point given in the order (hi, mid, lo), on the unit sphere in body coordinates.
    let place = |s: Vec3| {
        let mut p = [0.0; 3];
        (p[hi], p[mid], p[lo]) = (s[0], s[1], s[2]);
        unit(p)
    };
    let circle = |f: &dyn Fn(f64) -> Vec3| -> Vec<Vec3> {
        (0..=LEVEL_POINTS).map(|n| place(f(TAU * n as f64 / LEVEL_POINTS as f64))).collect()
    };
    let (upper, lower) = (big - middle > 1e-6 * spread, middle - small > 1e-6 * spread);
    for j in 1..=LEVELS_PER_SIDE {
        let f = j as f64 / (LEVELS_PER_SIDE + 1) as f64;
        for s in [1.0, -1.0] {
            if upper {
                let k = middle + f * (big - middle);
                let (x, y, z) = (s / (big - k).sqrt(), 1.0 / (k - middle).sqrt(), 1.0 / (k - small).sqrt());
                curves.push((circle(&|t| [x, y * t.cos(), z * t.sin()]), false, mid));
            }
            if lower {
                let k = small + f * (middle - small);
                let (x, y, z) = (1.0 / (big - k).sqrt(), 1.0 / (middle - k).sqrt(), s / (k - small).sqrt());
                curves.push((circle(&|t| [x * t.cos(), y * t.sin(), z]), false, mid));
            }
        }
    }
    if upper && lower {
        for s in [1.0, -1.0] {
            let m = unit([(middle - small).sqrt(), 0.0, s * (big - middle).sqrt()]);
            curves.push((circle(&|t| [m[0] * t.sin(), t.cos(), m[2] * t.sin()]), true, mid));
        }
    }
    curves
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn level_curves_keep_their_energy() {
        let inertia = [1.0, 2.0, 3.0];
        let levels = energy_levels(inertia);
        assert_eq!(levels.len(), 4 * LEVELS_PER_SIDE + 2);
        for (points, separatrix, middle) in levels {
            assert_eq!(middle, 1);
            let k = |p: &Vec3| (0..3).map(|i| p[i] * p[i] / inertia[i]).sum::<f64>();
            let k0 = k(&points[0]);
            assert!(points
                .iter()
                .all(|p| (k(p) - k0).abs() < 1e-12 && (p.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-12));
            if separatrix {
                assert!((k0 - 0.5).abs() < 1e-12, "{k0}");
            }
        }
        assert!(energy_levels([2.0; 3]).is_empty());
        assert_eq!(energy_levels([1.0, 1.0, 3.0]).len(), 2 * LEVELS_PER_SIDE);
    }
}
