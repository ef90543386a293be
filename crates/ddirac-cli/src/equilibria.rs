//! `ddirac equilibria`: the relative equilibrium of a spec's reduced discrete map
//! ([`ddirac::relative_equilibrium`]) on the momentum level of its initial data, nearest to its initial
//! shape, with the multipliers of the linearized map and the verdict on its stability. It writes
//! `DIR/equilibria.json`:
//!
//! ```text
//! {"equilibria": [{"shape": {name: value}, "momentum": [...], "group_velocity": [...],
//!                  "multipliers": [[re, im], ...], "stable": bool, ...}], ...}
//! ```
//!
//! (the names `equilibria`, `shape`, `momentum`, `group_velocity`, `multipliers` and `stable` are
//! fixed), and prints a table.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use ddirac::relative_equilibrium::{self, RelativeEquilibrium, SearchOptions};
use serde::Serialize;

use crate::diagnostics::CliError;
use crate::run_dir::RunDir;
use crate::{lock, output, run};

/// Options of `ddirac equilibria`.
pub struct Options {
    /// The spec file.
    pub spec: PathBuf,
    /// `--set` assignments.
    pub set: Vec<String>,
    /// `--out DIR`.
    pub out: Option<PathBuf>,
    /// `--quiet`.
    pub quiet: bool,
}

/// One relative equilibrium as `equilibria.json` writes it.
#[derive(Serialize)]
struct EquilibriumJson {
    shape: BTreeMap<String, f64>,
    shape_momentum: BTreeMap<String, f64>,
    group: Vec<String>,
    momentum: Vec<f64>,
    group_velocity: Vec<f64>,
    multipliers: Vec<[f64; 2]>,
    /// arg λ / h of each multiplier: the frequencies of small oscillations about it.
    frequencies: Vec<f64>,
    stable: bool,
    modulus_tolerance: f64,
    determinant: f64,
    residual: f64,
    iterations: usize,
    /// Angles among the group coordinates whose velocity is known only modulo 2π/h.
    ambiguous_group_velocity: Vec<String>,
}

#[derive(Serialize)]
struct FileJson {
    ddirac_version: &'static str,
    spec: String,
    system: String,
    rule: &'static str,
    order: u8,
    reduced: bool,
    step: f64,
    equilibria: Vec<EquilibriumJson>,
}

fn json(found: &RelativeEquilibrium) -> EquilibriumJson {
    let named = |names: &[String], values: &[f64]| names.iter().cloned().zip(values.iter().copied()).collect();
    EquilibriumJson {
        shape: named(&found.shape_names, &found.shape),
        shape_momentum: named(&found.shape_names, &found.shape_momentum),
        group: found.group_names.clone(),
        momentum: found.momentum.clone(),
        group_velocity: found.group_velocity.clone(),
        multipliers: found.multipliers.iter().map(|&(re, im)| [re, im]).collect(),
        frequencies: found.multipliers.iter().map(|&(re, im)| im.atan2(re) / found.step).collect(),
        stable: found.stable,
        modulus_tolerance: found.modulus_tolerance,
        determinant: found.determinant,
        residual: found.residual,
        iterations: found.iterations,
        ambiguous_group_velocity: found.ambiguous.clone(),
    }
}

/// `--out`, else `out/<spec file stem>-equilibria`.
fn output_dir(out: Option<&Path>, spec: &Path) -> PathBuf {
    match out {
        Some(out) => out.to_owned(),
        None => {
            let stem = spec.file_stem().map_or("run".into(), |s| s.to_string_lossy().into_owned());
            Path::new("out").join(format!("{stem}-equilibria"))
        }
    }
}

