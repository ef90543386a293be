//! The files of a run's trajectory, written into the run's staging directory (see
//! [`crate::run_dir`]), which moves them into the output directory only after the whole run
//! succeeded: an interrupted or failed run never leaves a file that looks finished, nor clobbers the
//! finished files of an earlier run.
//!
//! The trajectory is written in the [`Format`]s asked for: `csv` is `trajectory.csv`; `npy` is one
//! NumPy file per column of the CSV, with the same names, in the subdirectory `npy/` (`npy/t.npy`,
//! `npy/q1.npy`, `npy/p_q1.npy`, ..., `npy/energy.npy`, `npy/discrete_energy.npy` with NaN on the
//! last row, `npy/momentum_theta.npy`). Rows are streamed to every file as they come; nothing of
//! the trajectory is kept in memory.
//!
//! CSV numbers are the shortest decimal strings that read back as the same f64 ([`write_number`]):
//! positional between 10⁻⁴ and 10¹⁶, with an exponent outside (`1e-300`, not 300 characters).

use std::fmt::Write as _;
use std::fs::File;
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};

use ddirac::Row;
use toml::Spanned;

use crate::diagnostics::{SpecError, SpecSource};
use crate::npy;

/// A file format of the trajectory.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// `trajectory.csv`.
    Csv,
    /// `npy/<column>.npy`, one little-endian f64 array per column.
    Npy,
}

/// The formats a run writes: at least one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Formats {
    /// Write `trajectory.csv`.
    pub csv: bool,
    /// Write `npy/*.npy`.
    pub npy: bool,
}

impl Formats {
    /// The formats of a list (repetitions are harmless).
    pub fn of(list: &[Format]) -> Self {
        Self { csv: list.contains(&Format::Csv), npy: list.contains(&Format::Npy) }
    }

    /// The formats of `--format` if given (non-empty `flag`), else of `output.format`, else CSV only.
    pub fn choose(
        flag: &[Format],
        spec: Option<&Spanned<Vec<Format>>>,
        source: &SpecSource,
    ) -> Result<Self, Box<SpecError>> {
        if !flag.is_empty() {
            return Ok(Self::of(flag));
        }
        match spec {
            Some(list) if list.get_ref().is_empty() => Err(source
                .error(Some(list.span()), "`output.format` is empty", "no format")
                .with_help("write `format = [\"csv\"]`, `[\"npy\"]` or `[\"csv\", \"npy\"]`, or remove the key")),
            Some(list) => Ok(Self::of(list.get_ref())),
            None => Ok(Self::of(&[Format::Csv])),
        }
    }
}

/// The column names: `t, <q names>, p_<name>..., energy, discrete_energy, momentum_<group name>...`,
/// and `chart` (the chart of the atlas each step was in, 0 for the main chart) when the run switches
/// charts.
pub fn columns(coordinates: &[String], group: &[String], chart: bool) -> Vec<String> {
    std::iter::once("t".to_owned())
        .chain(coordinates.iter().cloned())
        .chain(coordinates.iter().map(|c| format!("p_{c}")))
        .chain(["energy".to_owned(), "discrete_energy".to_owned()])
        .chain(group.iter().map(|g| format!("momentum_{g}")))
        .chain(chart.then(|| "chart".to_owned()))
        .collect()
}

/// An I/O error on one file, naming it.
#[derive(Debug, thiserror::Error)]
#[error("cannot write `{}`: {source}", path.display())]
pub struct FileError {
    /// The file (or directory) the operation concerned.
    pub path: PathBuf,
    /// Why it failed.
    #[source]
    pub source: io::Error,
}

/// `Err(e)` as a [`FileError`] about `path`.
pub fn at<T>(path: &Path, result: io::Result<T>) -> Result<T, FileError> {
    result.map_err(|source| FileError { path: path.to_owned(), source })
}

