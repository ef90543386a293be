//! The example specs with a `[system]` table, each checked against numbers that do not come from the
//! code: the paper's Table 1, the built-in systems, Kepler's laws, conservation laws computed from the
//! initial data, and the exact motion of two point vortices.

use crate::common;

use std::f64::consts::PI;

use common::{assert_fails, example, numbers, run, succeed, Finished, TempDir};

/// max |a − b| / max(1, |b|) over the entries.
fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).map(|(x, y)| (x - y).abs() / y.abs().max(1.0)).fold(0.0, f64::max)
}

/// (max − min) / |first| of a column.
fn relative_spread(values: &[f64]) -> f64 {
    let (min, max) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    (max - min) / values[0].abs()
}

/// Largest deviation of a column from its first value.
fn drift(values: &[f64]) -> f64 {
    values.iter().map(|v| (v - values[0]).abs()).fold(0.0, f64::max)
}

/// The interior local minima of `values` sampled at `t`, refined by a parabola through the three
/// samples around each: (time, value).
fn minima(t: &[f64], values: &[f64]) -> Vec<(f64, f64)> {
    (1..values.len() - 1)
        .filter(|&i| values[i] < values[i - 1] && values[i] <= values[i + 1])
        .map(|i| {
            let (a, b, c) = (values[i - 1], values[i], values[i + 1]);
            let h = t[i + 1] - t[i];
            let curvature = a - 2.0 * b + c;
            let shift = 0.5 * (a - c) / curvature;
            (t[i] + shift * h, b - 0.25 * (a - c) * shift)
        })
        .collect()
}

#[test]
fn charged_particle_expression_reproduces_the_built_in_and_table_1() {
    for (steps, table_1) in [(100, "0.06626"), (10, "1.6781")] {
        let (dir, built_in_dir) = (TempDir::new("cp-expr"), TempDir::new("cp-built-in"));
        let set = format!("time.steps={steps}");
        let expression = succeed(&example("charged_particle_expression.toml"), &[&set], &dir);
        let built_in = succeed(&example("charged_particle.toml"), &[&set], &built_in_dir);
        let (a, b) = (expression.final_q(), built_in.final_q());
        assert!(relative_difference(&a, &b) <= 1e-12, "{a:?} vs {b:?}");
        // Paper, Table 1: ‖q(T) − q_N‖ for N = 100 and N = 10.
        let error = expression.summary["reference_error"].as_f64().unwrap();
        let digits = table_1.len() - 2;
        assert_eq!(format!("{error:.digits$}"), table_1, "N = {steps}");
        assert_eq!(expression.summary["system"], "charged particle");
        assert_eq!(expression.summary["coordinates"], serde_json::json!(["x", "y", "z", "theta"]));
    }
}

#[test]
fn double_spherical_pendulum_expression_follows_the_built_in() {
    let (dir, built_in_dir) = (TempDir::new("dsp-expr"), TempDir::new("dsp-built-in"));
    let expression = succeed(&example("double_spherical_pendulum_expression.toml"), &[], &dir);
    // The text system declares no atlas: the built-in one in its main chart too.
    let built_in = succeed(&example("double_spherical_pendulum.toml"), &["method.atlas=false"], &built_in_dir);
    assert_eq!(expression.summary["steps"], 10000);
    let (a, b) = (expression.final_q(), built_in.final_q());
    let relative = a.iter().zip(&b).map(|(x, y)| ((x - y) / y).abs()).fold(0.0, f64::max);
    assert!(relative <= 1e-7, "{a:?} vs {b:?}: {relative:e}");
    assert_eq!(drift(expression.column("momentum_vartheta1")), 0.0);
}

