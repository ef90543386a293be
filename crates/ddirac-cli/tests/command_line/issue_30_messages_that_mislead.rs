//! Messages that pointed the wrong way: a shard given twice was reported with a backwards range
//! ("members 64..48 are missing or given twice"), any unreadable file was "the spec file", `--shard
//! 0/0` asked for an index "in 0..0", a hint for `output.every` suggested a float the key refuses,
//! and a valid connection with a large entry was refused as if the Lagrangian were at fault.

use crate::common;

use std::path::{Path, PathBuf};

use common::{ddirac, example, stderr, TempDir};

const ENSEMBLE: &str = r#"
[ensemble]

[[ensemble.grid]]
key = "initial.q.phi1"
from = 1.5
to = 2.5
count = 6
"#;

/// The spec of an ensemble of 6 short members.
fn spec(dir: &TempDir) -> String {
    let base = std::fs::read_to_string(example("double_spherical_pendulum.toml")).unwrap();
    let text = base.replace("steps = 10000", "steps = 20").replace("duration = 100.0", "duration = 0.2");
    assert_ne!(text, base, "the example's [time] table changed");
    dir.file("spec.toml", &format!("{text}{ENSEMBLE}"))
}

/// Runs the 3 shards of the ensemble (members 0..2, 2..4, 4..6) into `dir/shards`; returns their
/// directories.
fn shards(dir: &TempDir) -> Vec<PathBuf> {
    let spec = spec(dir);
    let shards = dir.0.join("shards");
    (0..3)
        .map(|i| {
            let shard = format!("{i}/3");
            let args = ["ensemble", &spec, "--out", shards.to_str().unwrap(), "--quiet", "--shard", &shard];
            let output = ddirac(&args, &dir.0);
            assert!(output.status.success(), "{}", stderr(&output));
            shards.join(format!("shard-{i}-of-3"))
        })
        .collect()
}

/// `ddirac merge DIRS --out dir/merged`, which must fail with status 2; its stderr.
fn merge_refused(dirs: &[&Path], dir: &TempDir) -> String {
    merge_refused_with(dirs, dir, 2)
}

/// `ddirac merge DIRS --out dir/merged`, which must fail with status `code`; its stderr.
fn merge_refused_with(dirs: &[&Path], dir: &TempDir, code: i32) -> String {
    let out = dir.0.join("merged");
    let mut args: Vec<String> = vec!["merge".into()];
    args.extend(dirs.iter().map(|d| d.display().to_string()));
    args.extend(["--out".into(), out.display().to_string()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let output = ddirac(&args, &dir.0);
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(code), "{text}");
    assert!(!out.exists());
    text
}

#[test]
fn a_shard_given_twice_or_overlapping_or_missing_is_named_with_its_members() {
    let dir = TempDir::new("merge-messages");
    let parts = shards(&dir);
    let shown = |p: &Path| format!("`{}`", p.display());

    // The same directory twice.
    let text = merge_refused(&[&parts[0], &parts[1], &parts[2], &parts[1]], &dir);
    assert!(text.contains(&format!("{} is given twice (members 2..4)", shown(&parts[1]))), "{text}");
    assert!(!text.contains("4..2"), "a backwards range:\n{text}");

    // A copy of a shard in another directory: both directories named, with the members repeated.
    let copy = dir.0.join("copy-of-shard-1");
    std::fs::create_dir_all(copy.join("npy")).unwrap();
    for entry in ["final.csv", "members.csv", "summary.json"] {
        std::fs::copy(parts[1].join(entry), copy.join(entry)).unwrap();
    }
    for entry in std::fs::read_dir(parts[1].join("npy")).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), copy.join("npy").join(entry.file_name())).unwrap();
    }
    let text = merge_refused(&[&parts[0], &parts[1], &copy, &parts[2]], &dir);
    assert!(text.contains("(members 2..4) repeats members 2..4 of "), "{text}");
    assert!(text.contains(&shown(&parts[1])) && text.contains(&shown(&copy)), "both directories named:\n{text}");
    assert!(!text.contains("4..2"), "a backwards range:\n{text}");

    // A shard missing: the members that are in none of the directories.
    let text = merge_refused(&[&parts[2], &parts[0]], &dir);
    assert!(text.contains("members 2..4 of 6 are in none of the directories"), "{text}");
    let text = merge_refused(&[&parts[1], &parts[0]], &dir);
    assert!(text.contains("members 4..6 of 6 are in none of the directories"), "{text}");
}

#[test]
fn a_file_that_cannot_be_read_is_named_for_what_it_is() {
    let dir = TempDir::new("read-messages");
    let parts = shards(&dir);

    // A shard array missing.
    let array = parts[1].join("npy/final_p.npy");
    let aside = dir.0.join("final_p.npy");
    std::fs::rename(&array, &aside).unwrap();
    let text = merge_refused(&[&parts[0], &parts[1], &parts[2]], &dir);
    assert!(text.contains(&format!("`{}` is missing", array.display())), "{text}");
    assert!(!text.contains("spec file"), "{text}");
    std::fs::rename(&aside, &array).unwrap();

    // A shard's final.csv missing: a file of the shard, not the spec file.
    let table = parts[2].join("final.csv");
    std::fs::remove_file(&table).unwrap();
    let text = merge_refused_with(&[&parts[0], &parts[1], &parts[2]], &dir, 4);
    assert!(text.contains(&format!("cannot read the shard file `{}`", table.display())), "{text}");
    assert!(!text.contains("spec file"), "{text}");

    // A missing members file is the members file; a missing spec still the spec file.
    let spec = spec(&dir);
    let absent = dir.0.join("absent.csv");
    let output = ddirac(&["ensemble", &spec, "--members", absent.to_str().unwrap(), "--quiet"], &dir.0);
    assert_eq!(output.status.code(), Some(4), "{}", stderr(&output));
    assert!(
        stderr(&output).contains(&format!("cannot read the members file `{}`", absent.display())),
        "{}",
        stderr(&output)
    );
    let output = ddirac(&["run", "absent.toml", "--quiet"], &dir.0);
    assert_eq!(output.status.code(), Some(4), "{}", stderr(&output));
    assert!(stderr(&output).contains("cannot read the spec file `absent.toml`"), "{}", stderr(&output));
}

