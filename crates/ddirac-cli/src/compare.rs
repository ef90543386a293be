//! `ddirac run SPEC --compare`: the spec run twice, with the reduced equations (paper
//! `eq:geometricequations`, reconstruction of the group coordinates) and with the unreduced discrete
//! Lagrange–Dirac equations, everything else equal.
//!
//! The two runs go to `DIR/reduced` and `DIR/unreduced` as ordinary runs; `DIR/compare.csv` holds,
//! row by row, t and the differences reduced − unreduced of every coordinate (angles wrapped to
//! (−π, π]) and of the discrete energy L_d(q_k, q_{k+1}); `DIR/compare.png` / `.svg` draw them, the
//! middle panel being the paper's bottom panel of its energy figure (§7.2). Its numbers are written as
//! `trajectory.csv` writes them ([`output::number`]: the shortest text that reads back as the same
//! f64, at most 24 characters). The two flows agree to round-off, so the differences measure the
//! round-off of both; the wall times show what the reduction costs or saves.

use std::path::{Path, PathBuf};
use std::time::Instant;

use ddirac::{Coordinate, CoordinateKind};

use crate::diagnostics::CliError;
use crate::plot::{self, Envelope, Figure, Panel, RunSummary, Series, ToolError, TrajectoryFile};
use crate::progress::Progress;
use crate::run::{self, Loaded, RunOptions};
use crate::{estimate, lock, output, run_dir};

/// Name of the table of differences in the output directory.
pub const TABLE: &str = "compare.csv";

/// The two runs' directory names, reduced first.
const RUNS: [&str; 2] = ["reduced", "unreduced"];

/// Runs `options.spec` reduced and unreduced and compares them.
pub fn compare(options: &RunOptions) -> Result<(), miette::Report> {
    let text = run::read(&options.spec)?;
    if crate::rigid::names_rigid_body(&text, &options.set) {
        let request = crate::rigid::Request {
            spec: &options.spec,
            set: &options.set,
            out: options.out.as_deref(),
            quiet: options.quiet,
            format: &options.format,
        };
        return crate::rigid::compare::compare(&request, text);
    }
    let loaded = run::load_text(&options.spec, text, &options.set)?;
    loaded.print_notes();
    let Loaded { source, spec, mut plan, .. } = loaded;
    let formats =
        output::Formats::choose(&options.format, spec.output.format.as_ref(), &source).map_err(CliError::from)?;
    let dir = run::output_dir(options.out.as_deref(), &plan, &options.spec);
    estimate::check(&source, &spec, &plan, formats, &dir, 2, options.quiet).map_err(CliError::from)?;
    let plots = spec.output.plots.as_ref().is_some_and(|p| *p.get_ref());
    // DIR holds the two runs and their comparison: it is owned by this command while it lasts.
    let (lock, created) = run_dir::lock(&dir, &lock::command_line())?;
    // What the spec itself asks for: a failure of the run it does not ask for must not be labelled
    // as asked for in the spec (`reduced = false` is not "reduction asked here").
    let asked = plan.method.reduced;
    let reduced_span = plan.spans.reduced.take();
    let steps = plan.problem.steps as u64;
    let mut progress = Progress::new(2 * steps, options.quiet);
    let mut walls = vec![];
    let mut figures = 0;
    for (i, name) in RUNS.into_iter().enumerate() {
        plan.method.reduced = i == 0;
        plan.spans.reduced = if plan.method.reduced == asked { reduced_span.clone() } else { None };
        progress.stage(i as u64 * steps, name);
        let result = run::write_run(
            &source,
            &plan,
            &options.spec,
            &dir.join(name),
            formats,
            plots,
            Instant::now(),
            &mut progress,
        );
        match result {
            Ok(finished) => {
                walls.push(finished.summary.wall_seconds);
                figures += finished.figures;
            }
            Err(error) => {
                drop(lock);
                if created {
                    // Removes the directory this command made, if the failed run left it empty.
                    let _ = std::fs::remove_dir(&dir);
                }
                return Err(miette::Report::new(error).wrap_err(failed(name, asked, reduced_span.is_some())));
            }
        }
    }
    progress.finish();

    let coordinates = plan.system.coordinates();
    let differences = differences(&dir, &coordinates)?;
    figures += plot::save(&differences.figure, &dir)?.len() / 2;
    drop(lock);
    if !options.quiet {
        println!("{}", report(&differences.summary, &dir, &walls, &differences, figures));
    }
    Ok(())
}

/// What a failed run was: the one the spec asks for, or the other one `--compare` adds.
fn failed(name: &str, asked: bool, written: bool) -> String {
    let own = if asked { RUNS[0] } else { RUNS[1] };
    if name == own {
        return format!("the {name} run failed");
    }
    let says = match (asked, written) {
        (true, _) => "`reduced = true`",
        (false, true) => "`reduced = false`",
        (false, false) => "the unreduced equations (`reduced` is not set)",
    };
    format!("the {name} run failed: the spec asks for {says}, and --compare runs the {name} equations as well")
}

/// The largest differences and the figure of them.
struct Differences {
    /// max |Δq_i| per coordinate, in order.
    coordinates: Vec<(String, f64)>,
    /// max |ΔL_d| (None if no row has both discrete energies).
    discrete_energy: Option<f64>,
    figure: Figure,
    /// The summary of the reduced run.
    summary: RunSummary,
}

