//! `ddirac ensemble`: many runs of one spec that differ in initial data and/or parameters, in
//! parallel, into one output directory (see [`files`]); `ddirac merge` joins the directories of the
//! shards of one ensemble.
//!
//! The members come from a CSV file (one column per varied key, named as `--set` names it) or from
//! the spec's `[ensemble]` table ([`members`]). Member k is run exactly as `ddirac run SPEC --set
//! KEY=VALUE ...` with its values runs it ([`ddirac::ensemble::run_member`]), so its results equal
//! that run's bit for bit. Members that differ only in initial data share the spec's system (one
//! parse of its Lagrangian) and its compiled programs; members with their own parameters are each
//! validated as a spec of their own (a text system's parameters are runtime inputs of its compiled
//! programs, so they compile once too).

pub mod files;
pub mod members;
mod random;

use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use ddirac::ensemble::{MemberSystem, Rows, Status};
use ddirac::{Error, Input, Problem};

use crate::diagnostics::CliError;
use crate::initial_entries::{self, Entry};
use crate::run::{self, Loaded};
use crate::signals;
pub use members::{Key, Members};

/// Where the members of an ensemble come from.
pub enum MembersFrom {
    /// A CSV file.
    File(PathBuf),
    /// Columns of values keyed as `--set` names them (from Python).
    Columns(Vec<(String, Vec<f64>)>),
    /// The spec's `[ensemble]` table.
    Spec,
}

/// A spec with its members, ready to run.
pub struct Ensemble {
    /// The spec file.
    pub path: PathBuf,
    /// Its text, as read.
    pub text: String,
    /// The `--set` assignments applied to every member.
    pub set: Vec<String>,
    /// The spec with `set` applied, validated.
    pub base: Loaded,
    /// The members.
    pub members: Members,
    /// Whether the members' rows are kept.
    pub trajectories: bool,
}

/// The per-member diagnostics, each an array over the members (NaN for a failed member), in the
/// order they are written: name and meaning.
pub const DIAGNOSTICS: [(&str, &str); 7] = [
    ("energy_error", "max |H_k − H_0| over the reported rows"),
    ("energy_relative_error", "energy_error / |H_0| (NaN when H_0 = 0)"),
    ("momentum_map_drift", "max |J_k − J_0| over all steps"),
    ("newton_iterations", "Newton corrections over all steps"),
    ("newton_max_iterations", "largest number of corrections in one step"),
    ("newton_max_residual", "largest accepted residual norm"),
    ("reference_error", "‖q(T) − q_N‖ against the exact solution, where the system has one"),
];

/// A member that did not finish.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Failure {
    /// Its index in the ensemble.
    pub member: usize,
    /// The step that failed (0 for a member refused before its first step).
    pub step: usize,
    /// Its time.
    pub t: f64,
    /// Why.
    pub error: String,
}

/// The results of members `first .. first + finished.len()`, arrays over the members.
#[derive(Debug, Clone, Default)]
pub struct Results {
    /// The first member's index.
    pub first: usize,
    /// The number of coordinates.
    pub n: usize,
    /// Whether each member took all its steps.
    pub finished: Vec<bool>,
    /// The steps each member took.
    pub steps: Vec<u64>,
    /// The final configurations (members × n): q_N, or that of the failed step.
    pub final_q: Vec<f64>,
    /// The final momenta (members × n).
    pub final_p: Vec<f64>,
    /// [`DIAGNOSTICS`], in their order, each over the members.
    pub diagnostics: Vec<Vec<f64>>,
    /// The members that failed, in member order.
    pub failures: Vec<Failure>,
    /// How many members used each derivative path.
    pub derivatives: BTreeMap<String, usize>,
    /// For each warning kind, how many members warned of it.
    pub warnings: BTreeMap<String, usize>,
    /// The sum of the members' own wall times (set-up and steps), seconds.
    pub member_seconds: f64,
    /// How many members prepared a stepper of their own, and how many renewed the stepper of the
    /// member before them on their thread (sharing its traced and compiled derivatives).
    pub preparations: ddirac::ensemble::Preparations,
}

impl Results {
    fn new(first: usize, count: usize, n: usize) -> Self {
        Self {
            first,
            n,
            finished: vec![false; count],
            steps: vec![0; count],
            final_q: vec![f64::NAN; count * n],
            final_p: vec![f64::NAN; count * n],
            diagnostics: vec![vec![f64::NAN; count]; DIAGNOSTICS.len()],
            ..Self::default()
        }
    }

    /// The number of members.
    pub fn len(&self) -> usize {
        self.finished.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.finished.is_empty()
    }

