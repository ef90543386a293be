//! `ddirac::check`: invariance, regularity and primary-constraint findings against systems whose
//! answers are known by hand.

use ddirac::systems::ChargedParticle;
use ddirac::{check, Coordinate, InitialMomentum, Method, Problem, System};
use num_dual::DualNum;

/// Two point vortices, L = Σ ½Γ_i (x_i ẏ_i − y_i ẋ_i) − H, H = −Γ1Γ2/(2π) ln|r1 − r2|, with the
/// translation in x of both vortices written as the group coordinate X = x1 (x2 = X + dx).
struct Vortices;

impl System<4> for Vortices {
    fn coordinates(&self) -> [Coordinate; 4] {
        [Coordinate::group("X"), Coordinate::shape("y1"), Coordinate::shape("dx"), Coordinate::shape("y2")]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 4], v: &[D; 4]) -> D {
        let (g1, g2) = (1.0, 2.0);
        let (x1, y1, x2, y2) = (q[0], q[1], q[0] + q[2], q[3]);
        let (vx1, vy1, vx2, vy2) = (v[0], v[1], v[0] + v[2], v[3]);
        let kinetic = (x1 * vy1 - y1 * vx1) * (0.5 * g1) + (x2 * vy2 - y2 * vx2) * (0.5 * g2);
        let r2 = (x1 - x2) * (x1 - x2) + (y1 - y2) * (y1 - y2);
        kinetic + r2.ln() * (0.5 * g1 * g2 / (2.0 * std::f64::consts::PI))
    }
}

#[test]
fn the_charged_particle_is_invariant_regular_and_consistent() {
    let report = check(&ChargedParticle::default(), &ChargedParticle::paper_problem(100), &Method::default()).unwrap();
    assert_eq!(report.invariance.len(), 1);
    assert_eq!(report.invariance[0].coordinate, "theta");
    assert!(report.invariance[0].deviation < 1e-14, "{report:?}");
    assert_eq!(report.invariance[0].samples, ddirac::sampling::WANTED);
    assert_eq!(report.legendre_rank, 4);
    assert!(report.regular() && report.invariant() && report.momentum_consistent());
}

#[test]
fn point_vortices_are_degenerate_and_not_invariant() {
    let q0 = vec![0.0, 0.0, 1.0, 0.0];
    // On the primary constraint p = ∂L/∂v: p_x1 + p_x2 = −½(Γ1 y1 + Γ2 y2) for X, p_dx = −½Γ2 y2,
    // p_y1 = ½Γ1 x1, p_y2 = ½Γ2 x2.
    let consistent = vec![0.0, 0.0, 0.0, 1.0];
    let problem = Problem::new(0.05, 10, q0.clone(), InitialMomentum::Momentum(consistent));
    let report = check(&Vortices, &problem, &Method::default()).unwrap();
    assert_eq!(report.legendre_rank, 0, "L is linear in the velocities");
    assert!(!report.regular());
    assert!(!report.invariant(), "L_d is invariant only up to a boundary term: {report:?}");
    assert!(report.constraint_mismatch < 1e-14, "{report:?}");

    let inconsistent = Problem::new(0.05, 10, q0, InitialMomentum::Momentum(vec![0.3, 0.0, 0.0, 1.0]));
    let report = check(&Vortices, &inconsistent, &Method::default()).unwrap();
    assert!((report.constraint_mismatch - 0.3).abs() < 1e-12, "{report:?}");
    assert!(!report.momentum_consistent());
}
