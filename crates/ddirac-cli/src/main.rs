//! `ddirac`: runs discrete Dirac (reduced or unreduced) integrations described by TOML specs.
//!
//! ```text
//! ddirac run SPEC.toml [--out DIR] [--set KEY=VALUE]... [--quiet]
//! ddirac run SPEC.toml --compare [--out DIR] [--set KEY=VALUE]... [--quiet]
//! ddirac convergence SPEC.toml --steps 10,50,100,200 [--out DIR] [--set KEY=VALUE]... [--quiet]
//! ddirac plot DIR [--quiet]
//! ddirac ensemble SPEC.toml [--members FILE.csv] [--out DIR] [--threads T] [--shard I/N] [--set KEY=VALUE]... [--quiet]
//! ddirac merge DIR... --out DIR [--quiet]
//! ddirac check SPEC.toml [--set KEY=VALUE]...
//! ddirac systems
//! ddirac bench [--only GROUP,...] [--rounds R] [--batch-ms MS] [--quick] [--json PATH]
//! ```

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use ddirac_cli::{bench, check, compare, convergence, diagnostics, ensemble, equilibria, output, plot, run, signals};

/// Structure-preserving integrators for Lagrangian systems with abelian symmetry, after
/// "Discrete Dirac reduction of implicit Lagrangian systems with abelian symmetry groups".
///
/// A run is described by a TOML spec: a built-in system (`ddirac systems`) or a Lagrangian written
/// as an expression, the method (rule, variant, reduced or not), the time grid, the initial data and
/// the output. See the README and the specs in examples/.
#[derive(Debug, Parser)]
#[command(name = "ddirac", version, after_help = AFTER_HELP)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// A spec and the overrides applied to it.
#[derive(Debug, Args)]
struct SpecInput {
    /// The TOML spec (see examples/).
    spec: PathBuf,
    /// Override one spec value before it is read, e.g. `method.reduced=false` (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
}

/// A spec to run, where its output goes, and how talkative the run is.
#[derive(Debug, Args)]
struct SpecTarget {
    #[command(flatten)]
    input: SpecInput,
    /// Output directory [default: output.directory of the spec, else out/<spec file stem>].
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Print nothing on success.
    #[arg(long, short)]
    quiet: bool,
}

/// Examples and exit statuses, after the help of `ddirac`.
const AFTER_HELP: &str = "\
Examples:
  ddirac run examples/double_spherical_pendulum.toml
  ddirac run examples/charged_particle.toml --set method.reduced=false --out out/unreduced
  ddirac check examples/point_vortices.toml
  ddirac convergence examples/charged_particle.toml --steps 10,50,100,200
  ddirac plot out/double_spherical_pendulum

