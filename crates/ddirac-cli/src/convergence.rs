//! `ddirac convergence SPEC --steps 10,50,100,200`: the spec run with each number of steps N over
//! its duration T (h = T/N), and a table of N, h, the error of the final configuration and the
//! observed order between consecutive rows, p = ln(e_i / e_{i+1}) / ln(h_i / h_{i+1}).
//!
//! The error is ‖q_N − q(T)‖ against the system's exact solution when it has one (the summary's
//! `reference_error`; for the charged particle this is the paper's Table 1). Without one it is
//! ‖q_N − q_ref‖ against a reference run of the same method with [`REFERENCE_FACTOR`] times the
//! finest N (angle differences wrapped to (−π, π]). For a method of order p the reference's own
//! error is then 1/(8^p − 1) of the finest row's error (1/63 for p = 2), which the output estimates
//! with the observed order; measuring against the finest listed run instead would report its
//! neighbour's error 25 % too small and an order of 2.32 where it is 2.
//!
//! The observed order is *stable* where consecutive observed orders agree within [`STABLE`]; the
//! output says where it is, and the figure draws its slope line only there. Writes
//! `convergence.csv` and the log–log figure `convergence.png` / `.svg` into the output directory.

use std::path::PathBuf;
use std::time::Instant;

use ddirac::CoordinateKind;

use crate::diagnostics::CliError;
use crate::lock;
use crate::plot::{self, Figure, Panel, Scale, Series, ToolError};
use crate::progress::Progress;
use crate::run::{self, Loaded};
use crate::run_dir::RunDir;
use crate::spec::Plan;

/// Name of the table in the output directory.
pub const TABLE: &str = "convergence.csv";

/// Steps of the reference run, as a multiple of the finest N (systems without an exact solution).
pub const REFERENCE_FACTOR: u64 = 8;

/// Consecutive observed orders are stable when they differ by at most this fraction of the larger.
pub const STABLE: f64 = 0.1;

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
    /// The error of the final configuration.
    pub error: f64,
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
#[derive(Debug, Clone, PartialEq)]
pub enum Reference {
    /// The system's exact solution.
    Exact,
    /// A run of the same method with `steps` steps.
    Run {
        /// Its number of steps: [`REFERENCE_FACTOR`] × the finest N.
        steps: u64,
        /// Its outcome.
        outcome: Outcome,
    },
}

impl Reference {
    /// The method, in a few words, for the table's `reference` column.
    fn column(&self) -> String {
        match self {
            Self::Exact => "exact solution".into(),
            Self::Run { steps, .. } => format!("reference run N={steps}"),
        }
    }

    /// The method, in a sentence.
    fn against(&self) -> String {
        match self {
            Self::Exact => "‖q_N − q(T)‖ against the exact solution".into(),
            Self::Run { steps, .. } => format!(
                "‖q_N − q_ref‖ against a reference run of the same method with N = {steps} steps \
                 ({REFERENCE_FACTOR} × the finest N)"
            ),
        }
    }
}

/// Where the observed order is stable: the finest stretch of rows whose consecutive observed
/// orders agree within [`STABLE`].
#[derive(Debug, Clone, PartialEq)]
pub struct Stability {
    /// The first and last row of the stretch (indices into the rows).
    pub rows: (usize, usize),
    /// The mean of its observed orders.
    pub order: f64,
}

/// What a study needs of its spec: the system's name, the method in words, the duration T, the kinds
/// of the entries of the final configuration, the output directory, and a run with N steps.
struct Study<'a> {
    name: String,
    method: String,
    duration: f64,
    kinds: Vec<CoordinateKind>,
    dir: PathBuf,
    integrate: Box<RunWith<'a>>,
}

/// A run with N steps: `(N, progress, steps done before it, label)`.
type RunWith<'a> = dyn FnMut(u64, &mut Progress, u64, &str) -> Result<Outcome, miette::Report> + 'a;

