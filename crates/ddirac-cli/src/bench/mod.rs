//! `ddirac bench`: the project's speed comparisons, timed side by side in one process.
//!
//! Every comparison runs its contenders (whole integrations) in batches of about 20 ms, one batch
//! of each per round, the order rotated from round to round ([`harness`]); time ratios are formed
//! round by round and reported as the median with the interquartile range and the extremes over the
//! rounds, which keeps them meaningful on a machine whose load changes while it measures.
//!
//! Groups (`--only GROUP,...`, all by default):
//!
//! - `reduction`: reduced (+), reduced (−) and unreduced (+) on the double spherical pendulum
//!   (paper §7.2, midpoint, h = 0.01, 10⁴ steps) with the agreement of their trajectories, and
//!   reduced against unreduced for Kepler and the heavy top ([`reduction`]);
//! - `charged-particle`: the generic engine against the hand-written step and Boris (paper §7.1,
//!   left rule, reduced (+), h = 0.02) ([`charged_particle`]);
//! - `work-precision`: error ‖q(T) − q_N‖ at T = 20 and time of the same three for N = 50 … 12800,
//!   and their time ratios at equal error ([`work_precision`]); then the compositions of orders 2 … 8
//!   against DOP853 on three systems, with the work–precision figure ([`race`]);
//! - `expression`: the double spherical pendulum's Lagrangian written as text against the Rust one
//!   ([`expression`]);
//! - `linearity`: time per step for 10³, 10⁴ and 10⁵ steps ([`linearity`]);
//! - `scaling`: time per step of a chain of N pendula for N = 2 … 50 ([`scaling`]);
//! - `dimension`: the chain of N pendula in a fixed dimension against the same chain in a dynamic
//!   one, per step, with dual numbers and compiled derivatives ([`dimension`]);
//! - `ensemble`: members on 2 threads against 1, 10³ short members against the sum of their steps,
//!   and the peak memory of `ddirac ensemble` against its output ([`ensemble`]);
//! - `rigid`: the free rigid body's step on SO(3) against a hand-written LGVI ([`rigid`]);
//! - `sensitivities`: a step with its tangent map against the plain step ([`sensitivities`]).
//!
//! `--json PATH` writes every measurement, round by round, through a temporary file renamed into
//! place when complete.

mod charged_particle;
mod dimension;
#[cfg(feature = "dop853")]
mod dop853;
/// Without the `dop853` feature the race has no peer.
#[cfg(not(feature = "dop853"))]
mod dop853 {
    /// Whether this build has the peer.
    pub const AVAILABLE: bool = false;

    /// `None`: DOP853 is not in this build.
    pub fn integrate<S: ddirac::System<N>, const N: usize>(
        _system: &S,
        _q0: &[f64; N],
        _p0: &[f64; N],
        _duration: f64,
        _tolerance: f64,
        _energy: bool,
    ) -> Option<Result<(Vec<f64>, f64), miette::Report>> {
        None
    }

    /// The end of a rigid body's DOP853 run (never made in this build).
    pub struct RigidEnd {
        /// R(T).
        pub r: [[f64; 3]; 3],
        /// The largest relative energy error over the accepted steps.
        pub energy_error: f64,
    }

    /// `None`: DOP853 is not in this build.
    pub fn integrate_rigid(
        _inertia: [f64; 3],
        _weight: [f64; 3],
        _r0: [[f64; 3]; 3],
        _pi0: [f64; 3],
        _duration: f64,
        _tolerance: f64,
        _energy: bool,
    ) -> Option<Result<RigidEnd, miette::Report>> {
        None
    }
}
mod ensemble;
mod expression;
mod harness;
mod interpolation;
mod lgvi;
mod linearity;
mod print;
mod race;
mod reduction;
mod rigid;
mod rigid_race;
mod scaling;
mod sensitivities;
mod work_precision;

use std::hint::black_box;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use clap::{Args, ValueEnum};
use ddirac::{DynSystem, Method, OutputOptions, Problem, Rule, Summary, Variant};
use serde_json::{json, Map, Value};

