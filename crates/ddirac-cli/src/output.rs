//! Output files written atomically: each file is written under a temporary name in the target
//! directory (`.trajectory.csv.partial`) and renamed into place only after the whole run succeeded,
//! so an interrupted or failed run never leaves a file that looks finished, nor clobbers the
//! finished files of an earlier run.

use std::fmt::Write as _;
use std::fs::File;
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};

use ddirac::Row;

/// A file under its temporary name; removed on drop unless committed.
#[derive(Debug)]
pub struct Staged {
    temporary: PathBuf,
    target: PathBuf,
    committed: bool,
}

impl Staged {
    fn new(dir: &Path, name: &str) -> Self {
        Self { temporary: dir.join(format!(".{name}.partial")), target: dir.join(name), committed: false }
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.temporary);
        }
    }
}

/// Renames every staged file into place, in order. If one rename fails, the files already renamed
/// by this call are removed again and the remaining temporaries are dropped.
pub fn commit(files: Vec<Staged>) -> io::Result<()> {
    let mut done: Vec<PathBuf> = vec![];
    for mut file in files {
        if let Err(e) = std::fs::rename(&file.temporary, &file.target) {
            for path in &done {
                let _ = std::fs::remove_file(path);
            }
            return Err(e);
        }
        file.committed = true;
        done.push(file.target.clone());
    }
    Ok(())
}

/// `trajectory.csv`, streamed row by row.
pub struct Trajectory {
    staged: Staged,
    writer: csv::Writer<File>,
    field: String,
}

impl Trajectory {
    /// File name in the output directory.
    pub const NAME: &'static str = "trajectory.csv";

    /// Creates the temporary file and writes the header
    /// `t, <q names>, p_<name>..., energy, discrete_energy, momentum_<group name>...`.
    pub fn create(dir: &Path, coordinates: &[String], group: &[String]) -> io::Result<Self> {
        let staged = Staged::new(dir, Self::NAME);
        let mut writer = csv::Writer::from_writer(File::create(&staged.temporary)?);
        let header = std::iter::once("t".to_owned())
            .chain(coordinates.iter().cloned())
            .chain(coordinates.iter().map(|c| format!("p_{c}")))
            .chain(["energy".to_owned(), "discrete_energy".to_owned()])
            .chain(group.iter().map(|g| format!("momentum_{g}")));
        writer.write_record(header)?;
        Ok(Self { staged, writer, field: String::new() })
    }

    /// Appends one row; numbers are written with `{}`, which round-trips every f64.
    /// The last row has an empty `discrete_energy`.
    pub fn write(&mut self, row: &Row<'_>) -> io::Result<()> {
        let numbers = std::iter::once(Some(row.t))
            .chain(row.q.iter().chain(row.p).map(|&v| Some(v)))
            .chain([Some(row.energy), row.discrete_energy])
            .chain(row.momentum_map.iter().map(|&v| Some(v)));
        for value in numbers {
            self.field.clear();
            if let Some(v) = value {
                write!(self.field, "{v}").expect("writing to a String cannot fail");
            }
            self.writer.write_field(&self.field)?;
        }
        self.writer.write_record(None::<&[u8]>)?;
        Ok(())
    }

    /// Flushes and syncs the temporary file; it still has to be [`commit`]ted.
    pub fn finish(self) -> io::Result<Staged> {
        let file = self.writer.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        Ok(self.staged)
    }
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

    #[test]
    fn files_appear_only_on_commit_and_temporaries_never_stay() {
        let dir = std::env::temp_dir().join(format!("ddirac-output-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let names = ["q".to_owned()];
        let mut t = Trajectory::create(&dir, &names, &names).unwrap();
        let row =
            Row { k: 0, t: 0.1, q: &[1.0 / 3.0], p: &[2.0], energy: 3.0, discrete_energy: None, momentum_map: &[2.0] };
        t.write(&row).unwrap();
        let staged = t.finish().unwrap();
        assert!(dir.join(".trajectory.csv.partial").exists());
        assert!(!dir.join("trajectory.csv").exists());
        let dropped = json(&dir, "summary.json", &serde_json::json!({"a": 1})).unwrap();
        drop(dropped);
        assert!(!dir.join(".summary.json.partial").exists());
        commit(vec![staged]).unwrap();
        let text = std::fs::read_to_string(dir.join("trajectory.csv")).unwrap();
        assert_eq!(text, "t,q,p_q,energy,discrete_energy,momentum_q\n0.1,0.3333333333333333,2,3,,2\n");
        assert!(!dir.join(".trajectory.csv.partial").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
