//! Helpers shared by the command-line tests: running the binary
//! in a temporary directory, reading its output files, and reading miette's labels back from stderr.

// Each test crate uses a different subset of these helpers.
#![allow(dead_code)]

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

use serde_json::Value;

/// The path of a shipped example spec.
pub fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// A fresh directory under the system's temporary directory, removed on drop.
pub struct TempDir(pub PathBuf);

impl TempDir {
    pub fn new(name: &str) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::SeqCst);
        let path = std::env::temp_dir().join(format!("ddirac-specs-{}-{n}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).unwrap();
        Self(path)
    }

    /// The output directory of runs in this directory.
    pub fn out(&self) -> PathBuf {
        self.0.join("out")
    }

    /// Writes `text` as `name` in this directory and returns its path.
    pub fn file(&self, name: &str, text: &str) -> String {
        let path = self.0.join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_owned()
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Runs the binary with `args` in `cwd`.
pub fn ddirac(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ddirac")).args(args).current_dir(cwd).output().unwrap()
}

/// `ddirac run SPEC --out DIR/out --quiet --set ...`.
pub fn run(spec: &str, sets: &[&str], dir: &TempDir) -> Output {
    let out = dir.out();
    let mut args = vec!["run", spec, "--out", out.to_str().unwrap(), "--quiet"];
    for s in sets {
        args.extend(["--set", s]);
    }
    ddirac(&args, &dir.0)
}

/// `ddirac check SPEC --set ...`.
pub fn check(spec: &str, sets: &[&str], dir: &TempDir) -> Output {
    let mut args = vec!["check", spec];
    for s in sets {
        args.extend(["--set", s]);
    }
    ddirac(&args, &dir.0)
}

/// A finished run: its summary and its trajectory, column by column.
pub struct Finished {
    pub summary: Value,
    pub columns: HashMap<String, Vec<f64>>,
}

impl Finished {
    /// The column `name` of trajectory.csv (empty fields are NaN).
    pub fn column(&self, name: &str) -> &[f64] {
        self.columns.get(name).unwrap_or_else(|| panic!("no column `{name}`"))
    }

    /// `final.q` of summary.json.
    pub fn final_q(&self) -> Vec<f64> {
        numbers(&self.summary["final"]["q"])
    }
}

/// Runs `spec`, which must succeed, and reads its output files.
pub fn succeed(spec: &str, sets: &[&str], dir: &TempDir) -> Finished {
    let output = run(spec, sets, dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let summary = std::fs::read_to_string(dir.out().join("summary.json")).unwrap();
    let csv = std::fs::read_to_string(dir.out().join("trajectory.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(str::to_owned).collect();
    let mut columns: HashMap<String, Vec<f64>> = header.iter().map(|h| (h.clone(), vec![])).collect();
    for line in lines {
        for (name, field) in header.iter().zip(line.split(',')) {
            columns.get_mut(name).unwrap().push(field.parse().unwrap_or(f64::NAN));
        }
    }
    Finished { summary: serde_json::from_str(&summary).unwrap(), columns }
}

/// The numbers of a JSON array.
pub fn numbers(value: &Value) -> Vec<f64> {
    value.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect()
}

/// Asserts a failed command: non-zero exit, every `needle` in stderr, and no output file written.
pub fn assert_fails(output: &Output, dir: &TempDir, needles: &[&str]) -> String {
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(!output.status.success(), "the command succeeded; stderr: {stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "stderr lacks `{needle}`:\n{stderr}");
    }
    assert!(!dir.out().exists(), "a failed command left {} behind", dir.out().display());
    stderr
}

/// The characters of the quoted spec line containing `line` that miette underlines in `stderr`,
/// one string per label, left to right.
pub fn underlined(stderr: &str, line: &str) -> Vec<String> {
    let lines: Vec<&str> = stderr.lines().collect();
    let i = lines
        .iter()
        .position(|l| l.contains('│') && l.contains(line))
        .unwrap_or_else(|| panic!("the report does not quote `{line}`:\n{stderr}"));
    let source: Vec<char> = lines[i].chars().collect();
    let marks: Vec<char> = lines.get(i + 1).unwrap_or_else(|| panic!("no label under `{line}`")).chars().collect();
    let underline = |c: char| matches!(c, '─' | '┬' | '┴' | '┼' | '^');
    let gutter = marks.iter().position(|&c| c == '·').expect("an underline row starts with `·`") + 1;
    let mut runs = vec![];
    let mut j = gutter;
    while j < marks.len() {
        if underline(marks[j]) {
            let start = j;
            while j < marks.len() && underline(marks[j]) {
                j += 1;
            }
            runs.push(source[start.min(source.len())..j.min(source.len())].iter().collect());
        } else {
            j += 1;
        }
    }
    runs
}

/// The standard output of a command.
pub fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The standard error of a command.
pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The line of a printed report that starts with `key` (after the indentation).
pub fn line<'a>(report: &'a str, key: &str) -> &'a str {
    report.lines().find(|l| l.trim_start().starts_with(key)).unwrap_or_else(|| panic!("no `{key}` line:\n{report}"))
}

/// The `summary.json` of the run directory `dir.out()`.
pub fn summary(dir: &TempDir) -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir.out().join("summary.json")).unwrap()).unwrap()
}

