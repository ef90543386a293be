//! `ddirac ensemble` and `ddirac merge`: each member equals its single run bit for bit, shards
//! merge into the unsharded result, failing members are reported while the others complete, and
//! malformed members are refused.

use crate::common;

use std::collections::BTreeMap;
use std::path::Path;

use common::{ddirac, example, stderr, succeed, TempDir};
use ddirac_cli::npy;
use serde_json::Value;

/// `final.csv` as (status, values by column) per member.
fn final_rows(dir: &Path) -> Vec<(String, BTreeMap<String, f64>)> {
    let text = std::fs::read_to_string(dir.join("final.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(&header[..2], ["member", "status"]);
    lines
        .enumerate()
        .map(|(k, line)| {
            let fields: Vec<&str> = line.split(',').collect();
            assert_eq!(fields[0], k.to_string(), "members in order");
            let values =
                header[2..].iter().zip(&fields[2..]).map(|(h, f)| (h.to_string(), f.parse().unwrap())).collect();
            (fields[1].to_owned(), values)
        })
        .collect()
}

fn ensemble(args: &[&str], dir: &TempDir) -> std::process::Output {
    let mut all = vec!["ensemble"];
    all.extend_from_slice(args);
    ddirac(&all, &dir.0)
}

fn summary(dir: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// Runs an ensemble from a members file and checks every member against `ddirac run` with its
/// values set: the final q and p, and with trajectories the rows of q, bit for bit.
fn members_equal_single_runs(spec: &str, sets: &[&str], members: &str, expect_path: &str, renewed: bool) {
    let dir = TempDir::new("ensemble-single");
    let file = dir.file("members.csv", members);
    let out = dir.0.join("ens");
    let mut args = vec![
        spec,
        "--members",
        &file,
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        // One thread: members run one after another and renew one stepper where its derivatives
        // serve them.
        "--threads",
        "1",
        "--set",
        "ensemble.trajectories=true",
    ];
    for s in sets {
        args.extend(["--set", s]);
    }
    let output = ensemble(&args, &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    let s = summary(&out);
    assert!(s["derivatives"].get(expect_path).is_some(), "{}", s["derivatives"]);
    let renewals = s["steppers"]["renewed"].as_u64().unwrap();
    assert_eq!(renewals > 0, renewed, "{}", s["steppers"]);
    let rows = final_rows(&out);
    let header: Vec<String> = members.lines().next().unwrap().split(',').map(str::to_owned).collect();
    let q = npy::read(&out.join("npy/q.npy")).unwrap();
    let n = q.shape[2] as usize;
    let r = q.shape[1] as usize;
    let q_values: Vec<f64> = q.data.chunks(8).map(|b| f64::from_le_bytes(b.try_into().unwrap())).collect();
    for (k, line) in members.lines().skip(1).enumerate() {
        let mut member_sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        member_sets.extend(header.iter().zip(line.split(',')).map(|(h, v)| format!("{h}={v}")));
        let refs: Vec<&str> = member_sets.iter().map(String::as_str).collect();
        let single_dir = TempDir::new("ensemble-single-run");
        let single = succeed(spec, &refs, &single_dir);
        let (status, values) = &rows[k];
        assert_eq!(status, "ok");
        let coordinates: Vec<String> =
            single.summary["coordinates"].as_array().unwrap().iter().map(|c| c.as_str().unwrap().to_owned()).collect();
        for (i, name) in coordinates.iter().enumerate() {
            let last = |column: &str| *single.column(column).last().unwrap();
            assert_eq!(values[name].to_bits(), last(name).to_bits(), "member {k}, {name}");
            let p = format!("p_{name}");
            assert_eq!(values[&p].to_bits(), last(&p).to_bits(), "member {k}, {p}");
            let column = single.column(name);
            assert_eq!(column.len(), r);
            for (row, value) in column.iter().enumerate() {
                assert_eq!(q_values[(k * r + row) * n + i].to_bits(), value.to_bits(), "member {k}, row {row}, {name}");
            }
        }
    }
}

#[test]
fn members_that_differ_in_initial_data_equal_their_single_runs_bit_for_bit() {
    // 6000 steps: compiled derivatives under `auto`, programs shared by the members through the cache.
    let members = "initial.q.phi1,initial.p.vartheta2,initial.p.vartheta1\n2.25,1.0,0.0\n2.0,0.5,0.3\n1.5,0.8,-0.2\n";
    let sets = ["time.steps=6000", "time.duration=60.0", "output.every=50"];
    members_equal_single_runs(&example("double_spherical_pendulum.toml"), &sets, members, "compiled", true);
}

#[test]
fn members_with_their_own_conserved_momentum_equal_their_single_runs() {
    // The charged particle's reduced step has a closed form that holds μ = p_theta as a constant.
    let members = "initial.p.theta,initial.p.q1\n1.0,1.0\n0.5,1.0\n2.0,0.3\n";
    // Each member prepares its own stepper (its closed form holds its μ).
    let sets = ["method.derivatives=\"compiled\""];
    members_equal_single_runs(&example("charged_particle.toml"), &sets, members, "compiled", false);
}

#[test]
fn members_that_differ_in_parameters_equal_their_single_runs() {
    let members = "parameters.B0,initial.q.x\n1.0,0.0\n0.5,0.1\n2.0,-0.3\n";
    let sets = ["method.derivatives=\"compiled\""];
    // Each member has its own system (its own B0); the compiled programs come from the cache.
    members_equal_single_runs(&example("charged_particle_expression.toml"), &sets, members, "compiled", false);
}

/// The files of two ensemble directories, but summary.json, byte for byte.
fn assert_same_files(a: &Path, b: &Path) {
    let list = |dir: &Path| -> Vec<String> {
        let mut names: Vec<String> = ["final.csv", "members.csv"].map(String::from).to_vec();
        let mut arrays: Vec<String> = std::fs::read_dir(dir.join("npy"))
            .unwrap()
            .map(|e| format!("npy/{}", e.unwrap().file_name().to_str().unwrap()))
            .collect();
        arrays.sort();
        names.extend(arrays);
        names
    };
    assert_eq!(list(a), list(b));
    for name in list(a) {
        assert!(std::fs::read(a.join(&name)).unwrap() == std::fs::read(b.join(&name)).unwrap(), "{name} differs");
    }
}

const GENERATED: &str = r#"
[ensemble]
trajectories = true
samples = 3
seed = 11

[[ensemble.grid]]
key = "initial.q.phi1"
from = 1.5
to = 2.5
count = 3

[[ensemble.grid]]
key = "initial.p.vartheta2"
values = [0.5, 1.0]

[[ensemble.random]]
key = "initial.q.phi2"
uniform = [2.8, 3.0]
"#;

fn generated_spec(dir: &TempDir) -> String {
    let base = std::fs::read_to_string(example("double_spherical_pendulum.toml")).unwrap();
    let text = base.replace("steps = 10000", "steps = 300").replace("duration = 100.0", "duration = 3.0");
    dir.file("generated.toml", &format!("{text}{GENERATED}"))
}

#[test]
fn shards_merge_into_the_unsharded_run_byte_for_byte() {
    let dir = TempDir::new("ensemble-shards");
    let spec = generated_spec(&dir);
    let whole = dir.0.join("whole");
    let output = ensemble(&[&spec, "--out", whole.to_str().unwrap(), "--quiet", "--threads", "2"], &dir);
    assert!(output.status.success(), "{}", stderr(&output));
    let shards = dir.0.join("shards");
    for i in 0..3 {
        let shard = format!("{i}/3");
        let output =
            ensemble(&[&spec, "--out", shards.to_str().unwrap(), "--quiet", "--shard", &shard, "--threads", "1"], &dir);
        assert!(output.status.success(), "{}", stderr(&output));
    }
    // Given out of order.
    let parts: Vec<String> =
        [2, 0, 1].iter().map(|i| shards.join(format!("shard-{i}-of-3")).display().to_string()).collect();
    let merged = dir.0.join("merged");
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(String::as_str));
    args.extend(["--out", merged.to_str().unwrap(), "--quiet"]);
    let output = ddirac(&args, &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    assert_same_files(&whole, &merged);
    let (w, m) = (summary(&whole), summary(&merged));
    for key in ["members", "finished", "failed", "failures", "fingerprint", "derivatives", "keys"] {
        assert_eq!(w[key], m[key], "{key}");
    }
    assert_eq!(w["members"], 18);
    let q = npy::read(&whole.join("npy/q.npy")).unwrap();
    assert_eq!(q.shape, [18, 31, 4]);

    // A missing shard and a shard of another ensemble are refused.
    let output = ddirac(&["merge", &parts[1], &parts[2], "--out", dir.0.join("bad").to_str().unwrap()], &dir.0);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("are in none of the directories"), "{}", stderr(&output));
    let other = dir.0.join("other");
    let output = ensemble(
        &[&spec, "--out", other.to_str().unwrap(), "--quiet", "--shard", "1/3", "--set", "ensemble.seed=12"],
        &dir,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let other_part = other.join("shard-1-of-3");
    let output = ddirac(
        &["merge", &parts[1], other_part.to_str().unwrap(), &parts[0], "--out", dir.0.join("bad").to_str().unwrap()],
        &dir.0,
    );
    assert!(stderr(&output).contains("holds another ensemble"), "{}", stderr(&output));
    assert!(!dir.0.join("bad").exists());
}

#[test]
fn grids_are_cartesian_products_and_random_draws_repeat_with_their_seed() {
    let dir = TempDir::new("ensemble-generated");
    let spec = generated_spec(&dir);
    let members = |seed: &str, name: &str| -> Vec<Vec<f64>> {
        let out = dir.0.join(name);
        let set = format!("ensemble.seed={seed}");
        let output = ensemble(
            &[
                &spec,
                "--out",
                out.to_str().unwrap(),
                "--quiet",
                "--set",
                &set,
                "--set",
                "time.steps=2",
                "--set",
                "time.duration=0.02",
            ],
            &dir,
        );
        assert!(output.status.success(), "{}", stderr(&output));
        let text = std::fs::read_to_string(out.join("members.csv")).unwrap();
        assert_eq!(text.lines().next().unwrap(), "member,initial.q.phi1,initial.p.vartheta2,initial.q.phi2");
        text.lines().skip(1).map(|l| l.split(',').skip(1).map(|f| f.parse().unwrap()).collect()).collect()
    };
    let a = members("11", "a");
    assert_eq!(a.len(), 18);
    // First axis slowest, each grid point repeated for its 3 draws.
    let grid: Vec<(f64, f64)> = a.iter().map(|m| (m[0], m[1])).collect();
    let mut expected = vec![];
    for phi1 in [1.5, 2.0, 2.5] {
        for p in [0.5, 1.0] {
            expected.extend([(phi1, p); 3]);
        }
    }
    assert_eq!(grid, expected);
    assert!(a.iter().all(|m| (2.8..3.0).contains(&m[2])));
    let draws: Vec<f64> = a.iter().map(|m| m[2]).collect();
    assert!(draws.windows(2).all(|w| w[0] != w[1]), "distinct draws: {draws:?}");
    assert_eq!(a, members("11", "b"));
    assert_ne!(a, members("12", "c"));
}

#[test]
fn a_failing_member_is_reported_and_the_others_complete() {
    // With g = 10⁶ the pendulum swings at ω = 1000 rad/s, ten radians a step: Newton's method fails
    // (also on sub-steps down to h/64); the members around it go on.
    let dir = TempDir::new("ensemble-failing");
    let file =
        dir.file("members.csv", "initial.p.theta,initial.p.phi,parameters.g\n0.0,0.5,9.8\n0.0,0.5,1e6\n0.0,0.8,9.8\n");
    let out = dir.0.join("ens");
    let output = ensemble(
        &[
            &example("spherical_pendulum.toml"),
            "--members",
            &file,
            "--out",
            out.to_str().unwrap(),
            "--set",
            "time.step=0.01",
        ],
        &dir,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stderr(&output).contains("1 of 3 members failed"), "{}", stderr(&output));
    assert!(stderr(&output).contains("member 1 at step"), "{}", stderr(&output));
    let rows = final_rows(&out);
    let status: Vec<&str> = rows.iter().map(|(s, _)| s.as_str()).collect();
    assert_eq!(status, ["ok", "failed", "ok"]);
    let s = summary(&out);
    assert_eq!((s["finished"].as_u64(), s["failed"].as_u64()), (Some(2), Some(1)));
    let failure = &s["failures"][0];
    assert_eq!(failure["member"], 1);
    let step = failure["step"].as_u64().unwrap();
    assert!(step > 0 && step < 2000, "{failure}");
    assert!(failure["error"].as_str().unwrap().contains("Newton"), "{failure}");
    let steps = npy::read(&out.join("npy/steps.npy")).unwrap();
    let steps: Vec<i64> = steps.data.chunks(8).map(|b| i64::from_le_bytes(b.try_into().unwrap())).collect();
    assert_eq!(steps, [2000, step as i64, 2000]);
    assert_eq!(npy::read(&out.join("npy/status.npy")).unwrap().data, [0, 1, 0]);
    // The failed member's state is that of its failed step: finite.
    assert!(rows[1].1.values().all(|x| x.is_finite()), "{:?}", rows[1].1);
}

#[test]
fn malformed_members_are_refused_naming_the_place_and_nothing_is_written() {
    let dir = TempDir::new("ensemble-malformed");
    let spec = example("double_spherical_pendulum.toml");
    let cases: [(&str, &[&str]); 7] = [
        ("time.step\n0.1\n", &["`time.step` cannot vary across members", "initial.q.<coordinate>"]),
        ("initial.q.phi3\n0.1\n", &["column `initial.q.phi3`", "not a coordinate", "vartheta1, phi1, vartheta2, phi2"]),
        ("parameters.mass\n1\n", &["`mass` is not a parameter", "m1, m2, l1, l2, g"]),
        ("initial.q.phi1\n0.1\nabc\n", &["line 3, column `initial.q.phi1`: `abc` is not a number"]),
        ("initial.q.phi1\nnan\n", &["`nan` is not a finite number"]),
        ("initial.v.phi1\n0.1\n", &["entries of `initial.v` replace it only when all 4 coordinates are given"]),
        // Momenta and velocities together (this used to panic).
        (
            "initial.v.vartheta1,initial.v.phi1,initial.v.vartheta2,initial.v.phi2,initial.p.phi1\n0,0,0,0,1\n",
            &["`initial.p` and of `initial.v` are given together"],
        ),
    ];
    for (members, needles) in cases {
        let file = dir.file("members.csv", members);
        let out = dir.out();
        let output = ensemble(&[&spec, "--members", &file, "--out", out.to_str().unwrap()], &dir);
        assert_eq!(output.status.code(), Some(2), "{members}: {}", stderr(&output));
        for needle in needles {
            assert!(stderr(&output).contains(needle), "{members}: lacks `{needle}`:\n{}", stderr(&output));
        }
        assert!(!out.exists());
    }
    let output = ensemble(&[&spec, "--out", dir.out().to_str().unwrap()], &dir);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("no `[ensemble]` table and no members file"), "{}", stderr(&output));
    let output = ensemble(&[&spec, "--shard", "3/3"], &dir);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("0..3"), "{}", stderr(&output));
}