    fn record(&mut self, offset: usize, outcome: &ddirac::ensemble::Outcome, seconds: f64) {
        let n = self.n;
        self.final_q[offset * n..(offset + 1) * n].copy_from_slice(&outcome.final_q);
        self.final_p[offset * n..(offset + 1) * n].copy_from_slice(&outcome.final_p);
        self.member_seconds += seconds;
        match &outcome.status {
            Status::Finished(summary) => {
                self.finished[offset] = true;
                self.steps[offset] = summary.steps as u64;
                let e = &summary.energy;
                let energy_error = (e.max - e.initial).max(e.initial - e.min);
                let relative = if e.initial == 0.0 { f64::NAN } else { energy_error / e.initial.abs() };
                let newton = &summary.newton;
                let values = [
                    energy_error,
                    relative,
                    summary.momentum_map.max_drift,
                    newton.total_iterations as f64,
                    newton.max_iterations as f64,
                    newton.max_residual,
                    summary.reference_error.unwrap_or(f64::NAN),
                ];
                for (column, value) in self.diagnostics.iter_mut().zip(values) {
                    column[offset] = value;
                }
                let path = summary.derivatives.to_string();
                let short = path.split(" (").next().unwrap_or(&path).to_owned();
                *self.derivatives.entry(short).or_default() += 1;
                let mut kinds: Vec<&str> = summary.warnings.iter().map(|w| w.kind.name()).collect();
                kinds.dedup();
                for kind in kinds {
                    *self.warnings.entry(kind.to_owned()).or_default() += 1;
                }
            }
            Status::Failed { step, t, error } => {
                self.steps[offset] = *step as u64;
                let failure = Failure { member: self.first + offset, step: *step, t: *t, error: error.to_string() };
                let at = self.failures.partition_point(|f| f.member < failure.member);
                self.failures.insert(at, failure);
            }
        }
    }
}

impl Ensemble {
    /// Reads the spec at `path`, applies `set`, and reads or generates the members.
    pub fn load(path: &Path, set: &[String], from: MembersFrom) -> Result<Self, CliError> {
        let text = std::fs::read_to_string(path).map_err(|source| CliError::Read {
            what: "the spec file",
            path: path.to_owned(),
            source,
        })?;
        Self::from_text(path, text, set, from)
    }

    /// As [`Ensemble::load`], for the spec text `text` of the file `path`.
    pub fn from_text(path: &Path, text: String, set: &[String], from: MembersFrom) -> Result<Self, CliError> {
        let base = run::load_text(path, text.clone(), set)?;
        let table = base.spec.ensemble.as_ref();
        let members = match from {
            MembersFrom::File(file) => Members::read_csv(&file, &base.plan)?,
            MembersFrom::Columns(columns) => Members::from_columns(&columns, &base.plan, "the members given")?,
            MembersFrom::Spec => match table {
                Some(table) => Members::generate(&base.source, table, &base.plan)?,
                None => {
                    return Err(CliError::Members {
                        what: format!("the spec `{}`", path.display()),
                        why: "there is no `[ensemble]` table and no members file (`--members FILE.csv`)".into(),
                    })
                }
            },
        };
        let trajectories = table.and_then(|t| t.get_ref().trajectories.as_ref()).is_some_and(|t| *t.get_ref());
        Ok(Self { path: path.to_owned(), text, set: set.to_vec(), base, members, trajectories })
    }

    /// The coordinate names.
    pub fn coordinates(&self) -> Vec<String> {
        self.base.plan.system.coordinates().into_iter().map(|c| c.name).collect()
    }

    /// The number of rows each member reports: steps 0, every, 2 every, … and the last.
    pub fn rows(&self) -> usize {
        let (steps, every) = (self.base.plan.problem.steps, self.base.plan.output.every.max(1));
        steps.div_ceil(every) + 1
    }

    /// The times of the rows each member reports ([`Ensemble::rows`] of them).
    pub fn times(&self) -> Vec<f64> {
        let problem = &self.base.plan.problem;
        let every = self.base.plan.output.every.max(1);
        let mut t: Vec<f64> = (0..problem.steps).step_by(every).map(|k| k as f64 * problem.step).collect();
        t.push(problem.steps as f64 * problem.step);
        t
    }

    /// Member `i`'s system and problem.
    pub fn member(&self, i: usize) -> Result<(MemberSystem<'_>, Problem), CliError> {
        let values = self.members.row(i);
        let mut entries: Vec<Entry> = vec![];
        let mut entry_values = vec![];
        let mut set = self.set.clone();
        for (key, &value) in self.members.keys.iter().zip(values) {
            match key {
                Key::Entry(entry) => {
                    entries.push(entry.clone());
                    entry_values.push(value);
                }
                Key::Parameter(name) => set.push(format!("parameters.{name}={value:?}")),
            }
        }
        let (system, mut problem) = if self.members.share_the_system() {
            (MemberSystem::Shared(self.base.plan.system.as_ref()), self.base.plan.problem.clone())
        } else {
            let loaded = run::load_text(&self.path, self.text.clone(), &set).map_err(|e| member_error(i, e))?;
            (MemberSystem::Own(loaded.plan.system), loaded.plan.problem)
        };
        initial_entries::apply(&mut problem, &self.coordinates(), &entries, &entry_values)
            .map_err(|why| CliError::Members { what: format!("member {i}"), why })?;
        Ok((system, problem))
    }

