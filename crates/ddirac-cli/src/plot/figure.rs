//! A figure: a title over panels stacked vertically, each a chart of line series, drawn on any
//! plotters backend (PNG bitmap or SVG).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::segments::segments;
use super::ticks::{self, TickFormat};
use super::FONT;

/// The colours of successive series (a colour-blind-friendly qualitative palette).
pub(super) const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// Font sizes in pixels, for a figure 1200 pixels wide.
pub(super) const TITLE_SIZE: f64 = 30.0;
pub(super) const SUBTITLE_SIZE: f64 = 20.0;
pub(super) const CAPTION_SIZE: f64 = 24.0;
pub(super) const AXIS_SIZE: f64 = 22.0;
pub(super) const TICK_SIZE: f64 = 18.0;
pub(super) const LEGEND_SIZE: f64 = 18.0;

/// Labelled ticks per axis.
const X_TICKS: usize = 8;
const Y_TICKS: usize = 6;

/// A figure of panels stacked vertically, sharing the width.
#[derive(Debug, Clone)]
pub struct Figure {
    /// File name without extension (`energy_error`).
    pub name: String,
    /// The title over all panels.
    pub title: String,
    /// A smaller line under the title (what was run), if any.
    pub subtitle: Option<String>,
    /// The panels, top to bottom.
    pub panels: Vec<Panel>,
    /// Width in pixels.
    pub width: u32,
    /// Height of one panel in pixels.
    pub panel_height: u32,
}

/// Axis scaling of a panel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// Linear axes.
    Linear,
    /// Both axes logarithmic (all values must be positive).
    LogLog,
    /// Linear axes with the same length per unit on both (paths in a plane).
    Equal,
}

/// One chart.
#[derive(Debug, Clone)]
pub struct Panel {
    /// A caption over the chart, if any.
    pub caption: Option<String>,
    /// Name of the horizontal axis.
    pub x_label: String,
    /// Name of the vertical axis.
    pub y_label: String,
    /// The data.
    pub series: Vec<Series>,
    /// Axis scaling.
    pub scale: Scale,
}

/// One curve.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend entry; a legend is drawn when any series of the panel has one.
    pub name: Option<String>,
    /// The points, in drawing order; non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
    /// Mark each point with a dot.
    pub markers: bool,
    /// Draw the line dashed (reference lines).
    pub dashed: bool,
    /// Draw the line wide and pale, so that a line drawn over it stays visible where they coincide.
    pub wide: bool,
    /// The values are angles wrapped to (−π, π]: the line is broken where they wrap.
    pub wrapped: bool,
}

impl Series {
    /// A plain unnamed line.
    pub fn line(points: Vec<(f64, f64)>) -> Self {
        Self { name: None, points, markers: false, dashed: false, wide: false, wrapped: false }
    }

    /// A named line.
    pub fn named(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { name: Some(name.into()), ..Self::line(points) }
    }

    /// The same line, of angles wrapped to (−π, π] if `wrapped`.
    pub fn wrapped(mut self, wrapped: bool) -> Self {
        self.wrapped = wrapped;
        self
    }

    /// The pieces the line is drawn in (see [`segments`]).
    fn segments(&self) -> Vec<Vec<(f64, f64)>> {
        segments(&self.points, self.wrapped)
    }
}

impl Figure {
    /// A figure called `name` with one panel per entry of `panels`, 1200 pixels wide.
    pub fn new(name: &str, title: impl Into<String>, panels: Vec<Panel>) -> Self {
        let panel_height = if panels.len() > 1 { 320 } else { 640 };
        Self { name: name.to_owned(), title: title.into(), subtitle: None, panels, width: 1200, panel_height }
    }

    /// With a line under the title.
    pub fn subtitle(mut self, subtitle: impl Into<String>) -> Self {
        self.subtitle = Some(subtitle.into());
        self
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        let top = if self.subtitle.is_some() { 90 } else { 60 };
        (self.width, top + self.panel_height * self.panels.len().max(1) as u32)
    }
}

impl super::Drawing for Figure {
    fn name(&self) -> &str {
        &self.name
    }

    fn size(&self) -> (u32, u32) {
        Figure::size(self)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, k: u32) -> Result<(), String> {
        draw(self, root, k)
    }
}

impl Panel {
    /// With a caption over the chart.
    pub fn caption(mut self, caption: impl Into<String>) -> Self {
        self.caption = Some(caption.into());
        self
    }

