//! The output directory of `ddirac ensemble`, and `ddirac merge`.
//!
//! ```text
//! DIR/final.csv        member, status (ok | failed), <coordinate>..., p_<coordinate>...: one row per member
//! DIR/members.csv      member, then the varied keys: the values each member ran with
//! DIR/summary.json     counts, failures (member, step, t, error), derivative paths, warnings, shard
//! DIR/npy/final_q.npy  members × n          DIR/npy/final_p.npy   members × n
//! DIR/npy/status.npy   members (u1: 0 ok, 1 failed)            DIR/npy/steps.npy  members (i8: steps taken)
//! DIR/npy/<diagnostic>.npy  members (f8; see ensemble::DIAGNOSTICS)
//! with trajectories:   DIR/npy/t.npy (rows), q.npy and p.npy (members × rows × n), energy.npy (members × rows)
//! ```
//!
//! A rigid body's state is its attitude and body angular momentum, then its shape (if any): final.csv
//! has the columns `R11` … `R33`, `Pi1` … `Pi3` before the shape's, the arrays are `final_R.npy`
//! (members × 3 × 3), `final_Pi.npy` (members × 3) and with trajectories `R.npy` (members × rows × 3 × 3)
//! and `Pi.npy` (members × rows × 3); `final_q`, `final_p`, `q` and `p` hold the shape coordinates
//! and momenta and are written only when the body has shape coordinates; summary.json says
//! `"attitude": "SO(3)"`.
//!
//! Trajectories are written while the members run, each member's block at its place in the
//! preallocated arrays (so memory holds one member's rows per thread); a failed member's rows
//! after its failure are NaN. Everything goes through the run's staging directory and is committed
//! as a set ([`RunDir`]). A shard (`--shard I/N`) writes the same files for its contiguous part of
//! the members into `DIR/shard-I-of-N`; [`merge`] concatenates the parts along the member axis,
//! giving the files of the unsharded run byte for byte (all but the timings of `summary.json`).

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;

use serde::{Deserialize, Serialize};

use super::{Ensemble, Failure, Layout, MemberRows, MembersFrom, Results, DIAGNOSTICS};
use crate::diagnostics::CliError;
use crate::output::{self, FileError};
use crate::progress::Progress;
use crate::run_dir::RunDir;
use crate::{lock, npy};

/// Options of `ddirac ensemble`.
pub struct Options {
    /// The spec file.
    pub spec: PathBuf,
    /// `--set` assignments applied to every member.
    pub set: Vec<String>,
    /// `--members FILE.csv` (else the spec's `[ensemble]` table).
    pub members: Option<PathBuf>,
    /// `--out DIR`.
    pub out: Option<PathBuf>,
    /// `--threads T`.
    pub threads: Option<usize>,
    /// `--shard I/N`: (I, N).
    pub shard: Option<(usize, usize)>,
    /// `--quiet`.
    pub quiet: bool,
}

/// Which part of the ensemble a directory holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ShardJson {
    /// I of `--shard I/N`.
    pub index: usize,
    /// N.
    pub count: usize,
    /// The first member.
    pub first: usize,
    /// One past the last member.
    pub end: usize,
}

/// How the members' steppers were made.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
pub struct Steppers {
    /// Members that prepared their own.
    pub prepared: usize,
    /// Members that renewed the one before them.
    pub renewed: usize,
}