Exit status:
  0        success
  2        the spec or the command line is wrong (also: `check` finds that a run would be refused)
  3        the integration failed (Newton's method, a non-finite state, an energy jump made an error)
  4        a file cannot be read or written, or the output directory is in use by another run
  128 + n  stopped by signal n: 130 SIGINT, 143 SIGTERM, 129 SIGHUP (nothing is written)
  1        any other failure";

#[derive(Debug, Subcommand)]
enum Command {
    /// Integrate the problem of a spec file; writes trajectory.csv and summary.json.
    ///
    /// The output directory (`--out`, else `output.directory`, else out/<spec file stem>) is locked
    /// for the run (`DIR/.ddirac.lock`: a second run into it fails at once, naming this one). The
    /// files are written aside and moved in only when the run succeeds, replacing those of the
    /// earlier run in the directory as a set (listed in `DIR/.ddirac-files`); a failed or interrupted
    /// run leaves the directory as it was. A run that would write more than 1 GB says so first; one
    /// that would not fit on the disk is refused (thin it with `output.every`).
    #[command(after_help = "Examples:
  ddirac run examples/double_spherical_pendulum.toml
  ddirac run examples/charged_particle.toml --out out/cp --set time.steps=1000 --set output.every=10
  ddirac run examples/charged_particle.toml --format csv,npy --set output.plots=true
  ddirac run examples/double_spherical_pendulum.toml --compare --out out/compare")]
    Run {
        #[command(flatten)]
        target: SpecTarget,
        /// Trajectory formats, comma-separated: `csv` (trajectory.csv), `npy` (npy/<column>.npy)
        /// [default: output.format of the spec, else csv].
        #[arg(long, value_delimiter = ',', value_name = "FORMATS")]
        format: Vec<output::Format>,
        /// Run the spec twice, reduced and unreduced, into DIR/reduced and DIR/unreduced, and write
        /// their differences to DIR/compare.csv with a figure.
        #[arg(long)]
        compare: bool,
    },
    /// Run a spec with several step counts over its duration and tabulate the error and the
    /// observed order; writes convergence.csv and a log-log figure.
    #[command(after_help = "Example:
  ddirac convergence examples/charged_particle.toml --steps 10,50,100,200 --out out/convergence")]
    Convergence {
        #[command(flatten)]
        target: SpecTarget,
        /// Step counts N, comma-separated, e.g. `10,50,100,200`.
        #[arg(long, value_delimiter = ',', required = true, num_args = 1.., value_name = "N,...",
              value_parser = clap::value_parser!(u64).range(1..))]
        steps: Vec<u64>,
    },
    /// Run many members of one spec that differ in initial data and/or parameters, in parallel;
    /// writes final.csv (member, status, final q and p; a rigid body's R and Π), members.csv, NPY arrays with a leading member
    /// axis (final states, status, diagnostics, and with `[ensemble] trajectories = true` the rows of
    /// every member) and summary.json.
    ///
    /// The members come from `--members FILE.csv` (a header of spec keys as `--set` names them,
    /// `initial.q.<coordinate>`, `initial.p.<coordinate>`, `initial.v.<coordinate>`,
    /// `parameters.<name>`, and a rigid body's `initial.Pi.<i>`, `initial.Omega.<i>` (i = 1, 2, 3), then
    /// one row of numbers per member) or from the spec's `[ensemble]` table
    /// (grids and seeded random draws). Member k gives the same numbers as `ddirac run` with its
    /// values set. A member that fails is recorded (status `failed`, reason in summary.json) and the
    /// others go on. The output directory defaults to out/<spec file stem>-ensemble.
    #[command(after_help = "Examples:
  ddirac ensemble examples/magnetic_mirror.toml
  ddirac ensemble examples/charged_particle.toml --members members.csv --out out/sweep --threads 8
  ddirac ensemble examples/magnetic_mirror.toml --out out/mirror --shard $SLURM_ARRAY_TASK_ID/16
  ddirac merge out/mirror/shard-*-of-16 --out out/mirror/all")]
    Ensemble {
        #[command(flatten)]
        target: SpecTarget,
        /// The members: a CSV file with one column per varied spec key [default: the spec's
        /// `[ensemble]` table].
        #[arg(long, value_name = "FILE.csv")]
        members: Option<PathBuf>,
        /// Threads [default: all cores].
        #[arg(long, value_name = "T", value_parser = clap::value_parser!(u64).range(1..))]
        threads: Option<u64>,
        /// Run only the I-th of N contiguous parts of the members (I from 0, as
        /// SLURM_ARRAY_TASK_ID), into DIR/shard-I-of-N; join the parts with `ddirac merge`.
        #[arg(long, value_name = "I/N", value_parser = parse_shard)]
        shard: Option<(usize, usize)>,
    },
    /// Join the directories of the shards of one ensemble (`ddirac ensemble --shard I/N`) into one,
    /// equal to the unsharded run's files.
    #[command(after_help = "Example:
  ddirac merge out/mirror/shard-*-of-16 --out out/mirror/all")]
    /// Find the relative equilibrium of the spec's reduced discrete map (its rule and step h) on the
    /// momentum level of its initial data, nearest to its initial shape and shape momenta: the shape,
    /// the group velocity, the multipliers of the linearized map and whether it is stable; writes
    /// DIR/equilibria.json (default out/<spec file stem>-equilibria) and prints a table.
    ///
    /// With --family NAME=FROM:TO:COUNT the equilibrium is continued along the momentum of the group
    /// coordinate NAME over COUNT equally spaced values from FROM to TO (each search starting from
    /// the members before; where one fails, by pseudo-arclength continuation), through its folds
    /// (where the momentum turns back, the family continues on its other branch over the values already
    /// visited), with where the stability changes, the folds, where the family ends if it does, and a
    /// figure (family.png, family.svg: the shape against the momentum, stable solid, unstable dashed).
    #[command(after_help = "Examples:
  ddirac equilibria examples/spherical_pendulum.toml --set initial.q.theta=1.0 --set initial.p.theta=0 --set initial.p.phi=1.6
  ddirac equilibria examples/kepler.toml --set initial.q.r=0.7 --family phi=0.8:1.5:8")]
    Equilibria {
        #[command(flatten)]
        target: SpecTarget,
        /// Continue along the momentum of a group coordinate: NAME=FROM:TO:COUNT.
        #[arg(long, value_name = "NAME=FROM:TO:COUNT", value_parser = parse_family)]
        family: Option<(String, f64, f64, usize)>,
    },
    Merge {
        /// The shard directories, in any order.
        #[arg(required = true, num_args = 1..)]
        dirs: Vec<PathBuf>,
        /// The merged directory.
        #[arg(long, value_name = "DIR", required = true)]
        out: PathBuf,
        /// Print nothing on success.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Draw the figures (PNG and SVG) of a finished run from DIR/trajectory.csv and DIR/summary.json.
    #[command(after_help = "Example:
  ddirac run examples/kepler.toml --out out/kepler && ddirac plot out/kepler")]
    Plot {
        /// The output directory of `ddirac run`.
        dir: PathBuf,
        /// Print nothing on success.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Check a spec without integrating: invariance of L_d, 2π-periodicity of the angles, connection
    /// axioms, Legendre rank and the primary constraint; exits 2 when a run of the spec's method would
    /// be refused (the verdict and the message a run gives).
    #[command(after_help = "Examples:
  ddirac check examples/point_vortices.toml
  ddirac check examples/heavy_top.toml --set method.reduced=true")]
    Check {
        #[command(flatten)]
        input: SpecInput,
    },
    /// List the built-in systems with their coordinates and default parameters.
    #[command(after_help = "Example:
  ddirac systems")]
    Systems,
    /// Time the engine against its alternatives side by side in one process (contenders alternating
    /// round by round) and print the time ratios with their spread over the rounds.
    #[command(after_help = "Examples:
  ddirac bench --quick
  ddirac bench --only charged-particle,expression --rounds 25 --json bench.json")]
    Bench(bench::Options),
}

fn main() -> ExitCode {
    let command = Cli::parse().command;
    if matches!(command, Command::Run { .. } | Command::Convergence { .. } | Command::Ensemble { .. }) {
        signals::install();
    }
    // Long messages stay on one line, so that they can be searched for in logs. A report takes its
    // handler when it is made, so the hook is set before any command runs.
    let _ = miette::set_hook(Box::new(|_| {
        Box::new(miette::MietteHandlerOpts::new().wrap_lines(false).terminal_links(false).build())
    }));
    let result: Result<(), miette::Report> = match command {
        Command::Run { target: SpecTarget { input: SpecInput { spec, set }, out, quiet }, format, compare } => {
            let options = run::RunOptions { spec, out, set, quiet, format };
            if compare {
                compare::compare(&options)
            } else {
                run::run(&options).map_err(Into::into)
            }
        }
        Command::Convergence { target: SpecTarget { input: SpecInput { spec, set }, out, quiet }, steps } => {
            convergence::convergence(&convergence::Options { spec, steps, out, set, quiet })
        }
        Command::Ensemble {
            target: SpecTarget { input: SpecInput { spec, set }, out, quiet },
            members,
            threads,
            shard,
        } => {
            let threads = threads.map(|t| t as usize);
            let options = ensemble::files::Options { spec, set, members, out, threads, shard, quiet };
            ensemble::files::command(&options).map_err(Into::into)
        }
        Command::Equilibria { target: SpecTarget { input: SpecInput { spec, set }, out, quiet }, family } => {
            equilibria::command(&equilibria::Options { spec, set, out, quiet, family }).map_err(Into::into)
        }
        Command::Merge { dirs, out, quiet } => ensemble::files::merge(&dirs, &out, quiet).map_err(Into::into),
        Command::Plot { dir, quiet } => plot::command(&dir, quiet).map_err(Into::into),
        Command::Check { input: SpecInput { spec, set } } => {
            check::check(&check::CheckOptions { spec, set }).map_err(Into::into)
        }
        Command::Systems => {
            print!("{}", systems());
            Ok(())
        }
        Command::Bench(options) => bench::bench(&options),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("{error:?}");
            ExitCode::from(diagnostics::exit_code(&error))
        }
    }
}

