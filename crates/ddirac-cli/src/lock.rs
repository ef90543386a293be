//! The lock by which a run owns its output directory: `DIR/.ddirac.lock`, holding the process id,
//! the command and the start time of the run that holds it.
//!
//! The file is locked with `flock` for as long as the run lasts. The operating system releases that
//! lock when the process ends, however it ends, so a lock file left behind by a run that was killed
//! is stale by construction: the next run takes it over (no process id is ever compared, so a
//! reused id cannot keep a directory locked). A second run while the first is alive fails with a
//! message naming the first. The file is removed when the run ends.

use std::fs::{File, OpenOptions};
use std::io::{self, Read, Seek, Write};
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use crate::signals;

/// Name of the lock file in a locked directory.
pub const NAME: &str = ".ddirac.lock";

/// Why a directory cannot be locked.
#[derive(Debug)]
pub enum LockError {
    /// Another live run holds the lock: what its lock file says about it.
    Busy(Holder),
    /// The lock file cannot be created, read or locked.
    Io(PathBuf, io::Error),
}

/// The run that holds a lock, as its lock file describes it.
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct Holder {
    /// Process id.
    pub pid: Option<u32>,
    /// The command line.
    pub command: Option<String>,
    /// Start, in seconds since the Unix epoch.
    pub started: Option<u64>,
}

impl Holder {
    /// This process.
    fn this(command: &str) -> Self {
        let started = SystemTime::now().duration_since(UNIX_EPOCH).map(|d| d.as_secs()).ok();
        Self { pid: Some(std::process::id()), command: Some(command.to_owned()), started }
    }

    fn text(&self) -> String {
        let mut text = String::new();
        if let Some(pid) = self.pid {
            text.push_str(&format!("pid = {pid}\n"));
        }
        if let Some(command) = &self.command {
            text.push_str(&format!("command = {command:?}\n"));
        }
        if let Some(started) = self.started {
            text.push_str(&format!("started = {started}\n"));
        }
        text
    }

    /// Reads what [`Holder::text`] writes; unknown or damaged lines are skipped.
    fn parse(text: &str) -> Self {
        let mut holder = Self::default();
        for line in text.lines() {
            let Some((key, value)) = line.split_once(" = ") else { continue };
            match key {
                "pid" => holder.pid = value.parse().ok(),
                "command" => holder.command = serde_json::from_str(value).ok(),
                "started" => holder.started = value.parse().ok(),
                _ => {}
            }
        }
        holder
    }

    /// `pid 1234, `ddirac run a.toml`, started 12 s ago`, of what is known.
    pub fn describe(&self) -> String {
        let mut parts = vec![self.pid.map_or("process id unknown".to_owned(), |p| format!("pid {p}"))];
        if let Some(command) = &self.command {
            parts.push(format!("`{command}`"));
        }
        if let Some(started) = self.started {
            let now = SystemTime::now().duration_since(UNIX_EPOCH).map_or(started, |d| d.as_secs());
            parts.push(format!("started {} s ago", now.saturating_sub(started)));
        }
        parts.join(", ")
    }
}

/// A held lock; released, and its file removed, on drop.
#[derive(Debug)]
pub struct Lock {
    path: PathBuf,
    file: Option<File>,
    _registration: signals::Registration,
}

impl Lock {
    /// Locks the existing directory `dir` for this process, described by `command`.
    pub fn acquire(dir: &Path, command: &str) -> Result<Self, LockError> {
        let path = dir.join(NAME);
        let io = |e| LockError::Io(path.clone(), e);
        // Another run may remove the file between our open and our lock; then we hold the lock
        // of a file that is no longer there, and start again.
        for _ in 0..100 {
            let mut file =
                OpenOptions::new().read(true).write(true).create(true).truncate(false).open(&path).map_err(io)?;
            if !try_lock(&file).map_err(io)? {
                return Err(LockError::Busy(read_holder(&mut file)));
            }
            if !same_file(&file, &path) {
                continue;
            }
            // Registered only once held: a signal never removes the lock of another run.
            let registration = signals::register(signals::Cleanup { files: vec![path.clone()], ..Default::default() });
            file.set_len(0).map_err(io)?;
            file.write_all(Holder::this(command).text().as_bytes()).map_err(io)?;
            file.flush().map_err(io)?;
            return Ok(Self { path, file: Some(file), _registration: registration });
        }
        Err(io(io::Error::other("the lock file keeps being replaced by another process")))
    }
}

impl Drop for Lock {
    fn drop(&mut self) {
        // Removed while still locked, so that no other run locks the file on its way out.
        let _ = std::fs::remove_file(&self.path);
        drop(self.file.take());
    }
}

/// The command line of this process, for lock files.
pub fn command_line() -> String {
    let words: Vec<String> = std::env::args()
        .map(|a| if a.is_empty() || a.contains(char::is_whitespace) { format!("{a:?}") } else { a })
        .collect();
    words.join(" ")
}

fn read_holder(file: &mut File) -> Holder {
    // The holder writes its description right after locking: wait a moment if it is not there yet.
    for _ in 0..10 {
        let mut text = String::new();
        if file.rewind().is_ok() && file.read_to_string(&mut text).is_ok() && text.contains("pid = ") {
            return Holder::parse(&text);
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    Holder::default()
}

#[cfg(unix)]
fn try_lock(file: &File) -> io::Result<bool> {
    use std::os::unix::io::AsRawFd;
    // SAFETY: flock on a file descriptor this process owns; no memory is passed.
    if unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) } == 0 {
        return Ok(true);
    }
    let error = io::Error::last_os_error();
    match error.raw_os_error() {
        Some(libc::EWOULDBLOCK) => Ok(false),
        _ => Err(error),
    }
}

#[cfg(unix)]
fn same_file(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

/// Elsewhere than on Unix the file only describes the run: it does not exclude another one.
#[cfg(not(unix))]
fn try_lock(_file: &File) -> io::Result<bool> {
    Ok(true)
}

#[cfg(not(unix))]
fn same_file(_file: &File, _path: &Path) -> bool {
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_description_survives_a_round_trip_and_damage() {
        let holder = Holder { pid: Some(42), command: Some("ddirac run \"a b.toml\"".into()), started: Some(7) };
        assert_eq!(Holder::parse(&holder.text()), holder);
        assert_eq!(Holder::parse("pid = x\ngarbage\nstarted = 3"), Holder { started: Some(3), ..Holder::default() });
    }
}