/// `summary.json` of an ensemble.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SummaryJson {
    /// The version of ddirac that ran it.
    pub ddirac_version: String,
    /// The spec file.
    pub spec: String,
    /// What `ddirac merge` compares: spec, `--set`, members.
    pub fingerprint: String,
    /// The system's name.
    pub system: String,
    /// The coordinates (of a rigid body: its shape coordinates).
    pub coordinates: Vec<String>,
    /// `SO(3)` for a rigid body, whose state holds its attitude R and angular momentum Π.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub attitude: Option<String>,
    /// The varied keys.
    pub keys: Vec<String>,
    /// Members of the whole ensemble.
    pub members: usize,
    /// The part of them in this directory (`null` for all of them).
    pub shard: Option<ShardJson>,
    /// Members here that took all their steps.
    pub finished: usize,
    /// Members here that failed.
    pub failed: usize,
    /// The failed members.
    pub failures: Vec<Failure>,
    /// Steps and step of every member.
    pub steps: usize,
    /// The step size.
    pub step: f64,
    /// Rows per member in the trajectory arrays (0 without trajectories).
    pub rows: usize,
    /// How many members used each derivative path.
    pub derivatives: BTreeMap<String, usize>,
    /// For each warning kind, how many members warned of it.
    pub warnings: BTreeMap<String, usize>,
    /// Threads used.
    pub threads: usize,
    /// Members that prepared a stepper of their own (`prepared`) and members that renewed the
    /// stepper of the member before them on their thread, sharing its derivatives (`renewed`).
    pub steppers: Steppers,
    /// The sum of the members' own wall times, seconds.
    pub member_seconds: f64,
    /// Wall time of the command, seconds.
    pub total_wall_seconds: f64,
}

/// Runs `ddirac ensemble`.
pub fn command(options: &Options) -> Result<(), CliError> {
    let started = Instant::now();
    let from = options.members.clone().map_or(MembersFrom::Spec, MembersFrom::File);
    let ensemble = Ensemble::load(&options.spec, &options.set, from)?;
    ensemble.base.print_notes();
    let total = ensemble.members.len();
    let (range, shard) = match options.shard {
        Some((index, count)) => {
            if count == 0 || index >= count {
                let why = match count {
                    0 => "the number of shards N must be at least 1".into(),
                    _ => format!(
                        "the shard index {index} must be in 0..{count}, below the number of shards (it counts from \
                         0, as SLURM_ARRAY_TASK_ID)"
                    ),
                };
                return Err(CliError::Set { arg: format!("--shard {index}/{count}"), why });
            }
            let range = super::shard(total, index, count);
            (range.clone(), Some(ShardJson { index, count, first: range.start, end: range.end }))
        }
        None => (0..total, None),
    };
    let base = default_dir(options.out.as_deref(), &ensemble);
    let dir = match shard {
        Some(s) => base.join(format!("shard-{}-of-{}", s.index, s.count)),
        None => base,
    };
    let threads = options.threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from));
    let run_dir = RunDir::open(&dir, &lock::command_line())?;
    let staging = run_dir.staging().to_owned();
    std::fs::create_dir_all(staging.join("npy"))
        .map_err(|source| CliError::Output { path: staging.join("npy"), source })?;
    let trajectories =
        ensemble.trajectories.then(|| Trajectories::create(&staging, &ensemble, range.len())).transpose()?;
    let progress = Mutex::new(Progress::new(range.len() as u64, options.quiet));
    let keep = |offset: usize, rows: &MemberRows| -> Result<(), ddirac::OutputError> {
        match &trajectories {
            Some(t) => t.write(offset, rows).map_err(|e| Box::new(e) as ddirac::OutputError),
            None => Ok(()),
        }
    };
    let report = |done: usize| {
        if let Ok(mut p) = progress.lock() {
            p.update(done);
        }
    };
    let results = ensemble.run(range.clone(), Some(threads), &keep, &report);
    progress.into_inner().map(|mut p| p.finish()).ok();
    let results = results?;
    let mut files = write_results(&staging, &ensemble, &results)?;
    if let Some(t) = trajectories {
        files.extend(t.finish()?);
    }
    let summary = SummaryJson {
        ddirac_version: env!("CARGO_PKG_VERSION").into(),
        spec: options.spec.display().to_string(),
        fingerprint: ensemble.fingerprint(),
        system: ensemble.base.name(),
        coordinates: ensemble.coordinates(),
        attitude: ensemble.layout().attitude.then(|| "SO(3)".to_owned()),
        keys: ensemble.members.keys.iter().map(super::Key::name).collect(),
        members: total,
        shard,
        finished: results.finished.iter().filter(|f| **f).count(),
        failed: results.failures.len(),
        failures: results.failures.clone(),
        steps: ensemble.base.grid().1,
        step: ensemble.base.grid().0,
        rows: if ensemble.trajectories { ensemble.rows() } else { 0 },
        derivatives: results.derivatives.clone(),
        warnings: results.warnings.clone(),
        threads,
        steppers: Steppers { prepared: results.preparations.prepared, renewed: results.preparations.renewed },
        member_seconds: results.member_seconds,
        total_wall_seconds: started.elapsed().as_secs_f64(),
    };
    files.push(output::json(&staging, "summary.json", &summary)?);
    run_dir.commit(&files)?;
    report_failures(&summary);
    if !options.quiet {
        println!("{}", human(&summary, &dir));
    }
    Ok(())
}