#[test]
fn kepler_orbit_keeps_its_angular_momentum_and_obeys_the_third_law() {
    let dir = TempDir::new("kepler");
    let run = succeed(&example("kepler.toml"), &[], &dir);
    let (m, k, r0, p_phi) = (1.0f64, 1.0, 1.0, 0.8);
    // Energy from the initial data: E = p_φ²/(2 m r0²) − k/r0; a = −k/(2E); T = 2π sqrt(a³ m / k).
    let energy = p_phi * p_phi / (2.0 * m * r0 * r0) - k / r0;
    let a = -k / (2.0 * energy);
    let period = 2.0 * PI * (a * a * a * m / k).sqrt();
    assert!((run.summary["energy"]["initial"].as_f64().unwrap() - energy).abs() <= 1e-14);
    assert!(drift(run.column("momentum_phi")) <= 1e-15 * p_phi, "angular momentum drifts");
    assert!(drift(run.column("p_phi")) <= 1e-15 * p_phi);
    assert!(relative_spread(run.column("energy")) <= 1e-5, "{}", relative_spread(run.column("energy")));

    let (t, r, phi) = (run.column("t"), run.column("r"), run.column("phi"));
    let pericentres = minima(t, r);
    assert!(pericentres.len() >= 9, "{} pericentre passages", pericentres.len());
    let (first, last) = (pericentres[0], pericentres[pericentres.len() - 1]);
    let measured = (last.0 - first.0) / (pericentres.len() - 1) as f64;
    assert!(((measured - period) / period).abs() <= 1e-5, "period {measured} vs Kepler's {period}");
    // Starting at the apocentre r0 = a(1 + e), the pericentre is a(1 − e) = 2a − r0.
    for (_, r_min) in &pericentres {
        assert!((r_min - (2.0 * a - r0)).abs() <= 1e-5, "pericentre {r_min} vs {}", 2.0 * a - r0);
    }
    // The orbit closes: phi advances by 2π from one pericentre to the next.
    let phi_at = |time: f64| {
        let i = t.iter().position(|&s| s >= time).unwrap();
        phi[i - 1] + (phi[i] - phi[i - 1]) * (time - t[i - 1]) / (t[i] - t[i - 1])
    };
    let turns = (phi_at(last.0) - phi_at(first.0)) / (2.0 * PI * (pericentres.len() - 1) as f64);
    assert!((turns - 1.0).abs() <= 1e-4, "{turns} turns per radial period");

    // The same system written as a `[system]` table gives the same discrete motion; only the
    // built-in knows the exact orbit (Kepler's equation), within the scheme's O(h²) error of it.
    let expression_dir = TempDir::new("kepler-expression");
    let expression = succeed(&example("kepler_expression.toml"), &[], &expression_dir);
    assert!(relative_difference(&run.final_q(), &expression.final_q()) <= 1e-12);
    assert!(expression.summary["reference_error"].is_null());
    let error = run.summary["reference_error"].as_f64().unwrap();
    assert!(error <= 2e-4, "{error}");
}

