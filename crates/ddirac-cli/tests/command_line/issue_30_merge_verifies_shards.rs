//! `ddirac merge` took damaged shards with exit status 0: a `final.csv` with a row deleted, a
//! truncated `.npy` file, a summary of another ddirac version, an array missing from one shard. Each
//! is now refused, naming the damaged file, before anything is written: `--out` holds no merged
//! file afterwards (and an earlier merge in it stays as it was).

use crate::common;

use std::path::{Path, PathBuf};

use common::{ddirac, example, files_under, stderr, TempDir};

const ENSEMBLE: &str = r#"
[ensemble]
trajectories = true

[[ensemble.grid]]
key = "initial.q.phi1"
from = 1.5
to = 2.5
count = 3

[[ensemble.grid]]
key = "initial.p.vartheta2"
values = [0.5, 1.0]
"#;

/// Runs the 3 shards of an ensemble of 6 members (2 per shard) with trajectories into `dir/shards`.
fn shards(dir: &TempDir) -> PathBuf {
    let base = std::fs::read_to_string(example("double_spherical_pendulum.toml")).unwrap();
    let text = base.replace("steps = 10000", "steps = 40").replace("duration = 100.0", "duration = 0.4");
    assert_ne!(text, base, "the example's [time] table changed");
    let spec = dir.file("spec.toml", &format!("{text}{ENSEMBLE}"));
    let shards = dir.0.join("shards");
    for i in 0..3 {
        let shard = format!("{i}/3");
        let args =
            ["ensemble", &spec, "--out", shards.to_str().unwrap(), "--quiet", "--shard", &shard, "--threads", "1"];
        let output = ddirac(&args, &dir.0);
        assert!(output.status.success(), "{}", stderr(&output));
    }
    shards
}

fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// `ddirac merge` of the three shards in `shards` into `out`.
fn merge(shards: &Path, out: &Path, cwd: &Path) -> std::process::Output {
    let parts: Vec<String> = (0..3).map(|i| shards.join(format!("shard-{i}-of-3")).display().to_string()).collect();
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(String::as_str));
    args.extend(["--out", out.to_str().unwrap(), "--quiet"]);
    ddirac(&args, cwd)
}

/// The files under `dir`, with their contents, sorted by path.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    files_under(dir).into_iter().map(|f| (f.clone(), std::fs::read(dir.join(&f)).unwrap())).collect()
}