/// The trajectory, streamed row by row to `trajectory.csv` and/or `npy/<column>.npy`.
pub struct Trajectory {
    csv: Option<(csv::Writer<File>, PathBuf)>,
    npy: Vec<(npy::Column, PathBuf)>,
    field: String,
    dir: PathBuf,
    chart: bool,
}

impl Trajectory {
    /// Name of the CSV file in the output directory.
    pub const CSV: &'static str = "trajectory.csv";
    /// Name of the subdirectory of the NumPy files.
    pub const NPY_DIR: &'static str = "npy";

    /// Creates the files in the (empty) directory `dir`; the CSV starts with its header (see
    /// [`columns`]), each `.npy` file with a header for 0 rows.
    ///
    /// The `.npy` files are named after the columns, which must be distinct and made of ASCII letters,
    /// digits and `_` (as the names of built-in and expression coordinates are).
    pub fn create(
        dir: &Path,
        coordinates: &[String],
        group: &[String],
        chart: bool,
        formats: Formats,
    ) -> Result<Self, FileError> {
        let mut trajectory = Self::with_columns(dir, &columns(coordinates, group, chart), formats)?;
        trajectory.chart = chart;
        Ok(trajectory)
    }

    /// Creates the files of a trajectory with the columns `names` in the (empty) directory `dir`,
    /// for rows written by [`Trajectory::write_values`].
    pub fn with_columns(dir: &Path, names: &[String], formats: Formats) -> Result<Self, FileError> {
        let csv = match formats.csv {
            true => {
                let path = dir.join(Self::CSV);
                let mut writer = csv::Writer::from_writer(at(&path, File::create(&path))?);
                at(&path, writer.write_record(names).map_err(io::Error::from))?;
                Some((writer, path))
            }
            false => None,
        };
        let npy = match formats.npy {
            true => {
                let npy_dir = dir.join(Self::NPY_DIR);
                at(&npy_dir, check_file_names(names))?;
                // Not `create_dir_all`: once a signal has removed the staging directory, nothing
                // of the run may reappear.
                at(&npy_dir, std::fs::create_dir(&npy_dir))?;
                names
                    .iter()
                    .map(|name| {
                        let path = npy_dir.join(format!("{name}.npy"));
                        Ok((at(&path, npy::Column::create(&path))?, path))
                    })
                    .collect::<Result<_, FileError>>()?
            }
            false => vec![],
        };
        Ok(Self { csv, npy, field: String::new(), dir: dir.to_owned(), chart: false })
    }

    /// Appends one row. The last row has an empty `discrete_energy` in the CSV and NaN in
    /// `discrete_energy.npy`.
    pub fn write(&mut self, row: &Row<'_>) -> Result<(), FileError> {
        let chart = self.chart;
        let numbers = || {
            std::iter::once(Some(row.t))
                .chain(row.q.iter().chain(row.p).map(|&v| Some(v)))
                .chain([Some(row.energy), row.discrete_energy])
                .chain(row.momentum_map.iter().map(|&v| Some(v)))
                .chain(chart.then_some(Some(row.chart as f64)))
        };
        self.write_values(numbers)
    }

    /// Appends one row of values, one per column (`None`: an empty CSV field, NaN in the `.npy` file).
    pub fn write_values<I: Iterator<Item = Option<f64>>>(&mut self, numbers: impl Fn() -> I) -> Result<(), FileError> {
        if let Some((writer, path)) = &mut self.csv {
            for value in numbers() {
                self.field.clear();
                if let Some(v) = value {
                    write_number(&mut self.field, v);
                }
                at(path, writer.write_field(&self.field).map_err(io::Error::from))?;
            }
            at(path, writer.write_record(None::<&[u8]>).map_err(io::Error::from))?;
        }
        for ((column, path), value) in self.npy.iter_mut().zip(numbers()) {
            at(path, column.push(value.unwrap_or(f64::NAN)))?;
        }
        Ok(())
    }