    /// With axis scaling `scale`.
    pub fn scale(mut self, scale: Scale) -> Self {
        self.scale = scale;
        self
    }

    /// A linear chart of `series` with the given axis names.
    pub fn new(x_label: impl Into<String>, y_label: impl Into<String>, series: Vec<Series>) -> Self {
        Self { caption: None, x_label: x_label.into(), y_label: y_label.into(), series, scale: Scale::Linear }
    }

    /// The smallest and largest finite x and y over all series, including where lines of wrapped
    /// angles meet ±π (positive ones only for log axes).
    fn bounds(&self) -> Option<((f64, f64), (f64, f64))> {
        let positive = self.scale == Scale::LogLog;
        let pieces: Vec<Vec<(f64, f64)>> = self.series.iter().flat_map(Series::segments).collect();
        let mut points = pieces
            .iter()
            .flatten()
            .filter(|(x, y)| x.is_finite() && y.is_finite() && (!positive || (*x > 0.0 && *y > 0.0)));
        let &(x0, y0) = points.next()?;
        Some(points.fold(((x0, x0), (y0, y0)), |((xl, xh), (yl, yh)), &(x, y)| {
            ((xl.min(x), xh.max(x)), (yl.min(y), yh.max(y)))
        }))
    }
}

/// Lengths in pixels of a figure drawn `k` times its size (k > 1 for anti-aliased bitmaps).
#[derive(Debug, Clone, Copy)]
pub(super) struct Px(pub(super) u32);

impl Px {
    /// `v` pixels of the figure at its own size.
    pub(super) fn f(self, v: f64) -> f64 {
        v * f64::from(self.0)
    }

    /// `v` whole pixels of the figure at its own size.
    pub(super) fn u(self, v: u32) -> u32 {
        v * self.0
    }

    /// `v` whole pixels of the figure at its own size, signed.
    pub(super) fn i(self, v: i32) -> i32 {
        v * self.0 as i32
    }

    pub(super) fn font(self, size: f64) -> TextStyle<'static> {
        (FONT, self.f(size)).into_font().color(&BLACK)
    }
}

/// Draws `figure` on `root`, which must have `k` times the figure's size in each direction.
pub fn draw<DB: DrawingBackend>(figure: &Figure, root: &DrawingArea<DB, Shift>, k: u32) -> Result<(), String> {
    let px = Px(k.max(1));
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let body = titled(root, &figure.title, figure.subtitle.as_deref(), px)?;
    let areas = body.split_evenly((figure.panels.len().max(1), 1));
    // Panels over the same horizontal quantity share its range and name it once, under the last.
    let shared_x = figure.panels.windows(2).all(|w| w[0].x_label == w[1].x_label && w[0].scale == Scale::Linear);
    let x_range = shared_x
        .then(|| {
            let ranges = figure.panels.iter().filter_map(|p| p.bounds().map(|b| b.0));
            ranges.reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
        })
        .flatten();
    let frames: Vec<Frame> = figure.panels.iter().zip(&areas).map(|(p, a)| Frame::new(p, a, x_range, px)).collect();
    // One width for the space left of every panel, so that the plotting areas line up.
    let y_area = frames.iter().map(|f| f.y_area_width(root, px)).max().unwrap_or(0);
    let last = figure.panels.len().saturating_sub(1);
    for (i, ((panel, area), frame)) in figure.panels.iter().zip(&areas).zip(&frames).enumerate() {
        let x_desc = !shared_x || i == last;
        draw_panel(panel, area, frame, y_area, x_desc, px)?;
    }
    root.present().map_err(e)
}

/// Fills `root` white and writes the title and the subtitle, if any, at its top; returns the area
/// left under them.
pub(super) fn titled<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    subtitle: Option<&str>,
    px: Px,
) -> Result<DrawingArea<DB, Shift>, String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let mut body = root.margin(px.i(12), 0, 0, 0).titled(title, px.font(TITLE_SIZE)).map_err(e)?;
    if let Some(subtitle) = subtitle {
        body = body.titled(subtitle, px.font(SUBTITLE_SIZE).color(&BLACK.mix(0.7))).map_err(e)?;
    }
    Ok(body)
}

/// The ranges a panel shows and how its numbers are written.
///
/// Values are drawn as (v − offset) / 10^exponent, so that tick labels stay short: an offset is
/// taken when the spread is tiny compared with the values, a power of ten when the numbers are very
/// small or very large; both are stated in the axis name.
struct Frame {
    x: Axis,
    y: Axis,
}

