//! The double spherical pendulum written as text, shared by the expression tests, the expression
//! benchmark and the `expression` group of `ddirac bench`.

use ddirac::expression::ExpressionSpec;
use ddirac::Coordinate;

/// The double spherical pendulum's Lagrangian as written in the module doc of
/// `ddirac::systems::double_spherical_pendulum`, with θ1 = ϑ1 − ϑ2 and θ2 = ϑ1 + ϑ2.
pub fn double_spherical_pendulum_spec() -> ExpressionSpec {
    let string = |s: &str| s.to_owned();
    let cross = "phi1_dot*phi2_dot*sin(phi1)*sin(phi2) + phi1_dot*phi2_dot*cos(phi1)*cos(phi2)*cos(theta1 - theta2) \
                 + phi1_dot*theta2_dot*sin(phi2)*sin(theta1 - theta2)*cos(phi1) \
                 - phi2_dot*theta1_dot*sin(phi1)*sin(theta1 - theta2)*cos(phi2) \
                 + theta1_dot*theta2_dot*sin(phi1)*sin(phi2)*cos(theta1 - theta2)";
    let t2 = format!(
        "0.5*m2*(l1^2*phi1_dot^2 + l2^2*phi2_dot^2 + l1^2*theta1_dot^2*sin(phi1)^2 \
         + l2^2*theta2_dot^2*sin(phi2)^2 + 2*l1*l2*({cross}))"
    );
    ExpressionSpec {
        coordinates: vec![
            Coordinate::group("vartheta1").angle(),
            Coordinate::shape("phi1").angle(),
            Coordinate::shape("vartheta2").angle(),
            Coordinate::shape("phi2").angle(),
        ],
        lagrangian: string(
            "0.5*l1^2*m1*(phi1_dot^2 + theta1_dot^2*sin(phi1)^2) + T2 \
             - g*m1*l1*cos(phi1) - g*m2*(l1*cos(phi1) + l2*cos(phi2))",
        ),
        definitions: vec![
            (string("theta1"), string("vartheta1 - vartheta2")),
            (string("theta2"), string("vartheta1 + vartheta2")),
            (string("theta1_dot"), string("vartheta1_dot - vartheta2_dot")),
            (string("theta2_dot"), string("vartheta1_dot + vartheta2_dot")),
            (string("T2"), t2),
        ],
        parameters: vec![
            (string("m1"), 20.0),
            (string("m2"), 35.0),
            (string("l1"), 500.0),
            (string("l2"), 800.0),
            (string("g"), 9.8),
        ],
        exact_solution: vec![],
        ..ExpressionSpec::default()
    }
}
