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
//! programs, so they compile once too). A rigid body's members are run by [`rigid`], and their state
//! is R, Π (and q, p of a shape) where a system in coordinates has q, p ([`Layout`]).

pub mod files;
pub mod layout;
pub mod members;
mod random;
mod rigid;

use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use ddirac::ensemble::{MemberSystem, Status};
use ddirac::rigid::RigidProblem;
use ddirac::{Error, Input, Problem};
use rayon::prelude::*;

use crate::diagnostics::CliError;
use crate::initial_entries::{self, Entry};
use crate::rigid::plan::RigidModel;
use crate::rigid::LoadedRigid;
use crate::run::{self, Loaded};
use crate::signals;
pub use layout::Layout;
pub use members::{Key, Members, Variables};

/// Where the members of an ensemble come from.
pub enum MembersFrom {
    /// A CSV file.
    File(PathBuf),
    /// Columns of values keyed as `--set` names them (from Python).
    Columns(Vec<(String, Vec<f64>)>),
    /// The spec's `[ensemble]` table.
    Spec,
}

/// The spec of an ensemble with `--set` applied, validated: a system in coordinates or a rigid body.
pub enum Base {
    /// A system in coordinates.
    Coordinates(Box<Loaded>),
    /// A rigid body.
    Rigid(Box<LoadedRigid>),
}

impl Base {
    /// Reads the spec text `text` of the file `path` with `set` applied, as `ddirac run` would.
    fn load(path: &Path, text: String, set: &[String]) -> Result<Self, CliError> {
        Ok(if crate::rigid::names_rigid_body(&text, set) {
            Self::Rigid(Box::new(crate::rigid::load_text(path, text, set)?))
        } else {
            Self::Coordinates(Box::new(run::load_text(path, text, set)?))
        })
    }

    /// Prints what the overrides did that the user may not expect (see [`Loaded::print_notes`]).
    pub fn print_notes(&self) {
        if let Self::Coordinates(loaded) = self {
            loaded.print_notes();
        }
    }

    /// The system's name.
    pub fn name(&self) -> String {
        match self {
            Self::Coordinates(l) => l.plan.name.clone(),
            Self::Rigid(l) => l.plan.name.clone(),
        }
    }

    /// The step h and the number of steps N.
    pub fn grid(&self) -> (f64, usize) {
        match self {
            Self::Coordinates(l) => (l.plan.problem.step, l.plan.problem.steps),
            Self::Rigid(l) => (l.plan.problem.step, l.plan.problem.steps),
        }
    }

    /// Every how many steps a row is reported.
    pub fn every(&self) -> usize {
        match self {
            Self::Coordinates(l) => l.plan.output.every.max(1),
            Self::Rigid(l) => l.plan.every.max(1),
        }
    }

    /// The directory a single run of the spec at `spec` writes to.
    pub fn output_dir(&self, spec: &Path) -> PathBuf {
        match self {
            Self::Coordinates(l) => run::output_dir(None, &l.plan, spec),
            Self::Rigid(l) => {
                let request = crate::rigid::Request { spec, set: &[], out: None, quiet: true, format: &[] };
                crate::rigid::output_dir(&request, &l.plan)
            }
        }
    }

    /// What the members may vary.
    pub fn variables(&self) -> Variables {
        match self {
            Self::Coordinates(l) => Variables {
                coordinates: l.plan.system.coordinates().into_iter().map(|c| c.name).collect(),
                parameters: l.plan.parameters.iter().map(|(n, _)| n.clone()).collect(),
                rigid: false,
                momenta: matches!(l.plan.problem.initial, ddirac::InitialMomentum::Momentum(_)),
            },
            Self::Rigid(l) => Variables {
                coordinates: crate::rigid::shape_names(&l.plan),
                parameters: l.plan.parameters.iter().map(|(n, _)| n.clone()).collect(),
                rigid: true,
                momenta: matches!(l.plan.problem.initial, ddirac::rigid::RigidInitial::Momentum { .. }),
            },
        }
    }

