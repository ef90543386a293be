//! Rigid bodies on SO(3) (`ddirac::rigid`) against independent references: Euler's equations
//! integrated by classical Runge–Kutta with tiny steps (in R, Π and the shape), the orders of the
//! rules and compositions, the conserved quantities, reduced against unreduced, and the refusals.

use ddirac::num_dual::DualNum;
use ddirac::rigid::so3::{self, Matrix3};
use ddirac::rigid::{solve_rigid, RigidInitial, RigidProblem, RigidSummary, RigidSystem, Symmetry};
use ddirac::systems::RigidBody;
use ddirac::{Composition, Coordinate, Error, Input, Method, Reason, Rule};

/// A state of Euler's equations: R (rows), Π, the rotor angle s.
#[derive(Clone, Copy, Debug)]
struct Euler {
    r: Matrix3<f64>,
    pi: [f64; 3],
    s: f64,
}

/// The vector field of a body with principal moments `inertia`, weight m g at c, and a rotor of
/// inertia `rotor` about body axis 3 with momentum `p` (0 for none): Ω from Π and p, then
/// Π̇ = Π × Ω + m g (Γ × c), Ṙ = R Ω̂, ṡ = p/J − Ω3.
fn field(body: &RigidBody, rotor: f64, p: f64, x: &Euler) -> Euler {
    let [i1, i2, i3] = body.inertia;
    let omega = [x.pi[0] / i1, x.pi[1] / i2, (x.pi[2] - p) / i3];
    let gamma = [x.r[2][0], x.r[2][1], x.r[2][2]];
    let mg = body.m * body.g;
    let torque = so3::cross(&gamma, &body.c);
    let spin = so3::cross(&x.pi, &omega);
    let pi = [0, 1, 2].map(|i| spin[i] + mg * torque[i]);
    let r = so3::mul(&x.r, &so3::hat(&omega));
    let s = if rotor > 0.0 { p / rotor - omega[2] } else { 0.0 };
    Euler { r, pi, s }
}

fn axpy(x: &Euler, a: f64, d: &Euler) -> Euler {
    let mut y = *x;
    for i in 0..3 {
        for j in 0..3 {
            y.r[i][j] += a * d.r[i][j];
        }
        y.pi[i] += a * d.pi[i];
    }
    y.s += a * d.s;
    y
}

/// Classical RK4 over [0, t] in `n` steps.
fn reference(body: &RigidBody, rotor: f64, p: f64, x0: Euler, t: f64, n: usize) -> Euler {
    let h = t / n as f64;
    let mut x = x0;
    for _ in 0..n {
        let k1 = field(body, rotor, p, &x);
        let k2 = field(body, rotor, p, &axpy(&x, h / 2.0, &k1));
        let k3 = field(body, rotor, p, &axpy(&x, h / 2.0, &k2));
        let k4 = field(body, rotor, p, &axpy(&x, h, &k3));
        for (k, w) in [(k1, 1.0), (k2, 2.0), (k3, 2.0), (k4, 1.0)] {
            x = axpy(&x, h * w / 6.0, &k);
        }
    }
    x
}

/// The largest difference of R and Π.
fn gap(a: &Euler, b: &Euler) -> f64 {
    let mut worst = 0.0f64;
    for i in 0..3 {
        for j in 0..3 {
            worst = worst.max((a.r[i][j] - b.r[i][j]).abs());
        }
        worst = worst.max((a.pi[i] - b.pi[i]).abs());
    }
    worst
}

fn distance(summary: &RigidSummary, x: &Euler) -> f64 {
    gap(&Euler { r: summary.final_r, pi: summary.final_pi, s: 0.0 }, x)
}

fn tilted() -> Matrix3<f64> {
    so3::cayley(&[0.9, -0.4, 0.3])
}

