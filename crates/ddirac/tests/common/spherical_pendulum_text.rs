//! The spherical pendulum written as text with the atlas of `examples/spherical_pendulum.toml`: the
//! main chart (θ from the downward vertical, φ the azimuth, the group coordinate) and the lower and
//! upper caps (x, y), shared by the tests of text atlases.

use ddirac::expression::{ChartSpec, ExpressionSpec};
use ddirac::Coordinate;

/// The spherical pendulum of `examples/spherical_pendulum.toml`, with its two caps.
pub fn spherical_pendulum() -> ExpressionSpec {
    let string = |s: &str| s.to_owned();
    let pairs = |entries: [(&str, &str); 2]| entries.map(|(a, b)| (string(a), string(b))).to_vec();
    let cap = |name: &str, sign: &str| ChartSpec {
        name: name.into(),
        coordinates: vec![Coordinate::shape("x"), Coordinate::shape("y")],
        to_main: pairs([
            ("theta", &format!("atan2(sqrt(x^2 + y^2), {sign}sqrt(1 - x^2 - y^2))")),
            ("phi", "atan2(y, x)"),
        ]),
        from_main: pairs([("x", "sin(theta)*cos(phi)"), ("y", "sin(theta)*sin(phi)")]),
        quality: "sqrt(1 - x^2 - y^2)".into(),
    };
    ExpressionSpec {
        coordinates: vec![Coordinate::shape("theta").angle(), Coordinate::group("phi").angle()],
        lagrangian: "0.5*m*l^2*(theta_dot^2 + sin(theta)^2*phi_dot^2) + m*g*l*cos(theta)".into(),
        parameters: vec![("m".into(), 1.0), ("l".into(), 1.0), ("g".into(), 9.8)],
        quality: Some("abs(sin(theta))".into()),
        charts: vec![cap("lower cap", ""), cap("upper cap", "-")],
        ..ExpressionSpec::default()
    }
}
