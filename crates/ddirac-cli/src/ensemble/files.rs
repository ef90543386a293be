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

use ddirac::ensemble::Rows;
use serde::{Deserialize, Serialize};

use super::{Ensemble, Failure, MembersFrom, Results, DIAGNOSTICS};
use crate::diagnostics::CliError;
use crate::output::{self, FileError};
use crate::progress::Progress;
use crate::run_dir::RunDir;
use crate::{lock, npy, run};

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
    /// The coordinates.
    pub coordinates: Vec<String>,
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
    let total = ensemble.members.len();
    let (range, shard) = match options.shard {
        Some((index, count)) => {
            if count == 0 || index >= count {
                return Err(CliError::Set {
                    arg: format!("--shard {index}/{count}"),
                    why: "give I/N with 0 ≤ I < N (I counts from 0, as SLURM_ARRAY_TASK_ID)".into(),
                });
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
    let keep = |offset: usize, rows: &Rows| -> Result<(), ddirac::OutputError> {
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
        system: ensemble.base.plan.name.clone(),
        coordinates: ensemble.coordinates(),
        keys: ensemble.members.keys.iter().map(super::Key::name).collect(),
        members: total,
        shard,
        finished: results.finished.iter().filter(|f| **f).count(),
        failed: results.failures.len(),
        failures: results.failures.clone(),
        steps: ensemble.base.plan.problem.steps,
        step: ensemble.base.plan.problem.step,
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
    let single = run::output_dir(None, &ensemble.base.plan, &ensemble.path);
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
    let names = ensemble.coordinates();
    let n = names.len();
    let mut files = vec![];
    // final.csv
    let mut text = String::from("member,status");
    for name in &names {
        text.push(',');
        text.push_str(name);
    }
    for name in &names {
        text.push_str(",p_");
        text.push_str(name);
    }
    text.push('\n');
    for m in 0..results.len() {
        text.push_str(&(results.first + m).to_string());
        text.push_str(if results.finished[m] { ",ok" } else { ",failed" });
        for v in results.final_q[m * n..(m + 1) * n].iter().chain(&results.final_p[m * n..(m + 1) * n]) {
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
    let mut arrays: Vec<(String, &str, Vec<u64>, Vec<u8>)> = vec![
        ("final_q".into(), "<f8", vec![count, n as u64], npy::f64_bytes(&results.final_q)),
        ("final_p".into(), "<f8", vec![count, n as u64], npy::f64_bytes(&results.final_p)),
        ("status".into(), "|u1", vec![count], results.finished.iter().map(|f| u8::from(!f)).collect()),
        ("steps".into(), "<i8", vec![count], results.steps.iter().flat_map(|s| (*s as i64).to_le_bytes()).collect()),
    ];
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
    n: usize,
    /// q, p, energy: file, header length.
    files: [Mutex<(File, u64)>; 3],
}

const TRAJECTORY_FILES: [&str; 3] = ["q", "p", "energy"];

impl Trajectories {
    fn create(dir: &Path, ensemble: &Ensemble, members: usize) -> Result<Self, FileError> {
        let (rows, n) = (ensemble.rows(), ensemble.coordinates().len());
        let t = ensemble.times();
        let path = dir.join("npy/t.npy");
        output::at(&path, npy::write(&path, "<f8", &[t.len() as u64], &npy::f64_bytes(&t)))?;
        let (m, r) = (members as u64, rows as u64);
        let shapes = [vec![m, r, n as u64], vec![m, r, n as u64], vec![m, r]];
        let open = |name: &str, shape: &[u64]| -> Result<Mutex<(File, u64)>, FileError> {
            let path = dir.join(format!("npy/{name}.npy"));
            let header = npy::header_nd("<f8", shape);
            let mut file = output::at(&path, File::create(&path))?;
            output::at(&path, file.write_all(&header))?;
            let len = header.len() as u64 + shape.iter().product::<u64>() * 8;
            output::at(&path, file.set_len(len))?;
            Ok(Mutex::new((file, header.len() as u64)))
        };
        let files = [open("q", &shapes[0])?, open("p", &shapes[1])?, open("energy", &shapes[2])?];
        Ok(Self { dir: dir.to_owned(), rows, n, files })
    }

    /// Writes member `offset`'s rows into its block, NaN after its last row.
    fn write(&self, offset: usize, rows: &Rows) -> Result<(), FileError> {
        let (r, n) = (self.rows, self.n);
        let padded = |values: &[f64], width: usize| {
            let mut block = values.to_vec();
            block.resize(r * width, f64::NAN);
            npy::f64_bytes(&block)
        };
        let blocks = [(padded(&rows.q, n), n), (padded(&rows.p, n), n), (padded(&rows.energy, 1), 1)];
        for ((file, name), (bytes, width)) in self.files.iter().zip(TRAJECTORY_FILES).zip(blocks) {
            let path = self.dir.join(format!("npy/{name}.npy"));
            let mut guard = file.lock().expect("no panic while writing");
            let at = guard.1 + (offset * r * width * 8) as u64;
            output::at(&path, guard.0.seek(SeekFrom::Start(at)).and_then(|_| guard.0.write_all(&bytes)))?;
        }
        Ok(())
    }

    fn finish(self) -> Result<Vec<PathBuf>, FileError> {
        let mut files = vec![PathBuf::from("npy/t.npy")];
        for (file, name) in self.files.into_iter().zip(TRAJECTORY_FILES) {
            let relative = PathBuf::from(format!("npy/{name}.npy"));
            let path = self.dir.join(&relative);
            let (file, _) = file.into_inner().expect("no panic while writing");
            output::at(&path, file.sync_all())?;
            files.push(relative);
        }
        Ok(files)
    }
}

/// Runs `ddirac merge`: joins the directories of the shards of one ensemble into `out`.
pub fn merge(dirs: &[PathBuf], out: &Path, quiet: bool) -> Result<(), CliError> {
    let started = Instant::now();
    let read_summary = |dir: &PathBuf| -> Result<SummaryJson, CliError> {
        let path = dir.join("summary.json");
        let text = std::fs::read_to_string(&path).map_err(|source| CliError::Read { path: path.clone(), source })?;
        serde_json::from_str(&text)
            .map_err(|e| CliError::Merge(format!("`{}` is not the summary of an ensemble: {e}", path.display())))
    };
    let mut parts: Vec<(PathBuf, SummaryJson)> =
        dirs.iter().map(|d| read_summary(d).map(|s| (d.clone(), s))).collect::<Result<_, _>>()?;
    let Some((first_dir, first)) = parts.first().cloned() else {
        return Err(CliError::Merge("no directories given".into()));
    };
    for (dir, s) in &parts {
        if s.fingerprint != first.fingerprint || s.members != first.members {
            return Err(CliError::Merge(format!(
                "`{}` holds another ensemble than `{}` (another spec, --set or members)",
                dir.display(),
                first_dir.display()
            )));
        }
        if s.shard.is_none() {
            return Err(CliError::Merge(format!("`{}` holds a whole ensemble, not a shard", dir.display())));
        }
    }
    parts.sort_by_key(|(_, s)| s.shard.map(|s| s.first));
    let mut next = 0;
    for (dir, s) in &parts {
        let shard = s.shard.expect("checked above");
        if shard.first != next {
            let why = if shard.first < next { "overlaps the shard before it" } else { "leaves a gap before it" };
            return Err(CliError::Merge(format!(
                "`{}` (members {}..{}) {why}: members {next}..{} are missing or given twice",
                dir.display(),
                shard.first,
                shard.end,
                shard.first
            )));
        }
        next = shard.end;
    }
    if next != first.members {
        return Err(CliError::Merge(format!("members {next}..{} are in none of the directories", first.members)));
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
            let part = std::fs::read_to_string(&path).map_err(|source| CliError::Read { path, source })?;
            let body = if i == 0 { part.as_str() } else { part.split_once('\n').map_or("", |(_, b)| b) };
            text.push_str(body);
        }
        files.push(write_text(&staging, name, &text)?);
    }
    let mut names: Vec<String> = std::fs::read_dir(first_dir.join("npy"))
        .map_err(|source| CliError::Read { path: first_dir.join("npy"), source })?
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".npy"))
        .collect();
    names.sort();
    for name in names {
        let arrays: Vec<npy::Array> = parts
            .iter()
            .map(|(dir, _)| {
                let path = dir.join("npy").join(&name);
                npy::read(&path).map_err(|source| CliError::Read { path, source })
            })
            .collect::<Result<_, _>>()?;
        let (descr, shape, data) = if name == "t.npy" {
            if arrays.iter().any(|a| *a != arrays[0]) {
                return Err(CliError::Merge("the shards' time grids `npy/t.npy` differ".into()));
            }
            (arrays[0].descr.clone(), arrays[0].shape.clone(), arrays[0].data.clone())
        } else {
            if arrays.iter().any(|a| a.descr != arrays[0].descr || a.shape.get(1..) != arrays[0].shape.get(1..)) {
                return Err(CliError::Merge(format!("the shards' `npy/{name}` differ in type or shape")));
            }
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