/// An asymmetric heavy top released with a spin from a tilted attitude, and a free body near its
/// intermediate axis.
fn cases() -> Vec<(RigidBody, Matrix3<f64>, [f64; 3])> {
    let heavy = RigidBody { inertia: [1.0, 1.5, 0.8], m: 1.0, g: 9.81, c: [0.05, 0.0, 0.2] };
    let free = RigidBody::free(1.0, 2.0, 3.0);
    vec![(heavy, tilted(), [0.5, -0.3, 2.0]), (free, so3::identity(), [0.05, 2.0, 0.05])]
}

fn run(body: &RigidBody, r0: Matrix3<f64>, pi0: [f64; 3], h: f64, t: f64, method: &Method) -> RigidSummary {
    let steps = (t / h).round() as usize;
    let problem = RigidProblem::new(h, steps, r0, RigidInitial::Momentum { pi: pi0, p: vec![] });
    solve_rigid(body, problem, method, steps).unwrap().summary
}

/// The reference is converged: RK4 with 20 000 and 40 000 steps agree to 1e-12.
fn converged_reference(body: &RigidBody, r0: Matrix3<f64>, pi0: [f64; 3], t: f64) -> Euler {
    let x0 = Euler { r: r0, pi: pi0, s: 0.0 };
    let fine = reference(body, 0.0, 0.0, x0, t, 40_000);
    let coarse = reference(body, 0.0, 0.0, x0, t, 20_000);
    let off = gap(&coarse, &fine);
    assert!(off < 1e-11, "the reference itself is off by {off:e}");
    fine
}

fn slope(errors: &[f64]) -> f64 {
    (errors[0] / errors[errors.len() - 1]).log2() / (errors.len() - 1) as f64
}

#[test]
fn symmetric_rules_converge_at_order_2_and_one_sided_rules_at_order_1() {
    let t = 2.0;
    let (heavy, r0, pi0) = cases()[0];
    let exact = converged_reference(&heavy, r0, pi0, t);
    for (rule, order) in [(Rule::Midpoint, 2.0), (Rule::Trapezoid, 2.0), (Rule::Left, 1.0), (Rule::Right, 1.0)] {
        let method = Method { rule, ..Method::default() };
        let errors: Vec<f64> =
            [0.02, 0.01, 0.005].iter().map(|&h| distance(&run(&heavy, r0, pi0, h, t, &method), &exact)).collect();
        let observed = slope(&errors);
        assert!((observed - order).abs() < 0.15, "{rule:?}: errors {errors:?}, order {observed}");
    }
    // The free body's ℓ does not depend on R: every rule is the same step, of order 2.
    let (free, r0, pi0) = cases()[1];
    let exact = converged_reference(&free, r0, pi0, t);
    let errors: Vec<f64> = [0.02, 0.01, 0.005]
        .iter()
        .map(|&h| {
            let runs: Vec<RigidSummary> = Rule::ALL
                .iter()
                .map(|&rule| run(&free, r0, pi0, h, t, &Method { rule, ..Method::default() }))
                .collect();
            assert!(runs.iter().all(|s| s.final_r == runs[0].final_r && s.final_pi == runs[0].final_pi));
            distance(&runs[0], &exact)
        })
        .collect();
    assert!((slope(&errors) - 2.0).abs() < 0.15, "{errors:?}");
}

#[test]
fn compositions_reach_orders_4_and_6() {
    for (body, r0, pi0) in cases() {
        let t = 2.0;
        let exact = converged_reference(&body, r0, pi0, t);
        for (order, hs) in [(4u8, [0.1, 0.05, 0.025]), (6, [0.2, 0.1, 0.05])] {
            let method = Method { composition: Composition::for_order(order).unwrap(), ..Method::default() };
            let errors: Vec<f64> = hs.iter().map(|&h| distance(&run(&body, r0, pi0, h, t, &method), &exact)).collect();
            let observed = slope(&errors);
            assert!((observed - f64::from(order)).abs() < 0.4, "order {order} on {body:?}: {errors:?}, {observed}");
        }
        // Order 8 with h = 0.05 is within 1e-9 of the reference.
        let method = Method { composition: Composition::for_order(8).unwrap(), ..Method::default() };
        let error = distance(&run(&body, r0, pi0, 0.05, t, &method), &exact);
        assert!(error < 1e-9, "order 8 on {body:?}: {error:e}");
    }
}

