//! The discrete Lagrange–Pontryagin principles (paper §2.3.3 and §5): trajectories computed by the
//! integrators are stationary points of S⁺ (eq:lagrangepontryaginaction), of the corrected S⁻
//! (eq:lagrangepontryaginactionminus with the pairing sign flipped) and of the reduced actions
//! Σ e_{d±} (lemmas reducedactionlocal / …minus); perturbed trajectories and the printed S⁻ are not.
//!
//! Gradients are measured relative to `ActionGradient::scale`, the largest entry of any single term's
//! gradient (the size of the quantities that cancel, |p| and |D_i L_d|).

use ddirac::reduction::reduced_lagrangian::ReducedLagrangian;
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, TwoBody};
use ddirac::{
    solve, Connection, InitialMomentum, Method, OutputOptions, Problem, Rule, Solution, Split, System, Variant,
};
use ddirac_oracle::dirac_structure::Signs;
use ddirac_oracle::pontryagin::*;

use crate::common;
use common::sampler;

const STATIONARY: f64 = 1e-9;

fn run<S: System<4>>(system: &S, problem: &Problem, method: &Method) -> Solution {
    let solution = solve(system, problem, method, &OutputOptions::default()).expect("the run succeeds");
    assert_eq!(solution.q.len(), problem.steps + 1);
    solution
}

fn relative<const N: usize>(gradient: &ActionGradient<N>) -> f64 {
    gradient.max_abs() / gradient.scale
}

/// S⁺ is stationary on the trajectory, not on a perturbed one, and equals Σ L_d(q_k, q_{k+1}), both
/// evaluated here and as reported by the integrator (in its re-centred charts). Returns the relative
/// gradient.
fn check_plus_action<S: System<4>>(ld: &ddirac::DiscreteLagrangian<S>, solution: &Solution) -> f64 {
    let curve = PlusCurve::<4>::from_trajectory(&solution.q, &solution.p).unwrap();
    let stationary = relative(&action_plus_gradient(ld, &curve).unwrap());
    assert!(stationary < STATIONARY, "S⁺ gradient {stationary:.2e}");

    let mut perturbed = curve.clone();
    let middle = curve.q.len() / 2;
    perturbed.q[middle][0] += 1e-4;
    perturbed.q_plus[middle - 1][0] += 1e-4;
    let moved = relative(&action_plus_gradient(ld, &perturbed).unwrap());
    assert!(moved > 1e3 * STATIONARY, "a perturbed curve must not be stationary ({moved:.2e})");

    let action = action_plus(ld, &curve).unwrap();
    let direct: f64 = curve.q.windows(2).map(|w| ld.value(&w[0], &w[1])).sum();
    let reported: f64 = solution.discrete_energy[..curve.q_plus.len()].iter().sum();
    let size: f64 = curve.q.windows(2).map(|w| ld.value(&w[0], &w[1]).abs()).sum();
    assert!((action - direct).abs() <= 1e-12 * size, "S⁺ = {action} vs Σ L_d = {direct}");
    assert!((action - reported).abs() <= 1e-10 * size, "S⁺ = {action} vs reported Σ L_d = {reported}");
    stationary
}

/// Σ e_{d+} along Λ_{d+}(curve) is stationary and equals S⁺ (reduced variational principle).
fn check_reduced_plus<S: System<4>>(reduction: &ReducedLagrangian<S>, solution: &Solution) -> f64 {
    let curve = PlusCurve::<4>::from_trajectory(&solution.q, &solution.p).unwrap();
    let reduced = curve.trivialize(&reduction.connection, &reduction.split).unwrap();
    let stationary = relative(&reduced_action_plus_gradient(reduction, &reduced).unwrap());
    assert!(stationary < STATIONARY, "Σ e_d+ gradient {stationary:.2e}");
    let (s, e) = (action_plus(&reduction.ld, &curve).unwrap(), reduced_action_plus(reduction, &reduced).unwrap());
    assert!((s - e).abs() <= 1e-12 * s.abs().max(1.0), "S⁺ = {s}, Σ e_d+ = {e}");

    let mut perturbed = reduced.clone();
    let middle = reduced.p_next.len() / 2;
    let size = reduced.p_next.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    perturbed.p_next[middle][0] += 1e-4 * size;
    let moved = relative(&reduced_action_plus_gradient(reduction, &perturbed).unwrap());
    assert!(moved > 1e3 * STATIONARY, "a perturbed reduced curve must not be stationary ({moved:.2e})");
    stationary
}

