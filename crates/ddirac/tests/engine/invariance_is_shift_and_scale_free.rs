//! The invariance and periodicity verdicts do not depend on an additive constant or a factor in L
//! (the hypotheses are properties of the motion, which neither changes): a tilted spherical pendulum
//! is refused and an upright one accepted for every constant and factor, and their deviations scale
//! by nothing.

use ddirac::{check, num_dual::DualNum, Coordinate, InitialMomentum, Method, Problem, System};
use proptest::prelude::*;

/// L = s·(½(φ̇² + sin²φ θ̇²) − g (cos ε cos φ + sin ε sin φ cos θ)) + c: invariant under θ-shifts iff ε = 0.
struct Pendulum {
    tilt: f64,
    factor: f64,
    constant: f64,
}

impl System<2> for Pendulum {
    fn coordinates(&self) -> [Coordinate; 2] {
        [Coordinate::shape("phi").angle(), Coordinate::group("theta").angle()]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 2], v: &[D; 2]) -> D {
        let (phi, theta) = (q[0], q[1]);
        let kinetic = (v[0] * v[0] + phi.sin().powi(2) * v[1] * v[1]) * 0.5;
        let height = phi.cos() * self.tilt.cos() + phi.sin() * theta.cos() * self.tilt.sin();
        (kinetic - height * 9.81) * self.factor + self.constant
    }
}

fn report(tilt: f64, factor: f64, constant: f64) -> ddirac::CheckReport {
    let problem = Problem::new(0.01, 10, vec![1.0, 0.3], InitialMomentum::Velocity(vec![0.2, 1.0]));
    let method = Method { reduced: true, ..Method::default() };
    check(&Pendulum { tilt, factor, constant }, &problem, &method).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn verdicts_ignore_constants_and_factors(constant in -1e12f64..1e12, exponent in -8.0f64..8.0) {
        let factor = 10f64.powf(exponent);
        let method = Method { reduced: true, ..Method::default() };
        let tilted = report(0.01, factor, constant);
        let reference = report(0.01, 1.0, 0.0);
        prop_assert!(!tilted.invariant() && tilted.periodic());
        let refused = matches!(tilted.verdict(&method), Err(ddirac::Error::NotInvariant { .. }));
        prop_assert!(refused, "the tilted pendulum is not refused");
        // The deviation is a ratio of slopes: the same whatever the factor and constant.
        let (d, d0) = (tilted.invariance[0].deviation, reference.invariance[0].deviation);
        prop_assert!((d - d0).abs() <= 1e-6 * d0, "{d} against {d0}");

        let upright = report(0.0, factor, constant);
        prop_assert!(upright.invariant() && upright.periodic(), "{upright:?}");
        prop_assert!(upright.verdict(&method).unwrap().is_empty());
    }
}