#[test]
fn angular_momentum_casimir_and_orthogonality_are_kept_to_round_off() {
    // The free body: all of R Π and |Π|; 20 000 steps.
    let free = RigidBody::free(1.0, 2.0, 3.0);
    let summary = run(&free, tilted(), [0.05, 2.0, 0.05], 0.05, 1000.0, &Method::default());
    assert!(summary.momentum_map.max_relative_drift.unwrap() < 1e-12, "{:?}", summary.momentum_map);
    assert!(summary.casimir.max_relative_drift < 1e-12, "{:?}", summary.casimir);
    assert!(summary.orthogonality < 1e-13, "{}", summary.orthogonality);
    // Bounded energy error, no drift.
    let e = summary.energy;
    assert!((e.max - e.min) / e.initial < 1e-2, "{e:?}");
    assert!(summary.warnings.is_empty(), "{:?}", summary.warnings);
    // The heavy top: e3 · R Π only.
    let (heavy, r0, pi0) = cases()[0];
    let summary = run(&heavy, r0, pi0, 0.01, 200.0, &Method::default());
    assert_eq!(summary.symmetry, Symmetry::Vertical);
    assert!(summary.momentum_map.max_relative_drift.unwrap() < 1e-12, "{:?}", summary.momentum_map);
    assert!(summary.orthogonality < 1e-13);
    let e = summary.energy;
    assert!((e.max - e.min) / e.initial.abs() < 1e-2, "{e:?}");
}

/// A free body whose Lagrangian reads R (through ⟨R a, R b⟩, constant on SO(3)), with a rotor about
/// body axis 3: ℓ = ½ ⟨Ω, 𝕀Ω⟩ + ½ J (Ω3 + ṡ)² + κ ⟨R a, R b⟩.
struct Satellite {
    body: RigidBody,
    rotor: f64,
}

impl RigidSystem for Satellite {
    fn shape(&self) -> Vec<Coordinate> {
        vec![Coordinate::shape("rotor").angle()]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, r: &Matrix3<D>, w: &[D; 3], _s: &[D], v: &[D]) -> D {
        let [i1, i2, i3] = self.body.inertia;
        let kinetic = (w[0] * w[0] * i1 + w[1] * w[1] * i2 + w[2] * w[2] * i3) * 0.5;
        let spin = w[2] + v[0];
        let (a, b) = ([0.3, -1.0, 0.5], [0.2, 0.4, 1.0]);
        let ra = [0, 1, 2].map(|i| r[i][0] * a[0] + r[i][1] * a[1] + r[i][2] * a[2]);
        let rb = [0, 1, 2].map(|i| r[i][0] * b[0] + r[i][1] * b[1] + r[i][2] * b[2]);
        kinetic + spin * spin * (0.5 * self.rotor) + so3::dot(&ra, &rb) * 0.7
    }

    fn symmetry(&self) -> Symmetry {
        Symmetry::Rotations
    }
}

