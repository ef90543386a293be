//! The text of a system as a spec file gives it: its coordinates, Lagrangian, definitions,
//! parameters, exact solutions and atlas of charts.

use crate::Coordinate;

/// The text of a system: coordinates, Lagrangian, definitions, parameters and exact solutions, as a
/// spec file gives them.
///
/// ```
/// use ddirac::expression::ExpressionSpec;
/// use ddirac::Coordinate;
/// // A pendulum of length l: L = ½ m l² φ̇² + m g l cos φ.
/// let spec = ExpressionSpec {
///     coordinates: vec![Coordinate::shape("phi").angle()],
///     lagrangian: "0.5*m*l^2*phi_dot^2 + m*g*l*cos(phi)".into(),
///     parameters: vec![("m".into(), 1.0), ("l".into(), 2.0), ("g".into(), 9.8)],
///     ..ExpressionSpec::default()
/// };
/// let system = spec.into_dyn().unwrap();
/// assert_eq!(system.coordinates()[0].name, "phi");
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ExpressionSpec {
    /// The coordinates, in order; each `name` also declares the velocity `name_dot`.
    pub coordinates: Vec<Coordinate>,
    /// The Lagrangian.
    pub lagrangian: String,
    /// Definitions, name → source.
    pub definitions: Vec<(String, String)>,
    /// Parameters, name → value.
    pub parameters: Vec<(String, f64)>,
    /// Exact solutions, coordinate name → expression in `t` and the parameters.
    pub exact_solution: Vec<(String, String)>,
    /// With an atlas: where the main chart is good, an expression in the coordinates and the
    /// parameters (about 1 where regular, falling to 0 at its singular set).
    pub quality: Option<String>,
    /// The other charts of the atlas (paper §6; [`crate::atlas`]).
    pub charts: Vec<ChartSpec>,
}

/// A chart of a text system's atlas, as a spec gives it.
///
/// ```
/// use ddirac::expression::{ChartSpec, ExpressionSpec};
/// use ddirac::{Coordinate, System};
/// // A planar pendulum with a chart of its own: ψ = θ + 1.
/// let spec = ExpressionSpec {
///     coordinates: vec![Coordinate::shape("theta").angle()],
///     lagrangian: "0.5*theta_dot^2 + cos(theta)".into(),
///     quality: Some("1".into()),
///     charts: vec![ChartSpec {
///         name: "shifted".into(),
///         coordinates: vec![Coordinate::shape("psi").angle()],
///         to_main: vec![("theta".into(), "psi - 1".into())],
///         from_main: vec![("psi".into(), "theta + 1".into())],
///         quality: "1".into(),
///     }],
///     ..ExpressionSpec::default()
/// };
/// let system = ddirac::expression::ExpressionSystem::<1>::new(&spec).unwrap();
/// assert_eq!(system.charts()[0].name, "shifted");
/// assert_eq!(system.main_to_chart(1, &[0.5]), [1.5]);
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ChartSpec {
    /// A name for messages.
    pub name: String,
    /// The chart's coordinates, in order, with their roles (group coordinates are translated by the
    /// same symmetry as the main chart's) and kinds.
    pub coordinates: Vec<Coordinate>,
    /// The main chart's coordinates, name → expression in this chart's coordinates and the
    /// parameters (the map φ to the main chart).
    pub to_main: Vec<(String, String)>,
    /// This chart's coordinates, name → expression in the main chart's coordinates and the
    /// parameters (the map ψ = φ⁻¹ from it).
    pub from_main: Vec<(String, String)>,
    /// Where the chart is good: an expression in its coordinates and the parameters, about 1 where
    /// the chart is regular, falling to 0 at its singular set.
    pub quality: String,
}

/// Which part of a chart an expression or declaration is.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum ChartPart {
    /// The declaration of the chart's coordinate with this name.
    Coordinate(String),
    /// The expression of the main chart's coordinate with this name (`to_main`).
    ToMain(String),
    /// The expression of the chart's coordinate with this name (`from_main`).
    FromMain(String),
    /// The chart's measure (`quality`).
    Quality,
}

impl std::fmt::Display for ChartPart {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ChartPart::Coordinate(name) => write!(f, "coordinate `{name}`"),
            ChartPart::ToMain(name) => write!(f, "`to_main.{name}`"),
            ChartPart::FromMain(name) => write!(f, "`from_main.{name}`"),
            ChartPart::Quality => write!(f, "`quality`"),
        }
    }
}
