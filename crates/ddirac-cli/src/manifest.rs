//! The list of the files a run wrote into its output directory: `DIR/.ddirac-files`, one path per
//! line relative to the directory (`trajectory.csv`, `npy/t.npy`, `coordinates.png`, ...).
//!
//! The next run into the directory reads it to replace the earlier run's files as a set: what the
//! earlier run wrote and the new one does not is removed, and nothing else. Entries that could
//! leave the directory (absolute paths, `..`) or name ddirac's own bookkeeping are ignored, so a
//! damaged or edited list can never make a run delete a file outside its directory.

use std::io::{self, Write};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::lock;

/// Name of the list in an output directory.
pub const NAME: &str = ".ddirac-files";

const HEADER: &str = "# Files written by the ddirac run in this directory, relative to it. The next run into the \
                      directory replaces them as a set.";

/// The files listed in `dir`'s list; none if there is no list.
pub fn read(dir: &Path) -> io::Result<Vec<PathBuf>> {
    let text = match std::fs::read_to_string(dir.join(NAME)) {
        Ok(text) => text,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(vec![]),
        Err(e) => return Err(e),
    };
    Ok(text.lines().filter(|l| !l.starts_with('#')).map(PathBuf::from).filter(|p| acceptable(p)).collect())
}

/// Whether `entry` names a file strictly inside the directory, other than the list and the lock.
fn acceptable(entry: &Path) -> bool {
    let normal = entry.components().count() > 0 && entry.components().all(|c| matches!(c, Component::Normal(_)));
    normal && entry != Path::new(NAME) && entry != Path::new(lock::NAME)
}

/// Replaces `dir`'s list by `files` (written under a unique temporary name, then renamed).
pub fn write(dir: &Path, files: &[PathBuf]) -> io::Result<()> {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let temporary = dir.join(format!("{NAME}.{}-{n}.partial", std::process::id()));
    let mut text = format!("{HEADER}\n");
    for file in files.iter().filter(|f| acceptable(f)) {
        let line: Vec<String> = file.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
        text.push_str(&line.join("/"));
        text.push('\n');
    }
    let written = std::fs::File::create(&temporary).and_then(|mut f| {
        f.write_all(text.as_bytes())?;
        f.sync_all()
    });
    match written.and_then(|()| std::fs::rename(&temporary, dir.join(NAME))) {
        Ok(()) => Ok(()),
        Err(e) => {
            let _ = std::fs::remove_file(&temporary);
            Err(e)
        }
    }
}

/// Adds `files` (paths inside `dir`) to the list of `dir`, if it has one: figures drawn later by
/// `ddirac plot` belong to the run whose data they show.
pub fn record(dir: &Path, files: &[PathBuf]) -> io::Result<()> {
    if !dir.join(NAME).exists() {
        return Ok(());
    }
    let mut listed = read(dir)?;
    for file in files {
        let relative = file.strip_prefix(dir).unwrap_or(file).to_path_buf();
        if !listed.contains(&relative) {
            listed.push(relative);
        }
    }
    write(dir, &listed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_outside_the_directory_or_of_its_bookkeeping_are_ignored() {
        let dir = std::env::temp_dir().join(format!("ddirac-manifest-test-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        assert!(read(&dir).unwrap().is_empty());
        let text =
            "# comment\ntrajectory.csv\nnpy/t.npy\n../elsewhere.csv\n/etc/passwd\n\n.ddirac.lock\n.ddirac-files\n";
        std::fs::write(dir.join(NAME), text).unwrap();
        assert_eq!(read(&dir).unwrap(), [PathBuf::from("trajectory.csv"), PathBuf::from("npy/t.npy")]);
        record(&dir, &[dir.join("coordinates.png"), dir.join("npy/t.npy")]).unwrap();
        let listed = read(&dir).unwrap();
        assert_eq!(listed, ["trajectory.csv", "npy/t.npy", "coordinates.png"].map(PathBuf::from));
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "a temporary stays beside the list");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
