//! The atlas of charts (paper §6): a chart switch is symplectic and carries the momentum map over
//! exactly, switching back and forth costs no digits, and the double spherical pendulum of §7.2 runs
//! 10⁶ steps of h = 0.01 with its energy error bounded.

use std::f64::consts::PI;

use ddirac::systems::{DoubleSphericalPendulum, SphericalPendulum};
use ddirac::{atlas, InitialMomentum, Method, Problem, State, Stepper, System};

/// The one-step map (q, p) ↦ (q₁, p₁) in the main chart, from a cold state: the stepper chooses its
/// chart at (q, p), steps, and reports in the main chart.
fn one_step<S: System<N> + Clone, const N: usize>(stepper: &mut Stepper<S, N>, x: &[f64]) -> Vec<f64> {
    let (q, p) = (x[..N].try_into().unwrap(), x[N..].try_into().unwrap());
    stepper.restart(&State::new(0, q, p)).unwrap();
    stepper.step().unwrap();
    let row = stepper.row();
    row.q.iter().chain(&row.p).copied().collect()
}

/// max |MᵀJM − J| of the finite-difference Jacobian M of the one-step map at x (central
/// differences of relative size `eps`), and the chart the step was taken in.
fn symplecticity<S: System<N> + Clone, const N: usize>(
    system: S,
    x: [f64; 8],
    n: usize,
    method: &Method,
) -> (f64, usize) {
    let x = &x[..2 * n];
    let problem = Problem::new(0.01, 10, x[..n].to_vec(), InitialMomentum::Momentum(x[n..].to_vec()));
    let mut stepper = Stepper::new(system, &problem, method).unwrap();
    one_step(&mut stepper, x);
    let chart = stepper.current_chart();
    let columns: Vec<Vec<f64>> = (0..2 * n)
        .map(|j| {
            let eps = 1e-6 * x[j].abs().max(1.0);
            let (mut plus, mut minus) = (x.to_vec(), x.to_vec());
            plus[j] += eps;
            minus[j] -= eps;
            let (a, b) = (one_step(&mut stepper, &plus), one_step(&mut stepper, &minus));
            a.iter().zip(&b).map(|(a, b)| (a - b) / (2.0 * eps)).collect()
        })
        .collect();
    let m = |i: usize, j: usize| columns[j][i];
    let omega =
        |i: usize, j: usize| -> f64 { (0..n).map(|k| m(k, i) * m(n + k, j) - m(n + k, i) * m(k, j)).sum::<f64>() };
    let j_entry = |i: usize, j: usize| -> f64 {
        if i < n && j == i + n {
            1.0
        } else if i >= n && i == j + n {
            -1.0
        } else {
            0.0
        }
    };
    let worst = (0..2 * n)
        .flat_map(|i| (0..2 * n).map(move |j| (i, j)))
        .fold(0.0f64, |w, (i, j)| w.max((omega(i, j) - j_entry(i, j)).abs()));
    (worst, chart)
}

#[test]
fn a_step_in_another_chart_is_symplectic_in_the_main_chart() {
    for reduced in [false, true] {
        let method = Method { reduced, ..Method::default() };
        // 0.3 rad from the lower pole: the run takes its step in the lower cap.
        let (worst, chart) =
            symplecticity(SphericalPendulum::default(), [0.4, PI - 0.3, 0.0, 0.0, 0.05, 0.7, 0.0, 0.0], 2, &method);
        eprintln!("spherical pendulum, reduced {reduced}: max |MᵀJM − J| = {worst:.2e} (chart {chart})");
        assert_eq!(chart, 1);
        assert!(worst < 1e-8, "{worst:e}");
    }
}

