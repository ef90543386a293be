//! `ddirac run` of the rigid body (`system = "rigid_body"`, [`ddirac::systems::RigidBody`]): its spec
//! ([`plan`]), its run into an output directory (staged, locked and committed as a set, as every
//! run), and what it writes ([`report`]): `trajectory.csv` with the columns `t`, `R11` … `R33`,
//! `Pi1` … `Pi3`, `energy`, `momentum_x` … `momentum_z` (the spatial angular momentum R Π), the same
//! columns as `npy/<column>.npy`, `summary.json` with `final.R` (three rows) and `final.Pi`, and
//! with `output.plots = true` the figures of [`crate::plot`]'s rigid-body kind; `ddirac check`
//! ([`check`]) and `ddirac run --compare` ([`compare`]) of the same specs.

pub mod check;
pub mod compare;
pub mod plan;
pub mod report;

use std::path::{Path, PathBuf};
use std::time::Instant;

use ddirac::rigid::RigidStepper;

use crate::diagnostics::{CliError, SpecSource};
use crate::output::{self, Trajectory};
use crate::progress::Progress;
use crate::run_dir::RunDir;
use crate::{estimate, initial_entries, lock, overrides, plot, signals, spec};

pub use plan::RigidPlan;

pub use crate::spec::RIGID_BODY as NAME;

/// What `ddirac run` (and `check`) was asked, for a rigid body's spec.
pub struct Request<'a> {
    /// The spec file.
    pub spec: &'a Path,
    /// `--set KEY=VALUE` arguments, in order.
    pub set: &'a [String],
    /// `--out`.
    pub out: Option<&'a Path>,
    /// `--quiet`.
    pub quiet: bool,
    /// `--format` (empty: `output.format` of the spec, else CSV).
    pub format: &'a [output::Format],
}

/// Whether the spec text, with the `--set` assignments `set` applied, names a rigid system: the
/// built-in body (`system = "rigid_body"`) or a `[system]` table with an `attitude`. A text that does
/// not parse does not: its run reports the error.
pub fn names_rigid_body(text: &str, set: &[String]) -> bool {
    let named = |text: &str| {
        toml::from_str::<toml::Table>(text).ok().is_some_and(|t| match t.get("system") {
            Some(toml::Value::String(name)) => name == NAME,
            Some(toml::Value::Table(table)) => table.contains_key("attitude"),
            _ => false,
        })
    };
    let edits: Vec<String> = set.iter().filter(|a| a.trim_start().starts_with("system")).cloned().collect();
    if edits.is_empty() {
        return named(text);
    }
    overrides::apply(&SpecSource::new("spec".to_owned(), text.to_owned()), &edits).is_ok_and(|edited| named(&edited))
}

/// A rigid body's spec read, with its `--set` assignments applied, parsed and validated.
pub struct LoadedRigid {
    /// The spec text that diagnostics quote.
    pub source: SpecSource,
    /// The parsed spec.
    pub spec: spec::Spec,
    /// The validated spec.
    pub plan: RigidPlan,
}

/// Applies `set` to the spec text `text` of the file `path` and validates it as a rigid body's.
/// Assignments of initial entries (`initial.Pi.2=0.5`, `initial.v.a1=3`) are applied to the validated
/// problem ([`initial_entries::apply_rigid`]); the others edit the text.
pub fn load_text(path: &Path, text: String, set: &[String]) -> Result<LoadedRigid, CliError> {
    let (entries, edits) = initial_entries::split(set)?;
    let original = SpecSource::new(path.display().to_string(), text);
    let source = if edits.is_empty() {
        original
    } else {
        SpecSource::new(format!("{} (with --set)", path.display()), overrides::apply(&original, &edits)?)
    };
    let spec = spec::parse(&source)?;
    let mut plan = plan::validate(&source, &spec)?;
    if !entries.is_empty() {
        let list: Vec<initial_entries::Entry> = entries.iter().map(|(_, e, _)| e.clone()).collect();
        let values: Vec<f64> = entries.iter().map(|(_, _, v)| *v).collect();
        let shape = shape_names(&plan);
        initial_entries::apply_rigid(&mut plan.problem, &shape, &list, &values)
            .map_err(|why| CliError::Set { arg: entries[0].0.clone(), why })?;
    }
    Ok(LoadedRigid { source, spec, plan })
}