/// `I/N` of `--shard`.
/// `--family NAME=FROM:TO:COUNT`.
fn parse_family(text: &str) -> Result<(String, f64, f64, usize), String> {
    let form = "write NAME=FROM:TO:COUNT, the group coordinate and COUNT values of its momentum from FROM to TO \
                (e.g. `phi=0.5:3.0:26`)";
    let (name, range) = text.split_once('=').ok_or_else(|| form.to_owned())?;
    let parts: Vec<&str> = range.split(':').map(str::trim).collect();
    let [from, to, count] = parts.as_slice() else { return Err(form.to_owned()) };
    let number = |s: &str| s.parse::<f64>().map_err(|_| format!("`{s}` is not a number: {form}"));
    let (from, to) = (number(from)?, number(to)?);
    if !(from.is_finite() && to.is_finite()) {
        return Err(format!("the momenta must be finite numbers, not {from} and {to}"));
    }
    let count: usize = count.parse().map_err(|_| format!("`{count}` is not a count: {form}"))?;
    if count < 2 {
        return Err(format!("a family needs at least 2 values, not {count}"));
    }
    Ok((name.trim().to_owned(), from, to, count))
}

fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let (i, n) = text.split_once('/').ok_or("write the shard as I/N, e.g. 0/16")?;
    let i: usize = i.trim().parse().map_err(|_| format!("`{i}` is not a shard index"))?;
    let n: usize = n.trim().parse().map_err(|_| format!("`{n}` is not a number of shards"))?;
    if n == 0 {
        return Err("the number of shards N must be at least 1".into());
    }
    if i >= n {
        return Err(format!(
            "the shard index {i} must be in 0..{n}, below the number of shards (it counts from 0, as \
             SLURM_ARRAY_TASK_ID)"
        ));
    }
    Ok((i, n))
}