/// T = N h of a spec, cleaned of the last-bit error of the product (2 / 10⁴ × 10⁴ is not 2), so that
/// h = T/N is the step `ddirac run --set time.steps=N` takes.
fn cleaned(duration: f64) -> f64 {
    format!("{duration:.14e}").parse().unwrap_or(duration)
}

/// The method in words: `rule midpoint`, with its composition.
fn method_words(m: &ddirac::Method) -> String {
    format!("rule {}{}", m.rule.name(), crate::report::composition(m.composition))
}

/// The study of a spec in coordinates: the final configuration is q_N.
fn in_coordinates(options: &Options) -> Result<Study<'static>, miette::Report> {
    let loaded = run::load(&options.spec, &options.set)?;
    loaded.print_notes();
    let Loaded { mut plan, .. } = loaded;
    let method = method_words(&plan.method);
    let duration = cleaned(plan.problem.duration());
    Ok(Study {
        name: plan.name.clone(),
        method,
        duration,
        kinds: plan.system.coordinates().iter().map(|c| c.kind).collect(),
        dir: run::output_dir(options.out.as_deref(), &plan, &options.spec),
        integrate: Box::new(move |n, progress, done, label| integrate(&mut plan, n, duration, progress, done, label)),
    })
}

/// The study of a rigid system's spec: the final configuration is (R_N, s_N), the nine entries of the
/// attitude (rows) and the shape, so that the error is the Frobenius distance of the attitudes
/// together with that of the shapes.
fn rigid(options: &Options, text: String) -> Result<Study<'static>, miette::Report> {
    let crate::rigid::LoadedRigid { plan, .. } = crate::rigid::load_text(&options.spec, text, &options.set)?;
    let method = method_words(&plan.method);
    let duration = cleaned(plan.problem.step * plan.problem.steps as f64);
    let shape = ddirac::rigid::RigidSystem::shape(&plan.body);
    let kinds = std::iter::repeat_n(CoordinateKind::Real, 9).chain(shape.iter().map(|c| c.kind)).collect();
    let request = crate::rigid::Request {
        spec: &options.spec,
        set: &options.set,
        out: options.out.as_deref(),
        quiet: true,
        format: &[],
    };
    let dir = crate::rigid::output_dir(&request, &plan);
    let integrate = move |n: u64, progress: &mut Progress, done: u64, label: &str| {
        let mut problem = plan.problem.clone();
        problem.steps = n as usize;
        problem.step = duration / n as f64;
        progress.stage(done, label);
        let failed = |e: ddirac::Error| {
            miette::Report::new(CliError::Integration(e)).wrap_err(format!("the run with {label} failed"))
        };
        let mut stepper = ddirac::rigid::RigidStepper::new(&plan.body, problem, &plan.method).map_err(failed)?;
        while !stepper.is_finished() {
            stepper.step().map_err(failed)?;
            progress.update(stepper.k());
        }
        let summary = stepper.summary();
        crate::report::print_warnings(&summary.warnings);
        let final_q = summary.final_r.iter().flatten().chain(&summary.final_s).copied().collect();
        Ok(Outcome { reference_error: None, final_q, wall_seconds: summary.wall_seconds })
    };
    Ok(Study { name: plan.name.clone(), method, duration, kinds, dir, integrate: Box::new(integrate) })
}

