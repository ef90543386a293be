//! `ddirac run`: reads the spec, applies `--set`, validates, integrates while streaming rows to
//! `trajectory.csv` (and the exact solution, when the system has one, to `exact.csv`), writes
//! `summary.json` (and the figures), and commits the files only on success, replacing those of the earlier run in the directory as a set (see [`RunDir`]).

use std::path::{Path, PathBuf};
use std::time::Instant;

use ddirac::Role;

use crate::diagnostics::{CliError, SpecSource};
use crate::exact::ExactFile;
use crate::output::{self, Trajectory};
use crate::progress::Progress;
use crate::run_dir::RunDir;
use crate::{estimate, initial_entries, lock, overrides, plot, report, signals, spec};

/// Options of `ddirac run`.
pub struct RunOptions {
    /// The spec file.
    pub spec: PathBuf,
    /// `--out`.
    pub out: Option<PathBuf>,
    /// `--set KEY=VALUE` arguments, in order.
    pub set: Vec<String>,
    /// `--quiet`.
    pub quiet: bool,
    /// `--format` (empty: `output.format` of the spec, else CSV).
    pub format: Vec<output::Format>,
}

/// Runs a spec; on success the output directory holds `trajectory.csv` and `summary.json`.
pub fn run(options: &RunOptions) -> Result<(), CliError> {
    let started = Instant::now();
    let path = &options.spec;
    let text = read(path)?;
    if crate::rigid::names_rigid_body(&text, &options.set) {
        let request = crate::rigid::Request {
            spec: path,
            set: &options.set,
            out: options.out.as_deref(),
            quiet: options.quiet,
            format: &options.format,
        };
        return crate::rigid::run(&request, text, started);
    }
    let loaded = load_text(path, text, &options.set)?;
    loaded.print_notes();
    let Loaded { source, spec, plan, .. } = loaded;
    let formats = output::Formats::choose(&options.format, spec.output.format.as_ref(), &source)?;

    let dir = output_dir(options.out.as_deref(), &plan, path);
    estimate::check(&source, &spec, &plan, formats, &dir, 1, options.quiet)?;
    let plots = spec.output.plots.as_ref().is_some_and(|p| *p.get_ref());
    let mut progress = Progress::new(plan.problem.steps as u64, options.quiet);
    let result = write_run(&source, &plan, path, &dir, formats, plots, started, &mut progress);
    progress.finish();
    let finished = result?;
    if !options.quiet {
        println!("{}", finished.text);
    }
    Ok(())
}

/// A spec read, with its `--set` overrides applied, parsed and validated.
pub struct Loaded {
    /// The spec text that diagnostics quote.
    pub source: SpecSource,
    /// The parsed spec.
    pub spec: spec::Spec,
    /// The validated spec.
    pub plan: spec::Plan,
    /// What the overrides did that the user may not expect (a step h changed by overriding another
    /// key of `[time]`), for the commands to print before they run.
    pub notes: Vec<String>,
}

impl Loaded {
    /// Prints the notes on stderr, each as `note: …`.
    pub fn print_notes(&self) {
        for note in &self.notes {
            eprintln!("note: {note}");
        }
    }
}

/// Reads the spec at `path`, applies `set` and validates it.
pub fn load(path: &Path, set: &[String]) -> Result<Loaded, CliError> {
    load_text(path, read(path)?, set)
}

/// The text of the spec file at `path`.
pub fn read(path: &Path) -> Result<String, CliError> {
    std::fs::read_to_string(path).map_err(|source| CliError::Read {
        what: "the spec file",
        path: path.to_owned(),
        source,
    })
}

/// Applies `set` to the spec text `text` of the file `path` and validates it. Assignments of
/// initial entries by coordinate name (`initial.q.phi1=0.3`) are applied to the validated problem
/// ([`initial_entries`]); the others edit the text.
pub fn load_text(path: &Path, text: String, set: &[String]) -> Result<Loaded, CliError> {
    let original = SpecSource::new(path.display().to_string(), text);
    let (entries, edits) = initial_entries::split(set)?;
    let source = if edits.is_empty() {
        original.clone()
    } else {
        let edited = overrides::apply(&original, &edits)?;
        SpecSource::new(format!("{} (with --set)", path.display()), edited)
    };
    let spec = spec::parse(&source)?;
    let mut plan = spec::validate(&source, &spec)?;
    if !entries.is_empty() {
        let names: Vec<String> = plan.system.coordinates().into_iter().map(|c| c.name).collect();
        let list: Vec<initial_entries::Entry> = entries.iter().map(|(_, e, _)| e.clone()).collect();
        let values: Vec<f64> = entries.iter().map(|(_, _, v)| *v).collect();
        initial_entries::apply(&mut plan.problem, &names, &list, &values)
            .map_err(|why| CliError::Set { arg: entries[0].0.clone(), why })?;
    }
    let time_keys: Vec<&str> = edits
        .iter()
        .filter_map(|e| e.split_once('=')?.0.trim().strip_prefix("time."))
        .map(|key| key.trim_matches(|c| c == '"' || c == ' '))
        .collect();
    let notes = spec::changed_step(&original, &source, &time_keys).into_iter().collect();
    Ok(Loaded { source, spec, plan, notes })
}

