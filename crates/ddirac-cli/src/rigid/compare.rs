//! `ddirac run SPEC --compare` of a rigid system: the spec run twice, with the reduced equations (the
//! discrete Euler–Poincaré / Lagrange–Poincaré equations on (s, Π), R reconstructed) and with the
//! unreduced discrete Hamilton–Pontryagin equations on SO(3) × S, everything else equal; only a system
//! invariant under every rotation reduces (another is refused before anything runs).
//!
//! The runs go to `DIR/reduced` and `DIR/unreduced` as ordinary runs; `DIR/compare.csv` holds, row by
//! row, t and the differences reduced − unreduced of `R11` … `R33`, `Pi1` … `Pi3` and the shape
//! coordinates (`d_<column>`); `DIR/compare.png` / `.svg` draw them. The two flows agree to round-off.

use std::path::Path;
use std::time::Instant;

use ddirac::rigid::{RigidSystem, Symmetry};

use super::{load_text, output_dir, shape_names, write_run, LoadedRigid, Request};
use crate::diagnostics::CliError;
use crate::plot::{self, Envelope, Figure, Panel, Series, ToolError, TrajectoryFile};
use crate::progress::Progress;
use crate::{lock, output, run_dir};

/// Name of the table of differences in the output directory (as for systems in coordinates).
const TABLE: &str = "compare.csv";

/// The two runs' directory names, reduced first.
const RUNS: [&str; 2] = ["reduced", "unreduced"];

/// Runs the rigid system of the spec text `text` reduced and unreduced and compares them.
pub fn compare(request: &Request<'_>, text: String) -> Result<(), miette::Report> {
    let LoadedRigid { source, spec, mut plan } = load_text(request.spec, text, request.set)?;
    let symmetry = plan.body.symmetry();
    if symmetry != Symmetry::Rotations {
        let error = ddirac::Error::NotReducible { symmetry: symmetry.name() };
        let at = spec.method.reduced.as_ref().map_or(spec.system.span(), |r| r.span());
        return Err(CliError::from(
            source
                .error(Some(at), format!("--compare runs the reduced equations too, and {error}"), "this system")
                .with_help("run it without --compare: its unreduced run keeps the momenta its symmetry conserves"),
        )
        .into());
    }
    let formats =
        output::Formats::choose(request.format, spec.output.format.as_ref(), &source).map_err(CliError::from)?;
    let dir = output_dir(request, &plan);
    let (lock, created) = run_dir::lock(&dir, &lock::command_line())?;
    let plots = spec.output.plots.as_ref().is_some_and(|p| *p.get_ref());
    let steps = plan.problem.steps as u64;
    let mut progress = Progress::new(2 * steps, request.quiet);
    let mut walls = vec![];
    for (i, name) in RUNS.into_iter().enumerate() {
        plan.method.reduced = i == 0;
        progress.stage(i as u64 * steps, name);
        let result = write_run(
            &source,
            &spec,
            &plan,
            request.spec,
            &dir.join(name),
            formats,
            plots,
            Instant::now(),
            &mut progress,
        );
        match result {
            Ok((_, summary)) => walls.push(summary.wall_seconds),
            Err(error) => {
                drop(lock);
                if created {
                    let _ = std::fs::remove_dir(&dir);
                }
                return Err(miette::Report::new(error).wrap_err(format!("the {name} run failed")));
            }
        }
    }
    progress.finish();
    let mut columns: Vec<String> = (1..=3).flat_map(|i| (1..=3).map(move |j| format!("R{i}{j}"))).collect();
    columns.extend((1..=3).map(|i| format!("Pi{i}")));
    columns.extend(shape_names(&plan));
    let (largest, figure) = differences(&dir, &columns, &plan.name)?;
    let figures = plot::save(&figure, &dir)?.len() / 2;
    drop(lock);
    if !request.quiet {
        let (reduced, unreduced) = (walls[0], walls[1]);
        let worst = largest.iter().fold(("", 0.0f64), |w, (n, v)| if *v > w.1 { (n.as_str(), *v) } else { w });
        let lines = [
            format!("{}: reduced (by SO(3)) and unreduced runs", plan.name),
            format!("  reduced          {reduced:.3} s integrating, output {}", dir.join(RUNS[0]).display()),
            format!("  unreduced        {unreduced:.3} s integrating, output {}", dir.join(RUNS[1]).display()),
            format!("  time ratio       unreduced / reduced = {:.3}", unreduced / reduced.max(f64::MIN_POSITIVE)),
            if worst.1 == 0.0 {
                "  max |difference| 0: the runs agree bit for bit".to_owned()
            } else {
                format!("  max |difference| {:.3e} (in {})", worst.1, worst.0)
            },
            format!("  table            {}", dir.join(TABLE).display()),
            format!("  figures          {figures} (PNG and SVG), compare.png in {}", dir.display()),
        ];
        println!("{}", lines.join("\n"));
    }
    Ok(())
}