#[test]
fn a_switch_carries_the_momentum_map_exactly_and_back_and_forth_costs_no_digits() {
    let system = DoubleSphericalPendulum::default();
    let (q, p) = ([0.3, PI - 0.2, 0.5, 2.0], [1234.5, -200.25, 3000.125, 150.0]);
    let (mut q1, mut p1) = (q, p);
    for _ in 0..50_000 {
        let (qa, pa) = atlas::transition(&system, 0, 1, &q1, &p1).unwrap();
        // The group coordinate of chart 1 is θ2; its momentum is the momentum map, exactly.
        assert_eq!(pa[0], p[0]);
        let (qb, pb) = atlas::transition(&system, 1, 0, &qa, &pa).unwrap();
        (q1, p1) = (system.nearest_in_main(qb, &q1, &[ddirac::CoordinateKind::Angle; 4]), pb);
        assert_eq!(p1[0], p[0]);
    }
    let dq = q.iter().zip(&q1).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let dp = p.iter().zip(&p1).fold(0.0f64, |m, (a, b)| m.max((a - b).abs() / 3000.0));
    eprintln!("after 10⁵ switches: |Δq| = {dq:.2e}, |Δp|/|p| = {dp:.2e}");
    // A switch costs a few units of round-off, as a step does: 10⁵ of them (measured 2.5e-11 in p)
    // stay far from a digit of the Newton tolerance.
    assert!(dq < 1e-12 && dp < 1e-10, "{dq:e} {dp:e}");
}

/// The first finding: at h = 0.01 every variant failed after 1.4·10⁵–8.4·10⁵ steps, its energy
/// jumping at close pole passages. With the atlas, 10⁶ steps keep |ΔH/H₀| below 10⁻⁴ at every step
/// (measured 3.1e-7), and the reduced run equals the unreduced one to what round-off allows in this
/// motion (the paper's run already amplifies round-off 10⁵×; measured 7.9e-9 rad over the run).
#[test]
fn the_double_spherical_pendulum_runs_a_million_steps_with_bounded_energy() {
    let system = DoubleSphericalPendulum::default();
    let problem = Problem { steps: 1_000_000, ..DoubleSphericalPendulum::paper_problem(10_000) };
    let mut rows = vec![];
    for reduced in [false, true] {
        let mut stepper = Stepper::new(&system, &problem, &Method { reduced, ..Method::default() }).unwrap();
        let h0 = stepper.row().energy;
        let (mut worst, mut sampled) = (0.0f64, vec![]);
        while !stepper.is_finished() {
            stepper.step().unwrap();
            let row = stepper.row();
            worst = worst.max(((row.energy - h0) / h0).abs());
            if row.k % 1000 == 0 {
                sampled.push(row.q);
            }
        }
        let summary = stepper.finish().unwrap();
        eprintln!(
            "reduced {reduced}: max |ΔH/H0| = {worst:.3e}, {} chart switches, {} subdivided steps",
            summary.chart_switches, summary.newton.subdivided_steps
        );
        assert!(worst <= 1e-4, "reduced {reduced}: {worst:e}");
        assert!(summary.chart_switches > 0);
        rows.push(sampled);
    }
    let apart = rows[0].iter().flatten().zip(rows[1].iter().flatten()).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    eprintln!("reduced against unreduced: {apart:.2e} rad");
    assert!(apart < 1e-6, "{apart:e}");
}

