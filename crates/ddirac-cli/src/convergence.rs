//! `ddirac convergence SPEC --steps 10,50,100,200`: the spec run with each number of steps N over
//! its duration T (h = T/N), and a table of N, h, the error of the final configuration and the
//! observed order between consecutive rows, p = ln(e_i / e_{i+1}) / ln(h_i / h_{i+1}).
//!
//! The error is ‖q_N − q(T)‖ against the system's exact solution when it has one (the summary's
//! `reference_error`; for the charged particle this is the paper's Table 1), else ‖q_N − q_N*‖
//! against the final configuration q_N* of the finest run (angle differences wrapped to (−π, π]),
//! which then has no error of its own. Writes `convergence.csv` and the log–log figure
//! `convergence.png` / `.svg` into the output directory.

use std::path::PathBuf;
use std::time::Instant;

use ddirac::CoordinateKind;

use crate::diagnostics::CliError;
use crate::plot::{self, Figure, Panel, Scale, Series, ToolError};
use crate::progress::Progress;
use crate::run::{self, Loaded};

/// Name of the table in the output directory.
pub const TABLE: &str = "convergence.csv";

/// Options of `ddirac convergence`.
pub struct Options {
    /// The spec file.
    pub spec: PathBuf,
    /// The step counts N.
    pub steps: Vec<u64>,
    /// `--out`.
    pub out: Option<PathBuf>,
    /// `--set KEY=VALUE` arguments, in order.
    pub set: Vec<String>,
    /// `--quiet`.
    pub quiet: bool,
}

/// One row of the table.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// N.
    pub steps: u64,
    /// h = T/N.
    pub step: f64,
    /// The error of the final configuration (`None` for the finest run when it is the reference).
    pub error: Option<f64>,
    /// The observed order against the previous row.
    pub order: Option<f64>,
    /// Seconds spent integrating.
    pub wall_seconds: f64,
}

/// What the table needs of one run.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// ‖q_N − q(T)‖ against the exact solution, if the system has one.
    pub reference_error: Option<f64>,
    /// q_N.
    pub final_q: Vec<f64>,
    /// Seconds spent integrating.
    pub wall_seconds: f64,
}

impl From<ddirac::Summary> for Outcome {
    fn from(s: ddirac::Summary) -> Self {
        Self { reference_error: s.reference_error, final_q: s.final_q, wall_seconds: s.wall_seconds }
    }
}

/// What the errors are measured against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reference {
    /// The system's exact solution.
    Exact,
    /// The finest run.
    Finest,
}

/// Runs the convergence study and prints its table.
pub fn convergence(options: &Options) -> Result<(), miette::Report> {
    let started = Instant::now();
    let Loaded { plan, .. } = run::load(&options.spec, &options.set)?;
    let mut plan = plan;
    let mut steps = options.steps.clone();
    steps.sort_unstable();
    steps.dedup();
    // T = N h of the spec, cleaned of the last-bit error of the product (2 / 10⁴ × 10⁴ is not 2),
    // so that h = T/N is the step `ddirac run --set time.steps=N` takes.
    let duration: f64 = format!("{:.14e}", plan.problem.duration()).parse().unwrap_or(plan.problem.duration());
    let kinds: Vec<CoordinateKind> = plan.system.coordinates().iter().map(|c| c.kind).collect();

    let mut progress = Progress::new(steps.iter().sum(), options.quiet);
    let mut summaries: Vec<Outcome> = vec![];
    let mut done = 0;
    for &n in &steps {
        plan.problem.steps = n as usize;
        plan.problem.step = duration / n as f64;
        progress.stage(done, &format!("N = {n}"));
        let summary = plan
            .system
            .integrate(&plan.problem, &plan.method, &plan.output, &mut |row| {
                progress.update(row.k);
                Ok(())
            })
            .map_err(|e| {
                miette::Report::new(CliError::Integration(e)).wrap_err(format!("the run with N = {n} failed"))
            })?;
        summaries.push(summary.into());
        done += n;
    }
    progress.finish();

    let (rows, reference) = table(&steps, duration, &summaries, &kinds)?;
    let dir = run::output_dir(options.out.as_deref(), &plan, &options.spec);
    std::fs::create_dir_all(&dir).map_err(|source| ToolError::Write { path: dir.clone(), source })?;
    write_csv(&dir.join(TABLE), &rows)?;
    plot::save(&figure(&plan.name, duration, &rows, reference), &dir)?;
    if !options.quiet {
        println!("{}", text(&plan.name, duration, &rows, reference));
        println!("  table      {}", dir.join(TABLE).display());
        println!("  figure     convergence.png, convergence.svg in {}", dir.display());
        println!("  wall time  {:.3} s", started.elapsed().as_secs_f64());
    }
    Ok(())
}