/// `--out`, else `output.directory` of the spec followed by `-ensemble`, else
/// `out/<spec file stem>-ensemble`: not the directory of a single run of the spec.
fn default_dir(out: Option<&Path>, ensemble: &Ensemble) -> PathBuf {
    if let Some(out) = out {
        return out.to_owned();
    }
    let single = ensemble.base.output_dir(&ensemble.path);
    let mut name = single.file_name().map_or("run".into(), |n| n.to_os_string());
    name.push("-ensemble");
    single.with_file_name(name)
}

/// Prints a warning naming the failed members (the first few).
fn report_failures(summary: &SummaryJson) {
    if summary.failures.is_empty() {
        return;
    }
    let here = summary.finished + summary.failed;
    eprintln!(
        "warning [failed_members]: {} of {here} members failed (status `failed` in final.csv; reasons in summary.json):",
        summary.failed
    );
    for f in summary.failures.iter().take(5) {
        eprintln!("  member {} at step {} (t = {}): {}", f.member, f.step, f.t, f.error);
    }
    if summary.failures.len() > 5 {
        eprintln!("  … and {} more", summary.failures.len() - 5);
    }
}

/// The text printed after an ensemble.
fn human(summary: &SummaryJson, dir: &Path) -> String {
    let mut text = format!("ensemble of {} members of {} → {}\n", summary.members, summary.system, dir.display());
    if let Some(s) = summary.shard {
        text.push_str(&format!("  shard            {}/{}: members {}..{}\n", s.index, s.count, s.first, s.end));
    }
    text.push_str(&format!("  finished         {}\n  failed           {}\n", summary.finished, summary.failed));
    let paths: Vec<String> = summary.derivatives.iter().map(|(p, n)| format!("{p} ({n})")).collect();
    text.push_str(&format!("  derivatives      {}\n", paths.join(", ")));
    let s = summary.steppers;
    text.push_str(&format!(
        "  steppers         {} prepared, {} renewed from the member before\n",
        s.prepared, s.renewed
    ));
    text.push_str(&format!(
        "  wall             {:.3} s on {} threads (members' own time {:.3} s)",
        summary.total_wall_seconds, summary.threads, summary.member_seconds
    ));
    text
}

/// Writes `final.csv`, `members.csv` and the per-member arrays; returns their names.
fn write_results(dir: &Path, ensemble: &Ensemble, results: &Results) -> Result<Vec<PathBuf>, FileError> {
    let layout = ensemble.layout();
    let mut files = vec![];
    // final.csv
    let mut text = final_header(&layout);
    text.push('\n');
    for m in 0..results.len() {
        text.push_str(&(results.first + m).to_string());
        text.push_str(if results.finished[m] { ",ok" } else { ",failed" });
        for v in results.part(m, 0..results.width) {
            text.push(',');
            output::write_number(&mut text, *v);
        }
        text.push('\n');
    }
    files.push(write_text(dir, "final.csv", &text)?);
    // members.csv
    let mut text = String::from("member");
    for key in &ensemble.members.keys {
        text.push(',');
        text.push_str(&key.name());
    }
    text.push('\n');
    for m in 0..results.len() {
        text.push_str(&(results.first + m).to_string());
        for v in ensemble.members.row(results.first + m) {
            text.push(',');
            output::write_number(&mut text, *v);
        }
        text.push('\n');
    }
    files.push(write_text(dir, "members.csv", &text)?);
    // Arrays with a member axis.
    let count = results.len() as u64;
    let mut arrays: Vec<(String, &str, Vec<u64>, Vec<u8>)> = vec![];
    let mut at = 0;
    for part in layout.parts() {
        let width = part.width();
        let values: Vec<f64> = (0..results.len()).flat_map(|m| results.part(m, at..at + width).to_vec()).collect();
        let shape = std::iter::once(count).chain(part.shape.iter().map(|&d| d as u64)).collect();
        arrays.push((format!("final_{}", part.name), "<f8", shape, npy::f64_bytes(&values)));
        at += width;
    }
    arrays.push(("status".into(), "|u1", vec![count], results.finished.iter().map(|f| u8::from(!f)).collect()));
    arrays.push((
        "steps".into(),
        "<i8",
        vec![count],
        results.steps.iter().flat_map(|s| (*s as i64).to_le_bytes()).collect(),
    ));
    for ((name, _), column) in DIAGNOSTICS.iter().zip(&results.diagnostics) {
        arrays.push(((*name).into(), "<f8", vec![count], npy::f64_bytes(column)));
    }
    for (name, descr, shape, data) in arrays {
        let relative = PathBuf::from("npy").join(format!("{name}.npy"));
        let path = dir.join(&relative);
        output::at(&path, npy::write(&path, descr, &shape, &data))?;
        files.push(relative);
    }
    Ok(files)
}

