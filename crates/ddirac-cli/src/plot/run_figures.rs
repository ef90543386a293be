//! The figures of one run:
//!
//! - `coordinates`: each coordinate against time, one panel per coordinate, with the exact motion
//!   drawn under it (wide and pale) where the run wrote one (`exact.csv`);
//! - `exact_path`: where the exact motion is known for two coordinates or more, the computed and the
//!   exact path in the plane of the first two (the paper's §7.1 figure for the charged particle);
//! - `energy_error`: (H − H₀)/|H₀| against time (H − H₀ when H₀ = 0);
//! - `momentum_map`: (J − J₀)/s for each group coordinate (only for systems with a symmetry), s the
//!   summary's scale of the momenta (J − J₀ for a summary without one);
//! - `discrete_energy`: L_d(q_k, q_{k+1}) against t_k, the paper's "discrete energy";
//!
//! and for the double spherical pendulum the paper's figures (§7.2):
//!
//! - `phi1`: φ₁(t);
//! - `second_bob_path`: the (x, y) projection of the second mass,
//!   x = l1 sin φ1 cos θ1 + l2 sin φ2 cos θ2, y likewise with sin θ, θ1 = ϑ1 − ϑ2, θ2 = ϑ1 + ϑ2.

use ddirac::systems::DoubleSphericalPendulum;

use super::data::{RowView, RunSummary, TrajectoryFile};
use super::exact::Exact;
use super::figure::{Figure, Panel, Scale, Series};
use super::sample::{Envelope, Stride};
use super::ToolError;

/// Name of the double spherical pendulum in `summary.json`.
const PENDULUM: &str = "double_spherical_pendulum";
/// Its coordinates, in the order [`DoubleSphericalPendulum::second_bob`] takes them.
const PENDULUM_COORDINATES: [&str; 4] = ["vartheta1", "phi1", "vartheta2", "phi2"];

/// Everything gathered in one pass over the trajectory.
struct Gathered {
    coordinates: Vec<Envelope>,
    energy: Envelope,
    energy0: Option<f64>,
    has_energy: bool,
    momentum: Vec<Envelope>,
    momentum0: Vec<f64>,
    discrete_energy: Envelope,
    has_discrete_energy: bool,
    path: Option<(DoubleSphericalPendulum, [usize; 4], Stride)>,
    /// The computed path in the plane of the exact path's coordinates.
    plane: Option<([usize; 2], Stride)>,
}

impl Gathered {
    fn new(summary: &RunSummary, trajectory: &TrajectoryFile, exact: &Exact) -> Self {
        let rows = trajectory.rows;
        Self {
            coordinates: summary.coordinates.iter().map(|_| Envelope::new(rows)).collect(),
            energy: Envelope::new(rows),
            energy0: None,
            has_energy: false,
            momentum: trajectory.group.iter().map(|_| Envelope::new(rows)).collect(),
            momentum0: vec![],
            discrete_energy: Envelope::new(rows),
            has_discrete_energy: false,
            path: pendulum(summary).map(|(p, i)| (p, i, Stride::new(rows))),
            plane: exact.path.as_ref().and_then(|([x, y], _)| {
                let at = |name: &String| summary.coordinates.iter().position(|c| c == name);
                Some(([at(x)?, at(y)?], Stride::new(rows)))
            }),
        }
    }

    fn push(&mut self, row: &RowView<'_>) {
        for (envelope, &q) in self.coordinates.iter_mut().zip(row.q) {
            envelope.push(row.t, Some(q));
        }
        if let Some(h) = row.energy {
            let h0 = *self.energy0.get_or_insert(h);
            let error = if h0 == 0.0 { h - h0 } else { (h - h0) / h0.abs() };
            self.energy.push(row.t, Some(error));
            self.has_energy = true;
        }
        if self.momentum0.is_empty() {
            self.momentum0 = row.momentum.to_vec();
        }
        for ((envelope, &j), j0) in self.momentum.iter_mut().zip(row.momentum).zip(&self.momentum0) {
            envelope.push(row.t, Some(j - j0));
        }
        self.has_discrete_energy |= row.discrete_energy.is_some();
        self.discrete_energy.push(row.t, row.discrete_energy);
        if let Some(([x, y], plane)) = &mut self.plane {
            plane.push((row.q[*x], row.q[*y]));
        }
        if let Some((pendulum, index, path)) = &mut self.path {
            let bob = pendulum.second_bob(&index.map(|i| row.q[i]));
            path.push((bob[0], bob[1]));
        }
    }
}

/// The pendulum with the run's lengths, and where its coordinates are, if the run is of it.
fn pendulum(summary: &RunSummary) -> Option<(DoubleSphericalPendulum, [usize; 4])> {
    if summary.system != PENDULUM {
        return None;
    }
    let index = PENDULUM_COORDINATES.map(|name| summary.coordinates.iter().position(|c| c == name));
    let defaults = DoubleSphericalPendulum::default();
    let pendulum = DoubleSphericalPendulum {
        l1: summary.parameter("l1").unwrap_or(defaults.l1),
        l2: summary.parameter("l2").unwrap_or(defaults.l2),
        ..defaults
    };
    Some((pendulum, [index[0]?, index[1]?, index[2]?, index[3]?]))
}

