//! `--format npy` and `output.format`: the `.npy` files, read back by a reader written here from the
//! NumPy format description, hold exactly the numbers of `trajectory.csv`; NumPy itself reads them
//! when it is installed; failed runs leave no finished or partial `.npy` file.

use crate::common;

use common::TempDir;

use std::collections::BTreeSet;
use std::path::Path;
use std::process::{Command, Output};

const CHARGED_PARTICLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/charged_particle.toml");
const PENDULUM: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/double_spherical_pendulum.toml");

fn run(spec: &str, args: &[&str], dir: &TempDir) -> Output {
    let out = dir.out();
    let mut all = vec!["run", spec, "--out", out.to_str().unwrap(), "--quiet"];
    all.extend(args);
    Command::new(env!("CARGO_BIN_EXE_ddirac")).args(&all).current_dir(&dir.0).output().unwrap()
}

fn succeed(spec: &str, args: &[&str], dir: &TempDir) {
    let output = run(spec, args, dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
}

/// A 1-d array read from a `.npy` file, following the format description (versions 1.0 and 2.0).
#[derive(Debug)]
struct Array {
    descr: String,
    fortran_order: bool,
    shape: Vec<u64>,
    data: Vec<u8>,
}

impl Array {
    fn read(path: &Path) -> Self {
        let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(&bytes[..6], b"\x93NUMPY", "{}: no magic", path.display());
        let (header_len, start) = match bytes[6] {
            1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
            2 => (u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize, 12),
            v => panic!("version {v}"),
        };
        let end = start + header_len;
        assert_eq!(end % 64, 0, "the data of {} is not 64-byte aligned", path.display());
        let header = std::str::from_utf8(&bytes[start..end]).unwrap();
        assert!(header.ends_with('\n'), "header not ended by a newline: {header:?}");
        let dict = Dict::parse(header.trim_end());
        Array {
            descr: dict.string("descr"),
            fortran_order: dict.boolean("fortran_order"),
            shape: dict.tuple("shape"),
            data: bytes[end..].to_vec(),
        }
    }

    /// The values, after checking that the array is a 1-d little-endian f64 array of the right size.
    fn f64s(&self) -> Vec<f64> {
        assert_eq!(self.descr, "<f8");
        assert!(!self.fortran_order);
        assert_eq!(self.shape.len(), 1, "not 1-d: {:?}", self.shape);
        assert_eq!(self.data.len() as u64, 8 * self.shape[0], "data length and shape disagree");
        self.data.chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect()
    }
}

/// The header: a Python dict literal of string keys and string, boolean or tuple-of-int values.
struct Dict(Vec<(String, String)>);

impl Dict {
    fn parse(text: &str) -> Self {
        let inner = text.strip_prefix('{').and_then(|t| t.trim_end().strip_suffix('}')).expect("a dict");
        let mut entries = vec![];
        let mut rest = inner.trim_start();
        while !rest.is_empty() {
            let key_end = rest[1..].find('\'').unwrap() + 1;
            assert!(rest.starts_with('\''), "key not quoted: {rest}");
            let key = rest[1..key_end].to_owned();
            rest = rest[key_end + 1..].trim_start().strip_prefix(':').expect("a colon").trim_start();
            let value_end = match rest.as_bytes()[0] {
                b'\'' => rest[1..].find('\'').unwrap() + 2,
                b'(' => rest.find(')').unwrap() + 1,
                _ => rest.find(',').unwrap_or(rest.len()),
            };
            entries.push((key, rest[..value_end].trim().to_owned()));
            rest = rest[value_end..].trim_start();
            rest = rest.strip_prefix(',').unwrap_or(rest).trim_start();
        }
        Dict(entries)
    }

    fn get(&self, key: &str) -> &str {
        self.0.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str()).unwrap_or_else(|| panic!("no `{key}`"))
    }

    fn string(&self, key: &str) -> String {
        self.get(key).trim_matches('\'').to_owned()
    }

    fn boolean(&self, key: &str) -> bool {
        match self.get(key) {
            "True" => true,
            "False" => false,
            other => panic!("`{key}` is {other}"),
        }
    }

    fn tuple(&self, key: &str) -> Vec<u64> {
        let value = self.get(key);
        let inner = value.strip_prefix('(').and_then(|v| v.strip_suffix(')')).expect("a tuple");
        inner.split(',').map(str::trim).filter(|s| !s.is_empty()).map(|s| s.parse().unwrap()).collect()
    }
}

/// `trajectory.csv` as column names and columns; an empty field is `None`.
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<Option<f64>>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let names: Vec<String> = lines.next().unwrap().split(',').map(str::to_owned).collect();
    let mut columns = vec![vec![]; names.len()];
    for line in lines {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), names.len());
        for (column, field) in columns.iter_mut().zip(fields) {
            column.push(if field.is_empty() { None } else { Some(field.parse::<f64>().unwrap()) });
        }
    }
    (names, columns)
}

fn files_in(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect()
}

/// Every column of the CSV is a `.npy` file of the same name holding bit for bit the same numbers
/// (NaN where the CSV is empty), and `npy/` holds nothing else.
fn assert_npy_matches_csv(out: &Path) -> usize {
    let (names, columns) = read_csv(&out.join("trajectory.csv"));
    let expected: BTreeSet<String> = names.iter().map(|n| format!("{n}.npy")).collect();
    assert_eq!(files_in(&out.join("npy")), expected);
    for (name, column) in names.iter().zip(&columns) {
        let values = Array::read(&out.join("npy").join(format!("{name}.npy"))).f64s();
        assert_eq!(values.len(), column.len(), "{name}: row count");
        for (k, (value, csv)) in values.iter().zip(column).enumerate() {
            match csv {
                Some(csv) => assert_eq!(value.to_bits(), csv.to_bits(), "{name}[{k}]: {value} vs {csv}"),
                None => assert!(value.is_nan(), "{name}[{k}]: {value} where the CSV is empty"),
            }
        }
    }
    let rows = columns[0].len();
    let discrete = &columns[names.iter().position(|n| n == "discrete_energy").unwrap()];
    assert!(discrete[..rows - 1].iter().all(Option::is_some) && discrete[rows - 1].is_none());
    rows
}