/// Runs the convergence study and prints its table.
pub fn convergence(options: &Options) -> Result<(), miette::Report> {
    let started = Instant::now();
    let spec_text = run::read(&options.spec)?;
    let Study { name, method, duration, kinds, dir, integrate: mut integrate_n } =
        if crate::rigid::names_rigid_body(&spec_text, &options.set) {
            rigid(options, spec_text)?
        } else {
            in_coordinates(options)?
        };
    let mut steps = options.steps.clone();
    steps.sort_unstable();
    steps.dedup();
    // The output directory is this study's while it lasts; its files replace the earlier ones as a set.
    let run_dir = RunDir::open(&dir, &lock::command_line())?;

    let mut progress = Progress::new(steps.iter().sum(), options.quiet);
    let mut outcomes: Vec<Outcome> = vec![];
    let mut done = 0;
    for &n in &steps {
        outcomes.push(integrate_n(n, &mut progress, done, &format!("N = {n}"))?);
        done += n;
    }
    progress.finish();

    let reference = if outcomes.iter().all(|o| o.reference_error.is_some()) {
        Reference::Exact
    } else {
        let finest = steps[steps.len() - 1];
        if steps.len() < 2 {
            return Err(ToolError::Usage {
                message: "the system has no exact solution, so the errors are measured against a finer reference \
                          run, and one run gives no observed order to judge them by"
                    .into(),
                help: Some("give at least two step counts, e.g. `--steps 100,200,400,800`".into()),
            }
            .into());
        }
        let n = finest.checked_mul(REFERENCE_FACTOR).filter(|n| usize::try_from(*n).is_ok()).ok_or_else(|| {
            ToolError::Usage {
                message: format!("the reference run would need {REFERENCE_FACTOR} × {finest} steps, too many to count"),
                help: Some("give smaller step counts".into()),
            }
        })?;
        let mut progress = Progress::new(n, options.quiet);
        let outcome = integrate_n(n, &mut progress, 0, &format!("reference N = {n}"))?;
        progress.finish();
        Reference::Run { steps: n, outcome }
    };

    let rows = table(&steps, duration, &outcomes, &reference, &kinds);
    let staging = run_dir.staging().to_owned();
    write_csv(&staging.join(TABLE), &rows, &reference)?;
    let figures = plot::save(&figure(&name, duration, &rows, &reference), &staging)?;
    let mut files = vec![PathBuf::from(TABLE)];
    files.extend(figures.iter().filter_map(|p| p.strip_prefix(&staging).ok()).map(PathBuf::from));
    run_dir.commit(&files)?;
    if !options.quiet {
        println!("{}", text(&name, &method, duration, &rows, &reference));
        println!("  table      {}", dir.join(TABLE).display());
        println!("  figure     convergence.png, convergence.svg in {}", dir.display());
        println!("  wall time  {:.3} s", started.elapsed().as_secs_f64());
    }
    Ok(())
}

/// One run of `plan` with `n` steps over `duration`.
fn integrate(
    plan: &mut Plan,
    n: u64,
    duration: f64,
    progress: &mut Progress,
    done: u64,
    label: &str,
) -> Result<Outcome, miette::Report> {
    plan.problem.steps = n as usize;
    plan.problem.step = duration / n as f64;
    progress.stage(done, label);
    let summary = plan
        .system
        .integrate(&plan.problem, &plan.method, &plan.output, &mut |row| {
            progress.update(row.k);
            Ok(())
        })
        .map_err(|e| miette::Report::new(CliError::Integration(e)).wrap_err(format!("the run with {label} failed")))?;
    Ok(summary.into())
}

/// The rows, from the coarsest run to the finest.
fn table(
    steps: &[u64],
    duration: f64,
    outcomes: &[Outcome],
    reference: &Reference,
    kinds: &[CoordinateKind],
) -> Vec<Row> {
    let mut rows: Vec<Row> = vec![];
    for (&n, outcome) in steps.iter().zip(outcomes) {
        let step = duration / n as f64;
        let error = match reference {
            Reference::Exact => outcome.reference_error.unwrap_or(f64::NAN),
            Reference::Run { outcome: finer, .. } => distance(&outcome.final_q, &finer.final_q, kinds),
        };
        let order = match rows.last() {
            Some(Row { error: previous, step: h_previous, .. }) if *previous > 0.0 && error > 0.0 => {
                Some((previous / error).ln() / (h_previous / step).ln())
            }
            _ => None,
        };
        rows.push(Row { steps: n, step, error, order, wall_seconds: outcome.wall_seconds });
    }
    rows
}