    /// Runs members `range` on `threads` threads (default: all cores), giving each member's rows
    /// to `rows(offset in range, rows)` when trajectories are kept and reporting the number of
    /// members done to `progress`.
    pub fn run(
        &self,
        range: Range<usize>,
        threads: Option<usize>,
        rows: &(dyn Fn(usize, &Rows) -> Result<(), ddirac::OutputError> + Sync),
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<Results, CliError> {
        let plan = &self.base.plan;
        let n = plan.system.coordinates().len();
        let results = Mutex::new(Results::new(range.start, range.len(), n));
        let done = AtomicUsize::new(0);
        let first = range.start;
        let member = |i: usize| self.member(i).map_err(|e| Box::new(e) as ddirac::OutputError);
        let sink = |i: usize, outcome: ddirac::ensemble::Outcome| -> Result<(), ddirac::OutputError> {
            if let Some(kept) = &outcome.rows {
                rows(i - first, kept)?;
            }
            let seconds = match &outcome.status {
                Status::Finished(summary) => summary.wall_seconds,
                Status::Failed { .. } => 0.0,
            };
            results.lock().expect("no panic while recording").record(i - first, &outcome, seconds);
            progress(done.fetch_add(1, Ordering::Relaxed) + 1);
            Ok(())
        };
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads.unwrap_or(0)).build().map_err(|e| {
            CliError::Integration(Error::Invalid {
                what: Input::Argument("threads".into()),
                why: ddirac::Reason::Other(e.to_string()),
            })
        })?;
        let ran = pool
            .install(|| ddirac::ensemble::run(range, &member, &plan.method, &plan.output, self.trajectories, &sink));
        match ran {
            Ok(preparations) => {
                let mut results = results.into_inner().expect("no panic while recording");
                results.preparations = preparations;
                Ok(results)
            }
            Err(Error::Output(inner)) => Err(match inner.downcast::<CliError>() {
                Ok(cli) => *cli,
                Err(other) => match other.downcast::<crate::output::FileError>() {
                    Ok(file) => (*file).into(),
                    Err(other) => CliError::Output { path: self.path.clone(), source: std::io::Error::other(other) },
                },
            }),
            Err(error @ Error::Interrupted { .. }) => {
                signals::check(None)?;
                Err(CliError::Integration(error))
            }
            Err(error) => Err(CliError::Integration(error)),
        }
    }

    /// A fingerprint of what the members compute (spec text, `--set`, members, trajectories), that
    /// `ddirac merge` compares across shards: FNV-1a over their bytes.
    pub fn fingerprint(&self) -> String {
        let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
        let mut eat = |bytes: &[u8]| {
            for &b in bytes {
                hash ^= u64::from(b);
                hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
            }
            hash ^= 0xff;
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        };
        eat(self.text.as_bytes());
        for s in &self.set {
            eat(s.as_bytes());
        }
        for key in &self.members.keys {
            eat(key.name().as_bytes());
        }
        for v in &self.members.values {
            eat(&v.to_bits().to_le_bytes());
        }
        eat(&[u8::from(self.trajectories)]);
        format!("{hash:016x}")
    }
}

/// An error building member `i` from the spec, naming the member.
fn member_error(i: usize, error: CliError) -> CliError {
    match error {
        CliError::Spec(spec) => CliError::Members { what: format!("member {i}"), why: format!("{spec}") },
        other => other,
    }
}

/// The `I`-th of `N` contiguous parts of `0..members` (`--shard I/N`, I from 0).
pub fn shard(members: usize, index: usize, count: usize) -> Range<usize> {
    let at = |i: usize| ((i as u128 * members as u128) / count as u128) as usize;
    at(index)..at(index + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_are_contiguous_and_cover_every_member_once() {
        for members in [0, 1, 7, 100, 101] {
            for count in [1, 2, 3, 8] {
                let parts: Vec<Range<usize>> = (0..count).map(|i| shard(members, i, count)).collect();
                assert_eq!(parts[0].start, 0);
                assert_eq!(parts[count - 1].end, members);
                assert!(parts.windows(2).all(|w| w[0].end == w[1].start));
                assert!(parts.iter().all(|p| p.len() <= members.div_ceil(count)));
            }
        }
    }
}
