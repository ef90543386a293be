//! An output directory owned by one run for the run's lifetime.
//!
//! [`RunDir::open`] locks the directory ([`crate::lock`]) and makes a staging directory inside it,
//! `.ddirac-<pid>-<n>.partial`, unique to the run. Everything the run writes (trajectory, summary,
//! figures) goes there under its final name. [`RunDir::commit`] then replaces the files of the
//! earlier run in the directory — those listed in its [`manifest`] — by the new ones, as a set: the
//! earlier files are first moved aside into the staging directory, the new ones moved in, the list
//! rewritten, and the staging directory with the earlier files removed. If a move fails, everything
//! is moved back. A run that fails or is stopped before committing removes its staging directory:
//! the earlier run's files stay as they were.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::diagnostics::CliError;
use crate::lock::{Lock, LockError};
use crate::{manifest, signals};

/// Subdirectory of the staging directory that holds the earlier run's files during a commit.
const PREVIOUS: &str = "previous";

/// A locked output directory with the staging directory of the run.
#[derive(Debug)]
pub struct RunDir {
    dir: PathBuf,
    staging: PathBuf,
    /// The output directory did not exist before the run (removed again if the run fails).
    created: bool,
    committed: bool,
    lock: Option<Lock>,
    registration: Option<signals::Registration>,
}

impl RunDir {
    /// Creates `dir` if needed, locks it for this process (described by `command` in the lock) and
    /// makes the staging directory.
    pub fn open(dir: &Path, command: &str) -> Result<Self, CliError> {
        let (lock, created) = lock(dir, command)?;
        remove_stale(dir);
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let staging = dir.join(format!(".ddirac-{}-{n}.partial", std::process::id()));
        let cleanup = signals::Cleanup {
            trees: vec![staging.clone()],
            empty_dirs: if created { vec![dir.to_owned()] } else { vec![] },
            ..Default::default()
        };
        let run_dir = Self {
            dir: dir.to_owned(),
            staging: staging.clone(),
            created,
            committed: false,
            lock: Some(lock),
            registration: Some(signals::register(cleanup)),
        };
        std::fs::create_dir(&staging).map_err(|source| CliError::Output { path: staging, source })?;
        Ok(run_dir)
    }

    /// The directory the run writes its files into, under their final names.
    pub fn staging(&self) -> &Path {
        &self.staging
    }

    /// Replaces the earlier run's files by `files` (paths relative to the staging directory), as a
    /// set; refused once a signal was received.
    pub fn commit(mut self, files: &[PathBuf]) -> Result<(), CliError> {
        signals::check(None)?;
        let result = signals::critical(self.registration.as_ref(), || self.replace(files));
        if result.is_ok() {
            self.committed = true;
            self.registration = None;
        }
        result
    }

    fn replace(&self, files: &[PathBuf]) -> Result<(), CliError> {
        let list = self.dir.join(manifest::NAME);
        let listed = list.exists();
        let earlier = manifest::read(&self.dir).map_err(output_error(&list))?;
        let stale: Vec<&PathBuf> = earlier.iter().filter(|f| !files.contains(f)).collect();
        // Both sets listed while they are swapped: a process killed meanwhile leaves no file that
        // the next run would not know to remove.
        let both: Vec<PathBuf> = earlier.iter().chain(files.iter().filter(|f| !earlier.contains(f))).cloned().collect();
        manifest::write(&self.dir, &both).map_err(output_error(&list))?;

        if let Err(error) = self.swap(&earlier, files) {
            let _ = if listed { manifest::write(&self.dir, &earlier) } else { std::fs::remove_file(&list) };
            return Err(error);
        }
        for file in stale {
            // Directories the earlier run's files were in (`npy/`), if nothing else is left in them.
            for parent in file.ancestors().skip(1).filter(|p| !p.as_os_str().is_empty()) {
                let _ = std::fs::remove_dir(self.dir.join(parent));
            }
        }
        signals::remove_tree(&self.staging);
        Ok(())
    }

