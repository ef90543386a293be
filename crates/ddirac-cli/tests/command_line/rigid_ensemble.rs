//! `ddirac ensemble` of rigid bodies: every member is its single run (`ddirac run --set`) bit for
//! bit and follows Euler's equations (RK4 here); the state is written as R, Π (and the shape's q, p),
//! shards merge into the unsharded files, a failing member is recorded while the others finish, and
//! keys a rigid body cannot vary are refused with the reason.

use crate::common;

use std::collections::BTreeMap;
use std::path::Path;

use common::{assert_fails, ddirac, euler_rk4, gyrostat_rk4, stderr, succeed, TempDir, M3};
use ddirac_cli::npy;

/// A heavy asymmetric top tilted by 0.3 rad about the first axis (order 4, T = 2).
fn heavy() -> String {
    let (c, s) = (0.3f64.cos(), 0.3f64.sin());
    format!(
        "system = \"rigid_body\"\n[parameters]\nI1 = 1.0\nI2 = 1.3\nI3 = 0.4\nm = 1.0\ng = 9.8\nc1 = 0.05\nc3 = 0.5\n\
         [method]\norder = 4\n[time]\nstep = 0.005\nduration = 2.0\n[initial]\n\
         R = [[1, 0, 0], [0, {c:?}, {:?}], [0, {s:?}, {c:?}]]\nPi = [0.3, -0.2, 1.5]\n[output]\nevery = 40\n",
        -s
    )
}

/// `final.csv` as (status, values by column) per member.
fn final_rows(dir: &Path) -> Vec<(String, BTreeMap<String, f64>)> {
    let text = std::fs::read_to_string(dir.join("final.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines
        .map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            let values =
                header[2..].iter().zip(&fields[2..]).map(|(h, f)| (h.to_string(), f.parse().unwrap())).collect();
            (fields[1].to_owned(), values)
        })
        .collect()
}

fn floats(path: &Path) -> (Vec<u64>, Vec<f64>) {
    let array = npy::read(path).unwrap();
    assert_eq!(array.descr, "<f8", "{}", path.display());
    let values = array.data.chunks(8).map(|b| f64::from_le_bytes(b.try_into().unwrap())).collect();
    (array.shape, values)
}

fn state_of(row: &BTreeMap<String, f64>) -> (M3, [f64; 3]) {
    let r = [0, 1, 2].map(|i| [0, 1, 2].map(|j| row[&format!("R{}{}", i + 1, j + 1)]));
    (r, [0, 1, 2].map(|i| row[&format!("Pi{}", i + 1)]))
}

fn gap(a: &(M3, [f64; 3]), b: &(M3, [f64; 3])) -> f64 {
    let r = (0..9).map(|k| (a.0[k / 3][k % 3] - b.0[k / 3][k % 3]).abs()).fold(0.0, f64::max);
    (0..3).map(|i| (a.1[i] - b.1[i]).abs()).fold(r, f64::max)
}