struct Axis {
    range: (f64, f64),
    /// Major and minor ticks (linear axes; logarithmic ones are left to the chart).
    ticks: (Vec<f64>, Vec<f64>),
    offset: f64,
    exponent: i32,
    format: TickFormat,
    label: String,
}

impl Axis {
    /// An axis over data in [lo, hi] (before padding).
    fn linear(label: &str, (lo, hi): (f64, f64), pad: f64, ticks: usize) -> Self {
        let offset = ticks::offset(lo, hi).unwrap_or(0.0);
        let (a, b) = ticks::padded(lo - offset, hi - offset, pad);
        let magnitude = a.abs().max(b.abs());
        let exponent =
            if magnitude > 0.0 && !(1e-3..1e5).contains(&magnitude) { magnitude.log10().floor() as i32 } else { 0 };
        let unit = 10f64.powi(exponent);
        let range = (a / unit, b / unit);
        let mut label = label.to_owned();
        if offset != 0.0 {
            label = format!("{label} − {}", ticks::short_exact(offset));
        }
        if exponent != 0 {
            label = format!("{label}  [×10{}]", superscript(exponent));
        }
        let ticks = ticks::nice(range.0, range.1, ticks);
        let format = TickFormat::for_ticks(&ticks.0);
        Self { range, ticks, offset, exponent, format, label }
    }

    fn logarithmic(label: &str, (lo, hi): (f64, f64), factor: f64, count: usize) -> Self {
        let range = (lo / factor, hi * factor);
        let format = TickFormat::logarithmic();
        let ticks = ticks::logarithmic(range.0, range.1, count);
        Self { range, ticks, offset: 0.0, exponent: 0, format, label: label.to_owned() }
    }

    fn map(&self, v: f64) -> f64 {
        (v - self.offset) / 10f64.powi(self.exponent)
    }
}

impl Frame {
    /// The frame of `panel`, over `x_range` if given instead of its own data's.
    fn new<DB: DrawingBackend>(
        panel: &Panel,
        area: &DrawingArea<DB, Shift>,
        x_range: Option<(f64, f64)>,
        px: Px,
    ) -> Self {
        let ((xl, xh), (yl, yh)) = panel.bounds().unwrap_or(((0.0, 1.0), (0.0, 1.0)));
        let (xl, xh) = x_range.unwrap_or((xl, xh));
        // Room above the data for the legend: the fraction f of the height it takes.
        let f = legend_room(panel, area, px);
        let (yl, yh) = match panel.scale {
            Scale::LogLog if yh > yl => (yl, yh * (yh / yl).powf(f / (1.0 - f))),
            Scale::Linear if yh > yl => (yl, yh + (yh - yl) * f / (1.0 - f)),
            _ => (yl, yh),
        };
        let (x, y) = match panel.scale {
            Scale::LogLog => {
                let x = Axis::logarithmic(&panel.x_label, (xl, xh), 1.25, X_TICKS);
                (x, Axis::logarithmic(&panel.y_label, (yl, yh), 1.6, Y_TICKS))
            }
            Scale::Linear => (
                Axis::linear(&panel.x_label, (xl, xh), 0.0, X_TICKS),
                Axis::linear(&panel.y_label, (yl, yh), 0.05, Y_TICKS),
            ),
            Scale::Equal => {
                // Widen one range so that a unit has about the same length on both axes.
                let (x, y) = (ticks::padded(xl, xh, 0.05), ticks::padded(yl, yh, 0.05));
                let (w, h) = area.dim_in_pixel();
                let (w, h) = ((w as f64 - px.f(200.0)).max(1.0), (h as f64 - px.f(110.0)).max(1.0));
                let (dx, dy) = (x.1 - x.0, y.1 - y.0);
                let (x, y) = if dx / w > dy / h {
                    let (half, c) = (0.5 * dx * h / w, 0.5 * (y.0 + y.1));
                    (x, (c - half, c + half))
                } else {
                    let (half, c) = (0.5 * dy * w / h, 0.5 * (x.0 + x.1));
                    ((c - half, c + half), y)
                };
                (Axis::linear(&panel.x_label, x, 0.0, X_TICKS), Axis::linear(&panel.y_label, y, 0.0, X_TICKS))
            }
        };
        Self { x, y }
    }