#[test]
fn heavy_top_conserves_both_momenta_and_reduction_matches_the_unreduced_run() {
    let (dir, unreduced_dir) = (TempDir::new("top"), TempDir::new("top-unreduced"));
    let reduced = succeed(&example("heavy_top.toml"), &[], &dir);
    let unreduced = succeed(&example("heavy_top.toml"), &["method.reduced=false"], &unreduced_dir);
    // J = (p_φ, p_ψ) from v0 = (0, 0, 60) at θ0 = 0.6: p_ψ = I3 ω3 = 0.4 · 60, p_φ = p_ψ cos θ0.
    let (p_psi, theta0) = (0.4 * 60.0, 0.6f64);
    let j0 = numbers(&reduced.summary["momentum_map"]["initial"]);
    assert!((j0[0] - p_psi * theta0.cos()).abs() <= 1e-13 && (j0[1] - p_psi).abs() <= 1e-13, "{j0:?}");
    // The reduced scheme keeps μ = J exactly; the unreduced one to its Newton tolerance.
    for (run, tolerance) in [(&reduced, 1e-14), (&unreduced, 1e-10)] {
        let relative = run.summary["momentum_map"]["max_relative_drift"].as_f64().unwrap();
        assert!(relative <= tolerance, "{relative:e}");
        for column in ["momentum_phi", "momentum_psi"] {
            assert!(drift(run.column(column)) <= tolerance * p_psi, "{column}: {}", drift(run.column(column)));
        }
        assert!(relative_spread(run.column("energy")) <= 1e-9, "{}", relative_spread(run.column("energy")));
    }
    let (a, b) = (reduced.final_q(), unreduced.final_q());
    assert!(a[2] > 300.0, "psi reaches only {}", a[2]);
    assert!(relative_difference(&a, &b) <= 1e-10, "{a:?} vs {b:?}");
    // The built-in `heavy_top`, with M g l = 1 · 9.8 · 0.5, gives the same motion.
    let built_in_dir = TempDir::new("top-built-in");
    let spec = built_in_dir.file(
        "heavy_top_built_in.toml",
        "system = \"heavy_top\"\n[parameters]\nI1 = 1.0\nI3 = 0.4\nMgl = 4.9\n[method]\nrule = \"midpoint\"\n\
         reduced = true\n[time]\nstep = 0.002\nduration = 10.0\n[initial]\nq = [0.0, 0.6, 0.0]\nv = [0.0, 0.0, 60.0]\n",
    );
    let built_in = succeed(&spec, &[], &built_in_dir);
    assert!(relative_difference(&a, &built_in.final_q()) <= 1e-10, "{a:?} vs {:?}", built_in.final_q());
    // The axis nods: theta leaves θ0 and comes back.
    let theta = reduced.column("theta");
    assert!(theta.iter().fold(0.0f64, |m, v| m.max(v - theta0)) > 1e-3);
}

#[test]
fn two_bodies_reduced_with_the_centre_of_mass_connection_match_the_built_in() {
    let dirs = [TempDir::new("two-body"), TempDir::new("two-body-unreduced"), TempDir::new("two-body-built-in")];
    let spec = example("two_body.toml");
    let reduced = succeed(&spec, &[], &dirs[0]);
    let unreduced = succeed(&spec, &["method.reduced=false"], &dirs[1]);
    let built_in_spec = dirs[2].file(
        "two_body_built_in.toml",
        "system = \"two_body\"\n[parameters]\nm1 = 1.0\nm2 = 0.5\nk = 1.0\n[method]\nrule = \"midpoint\"\n\
         [time]\nstep = 0.005\nduration = 20.0\n[initial]\nq = [0.0, 0.0, 1.0, 0.0]\nv = [0.1, -0.2, 0.0, 1.1]\n",
    );
    let built_in = succeed(&built_in_spec, &[], &dirs[2]);
    let (m1, m2) = (1.0, 0.5);
    assert_eq!(
        reduced.summary["method"]["connection"],
        serde_json::json!([[-m2 / (m1 + m2), 0.0], [0.0, -m2 / (m1 + m2)]])
    );
    for other in [&unreduced, &built_in] {
        let d = relative_difference(&reduced.final_q(), &other.final_q());
        assert!(d <= 1e-9, "{:?} vs {:?}", reduced.final_q(), other.final_q());
    }
    // Total momentum P = m1 ṙ1 + m2 (ṙ1 + ṙ) from v0; the centre of mass moves by P T / M.
    let p = [m1 * 0.1 + m2 * (0.1 + 0.0), m1 * -0.2 + m2 * (-0.2 + 1.1)];
    for (axis, (g, x)) in [("r1x", "rx"), ("r1y", "ry")].into_iter().enumerate() {
        let momentum = reduced.column(&format!("momentum_{g}"));
        assert!((momentum[0] - p[axis]).abs() <= 1e-15 && drift(momentum) <= 1e-14, "{g}");
        let centre = |i: usize| reduced.column(g)[i] + m2 / (m1 + m2) * reduced.column(x)[i];
        let last = reduced.column("t").len() - 1;
        let moved = centre(last) - centre(0);
        assert!((moved - p[axis] * 20.0 / (m1 + m2)).abs() <= 1e-11, "{g}: {moved}");
    }
}