    /// Moves the `earlier` files aside and the new `files` in, and lists the new ones; undoes every
    /// move on failure.
    fn swap(&self, earlier: &[PathBuf], files: &[PathBuf]) -> Result<(), CliError> {
        let mut swap = Swap { moves: vec![] };
        let previous = self.staging.join(PREVIOUS);
        for file in earlier.iter().chain(files) {
            let target = self.dir.join(file);
            if std::fs::symlink_metadata(&target).is_ok_and(|m| m.is_file()) {
                let aside = previous.join(file);
                swap.make_parent(&aside)?;
                swap.rename(&target, &aside).map_err(output_error(&target))?;
            }
        }
        for file in files {
            let target = self.dir.join(file);
            swap.make_parent(&target)?;
            swap.rename(&self.staging.join(file), &target).map_err(output_error(&target))?;
        }
        let list = self.dir.join(manifest::NAME);
        manifest::write(&self.dir, files).map_err(output_error(&list))?;
        swap.moves.clear();
        Ok(())
    }
}

impl Drop for RunDir {
    fn drop(&mut self) {
        if !self.committed {
            signals::remove_tree(&self.staging);
        }
        drop(self.lock.take());
        if self.created && !self.committed {
            // Fails, as it should, if anything else is in the directory.
            let _ = std::fs::remove_dir(&self.dir);
        }
        drop(self.registration.take());
    }
}

/// The moves of a commit so far, undone in reverse order unless the commit completes.
struct Swap {
    moves: Vec<(PathBuf, PathBuf)>,
}

impl Swap {
    fn rename(&mut self, from: &Path, to: &Path) -> std::io::Result<()> {
        std::fs::rename(from, to)?;
        self.moves.push((from.to_owned(), to.to_owned()));
        Ok(())
    }

    /// Creates the missing directories above `path`, remembering them as moves to undo.
    fn make_parent(&mut self, path: &Path) -> Result<(), CliError> {
        let Some(parent) = path.parent() else { return Ok(()) };
        if parent.is_dir() {
            return Ok(());
        }
        self.make_parent(parent)?;
        std::fs::create_dir(parent).map_err(output_error(parent))?;
        self.moves.push((PathBuf::new(), parent.to_owned()));
        Ok(())
    }
}

impl Drop for Swap {
    fn drop(&mut self) {
        for (from, to) in self.moves.drain(..).rev() {
            if from.as_os_str().is_empty() {
                let _ = std::fs::remove_dir(&to);
            } else {
                let _ = std::fs::rename(&to, &from);
            }
        }
    }
}

/// Creates `dir` if needed and locks it for this process (described by `command` in the lock);
/// returns the lock and whether the directory was created.
pub fn lock(dir: &Path, command: &str) -> Result<(Lock, bool), CliError> {
    not_a_directory(dir)?;
    let created = !dir.exists();
    std::fs::create_dir_all(dir).map_err(output_error(dir))?;
    Lock::acquire(dir, command).map(|lock| (lock, created)).map_err(|e| {
        if created {
            let _ = std::fs::remove_dir(dir);
        }
        match e {
            LockError::Busy(holder) => CliError::Busy { dir: dir.to_owned(), holder: holder.describe() },
            LockError::Io(path, source) => CliError::Output { path, source },
        }
    })
}

/// Removes what runs that were killed (SIGKILL, a crash) left in `dir`: staging directories
/// `.ddirac-<pid>-<n>.partial` and temporary lists `.ddirac-files.<pid>-<n>.partial`. Called with
/// the lock held, so no live run owns them.
fn remove_stale(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(middle) = name
            .strip_suffix(".partial")
            .and_then(|n| n.strip_prefix(&format!("{}.", manifest::NAME)).or_else(|| n.strip_prefix(".ddirac-")))
        else {
            continue;
        };
        let ours = middle.split_once('-').is_some_and(|(pid, n)| {
            !pid.is_empty() && !n.is_empty() && pid.bytes().chain(n.bytes()).all(|b| b.is_ascii_digit())
        });
        if ours {
            let path = entry.path();
            if path.is_dir() {
                signals::remove_tree(&path);
            } else {
                let _ = std::fs::remove_file(&path);
            }
        }
    }
}

/// An I/O error about `path`.
fn output_error(path: &Path) -> impl FnOnce(std::io::Error) -> CliError {
    let path = path.to_owned();
    move |source| CliError::Output { path, source }
}

/// Refuses an output directory that names a file, or lies below one.
fn not_a_directory(dir: &Path) -> Result<(), CliError> {
    for path in dir.ancestors().filter(|p| !p.as_os_str().is_empty()) {
        if let Ok(metadata) = std::fs::metadata(path) {
            return match metadata.is_dir() {
                true => Ok(()),
                false => Err(CliError::NotADirectory { dir: dir.to_owned(), file: path.to_owned() }),
            };
        }
    }
    Ok(())
}
