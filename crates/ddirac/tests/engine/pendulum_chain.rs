//! The planar chain of pendula (`systems::PendulumChain`) against numbers computed without the
//! engine:
//!
//! * one link: the period against 2π√(l/g) at small amplitude and against the exact period
//!   2π√(l/g)/AGM(1, cos(θ0/2)) at large amplitude; the energy against −m g l cos θ0;
//! * two and three links: the trajectory against a classical RK4 integration of the explicit
//!   equations of motion M(θ) θ̈ = f(θ, θ̇), with error O(h²) and observed order 2;
//! * four links over 10⁴ steps: the energy error stays bounded, with no drift;
//! * three links near the hanging rest: the normal-mode frequencies of K v = ω² M(0) v, the known
//!   roots of λ³ − 9λ² + 18λ − 6, and single-mode motions that stay in their mode at that frequency;
//! * fifty links, a few steps on a thread with a large stack, against RK4.
//!
//! The reference dynamics below is written from the bob positions for links of any masses and
//! lengths, independently of the library's Lagrangian.

use crate::common;

use std::f64::consts::PI;

use common::{log_log_slope, max_abs_diff, method, run};
use ddirac::systems::{find, Parameters, PendulumChain, CHAIN_LINKS};
use ddirac::{Error, InitialMomentum, OutputOptions, Problem, Rule, Solution, System, Variant};
use nalgebra::{DMatrix, DVector};

/// A chain with bob masses `m[i]` and link lengths `l[i]`, in absolute angles from the downward
/// vertical: M_ij = l_i l_j cos(θ_i − θ_j) μ_max(i,j), μ_i = Σ_{k≥i} m_k, and
/// f_i = −Σ_j l_i l_j μ_max(i,j) sin(θ_i − θ_j) θ̇_j² − g l_i μ_i sin θ_i.
struct Reference {
    m: Vec<f64>,
    l: Vec<f64>,
    g: f64,
}

impl Reference {
    fn uniform(links: usize, m: f64, l: f64, g: f64) -> Self {
        Self { m: vec![m; links], l: vec![l; links], g }
    }

    /// μ_i, the mass at and below link i.
    fn mu(&self) -> Vec<f64> {
        let mut mu = self.m.clone();
        for i in (1..mu.len()).rev() {
            mu[i - 1] += mu[i];
        }
        mu
    }

    fn mass_matrix(&self, theta: &[f64]) -> DMatrix<f64> {
        let mu = self.mu();
        DMatrix::from_fn(theta.len(), theta.len(), |i, j| {
            self.l[i] * self.l[j] * (theta[i] - theta[j]).cos() * mu[i.max(j)]
        })
    }

    fn accelerations(&self, theta: &[f64], omega: &[f64]) -> Vec<f64> {
        let (n, mu) = (theta.len(), self.mu());
        let f = DVector::from_fn(n, |i, _| {
            let centrifugal: f64 = (0..n)
                .map(|j| self.l[i] * self.l[j] * mu[i.max(j)] * (theta[i] - theta[j]).sin() * omega[j] * omega[j])
                .sum();
            -centrifugal - self.g * self.l[i] * mu[i] * theta[i].sin()
        });
        self.mass_matrix(theta).lu().solve(&f).expect("M(θ) is positive definite").as_slice().to_vec()
    }

    /// ½ θ̇ᵀ M θ̇ − g Σ l_i μ_i cos θ_i.
    fn energy(&self, theta: &[f64], omega: &[f64]) -> f64 {
        let w = DVector::from_column_slice(omega);
        let mu = self.mu();
        let potential: f64 = (0..theta.len()).map(|i| -self.g * self.l[i] * mu[i] * theta[i].cos()).sum();
        0.5 * w.dot(&(self.mass_matrix(theta) * &w)) + potential
    }

    /// θ̇ = M(θ)⁻¹ p.
    fn velocity(&self, theta: &[f64], p: &[f64]) -> Vec<f64> {
        let p = DVector::from_column_slice(p);
        self.mass_matrix(theta).lu().solve(&p).expect("M(θ) is positive definite").as_slice().to_vec()
    }

