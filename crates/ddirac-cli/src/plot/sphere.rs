//! Curves on the unit sphere seen from far away (orthographic projection): the sphere's outline,
//! the near side of each curve solid and the far side pale and dashed, labelled points, a legend.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::figure::{titled, Px, LEGEND_SIZE, TICK_SIZE};
use super::Drawing;

/// A point or direction in space.
pub type Vec3 = [f64; 3];

pub fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `a` scaled to length 1 (`a` itself if it has length 0).
pub fn unit(a: Vec3) -> Vec3 {
    let n = dot(a, a).sqrt();
    if n > 0.0 {
        a.map(|x| x / n)
    } else {
        a
    }
}

/// Where the sphere is seen from: `toward` points from its centre to the viewer.
#[derive(Debug, Clone, Copy)]
pub struct View {
    right: Vec3,
    up: Vec3,
    pub toward: Vec3,
}

impl View {
    /// The view from the direction `toward`, with `up` (not parallel to it) drawn upward.
    pub fn new(toward: Vec3, up: Vec3) -> Self {
        let toward = unit(toward);
        let up = unit(std::array::from_fn(|i| up[i] - dot(up, toward) * toward[i]));
        Self { right: cross(up, toward), up, toward }
    }

    /// Screen coordinates (right, up) of `p` and its height toward the viewer.
    fn project(&self, p: Vec3) -> (f64, f64, f64) {
        (dot(p, self.right), dot(p, self.up), dot(p, self.toward))
    }
}

/// How a curve is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stroke {
    /// A computed path: wide, in its colour.
    Path,
    /// A level curve: thin and grey.
    Level,
    /// A distinguished level curve: thin and dark.
    Separatrix,
}

/// A curve on the unit sphere.
#[derive(Debug, Clone)]
pub struct Curve {
    /// Legend entry, if any.
    pub name: Option<String>,
    /// Points on the unit sphere, in order.
    pub points: Vec<Vec3>,
    pub color: RGBColor,
    pub stroke: Stroke,
}

/// A point marked on the sphere: a dot, with a label beside it or an entry in the legend.
#[derive(Debug, Clone)]
pub struct Mark {
    pub at: Vec3,
    pub label: Option<String>,
    pub legend: Option<String>,
    pub color: RGBColor,
    /// Radius in pixels.
    pub radius: f64,
    /// A ring rather than a dot.
    pub hollow: bool,
}

/// A figure of one sphere.
#[derive(Debug, Clone)]
pub struct SphereFigure {
    pub name: String,
    pub title: String,
    pub subtitle: Option<String>,
    pub view: View,
    pub curves: Vec<Curve>,
    pub marks: Vec<Mark>,
    /// A line of text under the legend (what the view is).
    pub note: Option<String>,
}

/// Width and height of the area under the title, in pixels.
const AREA: (f64, f64) = (1200.0, 900.0);

impl Drawing for SphereFigure {
    fn name(&self) -> &str {
        &self.name
    }

    fn size(&self) -> (u32, u32) {
        let top = if self.subtitle.is_some() { 90.0 } else { 60.0 };
        (AREA.0 as u32, (top + AREA.1) as u32)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, k: u32) -> Result<(), String> {
        let px = Px(k.max(1));
        let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let area = titled(root, &self.title, self.subtitle.as_deref(), px)?;
        let (_, h) = area.dim_in_pixel();
        let radius = (f64::from(h) / 2.0 - px.f(30.0)).min(px.f(410.0));
        let centre = (px.f(AREA.0) - radius - px.f(70.0), f64::from(h) / 2.0);
        let screen =
            |(x, y): (f64, f64)| ((centre.0 + radius * x).round() as i32, (centre.1 - radius * y).round() as i32);
        let c = screen((0.0, 0.0));
        area.draw(&Circle::new(c, radius as i32, RGBColor(246, 247, 251).filled())).map_err(e)?;
        // The far side first, the outline over it, then the near side.
        for front in [false, true] {
            if front {
                area.draw(&Circle::new(c, radius as i32, BLACK.mix(0.55).stroke_width(px.u(1)))).map_err(e)?;
            }
            for curve in &self.curves {
                let style = style(curve, front, px);
                for piece in pieces(&curve.points, &self.view).into_iter().filter(|(f, _)| *f == front) {
                    let points: Vec<(i32, i32)> = piece.1.into_iter().map(screen).collect();
                    if front || curve.stroke == Stroke::Level {
                        area.draw(&PathElement::new(points, style)).map_err(e)?;
                    } else {
                        area.draw(&DashedPathElement::new(points, px.u(7), px.u(6), style)).map_err(e)?;
                    }
                }
            }
        }
        for mark in &self.marks {
            let (x, y, depth) = self.view.project(mark.at);
            let color = if depth >= 0.0 { mark.color.mix(1.0) } else { mark.color.mix(0.35) };
            let at = screen((x, y));
            let r = px.f(mark.radius) as i32;
            let shape = if mark.hollow { color.stroke_width(px.u(2)) } else { color.filled() };
            area.draw(&Circle::new(at, r, shape)).map_err(e)?;
            if let Some(label) = &mark.label {
                // Outward from the centre, or up and to the right of a point near it.
                let (dx, dy) = if x.hypot(y) > 0.2 { (x / x.hypot(y), y / x.hypot(y)) } else { (0.6, 0.8) };
                let d = px.f(20.0);
                let place = (at.0 + (d * dx) as i32, at.1 - (d * dy) as i32);
                let font = px.font(TICK_SIZE).color(&color).pos(Pos::new(HPos::Center, VPos::Center));
                area.draw(&Text::new(label.clone(), place, font)).map_err(e)?;
            }
        }
        self.legend(&area, px)
    }
}