    /// Flushes and syncs the files (writing the row count into each `.npy` header); returns their
    /// names relative to the directory, the `.npy` files first and the CSV last.
    pub fn finish(mut self) -> Result<Vec<PathBuf>, FileError> {
        let mut written = vec![];
        for (column, path) in std::mem::take(&mut self.npy) {
            at(&path, column.finish())?;
            written.push(path);
        }
        if let Some((writer, path)) = self.csv.take() {
            let inner = at(&path, writer.into_inner().map_err(|e| e.into_error()))?;
            at(&path, inner.sync_all())?;
            written.push(path);
        }
        Ok(written.into_iter().map(|p| p.strip_prefix(&self.dir).map_or(p.clone(), Path::to_path_buf)).collect())
    }
}

/// Appends `v` to `field` as the shortest decimal string that reads back as `v`: positional for
/// 10⁻⁴ ≤ |v| < 10¹⁶ and 0 (`0.1`, `2`, `-0`), with an exponent otherwise (`1e-300`,
/// `1.2345e20`). Rust's `{}` and `{:e}` both print the fewest digits that round-trip; only the
/// notation is chosen here.
pub fn write_number(field: &mut String, v: f64) {
    let magnitude = v.abs();
    let positional = magnitude == 0.0 || !v.is_finite() || (1e-4..1e16).contains(&magnitude);
    let written = if positional { write!(field, "{v}") } else { write!(field, "{v:e}") };
    written.expect("writing to a String cannot fail");
}

/// `v` as [`write_number`] writes it.
pub fn number(v: f64) -> String {
    let mut text = String::new();
    write_number(&mut text, v);
    text
}

/// Refuses column names that are not plain file names, or that repeat (a coordinate named
/// `energy`, say: the spec refuses those before a run starts).
fn check_file_names(names: &[String]) -> io::Result<()> {
    for (i, name) in names.iter().enumerate() {
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("the column `{name}` cannot name a .npy file (only ASCII letters, digits and `_`)"),
            ));
        }
        if names[..i].contains(name) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("two columns are named `{name}`: rename the coordinate to write .npy files"),
            ));
        }
    }
    Ok(())
}

/// Writes `value` as pretty JSON to `dir/name`; returns `name`.
pub fn json(dir: &Path, name: &str, value: &impl serde::Serialize) -> Result<PathBuf, FileError> {
    let path = dir.join(name);
    let mut file = at(&path, File::create(&path))?;
    at(&path, serde_json::to_writer_pretty(&mut file, value).map_err(io::Error::from))?;
    at(&path, file.write_all(b"\n"))?;
    at(&path, file.sync_all())?;
    Ok(PathBuf::from(name))
}