#[test]
fn charged_particle_unreduced_run_is_stationary() {
    let system = ChargedParticle::default();
    let method = Method { rule: Rule::Left, ..Method::default() };
    let solution = run(&system, &ChargedParticle::paper_problem(100), &method);
    let ld = ddirac::DiscreteLagrangian::new(&system, Rule::Left, 0.2);
    let g = check_plus_action(&ld, &solution);
    eprintln!("charged particle, unreduced (+): |∇S⁺|/scale = {g:.2e}");
}

#[test]
fn charged_particle_reduced_run_is_stationary_for_s_plus_and_the_reduced_action() {
    let system = ChargedParticle::default();
    let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
    let solution = run(&system, &ChargedParticle::paper_problem(100), &method);
    let reduction = ReducedLagrangian::new(&system, Rule::Left, 0.2, Connection::zero(3, 1)).unwrap();
    let g = check_plus_action(&reduction.ld, &solution);
    let e = check_reduced_plus(&reduction, &solution);
    eprintln!("charged particle, reduced (+): |∇S⁺|/scale = {g:.2e}, |∇Σe_d+|/scale = {e:.2e}");
}

#[test]
fn double_spherical_pendulum_midpoint_run_is_stationary() {
    let system = DoubleSphericalPendulum::default();
    let paper = DoubleSphericalPendulum::paper_problem(10_000);
    let problem = Problem::new(0.01, 1000, paper.q0.clone(), paper.initial.clone());
    for reduced in [false, true] {
        // The paper's chart: the printed action is in its coordinates.
        let method = Method { rule: Rule::Midpoint, reduced, atlas: false, ..Method::default() };
        let solution = run(&system, &problem, &method);
        let reduction = ReducedLagrangian::new(&system, Rule::Midpoint, 0.01, Connection::zero(3, 1)).unwrap();
        let g = check_plus_action(&reduction.ld, &solution);
        let e = check_reduced_plus(&reduction, &solution);
        eprintln!("double spherical pendulum, reduced = {reduced}: |∇S⁺|/scale = {g:.2e}, |∇Σe_d+|/scale = {e:.2e}");
    }
}

fn two_body() -> (TwoBody, Problem) {
    let problem =
        Problem::new(0.01, 500, vec![0.0, 0.0, 1.0, 0.0], InitialMomentum::Velocity(vec![0.0, 0.0, 0.0, 1.1]));
    (TwoBody::default(), problem)
}

#[test]
fn two_body_reduced_plus_run_with_centre_of_mass_connection_is_stationary() {
    let (system, problem) = two_body();
    let k = system.centre_of_mass_connection().unwrap();
    let method = Method { rule: Rule::Midpoint, reduced: true, connection: Some(k.clone()), ..Method::default() };
    let solution = run(&system, &problem, &method);
    let reduction = ReducedLagrangian::new(&system, Rule::Midpoint, 0.01, k.clone()).unwrap();
    let g = check_plus_action(&reduction.ld, &solution);
    let e = check_reduced_plus(&reduction, &solution);
    eprintln!("two bodies, reduced (+), K ≠ 0: |∇S⁺|/scale = {g:.2e}, |∇Σe_d+|/scale = {e:.2e}");
}