/// The rows, from the coarsest run to the finest.
fn table(
    steps: &[u64],
    duration: f64,
    summaries: &[Outcome],
    kinds: &[CoordinateKind],
) -> Result<(Vec<Row>, Reference), ToolError> {
    let exact: Option<Vec<f64>> = summaries.iter().map(|s| s.reference_error).collect();
    let (errors, reference): (Vec<Option<f64>>, _) = match exact {
        Some(errors) => (errors.into_iter().map(Some).collect(), Reference::Exact),
        None => {
            if steps.len() < 2 {
                return Err(ToolError::Usage {
                    message: "the system has no exact solution, so the errors are measured against the finest run, \
                              and one run has nothing to be compared with"
                        .into(),
                    help: Some("give at least two step counts, e.g. `--steps 100,200,400,800`".into()),
                });
            }
            let finest = &summaries[summaries.len() - 1].final_q;
            let errors = summaries
                .iter()
                .enumerate()
                .map(|(i, s)| (i + 1 < summaries.len()).then(|| distance(&s.final_q, finest, kinds)))
                .collect();
            (errors, Reference::Finest)
        }
    };
    let mut rows: Vec<Row> = vec![];
    for ((&n, summary), error) in steps.iter().zip(summaries).zip(errors) {
        let step = duration / n as f64;
        let order = match (rows.last(), error) {
            (Some(Row { error: Some(previous), step: h_previous, .. }), Some(e)) if *previous > 0.0 && e > 0.0 => {
                Some((previous / e).ln() / (h_previous / step).ln())
            }
            _ => None,
        };
        rows.push(Row { steps: n, step, error, order, wall_seconds: summary.wall_seconds });
    }
    Ok((rows, reference))
}

/// ‖a − b‖ with the differences of angles wrapped to (−π, π].
fn distance(a: &[f64], b: &[f64], kinds: &[CoordinateKind]) -> f64 {
    a.iter()
        .zip(b)
        .zip(kinds)
        .map(|((x, y), kind)| {
            let d = x - y;
            // Wrapping only what exceeds π keeps tiny differences exact (wrap(−1e−18) rounds to 0).
            if *kind == CoordinateKind::Angle && d.abs() > std::f64::consts::PI {
                ddirac::chart::wrap(d)
            } else {
                d
            }
        })
        .map(|d| d * d)
        .sum::<f64>()
        .sqrt()
}

fn write_csv(path: &std::path::Path, rows: &[Row]) -> Result<(), ToolError> {
    let temporary = plot::Temporary::for_target(path);
    let mut writer = csv::Writer::from_path(temporary.path()).map_err(|e| ToolError::write(path, e))?;
    writer.write_record(["steps", "step", "error", "order", "wall_seconds"]).map_err(|e| ToolError::write(path, e))?;
    let opt = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
    for r in rows {
        let record = [r.steps.to_string(), r.step.to_string(), opt(r.error), opt(r.order), r.wall_seconds.to_string()];
        writer.write_record(&record).map_err(|e| ToolError::write(path, e))?;
    }
    writer.flush().map_err(|source| ToolError::Write { path: path.to_owned(), source })?;
    drop(writer);
    temporary.commit(path)
}

/// `value` with `digits` significant digits, in fixed notation when it is not too small or large.
fn significant(value: f64, digits: usize) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    let exponent = value.abs().log10().floor() as i32;
    if (-4..6).contains(&exponent) {
        let decimals = (digits as i32 - 1 - exponent).max(0) as usize;
        format!("{value:.decimals$}")
    } else {
        format!("{value:.*e}", digits - 1)
    }
}