#[test]
fn npy_columns_equal_the_csv_columns_bit_for_bit() {
    let dir = TempDir::new("cp");
    succeed(CHARGED_PARTICLE, &["--format", "csv,npy"], &dir);
    assert_eq!(assert_npy_matches_csv(&dir.out()), 101);
    let expected: BTreeSet<String> =
        [".ddirac-files", "exact.csv", "npy", "summary.json", "trajectory.csv"].map(str::to_owned).into();
    assert_eq!(files_in(&dir.out()), expected);

    // Another system, and a number of steps that is not a multiple of `every` (the last row is written).
    let dir = TempDir::new("dsp");
    let sets = ["--set", "output.every=7", "--set", "time.steps=100", "--set", "time.duration=1.0"];
    succeed(PENDULUM, &[&["--format", "npy,csv"][..], &sets].concat(), &dir);
    assert_eq!(assert_npy_matches_csv(&dir.out()), 16);
    let names = files_in(&dir.out().join("npy"));
    for name in ["t.npy", "vartheta1.npy", "p_phi2.npy", "discrete_energy.npy", "momentum_vartheta1.npy"] {
        assert!(names.contains(name), "no {name} in {names:?}");
    }
}

#[test]
fn the_format_is_chosen_by_the_spec_and_overridden_by_the_flag() {
    let dir = TempDir::new("spec-format");
    succeed(CHARGED_PARTICLE, &["--set", "output.format=[\"npy\"]"], &dir);
    let expected: BTreeSet<String> = [".ddirac-files", "npy", "summary.json"].map(str::to_owned).into();
    assert_eq!(files_in(&dir.out()), expected, "`format = [\"npy\"]` writes no CSV, not even `exact.csv`");
    let t = Array::read(&dir.out().join("npy/t.npy")).f64s();
    assert_eq!(t.len(), 101);
    assert_eq!(t[100], 20.0);

    let dir = TempDir::new("flag-format");
    succeed(CHARGED_PARTICLE, &["--set", "output.format=[\"npy\"]", "--format", "csv"], &dir);
    let expected: BTreeSet<String> =
        [".ddirac-files", "exact.csv", "summary.json", "trajectory.csv"].map(str::to_owned).into();
    assert_eq!(files_in(&dir.out()), expected, "`--format csv` overrides the spec");

    let dir = TempDir::new("bad-format");
    let output = run(CHARGED_PARTICLE, &["--set", "output.format=[\"npz\"]"], &dir);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(stderr.contains("unknown variant `npz`, expected `csv` or `npy`"), "{stderr}");
    let output = run(CHARGED_PARTICLE, &["--set", "output.format=[]"], &dir);
    assert!(String::from_utf8_lossy(&output.stderr).contains("`output.format` is empty"));
    assert!(!dir.out().exists());
}

#[test]
fn failed_runs_leave_no_npy_file_and_keep_earlier_ones() {
    let failing = ["--format", "csv,npy", "--set", "method.max_iterations=1", "--set", "method.tolerance=1e-16"];
    let fresh = TempDir::new("fail-fresh");
    let output = run(CHARGED_PARTICLE, &failing, &fresh);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("Newton's method"));
    assert!(!fresh.out().exists(), "a failed run into a new directory leaves {:?}", files_in(&fresh.out()));

    let dir = TempDir::new("fail-over");
    succeed(CHARGED_PARTICLE, &["--format", "npy,csv"], &dir);
    let before = std::fs::read(dir.out().join("npy/q1.npy")).unwrap();
    let output = run(CHARGED_PARTICLE, &failing, &dir);
    assert!(!output.status.success());
    assert_eq!(std::fs::read(dir.out().join("npy/q1.npy")).unwrap(), before);
    assert_eq!(assert_npy_matches_csv(&dir.out()), 101, "no temporary stays beside the earlier files");
}

/// NumPy reads the files and finds the CSV's numbers; skipped when NumPy is not importable.
#[test]
fn numpy_reads_the_files() {
    let available = Command::new("python3").args(["-c", "import numpy"]).output().is_ok_and(|o| o.status.success());
    if !available {
        eprintln!("numpy_reads_the_files: skipped, `python3 -c \"import numpy\"` fails");
        return;
    }
    let dir = TempDir::new("numpy");
    let sets = ["--set", "output.every=1", "--set", "time.steps=50", "--set", "time.duration=0.5"];
    succeed(PENDULUM, &[&["--format", "csv,npy"][..], &sets].concat(), &dir);
    let script = r#"
import sys, numpy as np
out = sys.argv[1]
csv = np.genfromtxt(out + "/trajectory.csv", delimiter=",", names=True)
for name in csv.dtype.names:
    a = np.load(out + "/npy/" + name + ".npy")
    assert a.dtype == np.float64 and a.shape == (51,), (name, a.dtype, a.shape)
    assert np.array_equal(a, csv[name], equal_nan=True), name
assert np.isnan(np.load(out + "/npy/discrete_energy.npy")[-1])
print("checked", len(csv.dtype.names))
"#;
    let output = Command::new("python3").args(["-c", script, dir.out().to_str().unwrap()]).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    // The double spherical pendulum switches charts: its trajectory has a `chart` column.
    assert_eq!(String::from_utf8_lossy(&output.stdout).trim(), "checked 13");
}