#[test]
fn a_satellite_with_a_rotor_follows_its_equations_and_reduces_to_round_off() {
    let satellite = Satellite { body: RigidBody::free(2.0, 3.0, 4.0), rotor: 0.5 };
    let (pi0, p0) = ([0.4, 1.5, 2.5], 1.2);
    let problem = |h: f64, t: f64| RigidProblem {
        s0: vec![0.3],
        ..RigidProblem::new(h, (t / h).round() as usize, tilted(), RigidInitial::Momentum { pi: pi0, p: vec![p0] })
    };
    let t = 2.0;
    let x0 = Euler { r: tilted(), pi: pi0, s: 0.3 };
    let exact = reference(&satellite.body, satellite.rotor, p0, x0, t, 40_000);
    let errors: Vec<f64> = [0.02, 0.01, 0.005]
        .iter()
        .map(|&h| {
            let summary = solve_rigid(&satellite, problem(h, t), &Method::default(), 1000).unwrap().summary;
            assert!((summary.final_p[0] - p0).abs() < 1e-12, "the rotor's momentum is conserved");
            distance(&summary, &exact).max((summary.final_s[0] - exact.s).abs())
        })
        .collect();
    assert!((slope(&errors) - 2.0).abs() < 0.15, "{errors:?}");

    // Reduced by SO(3) (ℓ at R = I) against unreduced (ℓ at R_k, with its torque), 2000 steps.
    let unreduced = solve_rigid(&satellite, problem(0.01, 20.0), &Method::default(), 1).unwrap();
    let reduced_method = Method { reduced: true, ..Method::default() };
    let reduced = solve_rigid(&satellite, problem(0.01, 20.0), &reduced_method, 1).unwrap();
    let mut worst = 0.0f64;
    for (a, b) in unreduced.rows.iter().zip(&reduced.rows) {
        for i in 0..3 {
            worst = worst.max((a.pi[i] - b.pi[i]).abs());
            for j in 0..3 {
                worst = worst.max((a.r[i][j] - b.r[i][j]).abs());
            }
        }
        worst = worst.max((a.s[0] - b.s[0]).abs()).max((a.p[0] - b.p[0]).abs());
    }
    assert!(worst < 1e-11, "reduced and unreduced differ by {worst:e}");
    assert!(reduced.summary.casimir.max_relative_drift < 1e-13, "{:?}", reduced.summary.casimir);
    assert!(reduced.summary.momentum_map.max_relative_drift.unwrap() < 1e-12);
}

