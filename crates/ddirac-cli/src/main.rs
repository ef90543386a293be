//! `ddirac`: runs discrete Dirac (reduced or unreduced) integrations described by TOML specs.
//!
//! ```text
//! ddirac run SPEC.toml [--out DIR] [--set KEY=VALUE]... [--quiet]
//! ddirac run SPEC.toml --compare [--out DIR] [--set KEY=VALUE]... [--quiet]
//! ddirac convergence SPEC.toml --steps 10,50,100,200 [--out DIR] [--set KEY=VALUE]... [--quiet]
//! ddirac plot DIR [--quiet]
//! ddirac check SPEC.toml [--set KEY=VALUE]...
//! ddirac systems
//! ddirac bench [--only GROUP,...] [--rounds R] [--batch-ms MS] [--quick] [--json PATH]
//! ```

mod bench;
mod check;
mod compare;
mod convergence;
mod diagnostics;
mod npy;
mod output;
mod overrides;
mod plot;
mod progress;
mod report;
mod run;
mod spec;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

/// Structure-preserving integrators for Lagrangian systems with abelian symmetry, after
/// "Discrete Dirac reduction of implicit Lagrangian systems with abelian symmetry groups".
#[derive(Debug, Parser)]
#[command(name = "ddirac", version, about)]
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

#[derive(Debug, Subcommand)]
enum Command {
    /// Integrate the problem of a spec file; writes trajectory.csv and summary.json.
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
    Convergence {
        #[command(flatten)]
        target: SpecTarget,
        /// Step counts N, comma-separated, e.g. `10,50,100,200`.
        #[arg(long, value_delimiter = ',', required = true, num_args = 1.., value_name = "N,...",
              value_parser = clap::value_parser!(u64).range(1..))]
        steps: Vec<u64>,
    },
    /// Draw the figures (PNG and SVG) of a finished run from DIR/trajectory.csv and DIR/summary.json.
    Plot {
        /// The output directory of `ddirac run`.
        dir: PathBuf,
        /// Print nothing on success.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Check a spec without integrating: invariance of L_d, connection axioms, Legendre rank and the
    /// primary constraint; exits non-zero when a run of the spec's method would be refused.
    Check {
        #[command(flatten)]
        input: SpecInput,
    },
    /// List the built-in systems with their coordinates and default parameters.
    Systems,
    /// Time the engine against its alternatives side by side in one process (contenders alternating
    /// round by round) and print the time ratios with their spread over the rounds.
    Bench(bench::Options),
}

fn main() -> ExitCode {
    let command = Cli::parse().command;
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
            ExitCode::FAILURE
        }
    }
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
    text
}
