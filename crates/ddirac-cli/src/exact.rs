//! `exact.csv`: the exact motion of a system that has one (the charged particle's gyration, an
//! expression system's `[exact]` table), at the times of the rows of `trajectory.csv`, for
//! `ddirac plot` to draw beside the computed trajectory.
//!
//! Columns: `t`, then each coordinate the exact solution is known for, named as in
//! `trajectory.csv`; angles are wrapped as the trajectory's are. The file is created at the first
//! row, when the initial momenta are known (a spec may give velocities), and only if the system has
//! an exact solution for them.

use std::fs::File;
use std::io;
use std::path::{Path, PathBuf};

use ddirac::{chart, CoordinateKind, DynSystem, Row};

use crate::output::{at, write_number, FileError};

/// The exact solution, streamed beside the trajectory.
pub struct ExactFile {
    dir: PathBuf,
    /// The writer and the coordinates it writes, once the first row has decided that there is one.
    state: State,
    field: String,
}

enum State {
    /// Before the first row.
    Unknown { q0: Vec<f64>, wrap: Vec<bool> },
    /// The system has an exact solution for this problem.
    Writing(Box<Writing>),
    /// It has none.
    None,
}

/// The open file and what each row needs.
struct Writing {
    writer: csv::Writer<File>,
    path: PathBuf,
    q0: Vec<f64>,
    p0: Vec<f64>,
    columns: Vec<usize>,
    wrap: Vec<bool>,
}

impl ExactFile {
    /// Name of the file in the output directory.
    pub const NAME: &'static str = "exact.csv";

    /// An exact file for a run from `q0` into `dir`; angles are written wrapped when `wrap_angles`.
    pub fn new(dir: &Path, system: &dyn DynSystem, q0: &[f64], wrap_angles: bool) -> Self {
        let wrap = system.coordinates().iter().map(|c| wrap_angles && c.kind == CoordinateKind::Angle).collect();
        Self { dir: dir.to_owned(), state: State::Unknown { q0: q0.to_vec(), wrap }, field: String::new() }
    }

    /// Writes the exact solution at the time of `row`; the first row (k = 0, whose momenta are p0)
    /// decides whether there is one.
    pub fn write(&mut self, system: &dyn DynSystem, row: &Row<'_>) -> Result<(), FileError> {
        if let State::Unknown { q0, wrap } = &mut self.state {
            let (q0, wrap, p0) = (std::mem::take(q0), std::mem::take(wrap), row.p.to_vec());
            self.state = match system.exact_solution(&q0, &p0, 0.0) {
                Some(exact) if exact.iter().any(Option::is_some) => {
                    let columns: Vec<usize> = (0..exact.len()).filter(|&i| exact[i].is_some()).collect();
                    let path = self.dir.join(Self::NAME);
                    let mut writer = csv::Writer::from_writer(at(&path, File::create(&path))?);
                    let names = system.coordinates();
                    let header = std::iter::once("t").chain(columns.iter().map(|&i| names[i].name.as_str()));
                    at(&path, writer.write_record(header).map_err(io::Error::from))?;
                    State::Writing(Box::new(Writing { writer, path, q0, p0, columns, wrap }))
                }
                _ => State::None,
            };
        }
        let State::Writing(open) = &mut self.state else { return Ok(()) };
        let Writing { writer, path, q0, p0, columns, wrap } = open.as_mut();
        let exact = system.exact_solution(q0, p0, row.t).unwrap_or_default();
        let value = |i: usize| exact.get(i).copied().flatten().map(|v| if wrap[i] { chart::wrap(v) } else { v });
        for value in std::iter::once(Some(row.t)).chain(columns.iter().map(|&i| value(i))) {
            self.field.clear();
            if let Some(v) = value {
                write_number(&mut self.field, v);
            }
            at(path, writer.write_field(&self.field).map_err(io::Error::from))?;
        }
        at(path, writer.write_record(None::<&[u8]>).map_err(io::Error::from))
    }

    /// Flushes and syncs the file; its name relative to the directory, if it was written.
    pub fn finish(self) -> Result<Option<PathBuf>, FileError> {
        let State::Writing(open) = self.state else { return Ok(None) };
        let Writing { writer, path, .. } = *open;
        let inner = at(&path, writer.into_inner().map_err(|e| e.into_error()))?;
        at(&path, inner.sync_all())?;
        Ok(Some(PathBuf::from(Self::NAME)))
    }
}