/// The header of `final.csv`.
fn final_header(layout: &Layout) -> String {
    std::iter::once("member".to_owned())
        .chain(std::iter::once("status".to_owned()))
        .chain(layout.columns())
        .collect::<Vec<_>>()
        .join(",")
}

fn write_text(dir: &Path, name: &str, text: &str) -> Result<PathBuf, FileError> {
    let path = dir.join(name);
    let mut file = output::at(&path, File::create(&path))?;
    output::at(&path, file.write_all(text.as_bytes()))?;
    output::at(&path, file.sync_all())?;
    Ok(PathBuf::from(name))
}

/// The trajectory arrays, preallocated and filled member by member.
struct Trajectories {
    dir: PathBuf,
    rows: usize,
    /// Per array (the parts of the state, then the energy): its name, the width of one row, its file
    /// and header length.
    files: Vec<TrajectoryFile>,
}

/// A trajectory array being written: its name, the width of one row, its file and header length.
type TrajectoryFile = (String, usize, Mutex<(File, u64)>);

/// The trajectory arrays of a layout: name and the shape of one row's value (the energy's is `[]`).
fn trajectory_parts(layout: &Layout) -> Vec<(String, Vec<u64>)> {
    let mut parts: Vec<(String, Vec<u64>)> =
        layout.parts().into_iter().map(|p| (p.name.to_owned(), p.shape.iter().map(|&d| d as u64).collect())).collect();
    parts.push(("energy".into(), vec![]));
    parts
}

impl Trajectories {
    fn create(dir: &Path, ensemble: &Ensemble, members: usize) -> Result<Self, FileError> {
        let rows = ensemble.rows();
        let t = ensemble.times();
        let path = dir.join("npy/t.npy");
        output::at(&path, npy::write(&path, "<f8", &[t.len() as u64], &npy::f64_bytes(&t)))?;
        let (m, r) = (members as u64, rows as u64);
        let mut files = vec![];
        for (name, row_shape) in trajectory_parts(&ensemble.layout()) {
            let shape: Vec<u64> = [m, r].into_iter().chain(row_shape.iter().copied()).collect();
            let path = dir.join(format!("npy/{name}.npy"));
            let header = npy::header_nd("<f8", &shape);
            let mut file = output::at(&path, File::create(&path))?;
            output::at(&path, file.write_all(&header))?;
            let len = header.len() as u64 + shape.iter().product::<u64>() * 8;
            output::at(&path, file.set_len(len))?;
            let width = row_shape.iter().product::<u64>() as usize;
            files.push((name, width, Mutex::new((file, header.len() as u64))));
        }
        Ok(Self { dir: dir.to_owned(), rows, files })
    }