#[test]
fn each_member_of_a_heavy_top_ensemble_is_its_single_run_and_follows_eulers_equations() {
    let dir = TempDir::new("rigid-ensemble-members");
    let spec = dir.file("top.toml", &heavy());
    let members = dir.file(
        "members.csv",
        "initial.Pi.3,parameters.c3,parameters.I2\n1.5,0.5,1.3\n1.2,0.4,1.25\n-0.8,0.6,1.4\n2.0,0.0,1.3\n",
    );
    let out = dir.0.join("ens");
    let output = ddirac(&["ensemble", &spec, "--members", &members, "--out", out.to_str().unwrap(), "--quiet"], &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    let rows = final_rows(&out);
    assert_eq!(rows.len(), 4);
    let (c, s) = (0.3f64.cos(), 0.3f64.sin());
    let r0 = [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]];
    for (k, (pi3, c3, i2)) in
        [(1.5, 0.5, 1.3), (1.2, 0.4, 1.25), (-0.8, 0.6, 1.4), (2.0, 0.0, 1.3)].into_iter().enumerate()
    {
        let (status, row) = &rows[k];
        assert_eq!(status, "ok");
        let state = state_of(row);
        // The single run with the member's values set, bit for bit.
        let single = TempDir::new(&format!("rigid-ensemble-single-{k}"));
        let sets = [format!("initial.Pi.3={pi3}"), format!("parameters.c3={c3}"), format!("parameters.I2={i2}")];
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        let finished = succeed(&spec, &sets, &single);
        let last = |column: &str| *finished.column(column).last().unwrap();
        for (i, j) in (0..3).flat_map(|i| (0..3).map(move |j| (i, j))) {
            assert_eq!(last(&format!("R{}{}", i + 1, j + 1)).to_bits(), state.0[i][j].to_bits(), "member {k}: R");
        }
        for i in 0..3 {
            assert_eq!(last(&format!("Pi{}", i + 1)).to_bits(), state.1[i].to_bits(), "member {k}: Π");
        }
        // Independent: Euler's equations by RK4 (order 4 at h = 0.005: within 1e-6 over T = 2, where
        // the midpoint rule alone is 1e-4 off).
        let reference = euler_rk4([1.0, i2, 0.4], [0.05 * 9.8, 0.0, c3 * 9.8], r0, [0.3, -0.2, pi3], 2.0, 40_000);
        assert!(gap(&state, &reference) < 1e-6, "member {k} off Euler's equations by {:e}", gap(&state, &reference));
    }
    let (shape, r) = floats(&out.join("npy/final_R.npy"));
    assert_eq!(shape, [4, 3, 3]);
    assert_eq!(r[9..18], (0..9).map(|j| rows[1].1[&format!("R{}{}", j / 3 + 1, j % 3 + 1)]).collect::<Vec<_>>());
    assert_eq!(floats(&out.join("npy/final_Pi.npy")).0, [4, 3]);
    assert!(!out.join("npy/final_q.npy").exists(), "a body without shape has no q");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["attitude"], "SO(3)");
    assert_eq!(summary["derivatives"]["closed form"], 4);
    // The heavy top conserves e3 · R Π: its drift is at round-off in every member.
    let (_, drift) = floats(&out.join("npy/momentum_map_drift.npy"));
    assert!(drift.iter().all(|d| *d < 1e-12), "{drift:?}");
}

/// The satellite with three rotors (text spec, SO(3)-reduced), shortened, with a grid of rotor rates.
fn satellite(dir: &TempDir) -> String {
    let text = std::fs::read_to_string(common::example("satellite_rotors.toml"))
        .unwrap()
        .replace("duration = 40.0", "duration = 2.0");
    dir.file(
        "satellite.toml",
        &format!(
            "{text}\n[ensemble]\ntrajectories = true\n\n[[ensemble.grid]]\nkey = \"initial.v.a2\"\nvalues = [0.0, \
             10.0, 30.0]\n\n[[ensemble.grid]]\nkey = \"initial.Omega.1\"\nvalues = [0.01, 0.2]\n"
        ),
    )
}