/// The turning angle of a spherical pendulum (m = l = 1) other than θ0: where
/// E = p_φ²/(2 sin²θ) − g cos θ with θ̇ = 0, by bisection on (0, θ0).
fn turning_angle(energy: f64, p_phi: f64, g: f64, theta0: f64) -> f64 {
    let f = |theta: f64| p_phi * p_phi / (2.0 * theta.sin().powi(2)) - g * theta.cos() - energy;
    let (mut lo, mut hi) = (1e-6, theta0 - 1e-6);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn spherical_pendulum_keeps_p_phi_and_turns_where_the_effective_potential_says() {
    let (dir, unreduced_dir) = (TempDir::new("sp"), TempDir::new("sp-unreduced"));
    let reduced = succeed(&example("spherical_pendulum.toml"), &[], &dir);
    let unreduced = succeed(&example("spherical_pendulum.toml"), &["method.reduced=false"], &unreduced_dir);
    let (g, theta0, phi_dot0) = (9.8, 1.0f64, 2.0);
    let p_phi = theta0.sin().powi(2) * phi_dot0;
    let energy = p_phi * phi_dot0 / 2.0 - g * theta0.cos();
    for run in [&reduced, &unreduced] {
        assert!((run.column("p_phi")[0] - p_phi).abs() <= 1e-15);
        // The example swings through the overlap of the main chart and the lower cap, where the run
        // takes glued unreduced steps (`ddirac::blend`): p_phi is kept as far as their L_d is invariant
        // in floating point (measured 1.6e-12 of it over the run).
        assert!(drift(run.column("momentum_phi")) <= 1e-11 * p_phi, "{}", drift(run.column("momentum_phi")));
        assert!((run.column("energy")[0] - energy).abs() <= 1e-14);
        assert!(relative_spread(run.column("energy")) <= 1e-4, "{}", relative_spread(run.column("energy")));
    }
    assert!(relative_difference(&reduced.final_q(), &unreduced.final_q()) <= 1e-10);
    let lowest = turning_angle(energy, p_phi, g, theta0);
    let turns = minima(reduced.column("t"), reduced.column("theta"));
    assert!(turns.len() >= 5, "{} turning points", turns.len());
    for (_, theta) in turns {
        assert!((theta - lowest).abs() <= 1e-4, "turns at {theta}, the effective potential says {lowest}");
    }
}

/// The vortex Hamiltonian and the direction of r2 − r1 at every row.
fn vortex_pair(run: &Finished, g1: f64, g2: f64) -> (Vec<f64>, Vec<f64>) {
    let (dx, y1, y2) = (run.column("dx"), run.column("y1"), run.column("y2"));
    let hamiltonian = (0..dx.len()).map(|i| -g1 * g2 / (2.0 * PI) * dx[i].hypot(y2[i] - y1[i]).ln()).collect();
    let angle = (0..dx.len()).map(|i| (y2[i] - y1[i]).atan2(dx[i])).collect();
    (hamiltonian, angle)
}

#[test]
fn point_vortices_conserve_h_and_turn_at_the_exact_rate() {
    let dir = TempDir::new("vortices");
    let run = succeed(&example("point_vortices.toml"), &[], &dir);
    let (g1, g2) = (3.0, 1.0);
    let (hamiltonian, angle) = vortex_pair(&run, g1, g2);
    let energy = run.column("energy");
    assert!((energy[0] - hamiltonian[0]).abs() <= 1e-15, "the energy column is H");
    assert!(relative_spread(energy) <= 1e-10, "{}", relative_spread(energy));
    assert!(relative_spread(&hamiltonian) <= 1e-10, "{}", relative_spread(&hamiltonian));

    // Ω = (G1 + G2)/(2π d²), d = 1.5, clockwise for this sign of the symplectic term; the midpoint
    // rule's phase error is O((Ω h)²).
    let omega = (g1 + g2) / (2.0 * PI * 1.5 * 1.5);
    let t = run.column("t");
    let mut turned = 0.0;
    for i in 1..angle.len() {
        turned += (angle[i] - angle[i - 1] + PI).rem_euclid(2.0 * PI) - PI;
    }
    let rate = turned / t[t.len() - 1];
    assert!(((rate + omega) / omega).abs() <= (omega * 0.01).powi(2), "rate {rate}, exact −{omega}");

    // The centre of vorticity stays at (G1 r1 + G2 r2)/(G1 + G2) = (1.225, 0.8).
    let (x1, y1, dx, y2) = (run.column("X"), run.column("y1"), run.column("dx"), run.column("y2"));
    for i in 0..t.len() {
        let centre = ((g1 * x1[i] + g2 * (x1[i] + dx[i])) / (g1 + g2), (g1 * y1[i] + g2 * y2[i]) / (g1 + g2));
        assert!((centre.0 - 1.225).abs() <= 1e-12 && (centre.1 - 0.8).abs() <= 1e-12, "{centre:?} at t = {}", t[i]);
    }
}

#[test]
fn reducing_point_vortices_is_refused_before_anything_is_written() {
    let dir = TempDir::new("vortices-reduced");
    let stderr = assert_fails(
        &run(&example("point_vortices.toml"), &["method.reduced=true"], &dir),
        &dir,
        &["not invariant under translation of the group coordinate `X`", "more than the tolerance 1e-9"],
    );
    assert_eq!(common::underlined(&stderr, "reduced = true"), ["true"]);
    assert_eq!(common::underlined(&stderr, "group = [\"X\"]"), ["\"X\""]);
    // Without the check, the reduced step's Jacobian is singular: the motion is undetermined, an error
    // that says so, no NaNs written.
    assert_fails(
        &run(&example("point_vortices.toml"), &["method.reduced=true", "method.check_invariance=false"], &dir),
        &dir,
        &["do not determine the motion", "rank 3 of 4"],
    );
}

#[test]
fn magnetic_mirror_keeps_p_phi_and_energy_and_reflects_a_trapped_particle_near_its_adiabatic_mirror_point() {
    let dir = TempDir::new("magnetic-mirror");
    let run = succeed(&example("magnetic_mirror.toml"), &[], &dir);
    // H = (p_r² + p_z²)/2m + (p_phi − r A_phi)²/(2 m r²) at z = 0, where r A_phi = B0 r²/2.
    let (r, p_r, p_z, p_phi) = (1.2f64, 0.3, 0.1, 1.0);
    let h0 = (p_r * p_r + p_z * p_z) / 2.0 + (p_phi - 0.5 * r * r).powi(2) / (2.0 * r * r);
    let energy = run.column("energy");
    assert!((energy[0] - h0).abs() < 1e-15, "{} against {h0}", energy[0]);
    // The magnetic field does no work: only the scheme's bounded oscillation remains.
    assert!(relative_spread(energy) < 1e-4, "{}", relative_spread(energy));
    assert_eq!(drift(run.column("p_phi")), 0.0);
    // Adiabatic invariant μ = E_⊥ / B: reflected where B(z)/B0 = 1 + 3 z²/(16 + z²) = H / E_⊥,0,
    // E_⊥,0 = H − p_z²/2 (z ≈ 0.62); the guiding centre's own excursion makes it approximate.
    let ratio = h0 / (h0 - p_z * p_z / 2.0);
    let mirror = (16.0 * (ratio - 1.0) / (3.0 - (ratio - 1.0))).sqrt();
    let reached = run.column("z").iter().fold(0.0f64, |m, z| m.max(z.abs()));
    assert!((reached - mirror).abs() < 0.25 * mirror, "reached |z| = {reached}, mirror point {mirror}");
}