    /// The space left of the plotting area: the widest tick label and the rotated axis name.
    fn y_area_width<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>, px: Px) -> u32 {
        let widest = self
            .y
            .ticks
            .0
            .iter()
            .map(|&v| area.estimate_text_size(&self.y.format.format(v), &px.font(TICK_SIZE)).map_or(0, |(w, _)| w))
            .max()
            .unwrap_or(0);
        widest + px.u(AXIS_SIZE as u32 + 36)
    }

    fn map(&self, &(x, y): &(f64, f64)) -> Option<(f64, f64)> {
        (x.is_finite() && y.is_finite()).then(|| (self.x.map(x), self.y.map(y)))
    }
}

/// An integer in Unicode superscript digits (−15 → ⁻¹⁵).
fn superscript(n: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let digits = n.unsigned_abs().to_string().chars().map(|c| DIGITS[c as usize - '0' as usize]).collect::<String>();
    if n < 0 {
        format!("⁻{digits}")
    } else {
        digits
    }
}

fn draw_panel<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, Shift>,
    frame: &Frame,
    y_area: u32,
    x_desc: bool,
    px: Px,
) -> Result<(), String> {
    let mut builder = ChartBuilder::on(area);
    let x_area = px.u(if x_desc { 64 } else { 36 });
    builder
        .margin_top(px.u(12))
        .margin_right(px.u(36))
        .margin_left(px.u(8))
        .x_label_area_size(x_area)
        .y_label_area_size(y_area);
    if let Some(caption) = &panel.caption {
        builder.caption(caption, px.font(CAPTION_SIZE));
    }
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let (x_fmt, y_fmt) = (|v: &f64| frame.x.format.format(*v), |v: &f64| frame.y.format.format(*v));
    macro_rules! finish {
        ($chart:expr) => {{
            let mut chart = $chart;
            let mut mesh = chart.configure_mesh();
            mesh.x_labels(X_TICKS)
                .y_labels(Y_TICKS)
                .max_light_lines(4)
                .x_label_formatter(&x_fmt)
                .y_label_formatter(&y_fmt)
                .y_desc(frame.y.label.as_str())
                .label_style(px.font(TICK_SIZE))
                .axis_desc_style(px.font(AXIS_SIZE))
                .set_all_tick_mark_size(px.u(5))
                .axis_style(BLACK.stroke_width(px.u(1)))
                .bold_line_style(BLACK.mix(0.12).stroke_width(px.u(1)))
                .light_line_style(BLACK.mix(0.04).stroke_width(px.u(1)));
            if x_desc {
                mesh.x_desc(frame.x.label.as_str());
            }
            mesh.draw().map_err(e)?;
            for (i, series) in panel.series.iter().enumerate() {
                let color = PALETTE[i % PALETTE.len()];
                let style = if series.wide {
                    ShapeStyle::from(&color.mix(0.4)).stroke_width(px.u(7))
                } else {
                    ShapeStyle::from(&color).stroke_width(px.u(2))
                };
                // One line per piece; the legend entry goes with the first (an empty line if none).
                let mut pieces = series.segments().into_iter();
                let mut piece = pieces.next().unwrap_or_default();
                let mut labelled = false;
                loop {
                    let points = piece.iter().filter_map(|p| frame.map(p));
                    let drawn = if series.dashed {
                        let (dash, gap) = (px.u(12), px.u(8));
                        chart.draw_series(DashedLineSeries::new(points, dash, gap, style)).map_err(e)?
                    } else {
                        chart.draw_series(LineSeries::new(points, style)).map_err(e)?
                    };
                    if let (Some(name), false) = (&series.name, labelled) {
                        labelled = true;
                        let dot = series.markers && series.points.len() == 1;
                        let (r, d) = (px.i(5), px.i(12));
                        drawn.label(name.as_str()).legend(move |(x, y)| -> DynElement<'static, DB, (i32, i32)> {
                            if dot {
                                Circle::new((x + d, y), r, color.filled()).into_dyn()
                            } else {
                                PathElement::new([(x, y), (x + 2 * d, y)], style).into_dyn()
                            }
                        });
                    }
                    match pieces.next() {
                        Some(next) => piece = next,
                        None => break,
                    }
                }
                if series.markers {
                    let r = px.i(5);
                    let dots =
                        series.points.iter().filter_map(|p| frame.map(p)).map(|p| Circle::new(p, r, color.filled()));
                    chart.draw_series(dots).map_err(e)?;
                }
            }
            if panel.series.iter().any(|s| s.name.is_some()) {
                chart
                    .configure_series_labels()
                    .label_font(px.font(LEGEND_SIZE))
                    .margin(px.u(10))
                    .legend_area_size(px.u(30))
                    .background_style(WHITE.mix(0.8))
                    .border_style(BLACK.mix(0.4).stroke_width(px.u(1)))
                    .position(legend_position(panel, frame))
                    .draw()
                    .map_err(e)?;
            }
        }};
    }
    let (x, y) = (frame.x.range.0..frame.x.range.1, frame.y.range.0..frame.y.range.1);
    match panel.scale {
        Scale::LogLog => {
            let log = |r: std::ops::Range<f64>| plotters::coord::combinators::LogCoord::from(r.log_scale());
            let (x, y) = (Ticked::new(log(x), &frame.x.ticks), Ticked::new(log(y), &frame.y.ticks));
            finish!(builder.build_cartesian_2d(x, y).map_err(e)?)
        }
        _ => {
            let linear = plotters::coord::types::RangedCoordf64::from;
            let (x, y) = (Ticked::new(linear(x), &frame.x.ticks), Ticked::new(linear(y), &frame.y.ticks));
            finish!(builder.build_cartesian_2d(x, y).map_err(e)?)
        }
    }
    Ok(())
}