/// The (−) run is stationary for S⁻ and Σ e_{d−} with the corrected pairing sign; as printed, the
/// gradient is of the size of the momenta. Σ e_{d−} = S⁻ for either sign.
#[test]
fn two_body_reduced_minus_run_is_stationary_for_the_corrected_s_minus_only() {
    let (system, problem) = two_body();
    let k = system.centre_of_mass_connection().unwrap();
    let method = Method {
        rule: Rule::Midpoint,
        variant: Variant::Minus,
        reduced: true,
        connection: Some(k.clone()),
        ..Method::default()
    };
    let solution = run(&system, &problem, &method);
    let reduction = ReducedLagrangian::new(&system, Rule::Midpoint, 0.01, k.clone()).unwrap();
    let curve = MinusCurve::<4>::from_trajectory(&solution.q, &solution.p).unwrap();
    let reduced = curve.trivialize(&reduction.connection, &Split::new(&system.coordinates())).unwrap();

    let corrected = relative(&action_minus_gradient(&reduction.ld, &curve, Signs::Corrected).unwrap());
    let printed = relative(&action_minus_gradient(&reduction.ld, &curve, Signs::AsPrinted).unwrap());
    let reduced_corrected = relative(&reduced_action_minus_gradient(&reduction, &reduced, Signs::Corrected).unwrap());
    let reduced_printed = relative(&reduced_action_minus_gradient(&reduction, &reduced, Signs::AsPrinted).unwrap());
    eprintln!(
        "two bodies, reduced (−): |∇S⁻|/scale corrected {corrected:.2e}, printed {printed:.2e}; \
         |∇Σe_d−|/scale corrected {reduced_corrected:.2e}, printed {reduced_printed:.2e}"
    );
    assert!(corrected < STATIONARY && reduced_corrected < STATIONARY);
    assert!(printed > 0.1 && reduced_printed > 0.1, "the printed S⁻ must not be stationary");

    for signs in [Signs::Corrected, Signs::AsPrinted] {
        let s = action_minus(&reduction.ld, &curve, signs).unwrap();
        let e = reduced_action_minus(&reduction, &reduced, signs).unwrap();
        assert!((s - e).abs() <= 1e-12 * s.abs().max(1.0), "{signs:?}: S⁻ = {s}, Σ e_d− = {e}");
    }
    let direct: f64 = curve.q.windows(2).map(|w| reduction.ld.value(&w[0], &w[1])).sum();
    let s = action_minus(&reduction.ld, &curve, Signs::Corrected).unwrap();
    assert!((s - direct).abs() <= 1e-12 * direct.abs().max(1.0));

    let mut perturbed = curve.clone();
    perturbed.q[250][2] += 1e-4;
    let moved = relative(&action_minus_gradient(&reduction.ld, &perturbed, Signs::Corrected).unwrap());
    assert!(moved > 1e3 * STATIONARY, "a perturbed curve must not be stationary ({moved:.2e})");
}

/// E_{d+} and e_{d+} agree pointwise through Λ_{d+} for arbitrary (not only stationary) arguments,
/// with a non-diagonal connection: e_{d+}([Λ_{d+}(q0, q0^+, q1, p1)]) = E_{d+}(q0, q0^+, q1, p1).
#[test]
fn reduced_energies_are_the_energies_in_trivialized_coordinates() {
    let system = TwoBody::default();
    let k = Connection::new(&[vec![-0.4, 0.3], vec![0.2, -0.7]]).unwrap();
    let reduction = ReducedLagrangian::new(&system, Rule::Midpoint, 0.1, k.clone()).unwrap();
    let ld = &reduction.ld;
    let (q0, q1) = ([0.3, -0.2, 1.0, 0.1], [0.5, 0.1, 0.8, 0.4]);
    let aux = [0.6, -0.1, 0.9, 0.3];
    let p = [0.7, -1.1, 0.4, 2.0];
    let curve = PlusCurve::<4> { q: vec![q0, q1], q_plus: vec![aux], p_next: vec![p] };
    let trivial = curve.trivialize(&reduction.connection, &reduction.split).unwrap();
    let e = energy_plus(ld, &curve.q[0], &aux, &curve.q[1], &p);
    let (t_plus, t_p) = (&trivial.q_plus[0], &trivial.p_next[0]);
    let reduced = reduced_energy_plus(
        &reduction,
        &q0[2..],
        (&t_plus[2..], &t_plus[..2]),
        (&q1[2..], &[q1[0] - q0[0], q1[1] - q0[1]]),
        &t_p[2..],
        &t_p[..2],
    )
    .unwrap();
    assert!((e - reduced).abs() < 1e-13 * e.abs().max(1.0), "E_d+ = {e}, e_d+ = {reduced}");

    let minus = MinusCurve::<4> { q: curve.q.clone(), q_minus: vec![aux], p: vec![p] };
    let trivial = minus.trivialize(&reduction.connection, &reduction.split).unwrap();
    let (t_minus, t_p) = (&trivial.q_minus[0], &trivial.p[0]);
    for signs in [Signs::Corrected, Signs::AsPrinted] {
        let e = energy_minus(ld, &aux, &q1, &p, &q0, signs);
        let reduced = reduced_energy_minus(
            &reduction,
            (&t_minus[2..], &t_minus[..2]),
            &q1[2..],
            &t_p[2..],
            &t_p[..2],
            (&q0[2..], &[q0[0] - q1[0], q0[1] - q1[1]]),
            signs,
        )
        .unwrap();
        assert!((e - reduced).abs() < 1e-13 * e.abs().max(1.0), "{signs:?}: E_d− = {e}, e_d− = {reduced}");
    }
}

