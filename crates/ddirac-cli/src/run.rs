//! `ddirac run`: reads the spec, applies `--set`, validates, integrates while streaming rows to
//! `trajectory.csv`, writes `summary.json`, and commits both files only on success.

use std::path::{Path, PathBuf};
use std::time::Instant;

use ddirac::Role;

use crate::diagnostics::{CliError, SpecSource};
use crate::output::{self, Trajectory};
use crate::progress::Progress;
use crate::{overrides, plot, report, spec};

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
    let Loaded { source, spec, plan } = load(path, &options.set)?;
    let formats = output::Formats::choose(&options.format, spec.output.format.as_ref(), &source)?;

    let dir = output_dir(options.out.as_deref(), &plan, path);
    let created = !dir.exists();
    let mut progress = Progress::new(plan.problem.steps as u64, options.quiet);
    let result = write_run(&source, &plan, path, &dir, formats, started, &mut progress);
    progress.finish();
    if result.is_err() && created {
        let _ = std::fs::remove_dir(&dir);
    }
    let (_, mut summary_text) = result?;
    if spec.output.plots.as_ref().is_some_and(|p| *p.get_ref()) {
        let figures = plot::plot_run(&dir)
            .map_err(|e| CliError::Output { dir: dir.clone(), source: std::io::Error::other(e) })?;
        summary_text.push_str(&format!("\n  figures          {} (PNG and SVG)", figures.len() / 2));
    }
    if !options.quiet {
        println!("{summary_text}");
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
}

/// Reads the spec at `path`, applies `set` and validates it.
pub fn load(path: &Path, set: &[String]) -> Result<Loaded, CliError> {
    let text = std::fs::read_to_string(path).map_err(|source| CliError::Read { path: path.to_owned(), source })?;
    let original = SpecSource::new(path.display().to_string(), text);
    let source = if set.is_empty() {
        original
    } else {
        let edited = overrides::apply(&original, set)?;
        SpecSource::new(format!("{} (with --set)", path.display()), edited)
    };
    let spec = spec::parse(&source)?;
    let plan = spec::validate(&source, &spec)?;
    Ok(Loaded { source, spec, plan })
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

/// Integrates and writes the output files, reporting each row to `progress`; returns the summary
/// and its human text.
pub fn write_run(
    source: &SpecSource,
    plan: &spec::Plan,
    spec: &Path,
    dir: &Path,
    formats: output::Formats,
    started: Instant,
    progress: &mut Progress,
) -> Result<(ddirac::Summary, String), CliError> {
    let io = |source| CliError::Output { dir: dir.to_owned(), source };
    std::fs::create_dir_all(dir).map_err(io)?;
    let coordinates = plan.system.coordinates();
    let names: Vec<String> = coordinates.iter().map(|c| c.name.clone()).collect();
    let group: Vec<String> = coordinates.iter().filter(|c| c.role == Role::Group).map(|c| c.name.clone()).collect();
    let mut trajectory = Trajectory::create(dir, &names, &group, formats).map_err(io)?;
    let summary = plan
        .system
        .integrate(&plan.problem, &plan.method, &plan.output, &mut |row| {
            progress.update(row.k);
            Ok(trajectory.write(row)?)
        })
        .map_err(|e| library_error(source, plan, dir, e))?;
    report::print_warnings(&summary.warnings);
    let mut staged = trajectory.finish().map_err(io)?;
    let total = started.elapsed().as_secs_f64();
    let json = report::summary_json(plan, &summary, spec, total);
    let summary_file = output::json(dir, "summary.json", &json).map_err(io)?;
    staged.push(summary_file);
    output::commit(staged).map_err(io)?;
    let text = report::human(plan, &summary, dir, total);
    Ok((summary, text))
}

/// A library error as a diagnostic: pointing at the spec value it concerns when there is one.
fn library_error(source: &SpecSource, plan: &spec::Plan, dir: &Path, error: ddirac::Error) -> CliError {
    if let ddirac::Error::Output(inner) = error {
        let source = match inner.downcast::<std::io::Error>() {
            Ok(io) => *io,
            Err(other) => std::io::Error::other(other),
        };
        return CliError::Output { dir: dir.to_owned(), source };
    }
    match plan.spans.diagnostic(source, &error) {
        Some(diagnostic) => diagnostic.into(),
        None => CliError::Integration(error),
    }
}