/// Reads both runs row by row, writes `compare.csv` and gathers the figure.
fn differences(dir: &Path, coordinates: &[Coordinate]) -> Result<Differences, ToolError> {
    let names: Vec<String> = coordinates.iter().map(|c| c.name.clone()).collect();
    let [reduced, unreduced] = RUNS.map(|name| TrajectoryFile::open(&dir.join(name), &names));
    let (reduced, unreduced) = (reduced?, unreduced?);
    if reduced.rows != unreduced.rows {
        return Err(ToolError::malformed(
            &unreduced.path,
            format!("{} rows, but the reduced run has {}", unreduced.rows, reduced.rows),
        ));
    }
    let rows = reduced.rows;
    let table = dir.join(TABLE);
    let temporary = plot::Temporary::for_target(&table);
    let mut writer = csv::Writer::from_path(temporary.path()).map_err(|e| ToolError::write(&table, e))?;
    let header = std::iter::once("t".to_owned())
        .chain(names.iter().map(|n| format!("d_{n}")))
        .chain(["d_discrete_energy".to_owned()]);
    writer.write_record(header).map_err(|e| ToolError::write(&table, e))?;

    let mut max_q = vec![0.0f64; names.len()];
    let mut max_ld: Option<f64> = None;
    let mut dq: Vec<Envelope> = names.iter().map(|_| Envelope::new(rows)).collect();
    let (mut ld_reduced, mut ld_unreduced, mut d_ld) = (Envelope::new(rows), Envelope::new(rows), Envelope::new(rows));
    let (mut a, mut b) = (reduced.rows()?, unreduced.rows()?);
    let mut fields: Vec<String> = vec![];
    while let (Some(r), Some(u)) = (a.next()?, b.next()?) {
        if (r.t - u.t).abs() > 1e-9 * r.t.abs().max(1.0) {
            return Err(ToolError::malformed(
                &unreduced.path,
                format!("t = {} where the reduced run has t = {}", u.t, r.t),
            ));
        }
        fields.clear();
        fields.push(output::number(r.t));
        for (i, c) in coordinates.iter().enumerate() {
            let mut d = r.q[i] - u.q[i];
            // Wrapping only what exceeds π keeps tiny differences exact (wrap(−1e−18) rounds to 0).
            if c.kind == CoordinateKind::Angle && d.abs() > std::f64::consts::PI {
                d = ddirac::chart::wrap(d);
            }
            max_q[i] = max_q[i].max(d.abs());
            dq[i].push(r.t, Some(d));
            fields.push(output::number(d));
        }
        let d = r.discrete_energy.zip(u.discrete_energy).map(|(x, y)| x - y);
        if let Some(d) = d {
            max_ld = Some(max_ld.unwrap_or(0.0).max(d.abs()));
        }
        ld_reduced.push(r.t, r.discrete_energy);
        ld_unreduced.push(r.t, u.discrete_energy);
        d_ld.push(r.t, d);
        fields.push(d.map_or(String::new(), output::number));
        writer.write_record(&fields).map_err(|e| ToolError::write(&table, e))?;
    }
    writer.flush().map_err(|source| ToolError::Write { path: table.clone(), source })?;
    drop(writer);
    temporary.commit(&table)?;

    let mut panels = vec![];
    if max_ld.is_some() {
        panels.push(Panel::new(
            "t",
            "L_d(q_k, q_k+1)",
            vec![
                Series { wide: true, ..Series::named("unreduced", ld_unreduced.finish()) },
                Series::named("reduced", ld_reduced.finish()),
            ],
        ));
        panels.push(
            Panel::new("t", "ΔL_d", vec![Series::line(d_ld.finish())]).caption("discrete energy, reduced − unreduced"),
        );
    }
    let series = coordinates
        .iter()
        .zip(dq)
        .map(|(c, e)| Series::named(format!("Δ{}", c.name), e.finish()).wrapped(c.kind == CoordinateKind::Angle))
        .collect();
    panels.push(Panel::new("t", "Δq", series).caption("coordinates, reduced − unreduced"));
    let summary = RunSummary::read(&dir.join(RUNS[0]))?;
    let figure = Figure::new("compare", format!("{}: reduced and unreduced runs", summary.system), panels)
        .subtitle(summary.description.replace(", reduced", ""));
    Ok(Differences { coordinates: names.into_iter().zip(max_q).collect(), discrete_energy: max_ld, figure, summary })
}

/// The text printed after a comparison.
fn report(summary: &RunSummary, dir: &Path, walls: &[f64], d: &Differences, figures: usize) -> String {
    let path = |name: &str| -> PathBuf { dir.join(name) };
    let largest: Vec<String> = d.coordinates.iter().map(|(n, v)| format!("{n} {v:.3e}")).collect();
    let (reduced, unreduced) = (walls[0], walls[1]);
    let mut lines = vec![
        format!("{}: reduced and unreduced runs of {}", summary.system, summary.description.replace(", reduced", "")),
        format!("  reduced          {reduced:.3} s integrating, output {}", path(RUNS[0]).display()),
        format!("  unreduced        {unreduced:.3} s integrating, output {}", path(RUNS[1]).display()),
        format!("  time ratio       unreduced / reduced = {:.3}", unreduced / reduced.max(f64::MIN_POSITIVE)),
        format!("  max |difference| {}", largest.join(", ")),
    ];
    if let Some(ld) = d.discrete_energy {
        lines.push(format!("                   discrete energy L_d {ld:.3e}"));
    }
    lines.push(format!("  table            {}", path(TABLE).display()));
    lines.push(format!("  figures          {figures} (PNG and SVG), compare.png in {}", dir.display()));
    lines.join("\n")
}