#[test]
fn no_shards_at_all_asks_for_at_least_one() {
    let dir = TempDir::new("shard-count");
    let spec = spec(&dir);
    for arg in ["0/0", "3/0"] {
        let output = ddirac(&["ensemble", &spec, "--shard", arg, "--quiet"], &dir.0);
        let text = stderr(&output);
        assert_eq!(output.status.code(), Some(2), "{text}");
        assert!(text.contains("the number of shards N must be at least 1"), "{arg}: {text}");
        assert!(!text.contains("0..0"), "{arg}: {text}");
    }
    let output = ddirac(&["ensemble", &spec, "--shard", "3/3", "--quiet"], &dir.0);
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{text}");
    assert!(text.contains("the shard index 3 must be in 0..3"), "{text}");
}

/// `ddirac run SPEC --out DIR/out --quiet --set ...`: exit status and stderr.
fn run(spec: &str, sets: &[&str], dir: &TempDir) -> (Option<i32>, String) {
    let output = common::run(spec, sets, dir);
    (output.status.code(), stderr(&output))
}

#[test]
fn an_integer_key_is_never_told_to_take_a_float() {
    let dir = TempDir::new("every-hint");
    let spec = example("charged_particle.toml");
    // Beyond TOML's integers: the range is named, no float suggested.
    let (code, text) = run(&spec, &["output.every=100000000000000000000"], &dir);
    assert_eq!(code, Some(2), "{text}");
    assert!(text.contains("TOML integers lie in -9223372036854775808..=9223372036854775807"), "{text}");
    assert!(!text.contains("`1e20`"), "a float suggested for an integer key:\n{text}");
    // The largest integer is taken: a row at the start and one at the end.
    let finished = common::succeed(&spec, &["output.every=9223372036854775807"], &dir);
    assert_eq!(finished.column("t").len(), 2);

    // A float for the integer key: the help names the integer it equals, and that integer runs.
    let (code, text) = run(&spec, &["output.every=1e1"], &dir);
    assert_eq!(code, Some(2), "{text}");
    assert!(text.contains("this key takes an integer: write `10`"), "{text}");
    let finished = common::succeed(&spec, &["output.every=10"], &dir);
    assert_eq!(finished.column("t").len(), 11);
    let (code, text) = run(&spec, &["output.every=1e20"], &dir);
    assert_eq!(code, Some(2), "{text}");
    assert!(text.contains("this key takes an integer, in -9223372036854775808..=9223372036854775807"), "{text}");
    // A number spelt otherwise: the float and, for keys that take one, the integer.
    let (code, text) = run(&spec, &["output.every=5."], &dir);
    assert_eq!(code, Some(2), "{text}");
    assert!(text.contains("write the number as `5.0` (`5` where the key takes an integer)"), "{text}");
    let (code, text) = run(&spec, &["time.steps=0100"], &dir);
    assert_eq!(code, Some(2), "{text}");
    assert!(text.contains("write the integer as `100`"), "{text}");
}

#[test]
fn a_connection_too_large_for_floating_point_is_named_as_the_cause() {
    let dir = TempDir::new("large-connection");
    let spec = example("two_body.toml");
    let short = "time.duration=1.0";
    // K = 10⁴ I satisfies the axioms of a connection, but the reduced unknowns sheared by it make the
    // step equations' Jacobian singular to double precision (condition about |K|⁴ = 10¹⁶).
    let large = "method.connection=[[10000.0, 0.0], [0.0, 10000.0]]";
    let (code, text) = run(&spec, &[short, large], &dir);
    assert_eq!(code, Some(2), "{text}");
    assert!(text.contains("invalid connection: with this K (largest entry 1e4)"), "{text}");
    assert!(text.contains("this connection"), "the connection is not pointed at:\n{text}");
    assert!(!text.contains("Lagrangian"), "the Lagrangian is blamed:\n{text}");
    assert!(!text.contains("do not determine the motion"), "{text}");

    // A moderate K reduces to the unreduced motion (the same q_N to round-off), so K alone makes the
    // difference above.
    let unreduced = common::succeed(&spec, &[short, "method.reduced=false"], &TempDir::new("unreduced"));
    let moderate = common::succeed(&spec, &[short, "method.connection=[[10.0, 0.0], [0.0, 10.0]]"], &dir);
    for (a, b) in moderate.final_q().iter().zip(unreduced.final_q()) {
        assert!((a - b).abs() < 1e-10, "{:?} against {:?}", moderate.final_q(), unreduced.final_q());
    }

    // A Lagrangian on which the relative position has no effect (no second body, no attraction) is
    // still reported as leaving the motion undetermined, with any K.
    let (code, text) = run(&spec, &[short, "parameters.m2=0.0", "parameters.k=0.0", large], &dir);
    assert_eq!(code, Some(2), "{text}");
    assert!(text.contains("do not determine the motion"), "{text}");
    assert!(!text.contains("invalid connection"), "{text}");
}