/// Reads both runs row by row, writes `compare.csv`; returns the largest difference of each column
/// and the figure of the differences.
fn differences(dir: &Path, columns: &[String], name: &str) -> Result<(Vec<(String, f64)>, Figure), ToolError> {
    let [reduced, unreduced] = RUNS.map(|run| TrajectoryFile::open(&dir.join(run), columns));
    let (reduced, unreduced) = (reduced?, unreduced?);
    if reduced.rows != unreduced.rows {
        let why = format!("{} rows, but the reduced run has {}", unreduced.rows, reduced.rows);
        return Err(ToolError::malformed(&unreduced.path, why));
    }
    let table = dir.join(TABLE);
    let temporary = plot::Temporary::for_target(&table);
    let mut writer = csv::Writer::from_path(temporary.path()).map_err(|e| ToolError::write(&table, e))?;
    let header = std::iter::once("t".to_owned()).chain(columns.iter().map(|c| format!("d_{c}")));
    writer.write_record(header).map_err(|e| ToolError::write(&table, e))?;
    let mut largest = vec![0.0f64; columns.len()];
    let mut envelopes: Vec<Envelope> = columns.iter().map(|_| Envelope::new(reduced.rows)).collect();
    let (mut a, mut b) = (reduced.rows()?, unreduced.rows()?);
    let mut fields: Vec<String> = vec![];
    while let (Some(r), Some(u)) = (a.next()?, b.next()?) {
        fields.clear();
        fields.push(output::number(r.t));
        for i in 0..columns.len() {
            let d = r.q[i] - u.q[i];
            largest[i] = largest[i].max(d.abs());
            envelopes[i].push(r.t, Some(d));
            fields.push(output::number(d));
        }
        writer.write_record(&fields).map_err(|e| ToolError::write(&table, e))?;
    }
    writer.flush().map_err(|source| ToolError::Write { path: table.clone(), source })?;
    drop(writer);
    temporary.commit(&table)?;
    let mut series: Vec<Vec<Series>> = vec![vec![], vec![], vec![]];
    for (i, (column, envelope)) in columns.iter().zip(envelopes).enumerate() {
        let panel = if i < 9 {
            0
        } else if i < 12 {
            1
        } else {
            2
        };
        series[panel].push(Series::named(format!("Δ{column}"), envelope.finish()));
    }
    let captions =
        ["attitude, reduced − unreduced", "body angular momentum, reduced − unreduced", "shape, reduced − unreduced"];
    let labels = ["ΔR", "ΔΠ", "Δs"];
    let panels = series
        .into_iter()
        .zip(captions.iter().zip(labels))
        .filter(|(s, _)| !s.is_empty())
        .map(|(s, (caption, label))| Panel::new("t", label, s).caption(*caption))
        .collect();
    let figure = Figure::new("compare", format!("{name}: reduced and unreduced runs"), panels);
    Ok((columns.iter().cloned().zip(largest).collect(), figure))
}