impl SphereFigure {
    /// The legend, in the upper left corner, and the note under it.
    fn legend<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>, px: Px) -> Result<(), String> {
        let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let dot = |m: &Mark| if m.hollow { m.color.stroke_width(px.u(2)) } else { m.color.filled() };
        let far = Curve { name: None, points: vec![], color: BLACK, stroke: Stroke::Path };
        let mut entries: Vec<(&str, Sample)> = vec![];
        entries.extend(self.curves.iter().filter_map(|c| Some((c.name.as_deref()?, Sample::Line(style(c, true, px))))));
        entries.push(("far side of the sphere", Sample::Dashed(style(&far, false, px))));
        entries.extend(self.marks.iter().filter_map(|m| Some((m.legend.as_deref()?, Sample::Dot(dot(m), m.radius)))));
        let font = px.font(LEGEND_SIZE);
        let line = px.f(1.5 * LEGEND_SIZE);
        let widest = entries.iter().map(|(t, _)| area.estimate_text_size(t, &font).map_or(0, |s| s.0)).max();
        let (x0, y0, sample) = (px.f(20.0), px.f(16.0), px.f(44.0));
        let width = widest.unwrap_or(0) as f64 + sample + px.f(30.0);
        let height = line * entries.len() as f64 + px.f(16.0);
        let corner = |x: f64, y: f64| (x.round() as i32, y.round() as i32);
        let frame = [corner(x0, y0), corner(x0 + width, y0 + height)];
        area.draw(&Rectangle::new(frame, WHITE.mix(0.85).filled())).map_err(e)?;
        area.draw(&Rectangle::new(frame, BLACK.mix(0.4).stroke_width(px.u(1)))).map_err(e)?;
        for (i, (text, sample_style)) in entries.iter().enumerate() {
            let y = y0 + px.f(8.0) + line * (i as f64 + 0.5);
            let (a, b) = (corner(x0 + px.f(10.0), y), corner(x0 + px.f(10.0) + sample, y));
            match *sample_style {
                Sample::Line(style) => area.draw(&PathElement::new([a, b], style)).map_err(e)?,
                Sample::Dashed(style) => {
                    area.draw(&DashedPathElement::new([a, b], px.u(7), px.u(6), style)).map_err(e)?
                }
                Sample::Dot(style, radius) => {
                    let centre = corner(x0 + px.f(10.0) + sample / 2.0, y);
                    area.draw(&Circle::new(centre, px.f(radius) as i32, style)).map_err(e)?;
                }
            }
            let at = corner(x0 + px.f(20.0) + sample, y);
            area.draw(&Text::new(text.to_string(), at, font.pos(Pos::new(HPos::Left, VPos::Center)))).map_err(e)?;
        }
        if let Some(note) = &self.note {
            let (_, h) = area.dim_in_pixel();
            let at = corner(x0, f64::from(h) - px.f(16.0));
            let grey = BLACK.mix(0.7);
            let font = px.font(TICK_SIZE).color(&grey).pos(Pos::new(HPos::Left, VPos::Bottom));
            area.draw(&Text::new(note.clone(), at, font)).map_err(e)?;
        }
        Ok(())
    }
}