    /// The spec's text as diagnostics quote it, and its `[ensemble]` table.
    fn table(&self) -> (&crate::diagnostics::SpecSource, Option<&toml::Spanned<crate::spec::EnsembleSpec>>) {
        match self {
            Self::Coordinates(l) => (&l.source, l.spec.ensemble.as_ref()),
            Self::Rigid(l) => (&l.source, l.spec.ensemble.as_ref()),
        }
    }
}

/// A member's rows: times, the state's parts ([`Layout::parts`], each rows × its width) and energies.
#[derive(Debug, Clone, Default)]
pub struct MemberRows {
    /// Times.
    pub t: Vec<f64>,
    /// The parts of the state, row after row.
    pub state: Vec<Vec<f64>>,
    /// The Hamiltonian of each row.
    pub energy: Vec<f64>,
}

impl MemberRows {
    fn new(parts: usize) -> Self {
        Self { state: vec![vec![]; parts], ..Self::default() }
    }

    /// The rows of a member in coordinates.
    fn of(rows: &ddirac::ensemble::Rows) -> Self {
        Self { t: rows.t.clone(), state: vec![rows.q.clone(), rows.p.clone()], energy: rows.energy.clone() }
    }
}

/// How a member ended, as the ensemble records it.
pub(crate) enum Ended {
    /// All steps taken: the steps, [`DIAGNOSTICS`] in order, the derivative path, the warning kinds.
    Finished { steps: usize, values: [f64; 7], derivatives: String, warnings: Vec<&'static str> },
    /// A failure at `step` (0 when refused before its first step).
    Failed { step: usize, t: f64, error: String },
}

impl Ended {
    /// A member that took its `steps`: [`DIAGNOSTICS`] from its energy, momentum map drift, Newton
    /// statistics and reference error, and each kind of its warnings once.
    #[allow(clippy::too_many_arguments)]
    fn finished(
        steps: usize,
        energy: &ddirac::Stats,
        momentum_map_drift: f64,
        newton: &ddirac::diagnostics::NewtonSummary,
        reference_error: Option<f64>,
        derivatives: String,
        warnings: &[ddirac::Warning],
    ) -> Self {
        let energy_error = (energy.max - energy.initial).max(energy.initial - energy.min);
        let relative = if energy.initial == 0.0 { f64::NAN } else { energy_error / energy.initial.abs() };
        let values = [
            energy_error,
            relative,
            momentum_map_drift,
            newton.total_iterations as f64,
            newton.max_iterations as f64,
            newton.max_residual,
            reference_error.unwrap_or(f64::NAN),
        ];
        let mut warnings: Vec<&'static str> = warnings.iter().map(|w| w.kind.name()).collect();
        warnings.sort_unstable();
        warnings.dedup();
        Self::Finished { steps, values, derivatives, warnings }
    }

