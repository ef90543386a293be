//! Output files written atomically: each file is written under a temporary name in its target
//! directory (`.trajectory.csv.partial`, `npy/.t.npy.partial`) and renamed into place only after the
//! whole run succeeded, so an interrupted or failed run never leaves a file that looks finished, nor
//! clobbers the finished files of an earlier run.
//!
//! The trajectory is written in the [`Format`]s asked for: `csv` is `trajectory.csv`; `npy` is one
//! NumPy file per column of the CSV, with the same names, in the subdirectory `npy/` (`npy/t.npy`,
//! `npy/q1.npy`, `npy/p_q1.npy`, ..., `npy/energy.npy`, `npy/discrete_energy.npy` with NaN on the
//! last row, `npy/momentum_theta.npy`). Rows are streamed to every file as they come; nothing of
//! the trajectory is kept in memory.

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

/// A file under its temporary name; removed on drop unless committed.
#[derive(Debug)]
pub struct Staged {
    temporary: PathBuf,
    target: PathBuf,
    committed: bool,
    /// A directory created for this file, removed with it if it is then empty.
    created_dir: Option<PathBuf>,
}

impl Staged {
    fn new(dir: &Path, name: &str) -> Self {
        Self {
            temporary: dir.join(format!(".{name}.partial")),
            target: dir.join(name),
            committed: false,
            created_dir: None,
        }
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.temporary);
            if let Some(dir) = &self.created_dir {
                // Fails, as it should, while the directory still holds anything.
                let _ = std::fs::remove_dir(dir);
            }
        }
    }
}

/// Renames every staged file into place, in order. If one rename fails, the files already renamed
/// by this call are removed again and the remaining temporaries are dropped.
pub fn commit(files: Vec<Staged>) -> io::Result<()> {
    let mut done: Vec<(PathBuf, Option<PathBuf>)> = vec![];
    for mut file in files {
        if let Err(e) = std::fs::rename(&file.temporary, &file.target) {
            for (path, _) in &done {
                let _ = std::fs::remove_file(path);
            }
            for dir in done.iter().filter_map(|(_, dir)| dir.as_ref()) {
                let _ = std::fs::remove_dir(dir);
            }
            return Err(e);
        }
        file.committed = true;
        done.push((file.target.clone(), file.created_dir.take()));
    }
    Ok(())
}

/// The column names: `t, <q names>, p_<name>..., energy, discrete_energy, momentum_<group name>...`.
pub fn columns(coordinates: &[String], group: &[String]) -> Vec<String> {
    std::iter::once("t".to_owned())
        .chain(coordinates.iter().cloned())
        .chain(coordinates.iter().map(|c| format!("p_{c}")))
        .chain(["energy".to_owned(), "discrete_energy".to_owned()])
        .chain(group.iter().map(|g| format!("momentum_{g}")))
        .collect()
}

/// The trajectory, streamed row by row to `trajectory.csv` and/or `npy/<column>.npy`.
pub struct Trajectory {
    csv: Option<(csv::Writer<File>, Staged)>,
    npy: Vec<(npy::Column, Staged)>,
    field: String,
}

impl Trajectory {
    /// Name of the CSV file in the output directory.
    pub const CSV: &'static str = "trajectory.csv";
    /// Name of the subdirectory of the NumPy files.
    pub const NPY_DIR: &'static str = "npy";

    /// Creates the temporary files; the CSV starts with its header (see [`columns`]), each `.npy`
    /// file with a header for 0 rows.
    ///
    /// The `.npy` files are named after the columns, which must be distinct and made of ASCII letters,
    /// digits and `_` (as the names of built-in and expression coordinates are).
    pub fn create(dir: &Path, coordinates: &[String], group: &[String], formats: Formats) -> io::Result<Self> {
        let names = columns(coordinates, group);
        let csv = match formats.csv {
            true => {
                let staged = Staged::new(dir, Self::CSV);
                let mut writer = csv::Writer::from_writer(File::create(&staged.temporary)?);
                writer.write_record(&names)?;
                Some((writer, staged))
            }
            false => None,
        };
        let npy = match formats.npy {
            true => {
                check_file_names(&names)?;
                let npy_dir = dir.join(Self::NPY_DIR);
                let created = !npy_dir.exists();
                std::fs::create_dir_all(&npy_dir)?;
                // On a failure the files made so far are dropped, and with the last of them the
                // directory if this call made it.
                names
                    .iter()
                    .map(|name| {
                        let mut staged = Staged::new(&npy_dir, &format!("{name}.npy"));
                        staged.created_dir = created.then(|| npy_dir.clone());
                        Ok((npy::Column::create(&staged.temporary)?, staged))
                    })
                    .collect::<io::Result<_>>()?
            }
            false => vec![],
        };
        Ok(Self { csv, npy, field: String::new() })
    }