#[test]
fn a_satellite_with_rotors_writes_attitude_and_shape_and_its_shards_merge_into_the_whole() {
    let dir = TempDir::new("rigid-ensemble-satellite");
    let spec = satellite(&dir);
    let whole = dir.0.join("whole");
    let output = ddirac(&["ensemble", &spec, "--out", whole.to_str().unwrap(), "--quiet"], &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    let rows = final_rows(&whole);
    assert_eq!(rows.len(), 6);
    // Against a gyrostat integrated by RK4: J = (1, 2, 3), K = 0.1, rotor momenta K (Ω_i + ȧ_i).
    for (k, (_, row)) in rows.iter().enumerate() {
        let (a2, w1) = ([0.0, 10.0, 30.0][k / 2], [0.01, 0.2][k % 2]);
        let omega = [w1, 2.0, 0.01];
        let rotors = [0.1 * omega[0], 0.1 * (omega[1] + a2), 0.1 * omega[2]];
        let pi0 = [0, 1, 2].map(|i| [1.0, 2.0, 3.0][i] * omega[i] + rotors[i]);
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let reference = gyrostat_rk4([1.0, 2.0, 3.0], rotors, [0.0; 3], identity, pi0, 2.0, 20_000);
        let state = state_of(row);
        // The midpoint rule at h = 0.01: an error of order h² |Ω|² ≈ 1e-3 at most over T = 2.
        assert!(gap(&state, &reference) < 5e-3, "member {k} off the gyrostat by {:e}", gap(&state, &reference));
        assert!((row["p_a2"] - rotors[1]).abs() < 1e-12, "member {k}: rotor momentum {}", row["p_a2"]);
    }
    let rows_per_member: usize = 21; // steps 0, 10, …, 200
    for (name, shape) in [
        ("R", vec![6, rows_per_member as u64, 3, 3]),
        ("Pi", vec![6, rows_per_member as u64, 3]),
        ("q", vec![6, rows_per_member as u64, 3]),
        ("p", vec![6, rows_per_member as u64, 3]),
        ("energy", vec![6, rows_per_member as u64]),
        ("final_q", vec![6, 3]),
    ] {
        assert_eq!(floats(&whole.join(format!("npy/{name}.npy"))).0, shape, "{name}");
    }
    // The last row of R.npy is the final attitude.
    let (_, r) = floats(&whole.join("npy/R.npy"));
    let last = &r[(rows_per_member - 1) * 9..rows_per_member * 9];
    assert_eq!(last, (0..9).map(|j| rows[0].1[&format!("R{}{}", j / 3 + 1, j % 3 + 1)]).collect::<Vec<_>>());
    // Shards, merged, give the unsharded files byte for byte.
    let shards = dir.0.join("shards");
    for i in 0..4 {
        let shard = format!("{i}/4");
        let output =
            ddirac(&["ensemble", &spec, "--shard", &shard, "--out", shards.to_str().unwrap(), "--quiet"], &dir.0);
        assert!(output.status.success(), "{}", stderr(&output));
    }
    let merged = dir.0.join("merged");
    let parts: Vec<String> = (0..4).map(|i| shards.join(format!("shard-{i}-of-4")).display().to_string()).collect();
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(String::as_str));
    args.extend(["--out", merged.to_str().unwrap(), "--quiet"]);
    let output = ddirac(&args, &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    let mut names: Vec<String> = std::fs::read_dir(whole.join("npy"))
        .unwrap()
        .map(|e| format!("npy/{}", e.unwrap().file_name().to_string_lossy()))
        .collect();
    names.extend(["final.csv".to_owned(), "members.csv".to_owned()]);
    for name in names {
        assert_eq!(std::fs::read(whole.join(&name)).unwrap(), std::fs::read(merged.join(&name)).unwrap(), "{name}");
    }
    // A shard with a damaged rotation array is refused.
    let damaged = shards.join("shard-1-of-4/npy/R.npy");
    let bytes = std::fs::read(&damaged).unwrap();
    std::fs::write(&damaged, &bytes[..bytes.len() - 8]).unwrap();
    let again = dir.0.join("again");
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(String::as_str));
    args.extend(["--out", again.to_str().unwrap()]);
    let output = ddirac(&args, &dir.0);
    assert_fails(&output, &dir, &["R.npy"]);
    assert!(!again.exists(), "a refused merge writes nothing");
}

#[test]
fn a_failing_member_is_recorded_and_the_others_finish() {
    let dir = TempDir::new("rigid-ensemble-failure");
    let spec = dir.file("top.toml", &heavy());
    // With g = 10⁹ the top swings at about 2·10⁴ rad/s, a hundred radians a step: Newton's method
    // fails; the members around it go on.
    let members = dir.file("members.csv", "parameters.g\n9.8\n1e9\n9.9\n");
    let out = dir.0.join("ens");
    let output = ddirac(&["ensemble", &spec, "--members", &members, "--out", out.to_str().unwrap()], &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stderr(&output).contains("warning [failed_members]: 1 of 3 members failed"), "{}", stderr(&output));
    assert!(stderr(&output).contains("member 1 at step"), "{}", stderr(&output));
    let rows = final_rows(&out);
    let statuses: Vec<&str> = rows.iter().map(|(s, _)| s.as_str()).collect();
    assert_eq!(statuses, ["ok", "failed", "ok"]);
    assert_eq!(npy::read(&out.join("npy/status.npy")).unwrap().data, [0, 1, 0]);
    let (_, energy_error) = floats(&out.join("npy/energy_error.npy"));
    assert!(energy_error[1].is_nan() && energy_error[0].is_finite() && energy_error[2].is_finite());
    // The failed member's state is that of its last step: R is still a rotation.
    let (r, _) = state_of(&rows[1].1);
    for i in 0..3 {
        for j in 0..3 {
            let rtr: f64 = (0..3).map(|l| r[l][i] * r[l][j]).sum();
            assert!((rtr - f64::from(u8::from(i == j))).abs() < 1e-12, "RᵀR − I: {rtr}");
        }
    }
    // A member whose parameters the body refuses refuses the ensemble, naming the member, as for a
    // system in coordinates.
    let members = dir.file("bad.csv", "parameters.I1\n1.0\n-1.0\n");
    let refused = dir.0.join("refused");
    let output = ddirac(&["ensemble", &spec, "--members", &members, "--out", refused.to_str().unwrap()], &dir.0);
    assert_fails(&output, &dir, &["member 1", "`I1`", "must be positive"]);
}