use crate::diagnostics::CliError;
use crate::plot::{write_atomically, ToolError};
use harness::{Contender, Newton, Schedule};

/// Options of `ddirac bench`.
#[derive(Debug, Args)]
pub struct Options {
    /// Comparison groups to run, comma-separated [default: all].
    #[arg(long, value_delimiter = ',', value_name = "GROUP,...")]
    only: Vec<Group>,
    /// Rounds per comparison [default: 15, with --quick 3].
    #[arg(long, value_name = "R", value_parser = clap::value_parser!(u64).range(1..))]
    rounds: Option<u64>,
    /// Target duration of one batch in milliseconds [default: 20, with --quick 2].
    #[arg(long, value_name = "MS", value_parser = clap::value_parser!(u64).range(1..))]
    batch_ms: Option<u64>,
    /// Few rounds, short batches and small step counts: a check that takes seconds, not a
    /// measurement.
    #[arg(long)]
    quick: bool,
    /// Write every measurement as JSON to this file.
    #[arg(long, value_name = "PATH")]
    json: Option<PathBuf>,
    /// Directory of the figures (`work-precision.png`, `.svg`).
    #[arg(long, value_name = "DIR", default_value = "out/bench")]
    figures: PathBuf,
}

/// A comparison group.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Group {
    /// Reduced against unreduced equations.
    Reduction,
    /// The engine against the hand-written step and Boris.
    ChargedParticle,
    /// Error against time of the engine, the hand-written step and Boris.
    WorkPrecision,
    /// A Lagrangian written as text against the same in Rust.
    Expression,
    /// Time per step against the number of steps.
    Linearity,
    /// Time per step against the number of coordinates.
    Scaling,
    /// A fixed dimension against a dynamic one.
    Dimension,
    /// Members on threads, set-up amortised, memory of ensembles.
    Ensemble,
    /// The rigid body's step on SO(3) against a hand-written LGVI.
    Rigid,
    /// A step with its tangent map against the plain step.
    Sensitivities,
}

impl Group {
    /// Every group, in the order they run.
    const ALL: [Group; 10] = [
        Group::Reduction,
        Group::ChargedParticle,
        Group::WorkPrecision,
        Group::Expression,
        Group::Linearity,
        Group::Scaling,
        Group::Dimension,
        Group::Ensemble,
        Group::Rigid,
        Group::Sensitivities,
    ];

    /// The name on the command line and in the JSON output.
    fn name(self) -> &'static str {
        match self {
            Group::Reduction => "reduction",
            Group::ChargedParticle => "charged-particle",
            Group::WorkPrecision => "work-precision",
            Group::Expression => "expression",
            Group::Linearity => "linearity",
            Group::Scaling => "scaling",
            Group::Dimension => "dimension",
            Group::Ensemble => "ensemble",
            Group::Rigid => "rigid",
            Group::Sensitivities => "sensitivities",
        }
    }

    fn run(self, settings: &Settings) -> Result<Value, miette::Report> {
        match self {
            Group::Reduction => reduction::run(settings),
            Group::ChargedParticle => charged_particle::run(settings),
            Group::WorkPrecision => work_precision::run(settings),
            Group::Expression => expression::run(settings),
            Group::Linearity => linearity::run(settings),
            Group::Scaling => scaling::run(settings),
            Group::Dimension => dimension::run(settings),
            Group::Ensemble => ensemble::run(settings),
            Group::Rigid => rigid::run(settings),
            Group::Sensitivities => sensitivities::run(settings),
        }
    }
}

/// What every group needs to know.
pub struct Settings {
    /// Rounds and batch length.
    pub schedule: Schedule,
    /// Small step counts.
    pub quick: bool,
    /// Where figures go.
    pub figures: PathBuf,
}