/// Central differences of `action` with respect to every entry of `variables[family][index]`.
fn check_against_differences<C: Clone>(
    curve: &C,
    gradient: &[Vec<[f64; 4]>; 3],
    entry: fn(&mut C, usize, usize, usize) -> &mut f64,
    first_q: usize,
    action: impl Fn(&C) -> f64,
) {
    let h = 1e-6;
    for (family, blocks) in gradient.iter().enumerate() {
        for (index, block) in blocks.iter().enumerate() {
            let index = if family == 0 { index + first_q } else { index };
            for (i, &g) in block.iter().enumerate() {
                let (mut up, mut down) = (curve.clone(), curve.clone());
                *entry(&mut up, family, index, i) += h;
                *entry(&mut down, family, index, i) -= h;
                let fd = (action(&up) - action(&down)) / (2.0 * h);
                assert!(
                    (fd - g).abs() < 1e-6 * (1.0 + g.abs()),
                    "family {family}, block {index}, entry {i}: AD {g}, FD {fd}"
                );
            }
        }
    }
}

/// The assembled AD gradients equal central differences of the action values, on a random curve that
/// is not a trajectory, for S⁺, S⁻ (both signs), Σ e_{d+} and Σ e_{d−} with a non-diagonal K.
#[test]
fn assembled_gradients_match_finite_differences() {
    let system = TwoBody::default();
    let k = Connection::new(&[vec![-0.4, 0.3], vec![0.2, -0.7]]).unwrap();
    let reduction = ReducedLagrangian::new(&system, Rule::Midpoint, 0.1, k.clone()).unwrap();
    let mut u = sampler(5);
    let mut point = || -> [f64; 4] { [u(), u(), 1.0 + 0.2 * u(), 0.5 + 0.2 * u()] };
    let q: Vec<[f64; 4]> = (0..4).map(|_| point()).collect();
    let aux: Vec<[f64; 4]> = (0..3).map(|_| point()).collect();
    let momenta: Vec<[f64; 4]> = (0..3).map(|_| point()).collect();

    let plus = PlusCurve { q: q.clone(), q_plus: aux.clone(), p_next: momenta.clone() };
    let minus = MinusCurve { q, q_minus: aux, p: momenta };
    let blocks = |g: ActionGradient<4>| [g.q, g.aux, g.momenta];
    let (plus_ref, minus_ref) = (plus_entry, minus_entry);

    let g = blocks(action_plus_gradient(&reduction.ld, &plus).unwrap());
    check_against_differences(&plus, &g, plus_ref, 1, |c| action_plus(&reduction.ld, c).unwrap());
    let g = blocks(reduced_action_plus_gradient(&reduction, &plus).unwrap());
    check_against_differences(&plus, &g, plus_ref, 1, |c| reduced_action_plus(&reduction, c).unwrap());
    for signs in [Signs::Corrected, Signs::AsPrinted] {
        let g = blocks(action_minus_gradient(&reduction.ld, &minus, signs).unwrap());
        check_against_differences(&minus, &g, minus_ref, 1, |c| action_minus(&reduction.ld, c, signs).unwrap());
        let g = blocks(reduced_action_minus_gradient(&reduction, &minus, signs).unwrap());
        check_against_differences(&minus, &g, minus_ref, 1, |c| reduced_action_minus(&reduction, c, signs).unwrap());
    }
}

fn plus_entry(c: &mut PlusCurve<4>, family: usize, k: usize, i: usize) -> &mut f64 {
    match family {
        0 => &mut c.q[k][i],
        1 => &mut c.q_plus[k][i],
        _ => &mut c.p_next[k][i],
    }
}

fn minus_entry(c: &mut MinusCurve<4>, family: usize, k: usize, i: usize) -> &mut f64 {
    match family {
        0 => &mut c.q[k][i],
        1 => &mut c.q_minus[k][i],
        _ => &mut c.p[k][i],
    }
}