/// A run of 10⁵ switches: a spherical pendulum whose polar angle swings between 0.45 and 0.9 rad from
/// the bottom, through the overlap of the main chart and the lower cap, where the charts' discrete
/// Lagrangians are glued into one (`ddirac::blend`). The momentum map keeps its digits. The energy error
/// stays bounded: one discrete Lagrangian has one modified energy (measured 1.6e-4 after 10⁵ switches,
/// against the polar chart alone's 7.0e-3; when the charts were switched at a step, with two modified
/// energies, it grew by about 5e-8 per switch to 4.9e-3).
#[test]
fn a_run_of_a_hundred_thousand_switches_keeps_the_momentum_map_and_the_energy_bounded() {
    let system = SphericalPendulum { g: 98.0, ..SphericalPendulum::default() };
    let q0 = [0.0, PI - 0.9];
    let p0 = [(q0[1].sin()).powi(2) * 3.0, 0.0];
    let problem = Problem::new(0.01, 1_700_000, q0.to_vec(), InitialMomentum::Momentum(p0.to_vec()));
    let run = |atlas: bool| {
        let mut stepper =
            Stepper::new(&system, &problem, &Method { reduced: true, atlas, ..Method::default() }).unwrap();
        let h0 = stepper.row().energy;
        let (mut worst, mut momentum) = (0.0f64, 0.0f64);
        while !stepper.is_finished() {
            stepper.step().unwrap();
            let row = stepper.row();
            worst = worst.max(((row.energy - h0) / h0).abs());
            momentum = momentum.max((row.p[0] - p0[0]).abs() / p0[0]);
        }
        (worst, momentum, stepper.finish().unwrap().chart_switches)
    };
    let (energy, momentum, switches) = run(true);
    let (polar, _, _) = run(false);
    eprintln!("{switches} switches: |ΔH/H0| {energy:.2e} (polar chart alone {polar:.2e}); momentum map {momentum:.1e} (relative)");
    assert!(switches >= 100_000, "{switches}");
    assert!(energy < 0.1 * polar, "{energy:e} against {polar:e}");
    assert!(momentum < 1e-9, "{momentum:e}");
}

/// The composition L ∘ Tφ of chart `chart` at (q, v), computed as `InChart` computes it without a
/// written form: φ on dual numbers q + ε v.
fn composed<S: System<N>, D: ddirac::Scalar, const N: usize>(system: &S, chart: usize, q: &[D; N], v: &[D; N]) -> D {
    use ddirac::num_dual::Dual;
    let lifted: [Dual<D>; N] = std::array::from_fn(|i| Dual::new(q[i], v[i]));
    let image = system.chart_to_main(chart, &lifted);
    system.lagrangian(&image.map(|x| x.re), &image.map(|x| x.eps))
}

/// The double spherical pendulum writes the Lagrangian of its charts of both bobs near the vertical
/// out (unit vectors instead of the spherical angles, a fifth of the operations): it is the
/// composition L ∘ Tφ, in value and in every first derivative (so in every derivative the steps use),
/// at points all over each of the four charts.
#[test]
fn the_written_lagrangians_of_the_double_pendulum_s_caps_are_the_composition() {
    use ddirac::num_dual::Dual64;
    let system = DoubleSphericalPendulum::default();
    let mut worst = 0.0f64;
    for chart in 3..=6 {
        for k in 0..50 {
            let s = |i: usize| ((k * 8 + i) as f64 * 0.618_033_988_75).fract() * 2.0 - 1.0;
            // Points of the open discs (radius up to 0.95), velocities of either sign.
            let q = [0.67 * s(0), 0.67 * s(1), 0.67 * s(2), 0.67 * s(3)];
            let v = [s(4), s(5), s(6), s(7)];
            let written = system.chart_lagrangian(chart, &q, &v).expect("charts 3 to 6 are written out");
            let reference = composed(&system, chart, &q, &v);
            let scale = reference.abs().max(1.0);
            worst = worst.max((written - reference).abs() / scale);
            for direction in 0..8 {
                let lift = |x: &[f64; 4], offset: usize| -> [Dual64; 4] {
                    std::array::from_fn(|i| {
                        if i + offset == direction {
                            Dual64::new(x[i], 1.0)
                        } else {
                            Dual64::from(x[i])
                        }
                    })
                };
                let (qd, vd) = (lift(&q, 0), lift(&v, 4));
                let a = system.chart_lagrangian(chart, &qd, &vd).unwrap().eps;
                let b = composed(&system, chart, &qd, &vd).eps;
                worst = worst.max((a - b).abs() / scale);
            }
        }
    }
    eprintln!("written against composed: {worst:.1e} (relative)");
    assert!(worst < 1e-12, "{worst:e}");
    // The other charts keep the composition.
    assert!(system.chart_lagrangian(1, &[0.1; 4], &[0.1; 4]).is_none());
}