impl From<FileError> for crate::diagnostics::CliError {
    fn from(e: FileError) -> Self {
        Self::Output { path: e.path, source: e.source }
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    fn temp_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("ddirac-output-test-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    const ROW: Row<'static> = Row {
        k: 0,
        t: 0.1,
        q: &[1.0 / 3.0],
        p: &[2.0],
        energy: 3.0,
        discrete_energy: None,
        momentum_map: &[2.0],
        chart: 0,
    };

    #[test]
    fn the_csv_holds_the_header_and_the_rows() {
        let dir = temp_dir("csv");
        let names = ["q".to_owned()];
        let mut t = Trajectory::create(&dir, &names, &names, false, Formats::of(&[Format::Csv])).unwrap();
        t.write(&ROW).unwrap();
        assert_eq!(t.finish().unwrap(), [PathBuf::from("trajectory.csv")]);
        assert!(!dir.join("npy").exists());
        let text = std::fs::read_to_string(dir.join("trajectory.csv")).unwrap();
        assert_eq!(text, "t,q,p_q,energy,discrete_energy,momentum_q\n0.1,0.3333333333333333,2,3,,2\n");
        assert_eq!(json(&dir, "summary.json", &serde_json::json!({"a": 1})).unwrap(), PathBuf::from("summary.json"));
        assert_eq!(std::fs::read_to_string(dir.join("summary.json")).unwrap(), "{\n  \"a\": 1\n}\n");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn npy_files_hold_the_row_count_and_nan_for_the_last_discrete_energy() {
        let dir = temp_dir("npy");
        let names = ["q".to_owned()];
        let mut t = Trajectory::create(&dir, &names, &names, false, Formats::of(&[Format::Npy])).unwrap();
        t.write(&ROW).unwrap();
        t.write(&ROW).unwrap();
        let written = t.finish().unwrap();
        assert_eq!(written.len(), 6);
        assert!(written.iter().all(|p| p.starts_with("npy") && p.extension().is_some_and(|e| e == "npy")));
        assert!(!dir.join("trajectory.csv").exists());
        let bytes = std::fs::read(dir.join("npy/discrete_energy.npy")).unwrap();
        assert_eq!(&bytes[..npy::HEADER_LEN], &npy::header(2));
        assert_eq!(bytes.len(), npy::HEADER_LEN + 16);
        assert!(f64::from_le_bytes(bytes[npy::HEADER_LEN..][..8].try_into().unwrap()).is_nan());
        let q = std::fs::read(dir.join("npy/q.npy")).unwrap();
        assert_eq!(f64::from_le_bytes(q[npy::HEADER_LEN..][..8].try_into().unwrap()), 1.0 / 3.0);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn column_names_that_clash_or_are_not_file_names_are_refused() {
        let dir = temp_dir("names");
        let npy = Formats::of(&[Format::Npy]);
        for bad in ["energy", "a/b", "..", ""] {
            let names = [bad.to_owned()];
            let error = Trajectory::create(&dir, &names, &[], false, npy).err().expect(bad);
            assert_eq!(error.source.kind(), io::ErrorKind::InvalidInput, "{bad}");
            assert_eq!(error.path, dir.join("npy"));
        }
        assert!(!dir.join("npy").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    fn written(v: f64) -> String {
        let mut field = String::new();
        write_number(&mut field, v);
        field
    }

    #[test]
    fn extreme_numbers_are_short_and_read_back_exactly() {
        let subnormal = f64::from_bits(1);
        let cases = [
            (0.0, "0"),
            (-0.0, "-0"),
            (1e-300, "1e-300"),
            (subnormal, "5e-324"),
            (-f64::MIN_POSITIVE, "-2.2250738585072014e-308"),
            (f64::MAX, "1.7976931348623157e308"),
            (1e16, "1e16"),
            (9999999999999998.0, "9999999999999998"),
            (1e-4, "0.0001"),
            (9.999999999999999e-5, "9.999999999999999e-5"),
            (0.1, "0.1"),
            (-2.5, "-2.5"),
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
        ];
        for (v, expected) in cases {
            let text = written(v);
            assert_eq!(text, expected);
            let back: f64 = text.parse().unwrap();
            assert!(back.to_bits() == v.to_bits() || (v.is_nan() && back.is_nan()), "{v:e} → {text}");
        }
    }

    proptest! {
        #[test]
        fn every_finite_number_reads_back_bit_for_bit_in_at_most_24_characters(bits in any::<u64>()) {
            let v = f64::from_bits(bits);
            prop_assume!(v.is_finite());
            let text = written(v);
            prop_assert!(text.len() <= 24, "{} has {} characters", text, text.len());
            prop_assert_eq!(text.parse::<f64>().unwrap().to_bits(), bits);
        }

        #[test]
        fn tiny_and_huge_magnitudes_read_back_bit_for_bit(mantissa in 1.0f64..10.0, exponent in -324i32..309) {
            let v = mantissa * 10f64.powi(exponent);
            prop_assume!(v.is_finite());
            let text = written(v);
            prop_assert!(text.len() <= 24, "{} has {} characters", text, text.len());
            prop_assert_eq!(text.parse::<f64>().unwrap().to_bits(), v.to_bits());
        }
    }
}
