//! The chart watch on a regular chart: an angle that turns by more than a radian per step is
//! reported as an under-resolved step (the Legendre map stays regular, so not as a singular chart).

use ddirac::{solve, Coordinate, InitialMomentum, Method, OutputOptions, Problem, System, WarningKind};
use num_dual::DualNum;

/// A pendulum, L = ½ θ̇² + 9.8 cos θ, spinning over the top.
struct Pendulum;

impl System<1> for Pendulum {
    fn coordinates(&self) -> [Coordinate; 1] {
        [Coordinate::shape("theta").angle()]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 1], v: &[D; 1]) -> D {
        v[0] * v[0] * 0.5 + q[0].cos() * 9.8
    }
}

fn warnings(speed: f64) -> Vec<ddirac::Warning> {
    let problem = Problem::new(0.01, 200, vec![0.0], InitialMomentum::Momentum(vec![speed]));
    solve(&Pendulum, &problem, &Method::default(), &OutputOptions::default()).unwrap().summary.warnings
}

#[test]
fn an_angle_turning_more_than_a_radian_per_step_is_under_resolved() {
    let found = warnings(150.0);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].kind, WarningKind::UnderResolved);
    assert_eq!((found[0].step, found[0].count), (Some(0), 200));
    assert!(found[0].message.starts_with("`theta` advanced by 1.5"), "{}", found[0].message);
}

#[test]
fn an_angle_turning_less_than_a_radian_per_step_is_not_reported() {
    assert!(warnings(90.0).is_empty());
}
