//! A Lagrangian that leaves the motion undetermined — one that vanishes, or on which some coordinate
//! has no effect — used to run silently: the step equations read 0 = 0, Newton's method "converged" at
//! once and the run reported a constant q with "warnings none" and exit code 0. It is refused before
//! the first step now, with the rank of the step's Jacobian D1D2 L_d there.

use ddirac::systems::Kepler;
use ddirac::{Coordinate, Error, InitialMomentum, Method, Problem, Stepper, System};
use num_dual::DualNum;

/// L = 0 (written with the velocity, as `0*x_dot` in a spec).
struct Vanishing;

impl System<1> for Vanishing {
    fn coordinates(&self) -> [Coordinate; 1] {
        [Coordinate::shape("x")]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, _q: &[D; 1], v: &[D; 1]) -> D {
        v[0] * 0.0
    }
}

/// L = ½ ẋ²: y has no effect on the motion, so nothing fixes it.
struct Forgotten;

impl System<2> for Forgotten {
    fn coordinates(&self) -> [Coordinate; 2] {
        [Coordinate::shape("x"), Coordinate::shape("y")]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, _q: &[D; 2], v: &[D; 2]) -> D {
        v[0] * v[0] * 0.5
    }
}

fn refusal<S: System<N>, const N: usize>(system: &S, problem: &Problem) -> Error {
    for method in [Method::default(), Method { composition: ddirac::Composition::Suzuki5, ..Method::default() }] {
        match Stepper::new(system, problem, &method) {
            Err(e @ Error::Undetermined { .. }) => {
                assert!(e.to_string().contains("do not determine the motion"), "{e}");
                assert!(ddirac::solve(system, problem, &method, &Default::default()).is_err());
            }
            Err(other) => panic!("another error: {other}"),
            Ok(_) => panic!("a run of an undetermined motion was prepared"),
        }
    }
    Stepper::new(system, problem, &Method::default()).err().expect("refused")
}

#[test]
fn a_vanishing_lagrangian_is_refused_with_rank_zero() {
    let problem = Problem::new(0.1, 10, vec![1.0], InitialMomentum::Velocity(vec![2.0]));
    assert!(matches!(refusal(&Vanishing, &problem), Error::Undetermined { rank: 0, coordinates: 1 }));
}

#[test]
fn a_coordinate_without_effect_is_refused_with_the_rank_of_the_others() {
    let problem = Problem::new(0.1, 10, vec![0.0, 0.0], InitialMomentum::Velocity(vec![1.0, 0.5]));
    assert!(matches!(refusal(&Forgotten, &problem), Error::Undetermined { rank: 1, coordinates: 2 }));
}

#[test]
fn a_determined_motion_is_not_refused() {
    let problem = Problem::new(0.01, 100, vec![1.0, 0.0], InitialMomentum::Momentum(vec![0.0, 0.7]));
    for reduced in [false, true] {
        assert!(Stepper::new(&Kepler::default(), &problem, &Method { reduced, ..Method::default() }).is_ok());
    }
}