    /// (θ(T), θ̇(T)) by classical RK4 with `steps` steps.
    fn rk4(&self, theta: &[f64], omega: &[f64], duration: f64, steps: usize) -> (Vec<f64>, Vec<f64>) {
        let n = theta.len();
        let h = duration / steps as f64;
        let rhs = |y: &[f64]| -> Vec<f64> {
            let mut dy = y[n..].to_vec();
            dy.extend(self.accelerations(&y[..n], &y[n..]));
            dy
        };
        let axpy = |y: &[f64], a: f64, k: &[f64]| -> Vec<f64> { y.iter().zip(k).map(|(y, k)| y + a * k).collect() };
        let mut y: Vec<f64> = theta.iter().chain(omega).copied().collect();
        for _ in 0..steps {
            let k1 = rhs(&y);
            let k2 = rhs(&axpy(&y, 0.5 * h, &k1));
            let k3 = rhs(&axpy(&y, 0.5 * h, &k2));
            let k4 = rhs(&axpy(&y, h, &k3));
            for i in 0..2 * n {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        (y[..n].to_vec(), y[n..].to_vec())
    }
}

fn midpoint() -> ddirac::Method {
    method(Rule::Midpoint, Variant::Plus, false, None)
}

fn chain<const N: usize>(m: f64, l: f64, g: f64) -> PendulumChain<N> {
    PendulumChain { m, l, g }
}

/// Times at which `values` (sampled at `t`) crosses zero downwards, linearly interpolated.
fn downward_crossings(t: &[f64], values: &[f64]) -> Vec<f64> {
    (0..values.len() - 1)
        .filter(|&k| values[k] > 0.0 && values[k + 1] <= 0.0)
        .map(|k| t[k] + (t[k + 1] - t[k]) * values[k] / (values[k] - values[k + 1]))
        .collect()
}

/// Mean spacing of the downward zero crossings of `values`, with how many crossings it used.
fn period(t: &[f64], values: &[f64]) -> (f64, usize) {
    let crossings = downward_crossings(t, values);
    assert!(crossings.len() >= 3, "only {} downward crossings", crossings.len());
    ((crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64, crossings.len())
}

/// Arithmetic–geometric mean.
fn agm(mut a: f64, mut b: f64) -> f64 {
    while (a - b).abs() > 1e-16 * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    a
}

#[test]
fn one_link_swings_with_the_pendulum_period_and_keeps_its_energy() {
    let (m, l, g) = (2.0, 0.5, 9.8);
    let system = chain::<1>(m, l, g);
    let omega = (g / l).sqrt();
    let small = 2.0 * PI / omega;
    let h = 1e-3;
    for theta0 in [0.01f64, 2.5] {
        // About 20 small-amplitude periods.
        let problem = Problem::new(h, 20_000, vec![theta0], InitialMomentum::Momentum(vec![0.0]));
        let solution = run(&system, &problem, &midpoint());
        let theta: Vec<f64> = solution.q.iter().map(|q| q[0]).collect();
        let (measured, crossings) = period(&solution.t, &theta);
        // Exact period of the pendulum released from rest at θ0.
        let exact = small / agm(1.0, (theta0 / 2.0).cos());
        // The midpoint rule lengthens a period by about (ω h)²/12 (tan(Ω h/2) = ω h/2 for a harmonic
        // oscillator); at θ0 = 2.5 the effective frequency is lower, so the same bound holds.
        let relative = (measured - exact) / exact;
        eprintln!(
            "θ0 = {theta0}: period {measured:.9} over {crossings} crossings, exact {exact:.9}, small-amplitude \
             {small:.9}; relative error {relative:.2e}, (ωh)²/12 = {:.2e}",
            (omega * h).powi(2) / 12.0
        );
        assert!(relative.abs() <= 2.0 * (omega * h).powi(2) / 12.0, "θ0 = {theta0}: {relative:e}");
        if theta0 < 0.1 {
            // Small amplitude: T = 2π√(l/g) (1 + θ0²/16 + …).
            assert!(((measured - small) / small).abs() <= theta0 * theta0 / 16.0 + (omega * h).powi(2) / 6.0);
        }
        // E = −m g l cos θ0 at rest; the variational integrator keeps it within O(h²).
        let energy0 = -m * g * l * theta0.cos();
        assert!((solution.energy[0] - energy0).abs() <= 1e-14 * energy0.abs(), "{}", solution.energy[0]);
        let spread = solution.energy.iter().map(|e| (e - energy0).abs()).fold(0.0, f64::max) / (m * g * l);
        eprintln!("  max |E − E0| / (m g l) = {spread:.2e}");
        assert!(spread <= (omega * h).powi(2) * theta0 * theta0, "{spread:e}");
    }
}

/// (‖q_N − θ(T)‖∞, ‖p_N − p(T)‖∞) of the midpoint rule against RK4, for the chain from (q0, v0)
/// with 100, 200, 400 and 800 steps over `duration`.
fn errors_at_end<const N: usize>(
    system: &PendulumChain<N>,
    q0: &[f64],
    v0: &[f64],
    duration: f64,
) -> (Vec<f64>, Vec<f64>) {
    let reference = Reference::uniform(N, system.m, system.l, system.g);
    let (theta, omega) = reference.rk4(q0, v0, duration, 40_000);
    // RK4 with half the steps agrees to 16 × its own error: far below the midpoint errors measured.
    let (coarse, _) = reference.rk4(q0, v0, duration, 20_000);
    assert!(max_abs_diff(&theta, &coarse) <= 1e-11, "RK4 reference: {}", max_abs_diff(&theta, &coarse));
    let p_end: Vec<f64> = (reference.mass_matrix(&theta) * DVector::from_column_slice(&omega)).as_slice().to_vec();
    [100, 200, 400, 800]
        .iter()
        .map(|&steps| {
            let problem =
                Problem::new(duration / steps as f64, steps, q0.to_vec(), InitialMomentum::Velocity(v0.to_vec()));
            let solution = run(system, &problem, &midpoint());
            let (q, p) = (&solution.summary.final_q, &solution.summary.final_p);
            let errors = (max_abs_diff(q, &theta), max_abs_diff(p, &p_end));
            eprintln!("N = {N}, {steps} steps: |q_N − θ(T)| = {:.3e}, |p_N − p(T)| = {:.3e}", errors.0, errors.1);
            errors
        })
        .unzip()
}

#[test]
fn two_and_three_links_follow_rk4_of_the_equations_of_motion_at_second_order() {
    let duration = 2.0;
    let hs: Vec<f64> = [100, 200, 400, 800].iter().map(|&n| duration / n as f64).collect();
    let two = errors_at_end(&chain::<2>(1.3, 0.7, 9.8), &[0.8, -0.5], &[0.5, -1.0], duration);
    let three = errors_at_end(&chain::<3>(1.3, 0.7, 9.8), &[0.8, -0.5, 0.3], &[0.5, -1.0, 0.7], duration);
    // Bounds on the finest run (h = 0.0025), measured 9.3·10⁻⁷ and 7.9·10⁻⁴: the three-link motion
    // is much livelier (its coarsest run is 5 % off).
    for (links, (q_errors, p_errors), bound) in [(2, two, 2e-6), (3, three, 2e-3)] {
        for (what, errors) in [("q", &q_errors), ("p", &p_errors)] {
            let order = log_log_slope(&hs, errors);
            let ratios: Vec<f64> = errors.windows(2).map(|e| e[0] / e[1]).collect();
            eprintln!("N = {links}, {what}: observed order {order:.4}, ratios on halving h {ratios:.3?}");
            assert!((order - 2.0).abs() <= 0.05, "N = {links}, {what}: order {order}");
            assert!(ratios.iter().all(|r| (r - 4.0).abs() <= 0.3), "N = {links}, {what}: {ratios:?}");
        }
        assert!(q_errors[3] <= bound, "N = {links}: {:e} at h = {}", q_errors[3], hs[3]);
    }
}

#[test]
fn four_links_keep_their_energy_without_drift_over_ten_thousand_steps() {
    let system = PendulumChain::<4>::default();
    let problem = PendulumChain::<4>::problem(10_000, 0.01);
    let solution = run(&system, &problem, &midpoint());
    let reference = Reference::uniform(4, 1.0, 1.0, 9.8);
    // Released from rest: E0 = V(θ0), and every row's energy is E(q, M(q)⁻¹ p).
    let energy0 = reference.energy(&problem.q0, &[0.0; 4]);
    assert!((solution.energy[0] - energy0).abs() <= 1e-13 * energy0.abs(), "{} vs {energy0}", solution.energy[0]);
    for k in (0..solution.t.len()).step_by(997) {
        let (q, p) = (&solution.q[k], &solution.p[k]);
        let e = reference.energy(q, &reference.velocity(q, p));
        assert!((solution.energy[k] - e).abs() <= 1e-12 * energy0.abs(), "row {k}: {} vs {e}", solution.energy[k]);
    }
    // The chain does move: its first link swings through zero many times.
    let theta1: Vec<f64> = solution.q.iter().map(|q| q[0]).collect();
    assert!(downward_crossings(&solution.t, &theta1).len() >= 10);

    let third = solution.energy.len() / 3;
    let deviation = |rows: &[f64]| {
        let max = rows.iter().map(|e| (e - energy0).abs()).fold(0.0, f64::max);
        (max, rows.iter().map(|e| e - energy0).sum::<f64>() / rows.len() as f64)
    };
    let (first, last) = (deviation(&solution.energy[..third]), deviation(&solution.energy[2 * third..]));
    let scale = energy0.abs();
    eprintln!(
        "|E0| = {scale:.4}: first third max |E − E0| = {:.3e}, mean {:.3e}; last third max {:.3e}, mean {:.3e}",
        first.0, first.1, last.0, last.1
    );
    // Bounded (measured 10⁻⁶ relative at h = 0.01); no drift: the last third deviates no more than
    // the first, and its mean offset has not moved away.
    assert!(last.0 <= 1e-5 * scale && first.0 <= 1e-5 * scale, "{first:?} {last:?}");
    assert!(last.0 <= 2.0 * first.0, "the energy error grows: {first:?} → {last:?}");
    assert!((last.1 - first.1).abs() <= 0.5 * first.0, "the mean energy drifts: {first:?} → {last:?}");
}

/// ω² and M(0)-orthonormal modes (columns) of K v = ω² M(0) v for the chain, by Cholesky
/// M(0) = C Cᵀ and the symmetric eigenproblem of C⁻¹ K C⁻ᵀ; sorted by frequency.
fn normal_modes(reference: &Reference, links: usize) -> (Vec<f64>, DMatrix<f64>) {
    let mass = reference.mass_matrix(&vec![0.0; links]);
    let mu = reference.mu();
    let stiffness =
        DMatrix::from_fn(links, links, |i, j| if i == j { reference.g * reference.l[i] * mu[i] } else { 0.0 });
    let c = mass.cholesky().expect("M(0) is positive definite").l();
    let c_inv = c.clone().try_inverse().unwrap();
    let eigen = (&c_inv * stiffness * c_inv.transpose()).symmetric_eigen();
    let mut order: Vec<usize> = (0..links).collect();
    order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
    let modes = c_inv.transpose() * &eigen.eigenvectors;
    (order.iter().map(|&k| eigen.eigenvalues[k]).collect(), DMatrix::from_fn(links, links, |i, k| modes[(i, order[k])]))
}

#[test]
fn three_links_near_rest_oscillate_in_their_normal_modes() {
    let (m, l, g) = (2.0, 0.5, 9.8);
    let reference = Reference::uniform(3, m, l, g);
    let (omega2, modes) = normal_modes(&reference, 3);
    // ω² l/g are the roots of λ³ − 9λ² + 18λ − 6 (equal masses and lengths).
    for w2 in &omega2 {
        let lambda = w2 * l / g;
        let cubic = lambda.powi(3) - 9.0 * lambda * lambda + 18.0 * lambda - 6.0;
        assert!(cubic.abs() <= 1e-12, "λ = {lambda}: {cubic:e}");
    }
    let lambdas: Vec<f64> = omega2.iter().map(|w2| w2 * l / g).collect();
    assert!((lambdas[0] - 0.41577).abs() <= 1e-5 && (lambdas[2] - 6.28995).abs() <= 1e-5, "{lambdas:?}");
    // Two links: ω² = (2 ∓ √2) g/l, the same construction.
    let (two, _) = normal_modes(&Reference::uniform(2, m, l, g), 2);
    assert!(
        (two[0] * l / g - (2.0 - 2f64.sqrt())).abs() <= 1e-12 && (two[1] * l / g - (2.0 + 2f64.sqrt())).abs() <= 1e-12
    );

    let system = chain::<3>(m, l, g);
    let mass0 = reference.mass_matrix(&[0.0; 3]);
    let h = 2e-3;
    for k in 0..3 {
        let omega = omega2[k].sqrt();
        let expected = 2.0 * PI / omega;
        // Amplitude 10⁻³ rad on the largest link angle, released from rest; about 10 periods.
        let shape = modes.column(k).into_owned();
        let q0: Vec<f64> = (&shape * (1e-3 / shape.amax())).as_slice().to_vec();
        let steps = (10.0 * expected / h).ceil() as usize;
        let solution = run(&system, &Problem::new(h, steps, q0, InitialMomentum::Momentum(vec![0.0; 3])), &midpoint());
        // Modal amplitudes a = Vᵀ M(0) θ (V is M(0)-orthonormal).
        let amplitudes: Vec<DVector<f64>> =
            solution.q.iter().map(|q| modes.transpose() * &mass0 * DVector::from_column_slice(q)).collect();
        let own: Vec<f64> = amplitudes.iter().map(|a| a[k]).collect();
        let own_max = own.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        let others =
            amplitudes.iter().flat_map(|a| (0..3).filter(|&j| j != k).map(move |j| a[j].abs())).fold(0.0, f64::max);
        let (measured, crossings) = period(&solution.t, &own);
        let relative = (measured - expected) / expected;
        eprintln!(
            "mode {k}: ω = {omega:.6}, period {measured:.8} vs {expected:.8} ({relative:.2e}, {crossings} crossings), \
             other modes {:.2e} of its amplitude",
            others / own_max
        );
        // Period: the midpoint rule's (ω h)²/12, plus O(amplitude²) from the nonlinearity.
        assert!(relative.abs() <= (omega * h).powi(2) / 12.0 + 1e-5, "mode {k}: {relative:e}");
        // The nonlinear coupling to the other modes is O(amplitude²) relative.
        assert!(others <= 1e-5 * own_max, "mode {k} leaks: {:e}", others / own_max);
    }
}

#[test]
fn the_chain_has_no_symmetry_to_reduce() {
    let problem = PendulumChain::<3>::problem(10, 0.01);
    let reduced = method(Rule::Midpoint, Variant::Plus, true, None);
    let result = ddirac::solve(&PendulumChain::<3>::default(), &problem, &reduced, &OutputOptions::default());
    assert!(matches!(result, Err(Error::NoSymmetry)), "{result:?}");
    let coordinates = PendulumChain::<3>::default().coordinates();
    assert!(coordinates.iter().all(|c| c.role == ddirac::Role::Shape && c.kind == ddirac::CoordinateKind::Angle));
    assert_eq!(coordinates[2].name, "theta3");
}

#[test]
fn the_built_in_takes_the_number_of_links_as_a_parameter() {
    let built_in = find("pendulum_chain").expect("registered");
    let defaults = (built_in.defaults)();
    assert_eq!(defaults, [("links", 4.0), ("m", 1.0), ("l", 1.0), ("g", 9.8)]);
    assert_eq!((built_in.build)(&[]).unwrap().coordinates().len(), 4);
    let set =
        |pairs: &[(&str, f64)]| -> Vec<(String, f64)> { pairs.iter().map(|(n, v)| (n.to_string(), *v)).collect() };
    for links in 1..=16 {
        assert!(CHAIN_LINKS.contains(&links));
    }
    assert!(!CHAIN_LINKS.contains(&17) && !CHAIN_LINKS.contains(&50));
    // The counts of CHAIN_LINKS run with arrays on the stack, the others in a dynamic dimension.
    for links in CHAIN_LINKS.iter().copied().chain([17, 20, 33, 50, 120]) {
        let system = (built_in.build)(&set(&[("links", links as f64)])).unwrap();
        let names: Vec<String> = system.coordinates().into_iter().map(|c| c.name).collect();
        assert_eq!(names.len(), links);
        assert_eq!(names[links - 1], format!("theta{links}"));
    }
    for bad in [0.0, -4.0, 2.5, 17.5] {
        let error = (built_in.build)(&set(&[("links", bad)])).err().expect("rejected").to_string();
        assert!(error.contains("parameter `links`") && error.contains(&format!("{bad}")), "{error}");
        assert!(error.contains("a positive whole number"), "{error}");
    }
    for huge in [5000.0, 1e30] {
        let error = (built_in.build)(&set(&[("links", huge)])).err().expect("rejected").to_string();
        assert!(error.contains("more than 4096") && error.contains("dense"), "{error}");
    }
    let error = (built_in.build)(&set(&[("links", f64::NAN)])).err().unwrap().to_string();
    assert!(error.contains("not finite"), "{error}");
    for (name, value) in [("m", 0.0), ("l", -1.0), ("g", f64::INFINITY), ("k", 1.0)] {
        let error = (built_in.build)(&set(&[("links", 3.0), (name, value)])).err().unwrap().to_string();
        assert!(error.contains(&format!("parameter `{name}`")), "{error}");
    }
    // A fixed-size chain accepts only its own number of links.
    let mut five = PendulumChain::<5>::default();
    assert!(five.set_parameter("links", 5.0).is_ok() && five.set_parameter("links", 6.0).is_err());

    // The registry's chain runs the same motion as the typed one, with the overrides applied.
    let overrides = set(&[("links", 3.0), ("m", 2.0), ("l", 0.5), ("g", 3.0)]);
    let system = (built_in.build)(&overrides).unwrap();
    let problem = PendulumChain::<3>::problem(50, 0.01);
    let summary = system.integrate(&problem, &midpoint(), &OutputOptions::default(), &mut |_| Ok(())).unwrap();
    let typed = run(&chain::<3>(2.0, 0.5, 3.0), &problem, &midpoint());
    assert_eq!(summary.final_q, typed.summary.final_q);
    // E0 = −g m l Σ μ_i cos θ_i with μ = (3, 2, 1) m.
    let energy0: f64 =
        problem.q0.iter().zip([3.0, 2.0, 1.0]).map(|(theta, mu)| -3.0 * 2.0 * 0.5 * mu * theta.cos()).sum();
    assert!((summary.energy.initial - energy0).abs() <= 1e-14 * energy0.abs());
}

/// Runs `f` on a thread with a 256 MiB stack (large chains keep their derivatives on the stack).
fn with_large_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new().stack_size(256 << 20).spawn(f).unwrap().join().unwrap()
}

#[test]
fn fifty_links_take_a_few_steps_like_rk4() {
    let (q_end, registry_q_end, h, steps) = with_large_stack(|| {
        let (h, steps) = (1e-3, 5);
        let problem = PendulumChain::<50>::problem(steps, h);
        let solution: Solution = run(&PendulumChain::<50>::default(), &problem, &midpoint());
        let registry = (find("pendulum_chain").unwrap().build)(&[("links".to_string(), 50.0)]).unwrap();
        let mut last = vec![];
        registry
            .integrate(&problem, &midpoint(), &OutputOptions::default(), &mut |row| {
                last = row.q.to_vec();
                Ok(())
            })
            .unwrap();
        (solution.summary.final_q, last, h, steps)
    });
    assert_eq!(q_end, registry_q_end);
    let problem = PendulumChain::<50>::problem(steps, h);
    let reference = Reference::uniform(50, 1.0, 1.0, 9.8);
    let duration = h * steps as f64;
    let (theta, _) = reference.rk4(&problem.q0, &[0.0; 50], duration, 50);
    let moved = max_abs_diff(&theta, &problem.q0);
    let error = max_abs_diff(&q_end, &theta);
    eprintln!("N = 50, {steps} steps of h = {h}: the chain moved {moved:.3e}, |q_N − θ(T)| = {error:.3e}");
    assert!(moved >= 1e-5, "{moved:e}");
    assert!(error <= 1e-3 * moved, "{error:e} against a motion of {moved:e}");
}
