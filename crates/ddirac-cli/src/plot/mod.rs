//! Figures of runs, as PNG and SVG files: `ddirac plot DIR`, `output.plots = true`, and the figures
//! of `ddirac run --compare` and `ddirac convergence`.
//!
//! Text is drawn with DejaVu Sans, embedded in the binary (`assets/`, Bitstream Vera license), so
//! that figures look the same on a machine without any font installed. PNG files are anti-aliased
//! (drawn at three times their size and averaged down); lines of angles written wrapped to (−π, π]
//! are broken where the angle wraps. Every file is written under a temporary name and renamed into
//! place once complete.

mod data;
mod error;
mod exact;
mod figure;
mod rigid;
mod rigid_data;
mod rigid_spheres;
mod run_figures;
mod sample;
mod segments;
mod sphere;
mod supersample;
mod ticks;

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;

pub use data::{RunSummary, TrajectoryFile};
pub use error::ToolError;
pub use figure::{Figure, Panel, Scale, Series};
pub use run_figures::run_figures;
pub use sample::Envelope;

/// The font family every figure uses; registered from the embedded font.
pub const FONT: &str = "sans-serif";

/// DejaVu Sans 2.37.
static FONT_DATA: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

fn register_font() {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        if plotters::style::register_font(FONT, FontStyle::Normal, FONT_DATA).is_err() {
            unreachable!("the embedded font is a valid TrueType font");
        }
    });
}

/// What [`save`] writes: a figure of charts ([`Figure`]) or of curves on a sphere.
pub trait Drawing {
    /// File name without extension.
    fn name(&self) -> &str;
    /// Width and height in pixels.
    fn size(&self) -> (u32, u32);
    /// Draws on `root`, which has `k` times [`Drawing::size`] in each direction.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, k: u32) -> Result<(), String>;
}

/// Writes `figure` as `DIR/<name>.png` and `DIR/<name>.svg`; returns both paths.
pub fn save<D: Drawing>(figure: &D, dir: &Path) -> Result<Vec<PathBuf>, ToolError> {
    register_font();
    let size = figure.size();
    let name = figure.name();

    let png = dir.join(format!("{name}.png"));
    // The bitmap backend picks the encoder from the extension, so the temporary name keeps it.
    let temporary = Temporary(dir.join(format!(".{name}.partial.png")));
    supersample::write_png(figure, &temporary.0, &png)?;
    temporary.commit(&png)?;

    let svg = dir.join(format!("{name}.svg"));
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
        figure.draw(&root, 1).map_err(|why| ToolError::write(&svg, why))?;
    }
    write_atomically(&svg, text.as_bytes())?;
    Ok(vec![png, svg])
}

/// Writes `bytes` to `path` through a temporary file in the same directory.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), ToolError> {
    let temporary = Temporary::for_target(path);
    std::fs::write(&temporary.0, bytes).map_err(|source| ToolError::Write { path: path.to_owned(), source })?;
    temporary.commit(path)
}

/// A file under a temporary name, removed on drop unless renamed into place.
pub struct Temporary(PathBuf);

impl Temporary {
    /// The temporary name of `target`: `.<name>.partial` in the same directory.
    pub fn for_target(target: &Path) -> Self {
        let name = target.file_name().map_or("output".into(), |n| n.to_string_lossy().into_owned());
        Self(target.with_file_name(format!(".{name}.partial")))
    }

    /// The temporary path.
    pub fn path(&self) -> &Path {
        &self.0
    }

    /// Renames the file to `target`.
    pub fn commit(self, target: &Path) -> Result<(), ToolError> {
        std::fs::rename(&self.0, target).map_err(|source| ToolError::Write { path: target.to_owned(), source })?;
        std::mem::forget(self);
        Ok(())
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// Draws every figure of the run in `dir` into `dir`; returns the files written.
pub fn plot_run(dir: &Path) -> Result<Vec<PathBuf>, ToolError> {
    if rigid_data::is_rigid_run(dir) {
        return rigid::plot_rigid_run(dir);
    }
    let summary = RunSummary::read(dir)?;
    let trajectory = TrajectoryFile::open(dir, &summary.coordinates)?;
    let exact = exact::read(dir)?;
    let mut written = vec![];
    for figure in run_figures(&summary, &trajectory, &exact)? {
        written.extend(save(&figure, dir)?);
    }
    Ok(written)
}

/// `ddirac plot DIR`: draws the figures of a finished run and lists them.
pub fn command(dir: &Path, quiet: bool) -> Result<(), ToolError> {
    let written = plot_run(dir)?;
    // The figures belong to the run whose data they show: the next run into `dir` replaces them.
    let list = dir.join(crate::manifest::NAME);
    crate::manifest::record(dir, &written).map_err(|source| ToolError::Write { path: list, source })?;
    if !quiet {
        println!("{} figures in {}:", written.len() / 2, dir.display());
        for path in written.iter().filter(|p| p.extension().is_some_and(|e| e == "png")) {
            let stem = path.file_stem().map_or(String::new(), |s| s.to_string_lossy().into_owned());
            println!("  {stem}.png, {stem}.svg");
        }
    }
    Ok(())
}