/// The printed table.
fn text(system: &str, duration: f64, rows: &[Row], reference: Reference) -> String {
    let against = match reference {
        Reference::Exact => "‖q_N − q(T)‖ against the exact solution",
        Reference::Finest => "‖q_N − q_N*‖ against the final configuration q_N* of the finest run",
    };
    let mut lines = vec![
        format!("{system}: convergence over T = {duration}, error {against}"),
        format!("  {:>8}  {:>12}  {:>12}  {:>6}", "N", "h", "error", "order"),
    ];
    for r in rows {
        let error = r.error.map_or("(reference)".to_owned(), |e| significant(e, 5));
        let order = r.order.map_or(String::new(), |p| format!("{p:.2}"));
        let step = significant(r.step, 6);
        let step = if step.contains('.') { step.trim_end_matches('0').trim_end_matches('.') } else { &step };
        lines.push(format!("  {:>8}  {:>12}  {:>12}  {:>6}", r.steps, step, error, order));
    }
    lines.join("\n")
}

/// The log–log figure of error against step, with a reference line of the last observed order.
fn figure(system: &str, duration: f64, rows: &[Row], reference: Reference) -> Figure {
    let points: Vec<(f64, f64)> = rows.iter().filter_map(|r| Some((r.step, r.error?))).filter(|p| p.1 > 0.0).collect();
    let mut series = vec![Series { markers: true, ..Series::named("error", points.clone()) }];
    if let (Some(order), Some(&(h, e))) = (rows.iter().rev().find_map(|r| r.order), points.last()) {
        let p = order.round().max(1.0);
        let h0 = points.first().map_or(h, |q| q.0);
        let line = vec![(h0, e * (h0 / h).powf(p)), (h, e)];
        series.push(Series { dashed: true, ..Series::named(format!("slope {p}"), line) });
    }
    let y_label = match reference {
        Reference::Exact => "‖q_N − q(T)‖",
        Reference::Finest => "‖q_N − q_N*‖ (finest run)",
    };
    let panel = Panel::new("step h", y_label, series).scale(Scale::LogLog);
    Figure::new("convergence", format!("{system}: error at T = {duration}"), vec![panel])
        .subtitle(format!("N = {}", rows.iter().map(|r| r.steps.to_string()).collect::<Vec<_>>().join(", ")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn observed_order_is_the_log_slope_between_rows() {
        // e = h²: order exactly 2.
        let summaries: Vec<Outcome> =
            [1.0f64, 0.5, 0.25].iter().map(|h| Outcome { reference_error: Some(h * h), ..outcome() }).collect();
        let (rows, reference) = table(&[1, 2, 4], 1.0, &summaries, &[CoordinateKind::Real]).unwrap();
        assert_eq!(reference, Reference::Exact);
        assert_eq!(rows[0].order, None);
        assert!((rows[1].order.unwrap() - 2.0).abs() < 1e-12);
        assert!((rows[2].order.unwrap() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn without_an_exact_solution_the_finest_run_is_the_reference() {
        let at = |q: f64| Outcome { final_q: vec![q], ..outcome() };
        let kinds = [CoordinateKind::Real];
        let (rows, reference) = table(&[10, 20, 40], 1.0, &[at(1.4), at(1.1), at(1.0)], &kinds).unwrap();
        assert_eq!(reference, Reference::Finest);
        assert!((rows[0].error.unwrap() - 0.4).abs() < 1e-12);
        assert!((rows[1].error.unwrap() - 0.1).abs() < 1e-12);
        assert_eq!(rows[2].error, None);
        assert!((rows[1].order.unwrap() - 2.0).abs() < 1e-9);
        assert!(table(&[10], 1.0, &[at(1.0)], &kinds).is_err());
    }

    #[test]
    fn angle_differences_are_wrapped() {
        let tau = std::f64::consts::TAU;
        assert!(distance(&[tau + 0.1], &[0.0], &[CoordinateKind::Angle]) - 0.1 < 1e-12);
        assert!((distance(&[tau + 0.1], &[0.0], &[CoordinateKind::Real]) - tau - 0.1).abs() < 1e-12);
    }

    #[test]
    fn significant_digits() {
        assert_eq!(significant(1.678_123, 5), "1.6781");
        assert_eq!(significant(0.259_712, 5), "0.25971");
        assert_eq!(significant(0.066_262_1, 5), "0.066262");
        assert_eq!(significant(2e-9, 3), "2.00e-9");
    }

    fn outcome() -> Outcome {
        Outcome { reference_error: None, final_q: vec![0.0], wall_seconds: 0.0 }
    }
}