    /// Appends one row. CSV numbers are written with `{}`, which round-trips every f64; the last
    /// row has an empty `discrete_energy` in the CSV and NaN in `discrete_energy.npy`.
    pub fn write(&mut self, row: &Row<'_>) -> io::Result<()> {
        let numbers = || {
            std::iter::once(Some(row.t))
                .chain(row.q.iter().chain(row.p).map(|&v| Some(v)))
                .chain([Some(row.energy), row.discrete_energy])
                .chain(row.momentum_map.iter().map(|&v| Some(v)))
        };
        if let Some((writer, _)) = &mut self.csv {
            for value in numbers() {
                self.field.clear();
                if let Some(v) = value {
                    write!(self.field, "{v}").expect("writing to a String cannot fail");
                }
                writer.write_field(&self.field)?;
            }
            writer.write_record(None::<&[u8]>)?;
        }
        for ((column, _), value) in self.npy.iter_mut().zip(numbers()) {
            column.push(value.unwrap_or(f64::NAN))?;
        }
        Ok(())
    }

    /// Flushes and syncs the temporary files (writing the row count into each `.npy` header); they
    /// still have to be [`commit`]ted. The `.npy` files come first, the CSV last.
    pub fn finish(mut self) -> io::Result<Vec<Staged>> {
        let mut staged = vec![];
        for (column, file) in std::mem::take(&mut self.npy) {
            column.finish()?;
            staged.push(file);
        }
        if let Some((writer, file)) = self.csv.take() {
            let inner = writer.into_inner().map_err(|e| e.into_error())?;
            inner.sync_all()?;
            staged.push(file);
        }
        Ok(staged)
    }
}

/// Refuses column names that are not plain file names, or that repeat (a coordinate named
/// `energy`, say).
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

/// Writes `value` as pretty JSON to a temporary file named after `name`, to be [`commit`]ted.
pub fn json(dir: &Path, name: &str, value: &impl serde::Serialize) -> io::Result<Staged> {
    let staged = Staged::new(dir, name);
    let mut file = File::create(&staged.temporary)?;
    serde_json::to_writer_pretty(&mut file, value)?;
    file.write_all(b"\n")?;
    file.sync_all()?;
    Ok(staged)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("ddirac-output-test-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    const ROW: Row<'static> =
        Row { k: 0, t: 0.1, q: &[1.0 / 3.0], p: &[2.0], energy: 3.0, discrete_energy: None, momentum_map: &[2.0] };

    #[test]
    fn files_appear_only_on_commit_and_temporaries_never_stay() {
        let dir = temp_dir("commit");
        let names = ["q".to_owned()];
        let mut t = Trajectory::create(&dir, &names, &names, Formats::of(&[Format::Csv])).unwrap();
        t.write(&ROW).unwrap();
        let staged = t.finish().unwrap();
        assert!(dir.join(".trajectory.csv.partial").exists());
        assert!(!dir.join("trajectory.csv").exists());
        assert!(!dir.join("npy").exists());
        let dropped = json(&dir, "summary.json", &serde_json::json!({"a": 1})).unwrap();
        drop(dropped);
        assert!(!dir.join(".summary.json.partial").exists());
        commit(staged).unwrap();
        let text = std::fs::read_to_string(dir.join("trajectory.csv")).unwrap();
        assert_eq!(text, "t,q,p_q,energy,discrete_energy,momentum_q\n0.1,0.3333333333333333,2,3,,2\n");
        assert!(!dir.join(".trajectory.csv.partial").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn npy_files_are_staged_and_an_abandoned_run_leaves_no_npy_directory() {
        let dir = temp_dir("npy");
        let names = ["q".to_owned()];
        let formats = Formats::of(&[Format::Npy]);
        let mut t = Trajectory::create(&dir, &names, &names, formats).unwrap();
        t.write(&ROW).unwrap();
        assert!(dir.join("npy/.discrete_energy.npy.partial").exists());
        drop(t);
        assert!(!dir.join("npy").exists(), "the directory made for the run stays behind");

        let mut t = Trajectory::create(&dir, &names, &names, formats).unwrap();
        t.write(&ROW).unwrap();
        t.write(&ROW).unwrap();
        let staged = t.finish().unwrap();
        assert_eq!(staged.len(), 6);
        assert!(!dir.join("trajectory.csv").exists() && !dir.join(".trajectory.csv.partial").exists());
        commit(staged).unwrap();
        let bytes = std::fs::read(dir.join("npy/discrete_energy.npy")).unwrap();
        assert_eq!(&bytes[..npy::HEADER_LEN], &npy::header(2));
        assert_eq!(bytes.len(), npy::HEADER_LEN + 16);
        assert!(f64::from_le_bytes(bytes[npy::HEADER_LEN..][..8].try_into().unwrap()).is_nan());
        let q = std::fs::read(dir.join("npy/q.npy")).unwrap();
        assert_eq!(f64::from_le_bytes(q[npy::HEADER_LEN..][..8].try_into().unwrap()), 1.0 / 3.0);
        let listed = std::fs::read_dir(dir.join("npy")).unwrap().count();
        assert_eq!(listed, 6, "temporaries left beside the committed files");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn column_names_that_clash_or_are_not_file_names_are_refused() {
        let dir = temp_dir("names");
        let npy = Formats::of(&[Format::Npy]);
        for bad in ["energy", "a/b", "..", ""] {
            let names = [bad.to_owned()];
            let error = Trajectory::create(&dir, &names, &[], npy).err().expect(bad);
            assert_eq!(error.kind(), io::ErrorKind::InvalidInput, "{bad}");
        }
        assert!(!dir.join("npy").exists());
        // CSV alone accepts any name.
        assert!(Trajectory::create(&dir, &["a/b".to_owned()], &[], Formats::of(&[Format::Csv])).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
