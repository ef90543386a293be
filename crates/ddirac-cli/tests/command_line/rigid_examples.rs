//! The shipped rigid-body examples against independent numbers: Euler's (and the gyrostat's)
//! equations integrated here by RK4, reduced runs against unreduced ones, and the conserved
//! quantities each example states.

use crate::common;

use common::{example, gyrostat_rk4, succeed, Finished, TempDir, M3};

fn final_state(run: &Finished) -> (M3, [f64; 3]) {
    let last = |name: &str| *run.column(name).last().unwrap();
    let r = [0, 1, 2].map(|i| [0, 1, 2].map(|j| last(&format!("R{}{}", i + 1, j + 1))));
    (r, [0, 1, 2].map(|i| last(&format!("Pi{}", i + 1))))
}

fn distance(a: &(M3, [f64; 3]), b: &(M3, [f64; 3])) -> f64 {
    let r = (0..9).map(|k| (a.0[k / 3][k % 3] - b.0[k / 3][k % 3]).abs()).fold(0.0, f64::max);
    (0..3).map(|i| (a.1[i] - b.1[i]).abs()).fold(r, f64::max)
}

/// The times at which Π2 changes sign.
fn flips(run: &Finished) -> Vec<f64> {
    let (t, pi2) = (run.column("t"), run.column("Pi2"));
    (1..t.len()).filter(|&k| (pi2[k] > 0.0) != (pi2[k - 1] > 0.0)).map(|k| t[k]).collect()
}

#[test]
fn dzhanibekov_flips_when_eulers_equations_say() {
    let dir = TempDir::new("dzhanibekov");
    let run = succeed(&example("dzhanibekov.toml"), &[], &dir);
    let flips = flips(&run);
    assert_eq!(flips.len(), 4, "{flips:?}");
    // The flips of the reference: Π2 of RK4 sampled every 0.1.
    let mut state = ([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], [0.01, 4.0, 0.03]);
    let mut reference = vec![];
    for k in 1..=400 {
        let next = gyrostat_rk4([1.0, 2.0, 3.0], [0.0; 3], [0.0; 3], state.0, state.1, 0.1, 100);
        if (next.1[1] > 0.0) != (state.1[1] > 0.0) {
            reference.push(k as f64 * 0.1);
        }
        state = next;
    }
    assert_eq!(reference.len(), 4, "{reference:?}");
    for (a, b) in flips.iter().zip(&reference) {
        assert!((a - b).abs() <= 0.15, "flips at {flips:?}, reference {reference:?}");
    }
    let s = &run.summary;
    assert!(s["casimir"]["max_relative_drift"].as_f64().unwrap() < 1e-13);
    assert!(s["momentum_map"]["max_relative_drift"].as_f64().unwrap() < 1e-13);
    // Reduced (the example) and unreduced agree to round-off.
    let unreduced_dir = TempDir::new("dzhanibekov-unreduced");
    let unreduced = succeed(&example("dzhanibekov.toml"), &["method.reduced=false"], &unreduced_dir);
    assert!(distance(&final_state(&run), &final_state(&unreduced)) < 1e-11);
}

#[test]
fn heavy_top_upright_follows_eulers_equations_and_keeps_its_vertical_momentum() {
    let dir = TempDir::new("heavy-top-upright");
    let run = succeed(&example("heavy_top_upright.toml"), &["time.duration=3.0"], &dir);
    let (c, s) = (0.9999500004166653, 0.009999833334166664);
    let r0 = [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]];
    let reference = gyrostat_rk4([1.0, 1.3, 0.4], [0.0; 3], [0.0, 0.0, 4.9], r0, [0.0, 0.0, 0.8], 3.0, 60_000);
    let state = final_state(&run);
    assert!(distance(&state, &reference) < 1e-7, "off by {:e}", distance(&state, &reference));
    // It has fallen: the body's third axis is far from the vertical.
    assert!(state.0[2][2] < 0.5, "R33 = {}", state.0[2][2]);
    let z = run.column("momentum_z");
    assert!(z.iter().all(|v| (v - z[0]).abs() < 1e-13));
    assert!(run.summary["orthogonality"].as_f64().unwrap() < 1e-14);
}

#[test]
fn satellite_rotors_follows_the_gyrostat_and_its_rotor_holds_the_intermediate_axis() {
    let dir = TempDir::new("satellite");
    let spec = example("satellite_rotors.toml");
    let run = succeed(&spec, &["method.order=4", "time.step=0.005", "time.duration=10.0"], &dir);
    // Rotor momenta p = K (Ω + ȧ): (0.1·0.01, 0.1·32, 0.1·0.01), constant; Π = J Ω + p.
    let rotors = [0.001, 3.2, 0.001];
    let pi0 = [0.01 + 0.001, 4.0 + 3.2, 0.03 + 0.001];
    let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let reference = gyrostat_rk4([1.0, 2.0, 3.0], rotors, [0.0; 3], identity, pi0, 10.0, 100_000);
    let state = final_state(&run);
    // Order 4 at h = 0.005: an error of about 1e-8.
    assert!(distance(&state, &reference) < 3e-8, "off by {:e}", distance(&state, &reference));
    for (name, p) in ["p_a1", "p_a2", "p_a3"].iter().zip(rotors) {
        assert!(run.column(name).iter().all(|v| (v - p).abs() < 1e-10), "{name} moved");
    }
    assert_eq!(run.summary["system"], "satellite with three rotors");
    assert_eq!(run.summary["shape"], serde_json::json!(["a1", "a2", "a3"]));
    // Reduced (the example) and unreduced agree.
    let unreduced_dir = TempDir::new("satellite-unreduced");
    let unreduced = succeed(
        &spec,
        &["method.order=4", "time.step=0.005", "time.duration=10.0", "method.reduced=false"],
        &unreduced_dir,
    );
    assert!(distance(&state, &final_state(&unreduced)) < 1e-11);
    // The whole example: the spin about the intermediate axis holds with rotor 2 spinning, and turns
    // over without it.
    let whole = TempDir::new("satellite-whole");
    let held = succeed(&spec, &[], &whole);
    assert!(held.column("Pi2").iter().all(|&v| (v - 7.2).abs() < 1e-4));
    let still = TempDir::new("satellite-still");
    let flipped = succeed(&spec, &["initial.v.a2=0.0"], &still);
    assert!(flipped.column("Pi2").iter().any(|&v| v < -2.0));
}