/// `ddirac run` of a rigid body's spec whose text is `text`.
pub fn run(request: &Request<'_>, text: String, started: Instant) -> Result<(), CliError> {
    let LoadedRigid { source, spec, plan } = load_text(request.spec, text, request.set)?;
    let formats = output::Formats::choose(request.format, spec.output.format.as_ref(), &source)?;
    let dir = output_dir(request, &plan);
    let columns = report::columns(&shape_names(&plan));
    let estimate = estimate::Estimate::of(plan.problem.steps, plan.every, columns.len(), formats);
    let grid = (plan.problem.steps, plan.every);
    estimate::check_estimate(&source, &spec, estimate, grid, &dir, 1, request.quiet)?;
    let mut progress = Progress::new(plan.problem.steps as u64, request.quiet);
    let plots = spec.output.plots.as_ref().is_some_and(|p| *p.get_ref());
    let result = write_run(&source, &spec, &plan, request.spec, &dir, formats, plots, started, &mut progress);
    progress.finish();
    let (text, _) = result?;
    if !request.quiet {
        println!("{text}");
    }
    Ok(())
}

/// The output directory: `--out`, else `output.directory` of the spec, else `out/<spec file stem>`.
pub fn output_dir(request: &Request<'_>, plan: &RigidPlan) -> PathBuf {
    match (request.out, &plan.directory) {
        (Some(out), _) => out.to_owned(),
        (None, Some(d)) => PathBuf::from(d),
        (None, None) => {
            let stem = request.spec.file_stem().map_or("run".into(), |s| s.to_string_lossy().into_owned());
            Path::new("out").join(stem)
        }
    }
}

/// Integrates and writes the trajectory and `summary.json` (and the figures, if `plots`) into `dir`;
/// returns the human summary and the library's.
#[allow(clippy::too_many_arguments)]
pub(crate) fn write_run(
    source: &SpecSource,
    spec: &spec::Spec,
    plan: &RigidPlan,
    path: &Path,
    dir: &Path,
    formats: output::Formats,
    plots: bool,
    started: Instant,
    progress: &mut Progress,
) -> Result<(String, ddirac::rigid::RigidSummary), CliError> {
    let run_dir = RunDir::open(dir, &lock::command_line())?;
    let staging = run_dir.staging();
    let mut trajectory = Trajectory::with_columns(staging, &report::columns(&shape_names(plan)), formats)?;
    let refused = |e: ddirac::Error| plan::refusal(source, spec, e);
    let mut stepper = RigidStepper::new(&plan.body, plan.problem.clone(), &plan.method).map_err(refused)?;
    let mut write = |stepper: &RigidStepper<'_, _>| -> Result<(), CliError> {
        let row = stepper.row();
        progress.update(row.k);
        signals::check(Some(row.k)).map_err(CliError::Interrupted)?;
        Ok(trajectory.write_values(|| report::values(&row))?)
    };
    write(&stepper)?;
    while !stepper.is_finished() {
        stepper.step().map_err(CliError::Integration)?;
        if stepper.k() % plan.every == 0 || stepper.is_finished() {
            write(&stepper)?;
        }
    }
    let summary = stepper.summary();
    crate::report::print_warnings(&summary.warnings);
    let mut files = trajectory.finish()?;
    let total = started.elapsed().as_secs_f64();
    let json = report::summary_json(plan, &summary, Some(path), Some(total));
    files.push(output::json(staging, "summary.json", &json)?);
    let mut text = report::human(plan, &summary, dir, total);
    if plots {
        let drawn = plot::plot_run(staging).map_err(|e| CliError::figure(dir, e))?;
        files.extend(drawn.iter().filter_map(|p| p.strip_prefix(staging).ok()).map(Path::to_path_buf));
        text.push_str(&format!("\n  figures          {} (PNG and SVG)", drawn.len() / 2));
    }
    run_dir.commit(&files)?;
    Ok((text, summary))
}

/// The names of the plan's shape coordinates.
pub fn shape_names(plan: &RigidPlan) -> Vec<String> {
    ddirac::rigid::RigidSystem::shape(&plan.body).into_iter().map(|c| c.name).collect()
}