/// Copies the intact shards, damages the copy with `damage` (given the copy's directory), and
/// asserts that merging it is refused naming `file` (relative to the copy) and every needle, that
/// a fresh `--out` is not left behind, and that an `--out` holding an earlier merge is unchanged.
fn refused(intact: &Path, dir: &TempDir, name: &str, damage: impl Fn(&Path), file: &str, needles: &[&str]) {
    let shards = dir.0.join(name);
    copy_tree(intact, &shards);
    damage(&shards);
    let out = dir.0.join(format!("{name}-out"));
    let output = merge(&shards, &out, &dir.0);
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{name}: merged with exit status {:?}:\n{text}", output.status.code());
    let damaged = shards.join(file).display().to_string();
    assert!(text.contains(&damaged), "{name}: the report does not name `{damaged}`:\n{text}");
    for needle in needles {
        assert!(text.contains(needle), "{name}: the report lacks `{needle}`:\n{text}");
    }
    assert!(!out.exists(), "{name}: the refused merge left `{}` behind", out.display());

    // Into a directory holding an earlier merge of the intact shards: nothing of it changes.
    let earlier = dir.0.join(format!("{name}-earlier"));
    let output = merge(intact, &earlier, &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    let before = files(&earlier);
    let output = merge(&shards, &earlier, &dir.0);
    assert_eq!(output.status.code(), Some(2), "{name}: {}", stderr(&output));
    assert!(
        files(&earlier) == before,
        "{name}: the refused merge changed the earlier merge in `{}`",
        earlier.display()
    );
}

#[test]
fn damaged_shards_are_refused_naming_the_file_and_nothing_is_written() {
    let dir = TempDir::new("merge-damaged");
    let intact = shards(&dir);

    // The intact copy merges: the damage alone makes the difference below.
    let copy = dir.0.join("intact-copy");
    copy_tree(&intact, &copy);
    let output = merge(&copy, &dir.0.join("merged"), &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    let q = ddirac_cli::npy::read(&dir.0.join("merged/npy/final_q.npy")).unwrap();
    assert_eq!(q.shape, [6, 4]);
    assert_eq!(std::fs::read_to_string(dir.0.join("merged/final.csv")).unwrap().lines().count(), 7);

    let delete_line = |file: &'static str, line: usize| {
        move |shards: &Path| {
            let path = shards.join(file);
            let text = std::fs::read_to_string(&path).unwrap();
            let mut lines: Vec<&str> = text.lines().collect();
            lines.remove(line);
            std::fs::write(&path, lines.join("\n") + "\n").unwrap();
        }
    };
    let truncate = |file: &'static str, bytes: u64| {
        move |shards: &Path| {
            let f = std::fs::OpenOptions::new().write(true).open(shards.join(file)).unwrap();
            let len = f.metadata().unwrap().len();
            f.set_len(len - bytes).unwrap();
        }
    };
    let remove = |file: &'static str| move |shards: &Path| std::fs::remove_file(shards.join(file)).unwrap();

    // A member's row deleted from final.csv / members.csv (the shard holds members 2..4).
    refused(
        &intact,
        &dir,
        "final-row",
        delete_line("shard-1-of-3/final.csv", 2),
        "shard-1-of-3/final.csv",
        &["has 1 rows, but the shard holds 2 members"],
    );
    refused(
        &intact,
        &dir,
        "members-row",
        delete_line("shard-2-of-3/members.csv", 1),
        "shard-2-of-3/members.csv",
        &["member `5` on line 2, where member 4 belongs"],
    );
    // Truncated arrays: one value of final_q (the old merge wrote a final_q.npy NumPy cannot read),
    // one value of the trajectories.
    refused(
        &intact,
        &dir,
        "final-q-truncated",
        truncate("shard-1-of-3/npy/final_q.npy", 8),
        "shard-1-of-3/npy/final_q.npy",
        &["needs 64 bytes of data, but the file holds 56", "truncated"],
    );
    refused(
        &intact,
        &dir,
        "q-truncated",
        truncate("shard-2-of-3/npy/q.npy", 3),
        "shard-2-of-3/npy/q.npy",
        &["truncated"],
    );
    // A summary of another ddirac version.
    refused(
        &intact,
        &dir,
        "version",
        |shards: &Path| {
            let path = shards.join("shard-2-of-3/summary.json");
            let text = std::fs::read_to_string(&path).unwrap();
            let version = format!("\"ddirac_version\": \"{}\"", env!("CARGO_PKG_VERSION"));
            assert!(text.contains(&version), "{text}");
            std::fs::write(&path, text.replace(&version, "\"ddirac_version\": \"0.0.1\"")).unwrap();
        },
        "shard-2-of-3/summary.json",
        &["by ddirac 0.0.1", &format!("by ddirac {}", env!("CARGO_PKG_VERSION"))],
    );
    // An array missing from one shard: the first (the old merge took the list of arrays from it and
    // left the array out) and another.
    refused(
        &intact,
        &dir,
        "missing-first",
        remove("shard-0-of-3/npy/energy_error.npy"),
        "shard-0-of-3/npy/energy_error.npy",
        &["is missing"],
    );
    refused(
        &intact,
        &dir,
        "missing-other",
        remove("shard-2-of-3/npy/steps.npy"),
        "shard-2-of-3/npy/steps.npy",
        &["is missing"],
    );
    // An array complete in itself, but of another shape than the shard's 2 members imply.
    refused(
        &intact,
        &dir,
        "shape",
        |shards: &Path| {
            let path = shards.join("shard-1-of-3/npy/status.npy");
            ddirac_cli::npy::write(&path, "|u1", &[3], &[0, 0, 0]).unwrap();
        },
        "shard-1-of-3/npy/status.npy",
        &["of shape (3)", "of shape (2)"],
    );
}