#[test]
fn keys_a_rigid_body_cannot_vary_are_refused_with_the_reason() {
    let dir = TempDir::new("rigid-ensemble-keys");
    let spec = dir.file("top.toml", &heavy());
    let satellite = satellite(&dir);
    let refused = |spec: &str, members: &str, needles: &[&str]| {
        let file = dir.file("members.csv", members);
        let out = dir.0.join("refused");
        let output = ddirac(&["ensemble", spec, "--members", &file, "--out", out.to_str().unwrap()], &dir.0);
        assert_fails(&output, &dir, needles);
        assert!(!out.exists(), "a refused ensemble writes nothing");
    };
    refused(&spec, "initial.Pi.4\n1\n", &["names no component", "1, 2 and 3"]);
    refused(&spec, "initial.Pi.x\n1\n", &["names no component"]);
    refused(&spec, "initial.R.1\n1\n", &["the attitude R is a rotation"]);
    refused(&spec, "initial.q.a\n1\n", &["this body has none"]);
    refused(&spec, "initial.Omega.1\n1\n", &["entries of `initial.Omega` or `initial.v` replace it only when all 3"]);
    refused(&spec, "initial.Omega.1,initial.Pi.2\n1,2\n", &["given together"]);
    refused(&spec, "parameters.I4\n1\n", &["`I4` is not a parameter", "I1, I2, I3"]);
    refused(&satellite, "initial.q.b\n1\n", &["`b` is not a shape coordinate", "a1, a2, a3"]);
    refused(&satellite, "initial.Pi.1\n1\n", &["replace it only when all 6 (three of the body"]);
    refused(&spec, "initial.Pi.1\nnan\n", &["not a finite number"]);
    // The whole vector of the other family replaces the spec's: Ω given for a spec with Π, and the
    // members equal the runs with that Ω.
    let file = dir.file("omega.csv", "initial.Omega.1,initial.Omega.2,initial.Omega.3\n0.3,-0.2,3.75\n");
    let out = dir.0.join("omega");
    let output = ddirac(&["ensemble", &spec, "--members", &file, "--out", out.to_str().unwrap(), "--quiet"], &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    // I3 = 0.4: Ω = (0.3, −0.2, 3.75) is Π = (0.3, −0.26, 1.5), a run the spec can say with Pi.
    let edited = dir.file("edited.toml", &heavy().replace("Pi = [0.3, -0.2, 1.5]", "Omega = [0.3, -0.2, 3.75]"));
    let finished = succeed(&edited, &[], &TempDir::new("rigid-ensemble-omega-single"));
    let pi = ["Pi1", "Pi2", "Pi3"].map(|c| finished.column(c).last().unwrap().to_bits());
    assert_eq!(pi, state_of(&final_rows(&out)[0].1).1.map(f64::to_bits));
}

#[test]
fn set_of_a_body_s_component_equals_the_spec_that_writes_it() {
    let dir = TempDir::new("rigid-set-component");
    let spec = dir.file("top.toml", &heavy());
    let set = succeed(&spec, &["initial.Pi.2=0.7"], &TempDir::new("rigid-set-component-set"));
    let edited = dir.file("edited.toml", &heavy().replace("Pi = [0.3, -0.2, 1.5]", "Pi = [0.3, 0.7, 1.5]"));
    let written = succeed(&edited, &[], &TempDir::new("rigid-set-component-written"));
    assert_eq!(set.summary["final"], written.summary["final"]);
    // And a system in coordinates refuses the body's components.
    let kepler = common::example("kepler.toml");
    let output = common::run(&kepler, &["initial.Pi.1=1"], &dir);
    assert_fails(&output, &dir, &["`initial.Pi.1` belongs to a rigid body"]);
}
