//! The planar chain of pendula written as text, shared by the tests of large text systems and the
//! `expression` group of `ddirac bench`.

use ddirac::expression::ExpressionSpec;
use ddirac::Coordinate;

/// The chain of `links` pendula (`ddirac::systems::PendulumChain`) as a text system: coordinates
/// `th1 … thN` (absolute angles from the downward vertical), and the running sums of its module doc as
/// definitions, vx_i = vx_{i−1} + θ̇_i cos θ_i, vy_i = vy_{i−1} + θ̇_i sin θ_i, d_i = d_{i−1} + cos θ_i:
/// L = ½ m l² Σ_i (vx_i² + vy_i²) + g m l Σ_i d_i.
pub fn chain_spec(links: usize) -> ExpressionSpec {
    let link = 1..=links;
    let previous = |name: &str, i: usize| if i == 1 { String::new() } else { format!("{name}{} + ", i - 1) };
    let definitions = link.clone().flat_map(|i| {
        [
            (format!("vx{i}"), format!("{}th{i}_dot*cos(th{i})", previous("vx", i))),
            (format!("vy{i}"), format!("{}th{i}_dot*sin(th{i})", previous("vy", i))),
            (format!("d{i}"), format!("{}cos(th{i})", previous("d", i))),
        ]
    });
    let speeds: Vec<String> = link.clone().map(|i| format!("vx{i}^2 + vy{i}^2")).collect();
    let depths: Vec<String> = link.clone().map(|i| format!("d{i}")).collect();
    ExpressionSpec {
        coordinates: link.map(|i| Coordinate::shape(&format!("th{i}")).angle()).collect(),
        lagrangian: format!("0.5*m*l^2*({}) + g*m*l*({})", speeds.join(" + "), depths.join(" + ")),
        definitions: definitions.collect(),
        parameters: vec![("m".into(), 1.0), ("l".into(), 1.0), ("g".into(), 9.8)],
        ..ExpressionSpec::default()
    }
}