/// Whether two observed orders agree within [`STABLE`] of the larger (both positive).
pub fn agree(a: f64, b: f64) -> bool {
    a > 0.0 && b > 0.0 && (a - b).abs() <= STABLE * a.max(b)
}

/// The finest stretch of rows over which the observed order is stable, if any.
pub fn stability(rows: &[Row]) -> Option<Stability> {
    let orders: Vec<Option<f64>> = rows.iter().map(|r| r.order).collect();
    stability_of(&orders)
}

/// The finest stretch of rows whose consecutive observed orders `orders` (one per row, `None` for the
/// first) agree within [`STABLE`]: the rule of `ddirac convergence` and of the Python package's
/// `ddirac.convergence`.
pub fn stability_of(orders: &[Option<f64>]) -> Option<Stability> {
    let pair = |i: usize| matches!((orders[i - 1], orders[i]), (Some(a), Some(b)) if agree(a, b));
    let last = (2..orders.len()).rev().find(|&i| pair(i))?;
    let mut first = last - 1;
    while first >= 2 && pair(first) {
        first -= 1;
    }
    let stable: Vec<f64> = orders[first..=last].iter().flatten().copied().collect();
    Some(Stability { rows: (first - 1, last), order: stable.iter().sum::<f64>() / stable.len() as f64 })
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

fn write_csv(path: &std::path::Path, rows: &[Row], reference: &Reference) -> Result<(), ToolError> {
    let temporary = plot::Temporary::for_target(path);
    let mut writer = csv::Writer::from_path(temporary.path()).map_err(|e| ToolError::write(path, e))?;
    writer
        .write_record(["steps", "step", "error", "order", "wall_seconds", "reference"])
        .map_err(|e| ToolError::write(path, e))?;
    let against = reference.column();
    for r in rows {
        // Shortest round-trip digits, with an exponent for tiny and huge numbers.
        let number = |v: f64| format!("{v:?}");
        let order = r.order.map_or(String::new(), number);
        let record =
            [r.steps.to_string(), number(r.step), number(r.error), order, number(r.wall_seconds), against.clone()];
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

/// `N = a…b` for the rows `first..=last`.
fn span(rows: &[Row], (first, last): (usize, usize)) -> String {
    format!("N = {}…{}", rows[first].steps, rows[last].steps)
}

/// What the output says about the observed order: where it is stable, or that it is not.
fn order_note(rows: &[Row]) -> String {
    let orders: Vec<String> = rows.iter().filter_map(|r| r.order).map(|p| format!("{p:.2}")).collect();
    let within = format!("consecutive observed orders within {:.0} %", 100.0 * STABLE);
    match stability(rows) {
        Some(s) if s.rows.1 + 1 == rows.len() => {
            format!("stable at {:.2} over {} ({within})", s.order, span(rows, s.rows))
        }
        Some(s) => format!(
            "stable at {:.2} over {} ({within}), but not over the finer rows (observed orders {}): \
             they may be limited by round-off",
            s.order,
            span(rows, s.rows),
            orders.join(", ")
        ),
        None if orders.len() < 2 => {
            "one observed order only: whether it is stable cannot be judged, so no slope line is drawn \
             (give three or more step counts)"
                .into()
        }
        None => format!(
            "not stable: no two consecutive observed orders ({}) agree within {:.0} %; the runs may be outside \
             the asymptotic range, so no slope line is drawn",
            orders.join(", "),
            100.0 * STABLE
        ),
    }
}

/// What the output says about the reference run: its size, and its own error as estimated from the
/// observed order of the finest rows.
fn reference_note(rows: &[Row], reference: &Reference) -> Option<String> {
    let Reference::Run { steps, outcome } = reference else { return None };
    let mut note = format!("N = {steps}, {:.3} s integrating", outcome.wall_seconds);
    let finest = rows.last()?;
    if let Some(p) = finest.order.filter(|p| *p > 0.0) {
        let share = 1.0 / ((REFERENCE_FACTOR as f64).powf(p) - 1.0);
        note.push_str(&format!(
            "; its own error, by the observed order {p:.2} of the finest rows, is ≈ {} ({:.1} % of the finest row's)",
            significant(finest.error * share, 2),
            100.0 * share
        ));
    }
    Some(note)
}

/// The printed table.
fn text(system: &str, method: &str, duration: f64, rows: &[Row], reference: &Reference) -> String {
    let mut lines = vec![
        format!("{system}: convergence over T = {duration} ({method}), error {}", reference.against()),
        format!("  {:>8}  {:>12}  {:>12}  {:>6}", "N", "h", "error", "order"),
    ];
    for r in rows {
        let order = r.order.map_or(String::new(), |p| format!("{p:.2}"));
        let step = significant(r.step, 6);
        let step = if step.contains('.') { step.trim_end_matches('0').trim_end_matches('.') } else { &step };
        lines.push(format!("  {:>8}  {:>12}  {:>12}  {:>6}", r.steps, step, significant(r.error, 5), order));
    }
    if let Some(note) = reference_note(rows, reference) {
        lines.push(format!("  reference  {note}"));
    }
    lines.push(format!("  order      {}", order_note(rows)));
    lines.join("\n")
}

/// The log–log figure of error against step, with a line of the observed order over the rows where
/// it is stable.
fn figure(system: &str, duration: f64, rows: &[Row], reference: &Reference) -> Figure {
    let points: Vec<(f64, f64)> = rows.iter().map(|r| (r.step, r.error)).filter(|p| p.1 > 0.0).collect();
    let mut series = vec![Series { markers: true, ..Series::named("error", points) }];
    let stability = stability(rows);
    if let Some(Stability { rows: (first, last), order }) = stability {
        // The nearest whole order when the observed one is within the stability margin of it.
        let slope = if (order - order.round()).abs() <= STABLE * order { order.round() } else { order };
        // Drawn a factor 2 below the errors, so that it does not hide them.
        let (h0, (h, e)) = (rows[first].step, (rows[last].step, 0.5 * rows[last].error));
        let line = vec![(h0, e * (h0 / h).powf(slope)), (h, e)];
        let name = format!("slope {slope} (observed {order:.2}, {})", span(rows, (first, last)));
        series.push(Series { dashed: true, ..Series::named(name, line) });
    }
    let y_label = match reference {
        Reference::Exact => "‖q_N − q(T)‖".to_owned(),
        Reference::Run { steps, .. } => format!("‖q_N − q_ref‖ (reference run, N = {steps})"),
    };
    let against = match reference {
        Reference::Exact => "errors against the exact solution".to_owned(),
        Reference::Run { steps, .. } => {
            format!("errors against a reference run with N = {steps} ({REFERENCE_FACTOR} × the finest N)")
        }
    };
    let caption = match stability {
        Some(Stability { rows: (first, last), order }) => {
            let only = if last + 1 == rows.len() { "" } else { " only" };
            format!("observed order {order:.2}, stable over {}{only}", span(rows, (first, last)))
        }
        None => "observed order not stable: no slope line".to_owned(),
    };
    let panel = Panel::new("step h", y_label, series).scale(Scale::LogLog).caption(caption);
    let listed = rows.iter().map(|r| r.steps.to_string()).collect::<Vec<_>>().join(", ");
    Figure::new("convergence", format!("{system}: error at T = {duration}"), vec![panel])
        .subtitle(format!("N = {listed}; {against}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows_with(errors: &[(u64, f64)]) -> Vec<Row> {
        let outcomes: Vec<Outcome> =
            errors.iter().map(|&(_, e)| Outcome { reference_error: Some(e), ..outcome() }).collect();
        let steps: Vec<u64> = errors.iter().map(|&(n, _)| n).collect();
        table(&steps, 1.0, &outcomes, &Reference::Exact, &[CoordinateKind::Real])
    }

    #[test]
    fn observed_order_is_the_log_slope_between_rows() {
        // e = h²: order exactly 2.
        let rows = rows_with(&[(1, 1.0), (2, 0.25), (4, 0.0625)]);
        assert_eq!(rows[0].order, None);
        assert!((rows[1].order.unwrap() - 2.0).abs() < 1e-12);
        assert!((rows[2].order.unwrap() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn without_an_exact_solution_the_errors_are_against_the_reference_run() {
        let at = |q: f64| Outcome { final_q: vec![q], ..outcome() };
        let kinds = [CoordinateKind::Real];
        let reference = Reference::Run { steps: 320, outcome: at(1.0) };
        let rows = table(&[10, 20, 40], 1.0, &[at(1.4), at(1.1), at(1.025)], &reference, &kinds);
        assert!((rows[0].error - 0.4).abs() < 1e-12);
        assert!((rows[1].error - 0.1).abs() < 1e-12);
        assert!((rows[2].error - 0.025).abs() < 1e-12);
        assert!((rows[2].order.unwrap() - 2.0).abs() < 1e-9);
        assert_eq!(reference.column(), "reference run N=320");
    }

    #[test]
    fn the_order_is_stable_where_consecutive_orders_agree_within_ten_percent() {
        // Orders 1.16, 1.97, 1.99 (the paper's Table 1): stable over N = 50…200.
        let rows = rows_with(&[(10, 1.6781), (50, 0.25971), (100, 0.066257), (200, 0.016642)]);
        let s = stability(&rows).unwrap();
        assert_eq!(s.rows, (1, 3));
        assert!((s.order - 1.98).abs() < 0.01, "{s:?}");
        assert!(order_note(&rows).starts_with("stable at 1.98 over N = 50…200"), "{}", order_note(&rows));
        // Orders 1, 3, 7: nowhere stable.
        let rows = rows_with(&[(1, 1.0), (2, 0.5), (4, 0.0625), (8, 0.0625 / 128.0)]);
        assert_eq!(stability(&rows), None);
        assert!(order_note(&rows).starts_with("not stable"));
        // Two rows: one order, nothing to compare it with.
        assert_eq!(stability(&rows[..2]), None);
        assert!(order_note(&rows[..2]).starts_with("one observed order only"));
    }

    #[test]
    fn the_slope_line_is_drawn_only_over_the_stable_rows() {
        let rows = rows_with(&[(1, 1.0), (2, 0.5), (4, 0.0625), (8, 0.0625 / 128.0)]);
        let drawn = figure("s", 1.0, &rows, &Reference::Exact);
        assert_eq!(drawn.panels[0].series.len(), 1, "no slope line where the order is not stable");
        // Orders 1, 2, 2: the line spans N = 2…8 with slope 2.
        let rows = rows_with(&[(1, 1.0), (2, 0.5), (4, 0.125), (8, 0.03125)]);
        let drawn = figure("s", 1.0, &rows, &Reference::Exact);
        let line = &drawn.panels[0].series[1];
        assert!(line.name.as_ref().unwrap().starts_with("slope 2 (observed 2.00, N = 2…8)"));
        assert_eq!(line.points, vec![(0.5, 0.25), (0.125, 0.015625)]);
    }

    #[test]
    fn the_reference_run_s_own_error_is_estimated_from_the_observed_order() {
        let rows = rows_with(&[(10, 4e-2), (20, 1e-2)]);
        let reference = Reference::Run { steps: 160, outcome: outcome() };
        let note = reference_note(&rows, &reference).unwrap();
        // 1e-2 / (8² − 1) = 1.6e-4, 1.6 %.
        assert!(note.contains("≈ 0.00016 (1.6 % of the finest row's)"), "{note}");
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