    /// Writes member `offset`'s rows into its block, NaN after its last row.
    fn write(&self, offset: usize, rows: &MemberRows) -> Result<(), FileError> {
        let r = self.rows;
        let values = rows.state.iter().chain(std::iter::once(&rows.energy));
        for ((name, width, file), values) in self.files.iter().zip(values) {
            let mut block = values.clone();
            block.resize(r * width, f64::NAN);
            let bytes = npy::f64_bytes(&block);
            let path = self.dir.join(format!("npy/{name}.npy"));
            let mut guard = file.lock().expect("no panic while writing");
            let at = guard.1 + (offset * r * width * 8) as u64;
            output::at(&path, guard.0.seek(SeekFrom::Start(at)).and_then(|_| guard.0.write_all(&bytes)))?;
        }
        Ok(())
    }

    fn finish(self) -> Result<Vec<PathBuf>, FileError> {
        let mut files = vec![PathBuf::from("npy/t.npy")];
        for (name, _, file) in self.files {
            let relative = PathBuf::from(format!("npy/{name}.npy"));
            let path = self.dir.join(&relative);
            let (file, _) = file.into_inner().expect("no panic while writing");
            output::at(&path, file.sync_all())?;
            files.push(relative);
        }
        Ok(files)
    }
}

/// The arrays of an ensemble directory of `members` members whose state is laid out as `layout`, with
/// `rows` rows per member (0 without trajectories): file name, element type and shape, as
/// [`write_results`] and [`Trajectories`] write them.
fn arrays(members: usize, layout: &Layout, rows: usize) -> Vec<(String, &'static str, Vec<u64>)> {
    let (m, r) = (members as u64, rows as u64);
    let mut arrays: Vec<(String, &'static str, Vec<u64>)> = layout
        .parts()
        .into_iter()
        .map(|p| {
            (
                format!("final_{}.npy", p.name),
                "<f8",
                std::iter::once(m).chain(p.shape.iter().map(|&d| d as u64)).collect(),
            )
        })
        .collect();
    arrays.push(("status.npy".into(), "|u1", vec![m]));
    arrays.push(("steps.npy".into(), "<i8", vec![m]));
    arrays.extend(DIAGNOSTICS.iter().map(|(name, _)| (format!("{name}.npy"), "<f8", vec![m])));
    if rows > 0 {
        arrays.push(("t.npy".into(), "<f8", vec![r]));
        for (name, shape) in trajectory_parts(layout) {
            arrays.push((format!("{name}.npy"), "<f8", [m, r].into_iter().chain(shape).collect()));
        }
    }
    arrays.sort();
    arrays
}

/// The layout of the ensemble a summary describes.
fn layout_of(s: &SummaryJson) -> Layout {
    Layout { coordinates: s.coordinates.clone(), attitude: s.attitude.is_some() }
}

/// A refusal of `ddirac merge`.
fn refuse(why: String) -> CliError {
    CliError::Merge(why)
}

/// `(a, b, c)` of a shape.
fn shape_text(shape: &[u64]) -> String {
    let dims: Vec<String> = shape.iter().map(u64::to_string).collect();
    format!("({})", dims.join(", "))
}

/// Checks the summary of the shard in `dir` against itself and against `reference`, the summary of
/// the directory `reference_dir`.
fn check_summary(dir: &Path, s: &SummaryJson, reference_dir: &Path, reference: &SummaryJson) -> Result<(), CliError> {
    let path = dir.join("summary.json");
    if s.ddirac_version != reference.ddirac_version {
        return Err(refuse(format!(
            "`{}` was written by ddirac {}, but `{}` by ddirac {}: merge shards run by one version",
            path.display(),
            s.ddirac_version,
            reference_dir.join("summary.json").display(),
            reference.ddirac_version
        )));
    }
    let differs: Vec<&str> = [
        ("the fingerprint of spec, --set and members", s.fingerprint != reference.fingerprint),
        ("the number of members", s.members != reference.members),
        ("the coordinates", s.coordinates != reference.coordinates || s.attitude != reference.attitude),
        ("the varied keys", s.keys != reference.keys),
        ("the steps", s.steps != reference.steps || s.step.to_bits() != reference.step.to_bits()),
        ("the rows per member", s.rows != reference.rows),
    ]
    .into_iter()
    .filter_map(|(what, differs)| differs.then_some(what))
    .collect();
    if !differs.is_empty() {
        return Err(refuse(format!(
            "`{}` holds another ensemble than `{}` (another spec, --set or members): {} differ",
            dir.display(),
            reference_dir.display(),
            differs.join(", ")
        )));
    }
    let Some(shard) = s.shard else {
        return Err(refuse(format!("`{}` holds a whole ensemble, not a shard", dir.display())));
    };
    let inconsistent = |why: String| refuse(format!("`{}` is inconsistent: {why}", path.display()));
    if shard.count == 0 || shard.index >= shard.count {
        return Err(inconsistent(format!("shard {}/{} does not exist", shard.index, shard.count)));
    }
    let range = super::shard(s.members, shard.index, shard.count);
    if (shard.first, shard.end) != (range.start, range.end) {
        return Err(inconsistent(format!(
            "shard {}/{} of {} members holds members {}..{}, not {}..{}",
            shard.index, shard.count, s.members, range.start, range.end, shard.first, shard.end
        )));
    }
    if s.finished + s.failed != range.len() || s.failures.len() != s.failed {
        return Err(inconsistent(format!(
            "{} finished and {} failed members ({} failures listed) in a shard of {}",
            s.finished,
            s.failed,
            s.failures.len(),
            range.len()
        )));
    }
    Ok(())
}

/// Checks `dir/name` (`final.csv` or `members.csv`) of a shard: the header `header`, then one row per
/// member of `shard` in order, each with a field per column, a status (`final.csv`) and numbers;
/// returns the text and how many members have the status `ok`.
fn check_table(dir: &Path, name: &str, header: &str, shard: ShardJson) -> Result<(String, usize), CliError> {
    let path = dir.join(name);
    let text =
        std::fs::read_to_string(&path).map_err(|source| CliError::Read { what: "the shard file", path, source })?;
    let path = dir.join(name);
    let bad = |why: String| refuse(format!("`{}` {why}", path.display()));
    let mut lines = text.lines();
    let found = lines.next().unwrap_or_default();
    if found != header {
        return Err(bad(format!("starts with `{found}`, not with the header `{header}` of this ensemble")));
    }
    let columns = header.split(',').count();
    let status = name == "final.csv";
    let mut count = 0;
    let mut ok = 0;
    for (k, line) in lines.enumerate() {
        let member = shard.first + k;
        let line_number = k + 2;
        if member >= shard.end {
            return Err(bad(format!(
                "has more than the {} rows of the shard's members {}..{} (line {line_number})",
                shard.end - shard.first,
                shard.first,
                shard.end
            )));
        }
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() != columns {
            return Err(bad(format!("has {} fields on line {line_number}, not {columns}", fields.len())));
        }
        if fields[0] != member.to_string() {
            return Err(bad(format!(
                "has member `{}` on line {line_number}, where member {member} belongs",
                fields[0]
            )));
        }
        let numbers = if status {
            match fields[1] {
                "ok" => ok += 1,
                "failed" => {}
                other => return Err(bad(format!("has the status `{other}` on line {line_number}, not ok or failed"))),
            }
            &fields[2..]
        } else {
            &fields[1..]
        };
        if let Some(field) = numbers.iter().find(|f| f.parse::<f64>().is_err()) {
            return Err(bad(format!("has `{field}` on line {line_number}, which is not a number")));
        }
        count += 1;
    }
    let expected = shard.end - shard.first;
    if count != expected {
        return Err(bad(format!(
            "has {count} rows, but the shard holds {expected} members ({}..{})",
            shard.first, shard.end
        )));
    }
    Ok((text, ok))
}

/// Checks the shard in `dir` completely against its summary `s`: `final.csv` and `members.csv` row by
/// row, and every array of the ensemble present with the type and shape its members and the run's
/// rows imply and with all its data (no other arrays).
fn check_files(dir: &Path, s: &SummaryJson) -> Result<(), CliError> {
    let shard = s.shard.expect("checked by check_summary");
    let coordinates = &s.coordinates;
    let layout = layout_of(s);
    let header = final_header(&layout);
    let (_, ok) = check_table(dir, "final.csv", &header, shard)?;
    if ok != s.finished {
        return Err(refuse(format!(
            "`{}` has {ok} members with the status ok, but `{}` counts {} finished",
            dir.join("final.csv").display(),
            dir.join("summary.json").display(),
            s.finished
        )));
    }
    let header: String =
        std::iter::once("member").chain(s.keys.iter().map(String::as_str)).collect::<Vec<_>>().join(",");
    check_table(dir, "members.csv", &header, shard)?;

    let npy_dir = dir.join("npy");
    let expected = arrays(shard.end - shard.first, &layout, s.rows);
    let mut present: Vec<String> = std::fs::read_dir(&npy_dir)
        .map_err(|source| CliError::Read { what: "the shard directory", path: npy_dir.clone(), source })?
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".npy"))
        .collect();
    present.sort();
    if let Some((missing, _, _)) = expected.iter().find(|(name, _, _)| !present.contains(name)) {
        return Err(refuse(format!(
            "`{}` is missing: every shard of this ensemble has the arrays {}",
            npy_dir.join(missing).display(),
            expected.iter().map(|(name, _, _)| name.as_str()).collect::<Vec<_>>().join(", ")
        )));
    }
    if let Some(extra) = present.iter().find(|name| !expected.iter().any(|(e, _, _)| e == *name)) {
        return Err(refuse(format!(
            "`{}` is not an array of an ensemble (remove it if it was put there by hand)",
            npy_dir.join(extra).display()
        )));
    }
    for (name, descr, shape) in &expected {
        let path = npy_dir.join(name);
        let found = npy::read_header(&path).map_err(|e| refuse(format!("`{}` is damaged: {e}", path.display())))?;
        if found.descr != *descr || found.shape != *shape {
            return Err(refuse(format!(
                "`{}` holds `{}` of shape {}, but the shard's {} members ({} coordinates, {} rows each) make it \
                 `{descr}` of shape {}",
                path.display(),
                found.descr,
                shape_text(&found.shape),
                shard.end - shard.first,
                coordinates.len(),
                s.rows,
                shape_text(shape)
            )));
        }
    }
    Ok(())
}