/// An axis with the ticks of [`ticks::nice`] or [`ticks::logarithmic`] rather than the chart's own
/// (which can drop the last tick to round-off).
struct Ticked<R> {
    inner: R,
    major: Vec<f64>,
    minor: Vec<f64>,
}

impl<R> Ticked<R> {
    fn new(inner: R, (major, minor): &(Vec<f64>, Vec<f64>)) -> Self {
        Self { inner, major: major.clone(), minor: minor.clone() }
    }
}

impl<R: plotters::coord::ranged1d::Ranged<ValueType = f64>> plotters::coord::ranged1d::Ranged for Ticked<R> {
    type FormatOption = plotters::coord::ranged1d::DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(value, limit)
    }

    fn key_points<Hint: plotters::coord::ranged1d::KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.major.clone()
        }
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.inner.range()
    }
}

/// The fraction of a panel's plotting height its legend takes (0 without a legend).
fn legend_room<DB: DrawingBackend>(panel: &Panel, area: &DrawingArea<DB, Shift>, px: Px) -> f64 {
    let entries = panel.series.iter().filter(|s| s.name.is_some()).count();
    if entries == 0 {
        return 0.0;
    }
    let caption = if panel.caption.is_some() { 1.6 * CAPTION_SIZE } else { 0.0 };
    let plot_height = (area.dim_in_pixel().1 as f64 - px.f(76.0 + caption)).max(1.0);
    (px.f(entries as f64 * 1.35 * LEGEND_SIZE + 24.0) / plot_height).min(0.5)
}

/// The corner of the plotting area where the legend hides the fewest points.
fn legend_position(panel: &Panel, frame: &Frame) -> SeriesLabelPosition {
    // The legend's box, as a fraction of the plotting area, measured from its corner.
    let (width, height) = (0.3, 0.08 + 0.07 * panel.series.iter().filter(|s| s.name.is_some()).count() as f64);
    let fraction = |v: f64, (lo, hi): (f64, f64), log: bool| {
        if log {
            (v.ln() - lo.ln()) / (hi.ln() - lo.ln())
        } else {
            (v - lo) / (hi - lo)
        }
    };
    let log = panel.scale == Scale::LogLog;
    let points: Vec<(f64, f64)> = panel
        .series
        .iter()
        .flat_map(|s| &s.points)
        .filter_map(|p| frame.map(p))
        .map(|(x, y)| (fraction(x, frame.x.range, log), fraction(y, frame.y.range, log)))
        .collect();
    let covered = |right: bool, top: bool| {
        points
            .iter()
            .filter(|(x, y)| {
                let x_in = if right { *x > 1.0 - width } else { *x < width };
                let y_in = if top { *y > 1.0 - height } else { *y < height };
                x_in && y_in
            })
            .count()
    };
    let corners = [
        (SeriesLabelPosition::UpperRight, covered(true, true)),
        (SeriesLabelPosition::UpperLeft, covered(false, true)),
        (SeriesLabelPosition::LowerRight, covered(true, false)),
        (SeriesLabelPosition::LowerLeft, covered(false, false)),
    ];
    corners.into_iter().min_by_key(|(_, n)| *n).map_or(SeriesLabelPosition::UpperRight, |(p, _)| p)
}