/// Runs the selected groups, printing each table as it is measured, and writes the JSON file.
pub fn bench(options: &Options) -> Result<(), miette::Report> {
    let started = Instant::now();
    let groups: Vec<Group> =
        Group::ALL.into_iter().filter(|g| options.only.is_empty() || options.only.contains(g)).collect();
    if let Some(path) = &options.json {
        // Fail before measuring for minutes, not after.
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(std::path::Path::new("."));
        if !dir.is_dir() {
            return Err(ToolError::Usage {
                message: format!("cannot write `{}`: `{}` is not a directory", path.display(), dir.display()),
                help: Some("create the directory first, or give another --json path".into()),
            }
            .into());
        }
    }
    let rounds = options.rounds.map_or(if options.quick { 3 } else { 15 }, |r| r as usize);
    let batch_ms = options.batch_ms.unwrap_or(if options.quick { 2 } else { 20 });
    let settings = Settings {
        schedule: Schedule { rounds, batch: Duration::from_millis(batch_ms) },
        quick: options.quick,
        figures: options.figures.clone(),
    };
    println!(
        "ddirac bench{}: {rounds} round{} per comparison, batches of about {batch_ms} ms, one batch of each contender \
         per round in an order rotated every round",
        if options.quick { " --quick (small step counts: a check, not a measurement)" } else { "" },
        if rounds == 1 { "" } else { "s" }
    );
    println!(
        "time per step: median over the rounds [IQR q1 – q3, range min – max]; ratios: formed in each round, then the \
         same summary"
    );
    let mut results = Map::new();
    for group in groups {
        println!();
        let value = group.run(&settings).map_err(|e| e.wrap_err(format!("bench group `{}` failed", group.name())))?;
        results.insert(group.name().to_owned(), value);
    }
    let seconds = started.elapsed().as_secs_f64();
    println!("\nwall time {seconds:.1} s");
    if let Some(path) = &options.json {
        let document = json!({
            "ddirac_version": env!("CARGO_PKG_VERSION"),
            "rounds": rounds,
            "batch_ms": batch_ms,
            "quick": options.quick,
            "wall_seconds": seconds,
            "groups": results,
        });
        let text = serde_json::to_string_pretty(&document).map_err(|e| ToolError::write(path, e))?;
        write_atomically(path, text.as_bytes())?;
        println!("measurements written to {}", path.display());
    }
    Ok(())
}

/// Engine runs report only their first and last rows.
pub const LAST_ROW_ONLY: OutputOptions = OutputOptions { every: usize::MAX, wrap_angles: false };

/// A method of the default Newton options.
pub fn method(rule: Rule, reduced: bool, variant: Variant) -> Method {
    // The paper's schemes in the paper's coordinates: no chart switches.
    Method { rule, variant, reduced, atlas: false, ..Method::default() }
}

/// The name of a method in tables: `reduced (+)`, `unreduced (−)`.
pub fn method_name(method: &Method) -> String {
    let variant = match method.variant {
        Variant::Plus => "+",
        Variant::Minus => "−",
    };
    format!("{} ({variant})", if method.reduced { "reduced" } else { "unreduced" })
}

/// An engine failure as a report naming the run.
fn failed(what: &str, error: ddirac::Error) -> miette::Report {
    miette::Report::new(CliError::Integration(error)).wrap_err(format!("the run `{what}` failed"))
}

/// The built-in system `name` with its default parameters, type-erased as a spec runs it.
///
/// The engine runs of the benchmarks go through the systems the library has erased (the registry,
/// `ExpressionSpec::into_dyn`), so that they time what a spec runs and this crate instantiates no
/// copy of the engine of its own (a typed system here would be compiled into it a second time).
pub fn built_in(name: &str) -> Result<Box<dyn DynSystem>, miette::Report> {
    built_in_with(name, &[])
}

/// [`built_in`] with some parameters set.
pub fn built_in_with(name: &str, parameters: &[(&str, f64)]) -> Result<Box<dyn DynSystem>, miette::Report> {
    let entry = ddirac::systems::find(name).ok_or_else(|| miette::miette!("no built-in system `{name}`"))?;
    let parameters: Vec<(String, f64)> = parameters.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    (entry.build)(&parameters).map_err(|e| miette::miette!("the built-in system `{name}` cannot be built: {e}"))
}