/// Runs `ddirac merge`: joins the directories of the shards of one ensemble into `out`.
///
/// Every shard is checked completely before anything is written (see [`check_summary`] and
/// [`check_files`]): a refusal leaves `out` as it was.
pub fn merge(dirs: &[PathBuf], out: &Path, quiet: bool) -> Result<(), CliError> {
    let started = Instant::now();
    let read_summary = |dir: &PathBuf| -> Result<SummaryJson, CliError> {
        let path = dir.join("summary.json");
        let text = std::fs::read_to_string(&path).map_err(|source| CliError::Read {
            what: "the shard summary",
            path: path.clone(),
            source,
        })?;
        serde_json::from_str(&text)
            .map_err(|e| refuse(format!("`{}` is not the summary of an ensemble: {e}", path.display())))
    };
    let mut parts: Vec<(PathBuf, SummaryJson)> =
        dirs.iter().map(|d| read_summary(d).map(|s| (d.clone(), s))).collect::<Result<_, _>>()?;
    let Some((first_dir, first)) = parts.first().cloned() else {
        return Err(refuse("no directories given".into()));
    };
    for (dir, s) in &parts {
        check_summary(dir, s, &first_dir, &first)?;
    }
    parts.sort_by_key(|(_, s)| s.shard.map(|s| s.first));
    let mut next = 0;
    for (k, (dir, s)) in parts.iter().enumerate() {
        let shard = s.shard.expect("checked above");
        if shard.first < next {
            let (before, b) = &parts[k - 1];
            let b = b.shard.expect("checked above");
            let same = std::fs::canonicalize(dir).ok().is_some_and(|d| std::fs::canonicalize(before).ok() == Some(d));
            let repeated = format!("{}..{}", shard.first, shard.end.min(b.end));
            return Err(refuse(if same {
                format!("`{}` is given twice (members {}..{})", dir.display(), shard.first, shard.end)
            } else {
                format!(
                    "`{}` (members {}..{}) repeats members {repeated} of `{}` (members {}..{}): give each shard once",
                    dir.display(),
                    shard.first,
                    shard.end,
                    before.display(),
                    b.first,
                    b.end
                )
            }));
        }
        if shard.first > next {
            return Err(refuse(format!(
                "members {next}..{} of {} are in none of the directories (the shard before `{}` is missing)",
                shard.first,
                s.members,
                dir.display()
            )));
        }
        next = shard.end;
    }
    if next != first.members {
        return Err(refuse(format!(
            "members {next}..{} of {} are in none of the directories (the last shards are missing)",
            first.members, first.members
        )));
    }
    for (dir, s) in &parts {
        check_files(dir, s)?;
    }

    let run_dir = RunDir::open(out, &lock::command_line())?;
    let staging = run_dir.staging().to_owned();
    let npy_dir = staging.join("npy");
    std::fs::create_dir_all(&npy_dir).map_err(|source| CliError::Output { path: npy_dir.clone(), source })?;
    let mut files = vec![];
    for name in ["final.csv", "members.csv"] {
        let mut text = String::new();
        for (i, (dir, _)) in parts.iter().enumerate() {
            let path = dir.join(name);
            let part = std::fs::read_to_string(&path).map_err(|source| CliError::Read {
                what: "the shard file",
                path,
                source,
            })?;
            let body = if i == 0 { part.as_str() } else { part.split_once('\n').map_or("", |(_, b)| b) };
            text.push_str(body);
        }
        files.push(write_text(&staging, name, &text)?);
    }
    for (name, _, _) in arrays(first.members, &layout_of(&first), first.rows) {
        let arrays: Vec<npy::Array> = parts
            .iter()
            .map(|(dir, _)| {
                let path = dir.join("npy").join(&name);
                npy::read(&path).map_err(|source| CliError::Read { what: "the shard array", path, source })
            })
            .collect::<Result<_, _>>()?;
        let (descr, shape, data) = if name == "t.npy" {
            if let Some(k) = arrays.iter().position(|a| *a != arrays[0]) {
                return Err(refuse(format!(
                    "the time grids `{}` and `{}` differ",
                    parts[0].0.join("npy/t.npy").display(),
                    parts[k].0.join("npy/t.npy").display()
                )));
            }
            (arrays[0].descr.clone(), arrays[0].shape.clone(), arrays[0].data.clone())
        } else {
            let mut shape = arrays[0].shape.clone();
            shape[0] = arrays.iter().map(|a| a.shape[0]).sum();
            (arrays[0].descr.clone(), shape, arrays.into_iter().flat_map(|a| a.data).collect())
        };
        let relative = PathBuf::from("npy").join(&name);
        let path = staging.join(&relative);
        output::at(&path, npy::write(&path, &descr, &shape, &data))?;
        files.push(relative);
    }
    let mut merged = first.clone();
    merged.shard = None;
    merged.finished = parts.iter().map(|(_, s)| s.finished).sum();
    merged.failed = parts.iter().map(|(_, s)| s.failed).sum();
    merged.failures = parts.iter().flat_map(|(_, s)| s.failures.clone()).collect();
    merged.member_seconds = parts.iter().map(|(_, s)| s.member_seconds).sum();
    merged.threads = parts.iter().map(|(_, s)| s.threads).max().unwrap_or(1);
    merged.steppers = Steppers {
        prepared: parts.iter().map(|(_, s)| s.steppers.prepared).sum(),
        renewed: parts.iter().map(|(_, s)| s.steppers.renewed).sum(),
    };
    let sum = |get: fn(&SummaryJson) -> &BTreeMap<String, usize>| {
        let mut total: BTreeMap<String, usize> = BTreeMap::new();
        for (_, s) in &parts {
            for (k, v) in get(s) {
                *total.entry(k.clone()).or_default() += v;
            }
        }
        total
    };
    merged.derivatives = sum(|s| &s.derivatives);
    merged.warnings = sum(|s| &s.warnings);
    merged.total_wall_seconds = started.elapsed().as_secs_f64();
    files.push(output::json(&staging, "summary.json", &merged)?);
    run_dir.commit(&files)?;
    if !quiet {
        println!("merged {} shards of {} members → {}", parts.len(), merged.members, out.display());
    }
    Ok(())
}