/// The text of `ddirac systems`.
fn systems() -> String {
    let mut text = String::new();
    for system in ddirac::systems::BUILT_IN {
        text.push_str(&format!("{}\n    {}\n", system.name, system.description));
        if let Ok(built) = (system.build)(&[]) {
            let coordinates: Vec<String> = built
                .coordinates()
                .iter()
                .map(|c| {
                    let role = if c.role == ddirac::Role::Group { "group" } else { "shape" };
                    let angle = if c.kind == ddirac::CoordinateKind::Angle { ", angle" } else { "" };
                    format!("{} ({role}{angle})", c.name)
                })
                .collect();
            text.push_str(&format!("    coordinates: {}\n", coordinates.join(", ")));
        }
        let parameters: Vec<String> = (system.defaults)().iter().map(|(n, v)| format!("{n} = {v}")).collect();
        text.push_str(&format!("    parameters:  {}\n\n", parameters.join(", ")));
    }
    let body = ddirac::systems::RigidBody::default_parameters();
    let parameters: Vec<String> =
        ddirac::systems::Parameters::parameters(&body).iter().map(|(n, v)| format!("{n} = {v}")).collect();
    text.push_str(&format!(
        "{}\n    a rigid body on SO(3) about a fixed point in gravity −g e3, centre of mass c in the body (a free \
         body when m·g·|c| = 0)\n    configuration: the attitude R (initial.R, body to space), with initial.Pi or \
         initial.Omega\n    parameters:  {}\n\n",
        ddirac_cli::rigid::NAME,
        parameters.join(", ")
    ));
    text
}
