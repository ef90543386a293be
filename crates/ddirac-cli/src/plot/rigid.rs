//! The figures of a rigid body's run (`system = "rigid_body"`), read from its `summary.json` and
//! its trajectory ([`super::rigid_data`]):
//!
//! - `momentum_sphere`: the body angular momentum Π on the sphere |Π| = |Π₀| with the level curves
//!   of the energy ½ Σ Πᵢ²/Iᵢ (Euler's top); for a heavy body, whose |Π| varies, Π/|Π| alone;
//! - `body_axes`: the tips of the body's axes in space, the columns R e₁, R e₂, R e₃ of R;
//! - `rigid_invariants`: the drift of the energy, of the conserved components of the angular
//!   momentum in space R Π, and (symmetry SO(3)) of |Π|, against time.

use std::path::{Path, PathBuf};

use super::figure::{Figure, Panel, Series};
use super::rigid_data::{gather, RigidData, RigidSummary};
use super::rigid_spheres::{body_axes, momentum_sphere};
use super::{save, ToolError};

/// The drift of the invariants against time, one panel each.
fn invariants(summary: &RigidSummary, data: RigidData) -> Option<Figure> {
    let mut panels = vec![];
    if let Some(e0) = data.energy0 {
        let label = if e0 == 0.0 { "E − E₀" } else { "(E − E₀)/|E₀|" };
        panels.push(Panel::new("t", label, vec![Series::line(data.energy.finish())]));
    }
    let conserved = summary.conserved();
    if !conserved.is_empty() {
        let mut momentum = data.momentum.map(Some);
        let series = conserved
            .iter()
            .filter_map(|&i| {
                let name = ["x", "y", "z"][i];
                Some(Series::named(format!("J_{name} − J_{name}(0)"), momentum[i].take()?.finish()))
            })
            .collect();
        panels.push(Panel::new("t", "J − J₀, J = R Π", series));
    }
    if summary.symmetry == "SO(3)" {
        panels.push(Panel::new("t", "|Π|/|Π₀| − 1", vec![Series::line(data.casimir.finish())]));
    }
    let names = match (conserved.len(), summary.symmetry == "SO(3)") {
        (3, true) => "energy, angular momentum in space and |Π|",
        (0, _) => "energy",
        _ => "energy and vertical angular momentum",
    };
    let title = format!("{}: drift of the {names}", summary.name);
    (!panels.is_empty()).then(|| Figure::new("rigid_invariants", title, panels).subtitle(summary.description.clone()))
}

/// Draws the figures of the rigid body's run in `dir` into `dir`; returns the files written.
pub fn plot_rigid_run(dir: &Path) -> Result<Vec<PathBuf>, ToolError> {
    let summary = RigidSummary::read(dir)?;
    let data = gather(dir)?;
    let mut written = save(&momentum_sphere(&summary, &data), dir)?;
    written.extend(save(&body_axes(&summary, &data), dir)?);
    if let Some(figure) = invariants(&summary, data) {
        written.extend(save(&figure, dir)?);
    }
    Ok(written)
}