/// One engine run reporting only its last row.
pub fn integrate_once(
    what: &str,
    system: &dyn DynSystem,
    problem: &Problem,
    method: &Method,
) -> Result<Summary, miette::Report> {
    system.integrate(problem, method, &LAST_ROW_ONLY, &mut |_| Ok(())).map_err(|e| failed(what, e))
}

/// An engine run as a contender called `name`: run once first, so that a failing run is reported
/// before any timing, and to count its Newton iterations and Jacobian evaluations.
pub fn engine<'a>(
    name: &str,
    what: &str,
    system: &'a dyn DynSystem,
    problem: &'a Problem,
    method: Method,
) -> Result<Contender<'a>, miette::Report> {
    let run = move || black_box(system).integrate(black_box(problem), &method, &LAST_ROW_ONLY, &mut |_| Ok(()));
    timed_run(name, what, problem.steps, run)
}

/// A contender from a closure making one engine run of `steps` steps (reporting only its last row):
/// run once first, so that a failing run is reported before any timing, and to count its Newton
/// iterations.
pub fn timed_run<'a>(
    name: &str,
    what: &str,
    steps: usize,
    mut run: impl FnMut() -> Result<Summary, ddirac::Error> + 'a,
) -> Result<Contender<'a>, miette::Report> {
    let summary = run().map_err(|e| failed(what, e))?;
    let per_step = |n: usize| n as f64 / steps.max(1) as f64;
    let newton = Newton {
        iterations: per_step(summary.newton.total_iterations),
        jacobians: per_step(summary.newton.total_jacobians),
    };
    let what = what.to_owned();
    let timed = move || {
        black_box(run().map_err(|e| failed(&what, e))?);
        Ok(())
    };
    Ok(Contender::new(name, steps, timed).with_newton(newton))
}

/// The measurements of a group as JSON.
pub fn to_json(value: &impl serde::Serialize) -> Result<Value, miette::Report> {
    serde_json::to_value(value).map_err(|e| miette::miette!("cannot encode the measurements: {e}"))
}

/// The largest |a_i − b_i| over the rows and coordinates of two trajectories of equal shape; NaN
/// if any difference is NaN or the shapes differ.
pub fn max_difference<R: AsRef<[f64]>>(a: &[R], b: &[R]) -> f64 {
    if a.len() != b.len() || a.iter().zip(b).any(|(x, y)| x.as_ref().len() != y.as_ref().len()) {
        return f64::NAN;
    }
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| x.as_ref().iter().zip(y.as_ref()).map(|(u, v)| (u - v).abs()))
        .fold(0.0, |largest: f64, d| if d > largest || d.is_nan() { d } else { largest })
}

/// A contender taking `steps` steps of a prepared stepper from its first state, and the q it ends at.
pub(crate) fn stepping<'a>(
    name: &str,
    system: &'a dyn DynSystem,
    problem: &Problem,
    method: &Method,
) -> Result<(Contender<'a>, Vec<f64>), miette::Report> {
    let failed = |e: ddirac::Error| miette::miette!("the chain ({name}) failed: {e}");
    let mut stepper = system.stepper(problem, method).map_err(failed)?;
    let first = stepper.state();
    let steps = problem.steps;
    let mut batch = move || -> Result<Vec<f64>, ddirac::Error> {
        stepper.restart(&first)?;
        for _ in 0..steps {
            black_box(stepper.step()?);
        }
        Ok(stepper.state().q().to_vec())
    };
    let end = batch().map_err(failed)?;
    let name_owned = name.to_owned();
    let run = move || {
        batch().map_err(|e| miette::miette!("the chain ({name_owned}) failed: {e}"))?;
        Ok(())
    };
    Ok((Contender::new(name, steps, run), end))
}