/// The output directory: `--out`, else `output.directory` of the spec, else `out/<spec file stem>`.
pub fn output_dir(out: Option<&Path>, plan: &spec::Plan, spec: &Path) -> PathBuf {
    match (out, &plan.directory) {
        (Some(out), _) => out.to_owned(),
        (None, Some(d)) => PathBuf::from(d),
        (None, None) => {
            let stem = spec.file_stem().map_or("run".into(), |s| s.to_string_lossy().into_owned());
            Path::new("out").join(stem)
        }
    }
}

/// What [`write_run`] did.
pub struct Finished {
    /// The run's summary.
    pub summary: ddirac::Summary,
    /// Its human text.
    pub text: String,
    /// The number of figures drawn (each as PNG and SVG).
    pub figures: usize,
}

/// Integrates and writes the output files (and the figures, if `plots`) into `dir`, which the run
/// owns meanwhile; reports each row to `progress`.
#[allow(clippy::too_many_arguments)]
pub fn write_run(
    source: &SpecSource,
    plan: &spec::Plan,
    spec: &Path,
    dir: &Path,
    formats: output::Formats,
    plots: bool,
    started: Instant,
    progress: &mut Progress,
) -> Result<Finished, CliError> {
    let run_dir = RunDir::open(dir, &lock::command_line())?;
    let staging = run_dir.staging();
    let coordinates = plan.system.coordinates();
    let names: Vec<String> = coordinates.iter().map(|c| c.name.clone()).collect();
    let group: Vec<String> = coordinates.iter().filter(|c| c.role == Role::Group).map(|c| c.name.clone()).collect();
    let switching = plan.method.atlas && !plan.system.charts().is_empty();
    let mut trajectory = Trajectory::create(staging, &names, &group, switching, formats)?;
    let system = plan.system.as_ref();
    // The exact solution goes with the CSV: a run asked for NumPy files only writes no CSV at all.
    let mut exact = formats.csv.then(|| ExactFile::new(staging, system, &plan.problem.q0, plan.output.wrap_angles));
    let summary = plan
        .system
        .integrate(&plan.problem, &plan.method, &plan.output, &mut |row| {
            progress.update(row.k);
            signals::check(Some(row.k))?;
            if let Some(exact) = &mut exact {
                exact.write(system, row)?;
            }
            Ok(trajectory.write(row)?)
        })
        .map_err(|e| library_error(source, plan, dir, e))?;
    report::print_warnings(&summary.warnings);
    let mut files = trajectory.finish()?;
    if let Some(exact) = exact {
        files.extend(exact.finish()?);
    }
    let total = started.elapsed().as_secs_f64();
    let json = report::summary_json(plan, &summary, spec, total);
    files.push(output::json(staging, "summary.json", &json)?);
    let mut text = report::human(plan, &summary, dir, total);
    let mut figures = 0;
    if plots {
        let drawn = plot::plot_run(staging).map_err(|e| CliError::figure(dir, e))?;
        figures = drawn.len() / 2;
        files.extend(drawn.iter().filter_map(|p| p.strip_prefix(staging).ok()).map(Path::to_path_buf));
        text.push_str(&format!("\n  figures          {figures} (PNG and SVG)"));
    }
    run_dir.commit(&files)?;
    Ok(Finished { summary, text, figures })
}

/// A library error as a diagnostic: pointing at the spec value it concerns when there is one. A
/// numerical failure stays one ([`CliError::Integration`] or [`CliError::IntegrationAt`]).
fn library_error(source: &SpecSource, plan: &spec::Plan, dir: &Path, error: ddirac::Error) -> CliError {
    use ddirac::Error as E;
    if let E::Output(inner) = error {
        let inner = match inner.downcast::<signals::Interrupted>() {
            Ok(interrupted) => return CliError::Interrupted(*interrupted),
            Err(other) => other,
        };
        return match inner.downcast::<output::FileError>() {
            Ok(file) => (*file).into(),
            Err(other) => CliError::Output { path: dir.to_owned(), source: std::io::Error::other(other) },
        };
    }
    if let E::Interrupted { step, .. } = error {
        if let Err(interrupted) = signals::check(Some(step)) {
            return CliError::Interrupted(interrupted);
        }
    }
    let numerical = !matches!(
        error,
        E::Size { .. }
            | E::NonFinite { .. }
            | E::Invalid { .. }
            | E::NotInvariant { .. }
            | E::NotPeriodic { .. }
            | E::Undecided { .. }
            | E::OffPrimaryConstraint { .. }
            | E::Undetermined { .. }
            | E::NoSymmetry
            | E::Chart { .. }
            | E::NotCompiled(_)
    );
    match (plan.spans.diagnostic(source, &error), numerical) {
        (Some(diagnostic), true) => CliError::IntegrationAt(diagnostic),
        (Some(diagnostic), false) => diagnostic.into(),
        (None, _) => CliError::Integration(error),
    }
}
