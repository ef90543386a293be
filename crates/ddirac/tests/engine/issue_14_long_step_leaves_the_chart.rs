//! A long step whose predicted point leaves the domain of the chart it starts in (the disc of a
//! hemisphere's projection) made compiled derivatives refuse the run: the trace at that point is not
//! finite ("compiled derivatives are not available: the value is not finite at the trace point"), as
//! the race of `ddirac bench --only work-precision` found in its long run of order 8 on the double
//! spherical pendulum (h = 1.9). The derivatives are now prepared at the step's start, a point of the
//! chart, and the run goes on.

use std::f64::consts::PI;

use ddirac::systems::SphericalPendulum;
use ddirac::{Differentiation, InitialMomentum, Method, Problem, Stepper};

#[test]
fn compiled_derivatives_serve_a_chart_whose_predicted_point_is_outside_it() {
    let system = SphericalPendulum::default();
    // 0.6 rad from the lower pole (main chart's measure 0.56: the run starts in the lower cap),
    // moving up at 3 rad/s: h v carries the cap's x from 0.56 to about 1.8, off the unit disc.
    let (phi, rate, h) = (PI - 0.6, -3.0, 0.5);
    let p = [0.0, system.m * system.l * system.l * rate];
    let problem = Problem::new(h, 4, vec![0.0, phi], InitialMomentum::Momentum(p.to_vec()));
    for reduced in [false, true] {
        let method = Method { reduced, differentiation: Differentiation::Compiled, ..Method::default() };
        let stepper = Stepper::new(&system, &problem, &method);
        let stepper = stepper.unwrap_or_else(|e| panic!("reduced {reduced}: {e}"));
        assert_eq!(stepper.current_chart(), 1, "the run starts in the lower cap");
    }
}