    /// How a member in coordinates ended.
    fn of(status: &Status) -> Self {
        match status {
            Status::Finished(summary) => {
                let path = summary.derivatives.to_string();
                let derivatives = path.split(" (").next().unwrap_or(&path).to_owned();
                Self::finished(
                    summary.steps,
                    &summary.energy,
                    summary.momentum_map.max_drift,
                    &summary.newton,
                    summary.reference_error,
                    derivatives,
                    &summary.warnings,
                )
            }
            Status::Failed { step, t, error } => Self::Failed { step: *step, t: *t, error: error.to_string() },
        }
    }
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
    pub base: Base,
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
    /// The number of values of a member's state ([`Layout::width`]).
    pub width: usize,
    /// Whether each member took all its steps.
    pub finished: Vec<bool>,
    /// The steps each member took.
    pub steps: Vec<u64>,
    /// The final states (members × width, the parts of [`Layout::parts`] in order): that after the
    /// last step, or that of the failed step.
    pub final_state: Vec<f64>,
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
    fn new(first: usize, count: usize, width: usize) -> Self {
        Self {
            first,
            width,
            finished: vec![false; count],
            steps: vec![0; count],
            final_state: vec![f64::NAN; count * width],
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

    /// Member `offset`'s final values of the part at `at` (a range of [`Layout`]'s columns).
    pub fn part(&self, offset: usize, at: Range<usize>) -> &[f64] {
        let start = offset * self.width;
        &self.final_state[start + at.start..start + at.end]
    }

    fn record(&mut self, offset: usize, state: &[f64], ended: Ended, seconds: f64) {
        let width = self.width;
        self.final_state[offset * width..(offset + 1) * width].copy_from_slice(state);
        self.member_seconds += seconds;
        match ended {
            Ended::Finished { steps, values, derivatives, warnings } => {
                self.finished[offset] = true;
                self.steps[offset] = steps as u64;
                for (column, value) in self.diagnostics.iter_mut().zip(values) {
                    column[offset] = value;
                }
                *self.derivatives.entry(derivatives).or_default() += 1;
                for kind in warnings {
                    *self.warnings.entry(kind.to_owned()).or_default() += 1;
                }
            }
            Ended::Failed { step, t, error } => {
                self.steps[offset] = step as u64;
                let failure = Failure { member: self.first + offset, step, t, error };
                let at = self.failures.partition_point(|f| f.member < failure.member);
                self.failures.insert(at, failure);
            }
        }
    }
}

/// A member's system and problem.
pub enum Member<'e> {
    /// Of a system in coordinates.
    Coordinates(MemberSystem<'e>, Problem),
    /// Of a rigid body: its own body (when parameters vary) or the spec's.
    Rigid(std::borrow::Cow<'e, RigidModel>, RigidProblem),
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
        let base = Base::load(path, text.clone(), set)?;
        if matches!(&base, Base::Coordinates(l) if l.plan.method.sensitivities) {
            return Err(CliError::Members {
                what: format!("the spec `{}`", path.display()),
                why: "an ensemble writes no tangent maps: `method.sensitivities = true` is for `ddirac run` (and \
                      Python's `simulate`); remove it here"
                    .into(),
            });
        }
        let variables = base.variables();
        let (source, table) = base.table();
        let members = match from {
            MembersFrom::File(file) => Members::read_csv(&file, &variables)?,
            MembersFrom::Columns(columns) => Members::from_columns(&columns, &variables, "the members given")?,
            MembersFrom::Spec => match table {
                Some(table) => Members::generate(source, table, &variables)?,
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

    /// The coordinate names (of a rigid body: its shape coordinates).
    pub fn coordinates(&self) -> Vec<String> {
        match &self.base {
            Base::Coordinates(l) => l.plan.system.coordinates().into_iter().map(|c| c.name).collect(),
            Base::Rigid(l) => crate::rigid::shape_names(&l.plan),
        }
    }

    /// What each member's state is written as.
    pub fn layout(&self) -> Layout {
        Layout { coordinates: self.coordinates(), attitude: matches!(self.base, Base::Rigid(_)) }
    }

    /// The number of rows each member reports: steps 0, every, 2 every, … and the last.
    pub fn rows(&self) -> usize {
        let ((_, steps), every) = (self.base.grid(), self.base.every());
        steps.div_ceil(every) + 1
    }

    /// The times of the rows each member reports ([`Ensemble::rows`] of them).
    pub fn times(&self) -> Vec<f64> {
        let ((step, steps), every) = (self.base.grid(), self.base.every());
        let mut t: Vec<f64> = (0..steps).step_by(every).map(|k| k as f64 * step).collect();
        t.push(steps as f64 * step);
        t
    }

    /// Member `i`'s system and problem.
    pub fn member(&self, i: usize) -> Result<Member<'_>, CliError> {
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
        let shared = self.members.share_the_system();
        let invalid = |why| CliError::Members { what: format!("member {i}"), why };
        match &self.base {
            Base::Coordinates(base) => {
                let (system, mut problem) = if shared {
                    (MemberSystem::Shared(base.plan.system.as_ref()), base.plan.problem.clone())
                } else {
                    let loaded = run::load_text(&self.path, self.text.clone(), &set).map_err(|e| member_error(i, e))?;
                    (MemberSystem::Own(loaded.plan.system), loaded.plan.problem)
                };
                initial_entries::apply(&mut problem, &self.coordinates(), &entries, &entry_values).map_err(invalid)?;
                Ok(Member::Coordinates(system, problem))
            }
            Base::Rigid(base) => {
                let (body, mut problem) = if shared {
                    (std::borrow::Cow::Borrowed(&base.plan.body), base.plan.problem.clone())
                } else {
                    let loaded =
                        crate::rigid::load_text(&self.path, self.text.clone(), &set).map_err(|e| member_error(i, e))?;
                    (std::borrow::Cow::Owned(loaded.plan.body), loaded.plan.problem)
                };
                initial_entries::apply_rigid(&mut problem, &self.coordinates(), &entries, &entry_values)
                    .map_err(invalid)?;
                Ok(Member::Rigid(body, problem))
            }
        }
    }

    /// Runs members `range` on `threads` threads (default: all cores), giving each member's rows
    /// to `rows(offset in range, rows)` when trajectories are kept and reporting the number of
    /// members done to `progress`.
    pub fn run(
        &self,
        range: Range<usize>,
        threads: Option<usize>,
        rows: &(dyn Fn(usize, &MemberRows) -> Result<(), ddirac::OutputError> + Sync),
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<Results, CliError> {
        let count = range.len();
        let results = Mutex::new(Results::new(range.start, count, self.layout().width()));
        let done = AtomicUsize::new(0);
        let first = range.start;
        let sink = |i: usize, state: &[f64], ended: Ended, kept: Option<&MemberRows>, seconds: f64| {
            if let Some(kept) = kept {
                rows(i - first, kept)?;
            }
            results.lock().expect("no panic while recording").record(i - first, state, ended, seconds);
            progress(done.fetch_add(1, Ordering::Relaxed) + 1);
            Ok::<(), ddirac::OutputError>(())
        };
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads.unwrap_or(0)).build().map_err(|e| {
            CliError::Integration(Error::Invalid {
                what: Input::Argument("threads".into()),
                why: ddirac::Reason::Other(e.to_string()),
            })
        })?;
        let ran = pool.install(|| match &self.base {
            Base::Coordinates(base) => {
                let plan = &base.plan;
                let member = |i: usize| match self.member(i) {
                    Ok(Member::Coordinates(system, problem)) => Ok((system, problem)),
                    Ok(Member::Rigid(..)) => unreachable!("the members of a system in coordinates"),
                    Err(e) => Err(Box::new(e) as ddirac::OutputError),
                };
                let sink = |i: usize, outcome: ddirac::ensemble::Outcome| {
                    let seconds = match &outcome.status {
                        Status::Finished(summary) => summary.wall_seconds,
                        Status::Failed { .. } => 0.0,
                    };
                    let state: Vec<f64> = outcome.final_q.iter().chain(&outcome.final_p).copied().collect();
                    let kept = outcome.rows.as_ref().map(MemberRows::of);
                    sink(i, &state, Ended::of(&outcome.status), kept.as_ref(), seconds)
                };
                ddirac::ensemble::run(range, &member, &plan.method, &plan.output, self.trajectories, &sink)
            }
            Base::Rigid(base) => {
                let plan = &base.plan;
                range.into_par_iter().try_for_each(|i| {
                    if ddirac::interrupt::requested() {
                        return Err(Error::Interrupted { step: 0, t: 0.0 });
                    }
                    let (body, problem) = match self.member(i) {
                        Ok(Member::Rigid(body, problem)) => (body, problem),
                        Ok(Member::Coordinates(..)) => unreachable!("the members of a rigid body"),
                        Err(e) => return Err(Error::Output(Box::new(e))),
                    };
                    let outcome = rigid::run_member(&body, problem, &plan.method, plan.every, self.trajectories)?;
                    sink(i, &outcome.state, outcome.ended, outcome.rows.as_ref(), outcome.seconds)
                        .map_err(Error::Output)
                })?;
                Ok(ddirac::ensemble::Preparations { prepared: count, renewed: 0 })
            }
        });
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
