//! `ddirac`: runs discrete Dirac (reduced or unreduced) integrations described by TOML specs.
//!
//! ```text
//! ddirac run SPEC.toml [--out DIR] [--set KEY=VALUE]... [--quiet]
//! ddirac systems
//! ```

mod diagnostics;
mod npy;
mod output;
mod overrides;
mod report;
mod run;
mod spec;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Structure-preserving integrators for Lagrangian systems with abelian symmetry, after
/// "Discrete Dirac reduction of implicit Lagrangian systems with abelian symmetry groups".
#[derive(Debug, Parser)]
#[command(name = "ddirac", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Integrate the problem of a spec file; writes trajectory.csv and summary.json.
    Run {
        /// The TOML spec (see examples/).
        spec: PathBuf,
        /// Output directory [default: output.directory of the spec, else out/<spec file stem>].
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Override one spec value before it is read, e.g. `method.reduced=false` (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Print nothing on success.
        #[arg(long, short)]
        quiet: bool,
        /// Trajectory formats, comma-separated: `csv` (trajectory.csv), `npy` (npy/<column>.npy)
        /// [default: output.format of the spec, else csv].
        #[arg(long, value_delimiter = ',', value_name = "FORMATS")]
        format: Vec<output::Format>,
    },
    /// List the built-in systems with their coordinates and default parameters.
    Systems,
}

fn main() -> ExitCode {
    let command = Cli::parse().command;
    let result = match command {
        Command::Run { spec, out, set, quiet, format } => run::run(&run::RunOptions { spec, out, set, quiet, format }),
        Command::Systems => {
            print!("{}", systems());
            Ok(())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            // Long messages stay on one line, so that they can be searched for in logs.
            let _ = miette::set_hook(Box::new(|_| {
                Box::new(miette::MietteHandlerOpts::new().wrap_lines(false).terminal_links(false).build())
            }));
            eprintln!("{:?}", miette::Report::new(error));
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