#[test]
fn attitudes_that_are_not_rotations_are_refused() {
    let body = RigidBody::free(1.0, 2.0, 3.0);
    let initial = RigidInitial::Momentum { pi: [0.0, 1.0, 0.0], p: vec![] };
    let sheared = [[1.0, 1e-9, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let reflection = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]];
    let scaled = [[1.0 + 1e-10, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for r0 in [sheared, reflection, scaled] {
        let error =
            solve_rigid(&body, RigidProblem::new(0.01, 10, r0, initial.clone()), &Method::default(), 1).unwrap_err();
        assert!(
            matches!(error, Error::Invalid { what: Input::InitialAttitude, why: Reason::NotARotation { .. } }),
            "{error}"
        );
    }
    let nan = [[f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let error =
        solve_rigid(&body, RigidProblem::new(0.01, 10, nan, initial.clone()), &Method::default(), 1).unwrap_err();
    assert!(matches!(error, Error::NonFinite { what: Input::InitialAttitude, entry: Some(0), .. }), "{error}");
    // Within the tolerance: accepted (a rotation rounded to 12 digits).
    let rounded = tilted().map(|row| row.map(|x| (x * 1e13).round() / 1e13));
    assert!(solve_rigid(&body, RigidProblem::new(0.01, 10, rounded, initial), &Method::default(), 1).is_ok());
}

#[test]
fn a_heavy_top_is_not_reduced_by_so3() {
    let (heavy, r0, pi0) = cases()[0];
    let problem = RigidProblem::new(0.01, 10, r0, RigidInitial::Momentum { pi: pi0, p: vec![] });
    let error = solve_rigid(&heavy, problem, &Method { reduced: true, ..Method::default() }, 1).unwrap_err();
    assert!(matches!(error, Error::NotReducible { symmetry: "vertical" }), "{error}");
    assert!(error.to_string().contains("e3 · R Π"), "{error}");
}

/// A heavy body that declares invariance under every rotation.
struct Mislabelled(RigidBody);

impl RigidSystem for Mislabelled {
    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, r: &Matrix3<D>, w: &[D; 3], _s: &[D], _v: &[D]) -> D {
        let [i1, i2, i3] = self.0.inertia;
        let height = r[2][0] * self.0.c[0] + r[2][1] * self.0.c[1] + r[2][2] * self.0.c[2];
        (w[0] * w[0] * i1 + w[1] * w[1] * i2 + w[2] * w[2] * i3) * 0.5 - height * (self.0.m * self.0.g)
    }

    fn symmetry(&self) -> Symmetry {
        Symmetry::Rotations
    }
}

#[test]
fn a_declared_symmetry_the_lagrangian_lacks_is_refused() {
    let (heavy, r0, pi0) = cases()[0];
    let problem = RigidProblem::new(0.01, 10, r0, RigidInitial::Momentum { pi: pi0, p: vec![] });
    for reduced in [false, true] {
        let method = Method { reduced, ..Method::default() };
        let error = solve_rigid(&Mislabelled(heavy), problem.clone(), &method, 1).unwrap_err();
        assert!(matches!(error, Error::NotInvariantUnderRotations { symmetry: "SO(3)", .. }), "{error}");
    }
}

#[test]
fn initial_angular_velocity_is_mapped_to_momentum() {
    // Π0 = 𝕀 Ω0 for the rigid body: the same run either way.
    let body = RigidBody::free(1.0, 2.0, 3.0);
    let omega = [0.3, -0.2, 0.5];
    let by_velocity = RigidProblem::new(0.01, 50, tilted(), RigidInitial::Velocity { omega, v: vec![] });
    let by_momentum = RigidProblem::new(0.01, 50, tilted(), RigidInitial::Momentum { pi: [0.3, -0.4, 1.5], p: vec![] });
    let a = solve_rigid(&body, by_velocity, &Method::default(), 50).unwrap().summary;
    let b = solve_rigid(&body, by_momentum, &Method::default(), 50).unwrap().summary;
    assert_eq!(a.final_r, b.final_r);
    assert_eq!(a.final_pi, b.final_pi);
    // The energy ½ ⟨Π, Ω⟩.
    assert!((a.energy.initial - 0.5 * (0.09 + 0.08 + 0.75)).abs() < 1e-15);
}

/// The examples' bodies at T = 10: the Dzhanibekov flip (examples/dzhanibekov.toml) and the heavy top
/// released near upright (examples/heavy_top_upright.toml), order 8 at h = 0.01 against RK4 of
/// Euler's equations converged to 1e-11.
#[test]
fn order_8_is_within_1e_8_of_the_converged_reference_on_the_examples() {
    let c = 0.01f64.cos();
    let s = 0.01f64.sin();
    let upright = [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]];
    let examples = [
        (RigidBody::free(1.0, 2.0, 3.0), so3::identity(), [0.01, 4.0, 0.03]),
        (RigidBody { inertia: [1.0, 1.3, 0.4], m: 1.0, g: 9.8, c: [0.0, 0.0, 0.5] }, upright, [0.0, 0.0, 0.8]),
    ];
    let method = Method { composition: Composition::select(Some(8), None).unwrap(), ..Method::default() };
    for (body, r0, pi0) in examples {
        // RK4 with 10⁵ and 2·10⁵ steps, agreeing to 1e-10 (the heavy top's motion is chaotic: round-off grows).
        let x0 = Euler { r: r0, pi: pi0, s: 0.0 };
        let reference = reference(&body, 0.0, 0.0, x0, 10.0, 200_000);
        let coarse = gap(&self::reference(&body, 0.0, 0.0, x0, 10.0, 100_000), &reference);
        assert!(coarse < 1e-10, "the reference itself is off by {coarse:e}");
        let summary = run(&body, r0, pi0, 0.01, 10.0, &method);
        let off = distance(&summary, &reference);
        assert!(off < 1e-8, "{body:?}: order 8 is off by {off:e}");
    }
}

/// 10⁵ steps of the free body and of the heavy top: the conserved quantities and RᵀR = I to 1e-12.
#[test]
fn a_hundred_thousand_steps_keep_the_invariants_to_1e_12() {
    for (body, r0, pi0) in cases() {
        let summary = run(&body, r0, pi0, 0.01, 1000.0, &Method::default());
        assert_eq!(summary.steps, 100_000);
        assert!(summary.momentum_map.max_relative_drift.unwrap() < 1e-12, "{:?}", summary.momentum_map);
        if summary.symmetry == Symmetry::Rotations {
            assert!(summary.casimir.max_relative_drift < 1e-12, "{:?}", summary.casimir);
        }
        assert!(summary.orthogonality < 1e-12, "{}", summary.orthogonality);
    }
}