/// Runs `ddirac equilibria`.
pub fn command(options: &Options) -> Result<(), CliError> {
    let loaded = run::load(&options.spec, &options.set)?;
    loaded.print_notes();
    let plan = &loaded.plan;
    let found =
        relative_equilibrium::find(plan.system.as_ref(), &plan.problem, &plan.method, &SearchOptions::default())
            .map_err(CliError::Integration)?;
    let dir = output_dir(options.out.as_deref(), &options.spec);
    let run_dir = RunDir::open(&dir, &lock::command_line())?;
    let file = FileJson {
        ddirac_version: env!("CARGO_PKG_VERSION"),
        spec: options.spec.display().to_string(),
        system: plan.name.clone(),
        rule: plan.method.rule.name(),
        order: plan.method.composition.order(),
        reduced: plan.method.reduced,
        step: plan.problem.step,
        equilibria: vec![json(&found)],
    };
    let written = output::json(run_dir.staging(), "equilibria.json", &file)?;
    run_dir.commit(&[written])?;
    for name in &found.ambiguous {
        eprintln!(
            "warning [ambiguous_group_velocity]: `{name}` turns by more than π/2 in a step of h = {}: its increment is \
             known only modulo 2π, so its group velocity only modulo 2π/h = {:.6} (the shape and the multipliers are \
             not affected); take a smaller step to know it",
            found.step,
            2.0 * std::f64::consts::PI / found.step
        );
    }
    if (found.determinant - 1.0).abs() > 1e-6 {
        eprintln!(
            "warning [not_symplectic]: det DΦ_h = {:.6} at the equilibrium, not 1: the map does not preserve volume on \
             this level, and the multipliers need not pair as a symplectic map's",
            found.determinant
        );
    }
    if !options.quiet {
        println!("{}", table(&plan.name, &found, &dir, plan.method.rule.name(), plan.method.composition.order()));
    }
    Ok(())
}

/// The printed table.
fn table(system: &str, found: &RelativeEquilibrium, dir: &Path, rule: &str, order: u8) -> String {
    let pairs = |names: &[String], values: &[f64], prefix: &str| {
        names.iter().zip(values).map(|(n, v)| format!("{prefix}{n} = {v}")).collect::<Vec<_>>().join(", ")
    };
    let level = if found.group_names.is_empty() {
        "no group coordinates: an equilibrium".to_owned()
    } else {
        format!("on the level {}", pairs(&found.group_names, &found.momentum, "p_"))
    };
    let mut text = format!(
        "relative equilibrium of {system} (rule {rule}, order {order}, h = {}) {level} → {}\n",
        found.step,
        dir.display()
    );
    text.push_str(&format!("  shape            {}\n", pairs(&found.shape_names, &found.shape, "")));
    text.push_str(&format!("  shape momenta    {}\n", pairs(&found.shape_names, &found.shape_momentum, "p_")));
    if !found.group_names.is_empty() {
        let velocity: Vec<String> =
            found.group_names.iter().zip(&found.group_velocity).map(|(n, v)| format!("{n}: {v}")).collect();
        text.push_str(&format!("  group velocity   {} per unit time\n", velocity.join(", ")));
    }
    for (k, &(re, im)) in found.multipliers.iter().enumerate() {
        let label = if k == 0 { "  multipliers      " } else { "                   " };
        let modulus = re.hypot(im);
        text.push_str(&format!(
            "{label}{re:.12} {} {:.12}i   |λ| − 1 = {:.1e}, angle / h = {:.6}\n",
            if im < 0.0 { "−" } else { "+" },
            im.abs(),
            modulus - 1.0,
            im.atan2(re) / found.step
        ));
    }
    let verdict = if found.stable {
        format!("stable: every multiplier on the unit circle (to {:.0e})", found.modulus_tolerance)
    } else {
        format!("unstable: a multiplier off the unit circle by {:.2e}", found.off_circle())
    };
    text.push_str(&format!("  verdict          {verdict}\n"));
    text.push_str(&format!(
        "  found in         {} Newton corrections, ‖Φ_h(x) − x‖∞ = {:.1e}",
        found.iterations, found.residual
    ));
    text
}