/// The figures of the run described by `summary` whose trajectory is `trajectory`, with its exact
/// motion `exact` where the system has one.
pub fn run_figures(summary: &RunSummary, trajectory: &TrajectoryFile, exact: &Exact) -> Result<Vec<Figure>, ToolError> {
    let mut gathered = Gathered::new(summary, trajectory, exact);
    trajectory.for_each(|row| gathered.push(row))?;
    let Gathered {
        coordinates,
        energy,
        energy0,
        has_energy,
        momentum,
        discrete_energy,
        has_discrete_energy,
        path,
        plane,
        ..
    } = gathered;
    let system = &summary.system;
    let titled = |name: &str, title: String, panels: Vec<Panel>| {
        Figure::new(name, title, panels).subtitle(summary.description.clone())
    };

    let mut phi1 = None;
    let mut panels = vec![];
    for (name, envelope) in summary.coordinates.iter().zip(coordinates) {
        let points = envelope.finish();
        if path.is_some() && name == "phi1" {
            phi1 = Some(points.clone());
        }
        let wrapped = summary.is_wrapped(name);
        let series = match exact.series.iter().find(|(n, _)| n == name) {
            Some((_, exact)) => vec![
                Series { wide: true, ..Series::named("exact", exact.clone()) }.wrapped(wrapped),
                Series::named("computed", points).wrapped(wrapped),
            ],
            None => vec![Series::line(points).wrapped(wrapped)],
        };
        panels.push(Panel::new("t", name.as_str(), series));
    }
    let mut figures = vec![titled("coordinates", format!("{system}: coordinates"), panels)];

    if let (Some(([x, y], exact_path)), Some((_, plane))) = (&exact.path, plane) {
        let series = vec![
            Series { wide: true, ..Series::named("exact", exact_path.clone()) },
            Series::named("computed", plane.finish()),
        ];
        let panel = Panel::new(x.as_str(), y.as_str(), series).scale(Scale::Equal);
        let title = format!("{system}: path in the ({x}, {y}) plane, computed and exact");
        figures.push(titled("exact_path", title, vec![panel]));
    }

    if has_energy {
        let relative = energy0.is_some_and(|h0| h0 != 0.0);
        let (label, what) =
            if relative { ("(H − H₀)/|H₀|", "relative energy error") } else { ("H − H₀", "energy error") };
        let panel = Panel::new("t", label, vec![Series::line(energy.finish())]);
        figures.push(titled("energy_error", format!("{system}: {what}"), vec![panel]));
    }

    if !momentum.is_empty() {
        // Relative to the momenta's size, as the summary reports it: a drift of 1e-9 means nothing
        // until it is set against momenta of 1 or of 10⁶.
        let scale = summary.momentum_scale.unwrap_or(1.0);
        let series = trajectory
            .group
            .iter()
            .zip(momentum)
            .map(|(g, envelope)| {
                let points = envelope.finish().into_iter().map(|(t, j)| (t, j / scale)).collect();
                Series::named(format!("J_{g} − J_{g}(0)"), points)
            })
            .collect();
        let (label, title) = match summary.momentum_scale {
            Some(s) => (
                "(J − J₀)/s".to_owned(),
                format!("{system}: momentum map drift relative to s = {s:.3e}, the largest of |J₀| and the momenta"),
            ),
            None => ("J − J₀".to_owned(), format!("{system}: momentum map drift")),
        };
        let panel = Panel::new("t", label.as_str(), series);
        figures.push(titled("momentum_map", title, vec![panel]));
    }

    if has_discrete_energy {
        let panel = Panel::new("t", "L_d(q_k, q_k+1)", vec![Series::line(discrete_energy.finish())]);
        figures.push(titled("discrete_energy", format!("{system}: discrete energy L_d(q_k, q_k+1)"), vec![panel]));
    }

    if let (Some(phi1), Some((_, _, path))) = (phi1, path) {
        let panel = Panel::new("t", "φ₁", vec![Series::line(phi1).wrapped(summary.is_wrapped("phi1"))]);
        figures.push(titled("phi1", format!("{system}: φ₁(t)"), vec![panel]));
        let path = path.finish();
        let start = path.first().map(|&p| Series { markers: true, ..Series::named("start", vec![p]) });
        let series = std::iter::once(Series::named("second mass", path)).chain(start).collect();
        let panel = Panel::new("x", "y", series).scale(Scale::Equal);
        let mut figure =
            titled("second_bob_path", format!("{system}: second mass, projection on the (x, y) plane"), vec![panel]);
        figure.panel_height = 1000;
        figures.push(figure);
    }
    Ok(figures)
}