/// What a legend entry shows.
enum Sample {
    Line(ShapeStyle),
    Dashed(ShapeStyle),
    Dot(ShapeStyle, f64),
}

/// The style of `curve` on the near side (`front`) or the far side of the sphere.
fn style(curve: &Curve, front: bool, px: Px) -> ShapeStyle {
    let (alpha, width) = match (curve.stroke, front) {
        (Stroke::Path, true) => (1.0, 2.5),
        (Stroke::Path, false) => (0.4, 2.0),
        (Stroke::Separatrix, true) => (0.75, 1.6),
        (Stroke::Separatrix, false) => (0.3, 1.3),
        (Stroke::Level, true) => (0.4, 1.0),
        (Stroke::Level, false) => (0.14, 1.0),
    };
    curve.color.mix(alpha).stroke_width((px.f(width)).round().max(1.0) as u32)
}

/// The largest angle (radians) between the points drawn of a curve: samples further apart are
/// joined by an arc of the great circle through them, in up to [`ARC_POINTS`] chords.
const ARC_STEP: f64 = 0.05;
const ARC_POINTS: usize = 8;

/// `points` with points added on the great circle between samples more than [`ARC_STEP`] apart.
fn arcs(points: &[Vec3]) -> Vec<Vec3> {
    let mut out = Vec::with_capacity(points.len());
    for pair in points.windows(2) {
        let (p, q) = (pair[0], pair[1]);
        let angle = dot(p, q).clamp(-1.0, 1.0).acos();
        // Nearly opposite points have no one great circle between them: a chord it is.
        let n = if angle < 3.0 { ((angle / ARC_STEP).ceil() as usize).clamp(1, ARC_POINTS) } else { 1 };
        out.extend((0..n).map(|i| {
            let s = i as f64 / n as f64;
            unit(std::array::from_fn(|j| p[j] + s * (q[j] - p[j])))
        }));
    }
    out.extend(points.last());
    out
}

/// The curve through `points` in pieces on the near side (true) and the far side (false) of the
/// sphere, in screen coordinates; a piece ends and the next begins where the curve crosses the
/// outline.
fn pieces(points: &[Vec3], view: &View) -> Vec<(bool, Vec<(f64, f64)>)> {
    let mut pieces: Vec<(bool, Vec<(f64, f64)>)> = vec![];
    let mut last: Option<(f64, f64, f64)> = None;
    let points: Vec<Vec3> = points.iter().copied().filter(|p| p.iter().all(|x| x.is_finite())).collect();
    for p in arcs(&points) {
        let (x, y, d) = view.project(p);
        let front = d >= 0.0;
        match (last, pieces.last_mut()) {
            (Some((x0, y0, d0)), Some((side, piece))) if *side != front => {
                // The crossing: where the height changes sign, moved onto the outline.
                let s = d0 / (d0 - d);
                let (cx, cy) = (x0 + s * (x - x0), y0 + s * (y - y0));
                let n = cx.hypot(cy).max(f64::MIN_POSITIVE);
                piece.push((cx / n, cy / n));
                pieces.push((front, vec![(cx / n, cy / n), (x, y)]));
            }
            (_, Some((_, piece))) => piece.push((x, y)),
            (_, None) => pieces.push((front, vec![(x, y)])),
        }
        last = Some((x, y, d));
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_great_circle_is_cut_where_it_crosses_the_outline() {
        // The equator seen from above the x axis: the half with x > 0 is near, the rest far.
        let view = View::new([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
        let circle: Vec<Vec3> = (0..=40)
            .map(|i| f64::from(i) * std::f64::consts::TAU / 40.0 + 0.01)
            .map(|a| [a.cos(), a.sin(), 0.0])
            .collect();
        let cut = pieces(&circle, &view);
        assert_eq!(cut.iter().map(|p| p.0).collect::<Vec<_>>(), [true, false, true]);
        for (_, piece) in &cut {
            for (x, y) in piece {
                assert!(x.hypot(*y) <= 1.0 + 1e-12);
            }
        }
        // The near half ends on the outline, at (±1, 0) on the screen.
        let end = cut[0].1.last().unwrap();
        assert!((end.0.abs() - 1.0).abs() < 1e-12 && end.1.abs() < 1e-12, "{end:?}");
    }
}