/// Every file under `dir`, as paths relative to it ('/'-separated), sorted.
pub fn files_under(dir: &Path) -> std::collections::BTreeSet<String> {
    let mut found = std::collections::BTreeSet::new();
    let mut stack = vec![dir.to_owned()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                found.insert(path.strip_prefix(dir).unwrap().to_string_lossy().replace('\\', "/"));
            }
        }
    }
    found
}

/// A 3 × 3 matrix as rows.
pub type M3 = [[f64; 3]; 3];

fn mul(a: &M3, b: &M3) -> M3 {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// Euler's equations of a rigid body (principal moments I, gravity's m g c) from (R0, Π0) over `t` by
/// RK4 with `n` steps: Π̇ = Π × Ω + Γ × m g c, Γ = Rᵀe3, Ṙ = R Ω̂, Ω = I⁻¹Π.
pub fn euler_rk4(inertia: [f64; 3], mgc: [f64; 3], r0: M3, pi0: [f64; 3], t: f64, n: usize) -> (M3, [f64; 3]) {
    gyrostat_rk4(inertia, [0.0; 3], mgc, r0, pi0, t, n)
}

/// The same for a gyrostat, a body with rotors of constant momenta `rotors` along its axes:
/// Ω = J⁻¹(Π − rotors).
pub fn gyrostat_rk4(
    inertia: [f64; 3],
    rotors: [f64; 3],
    mgc: [f64; 3],
    r0: M3,
    pi0: [f64; 3],
    t: f64,
    n: usize,
) -> (M3, [f64; 3]) {
    let field = |r: &M3, pi: &[f64; 3]| -> (M3, [f64; 3]) {
        let omega = [0, 1, 2].map(|i| (pi[i] - rotors[i]) / inertia[i]);
        let gamma = [r[2][0], r[2][1], r[2][2]];
        let torque = cross(gamma, mgc);
        let spin = cross(*pi, omega);
        let hat = [[0.0, -omega[2], omega[1]], [omega[2], 0.0, -omega[0]], [-omega[1], omega[0], 0.0]];
        (mul(r, &hat), [0, 1, 2].map(|i| spin[i] + torque[i]))
    };
    let h = t / n as f64;
    let (mut r, mut pi) = (r0, pi0);
    let add = |r: &M3, pi: &[f64; 3], k: &(M3, [f64; 3]), a: f64| -> (M3, [f64; 3]) {
        let rr = [0, 1, 2].map(|i| [0, 1, 2].map(|j| r[i][j] + a * k.0[i][j]));
        (rr, [0, 1, 2].map(|i| pi[i] + a * k.1[i]))
    };
    for _ in 0..n {
        let k1 = field(&r, &pi);
        let s2 = add(&r, &pi, &k1, h / 2.0);
        let k2 = field(&s2.0, &s2.1);
        let s3 = add(&r, &pi, &k2, h / 2.0);
        let k3 = field(&s3.0, &s3.1);
        let s4 = add(&r, &pi, &k3, h);
        let k4 = field(&s4.0, &s4.1);
        let (r0, pi0) = (r, pi);
        r = [0, 1, 2].map(|i| {
            [0, 1, 2].map(|j| r0[i][j] + h / 6.0 * (k1.0[i][j] + 2.0 * k2.0[i][j] + 2.0 * k3.0[i][j] + k4.0[i][j]))
        });
        pi = [0, 1, 2].map(|i| pi0[i] + h / 6.0 * (k1.1[i] + 2.0 * k2.1[i] + 2.0 * k3.1[i] + k4.1[i]));
    }
    (r, pi)
}
