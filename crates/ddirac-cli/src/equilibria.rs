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
//! fixed), and prints a table. With `--family NAME=FROM:TO:COUNT` it continues the equilibrium along the
//! momentum of the group coordinate NAME ([`relative_equilibrium::family`]): `equilibria` lists the
//! members in the family's order, `family` says where the stability changes, where the family turns
//! back at a fold (`folds`) and where it ended, and `family.png` and `family.svg` draw the shape
//! against the momentum through the folds (stable solid, unstable dashed).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use ddirac::relative_equilibrium::{self, Family, Fold, RelativeEquilibrium, SearchOptions};
use serde::Serialize;

use crate::diagnostics::CliError;
use crate::plot::{self, Figure, Panel, Series};
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
    /// `--family NAME=FROM:TO:COUNT`: the group coordinate, the first and last momentum, the count.
    pub family: Option<(String, f64, f64, usize)>,
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
    #[serde(skip_serializing_if = "Option::is_none")]
    family: Option<FamilyJson>,
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
    let search = SearchOptions::default();
    let (members, family) = match &options.family {
        None => {
            let found = relative_equilibrium::find(plan.system.as_ref(), &plan.problem, &plan.method, &search)
                .map_err(CliError::Integration)?;
            (vec![found], None)
        }
        Some((along, from, to, count)) => {
            let values = linspace(*from, *to, *count);
            let family = relative_equilibrium::family(
                plan.system.as_ref(),
                &plan.problem,
                &plan.method,
                along,
                &values,
                &search,
            )
            .map_err(CliError::Integration)?;
            (family.members.clone(), Some(family))
        }
    };
    let dir = output_dir(options.out.as_deref(), &options.spec);
    let run_dir = RunDir::open(&dir, &lock::command_line())?;
    let staging = run_dir.staging().to_owned();
    let file = FileJson {
        ddirac_version: env!("CARGO_PKG_VERSION"),
        spec: options.spec.display().to_string(),
        system: plan.name.clone(),
        rule: plan.method.rule.name(),
        order: plan.method.composition.order(),
        reduced: plan.method.reduced,
        step: plan.problem.step,
        equilibria: members.iter().map(json).collect(),
        family: family.as_ref().map(|f| FamilyJson {
            along: f.along.clone(),
            values: f.values(),
            stability_changes: f.stability_changes().into_iter().map(|(a, b)| [a, b]).collect(),
            folds: f.folds.iter().map(|fold| fold_json(f, fold)).collect(),
            ended: f.ended.as_ref().map(|(at, why)| EndedJson { at: *at, why: why.to_string() }),
        }),
    };
    let mut files = vec![output::json(&staging, "equilibria.json", &file)?];
    if let Some(family) = &family {
        let drawn = plot::save(&family_figure(&plan.name, family), &staging).map_err(|e| CliError::figure(&dir, e))?;
        files.extend(drawn.iter().filter_map(|p| p.strip_prefix(&staging).ok()).map(Path::to_path_buf));
    }
    run_dir.commit(&files)?;
    let mut warned = std::collections::BTreeSet::new();
    for found in &members {
        for name in found.ambiguous.iter().filter(|n| warned.insert((*n).clone())) {
            eprintln!(
                "warning [ambiguous_group_velocity]: `{name}` turns by more than π/2 in a step of h = {}: its increment \
                 is known only modulo 2π, so its group velocity only modulo 2π/h = {:.6} (the shape and the \
                 multipliers are not affected); take a smaller step to know it",
                found.step,
                2.0 * std::f64::consts::PI / found.step
            );
        }
    }
    if let Some(found) = members.iter().find(|f| (f.determinant - 1.0).abs() > 1e-6) {
        eprintln!(
            "warning [not_symplectic]: det DΦ_h = {:.6} at a relative equilibrium, not 1: the map does not preserve \
             volume on this level, and the multipliers need not pair as a symplectic map's",
            found.determinant
        );
    }
    if !options.quiet {
        match &family {
            None => {
                let (rule, order) = (plan.method.rule.name(), plan.method.composition.order());
                println!("{}", table(&plan.name, &members[0], &dir, rule, order));
            }
            Some(family) => println!("{}", family_table(&plan.name, family, &dir)),
        }
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

/// `family` of `equilibria.json`.
#[derive(Serialize)]
struct FamilyJson {
    along: String,
    values: Vec<f64>,
    stability_changes: Vec<[f64; 2]>,
    folds: Vec<FoldJson>,
    ended: Option<EndedJson>,
}

/// A fold of the family in `equilibria.json`: the momentum there, the shape, and the index of the first
/// member past it (in `equilibria`).
#[derive(Serialize)]
struct FoldJson {
    momentum: f64,
    shape: BTreeMap<String, f64>,
    shape_momentum: BTreeMap<String, f64>,
    next_member: usize,
}

fn fold_json(family: &Family, fold: &Fold) -> FoldJson {
    let names = family.members.first().map(|m| m.shape_names.clone()).unwrap_or_default();
    let named = |values: &[f64]| names.iter().cloned().zip(values.iter().copied()).collect();
    FoldJson {
        momentum: fold.momentum,
        shape: named(&fold.shape),
        shape_momentum: named(&fold.shape_momentum),
        next_member: fold.next_member,
    }
}

#[derive(Serialize)]
struct EndedJson {
    at: f64,
    why: String,
}

/// `count` equally spaced values from `from` to `to`, both included.
fn linspace(from: f64, to: f64, count: usize) -> Vec<f64> {
    if count < 2 {
        return vec![from];
    }
    let step = (to - from) / (count - 1) as f64;
    (0..count).map(|i| if i + 1 == count { to } else { from + step * i as f64 }).collect()
}

/// The family's figure: each shape coordinate against the momentum, stable stretches solid and
/// unstable ones dashed.
fn family_figure(system: &str, family: &Family) -> Figure {
    let values = family.values();
    // The members in the family's order with its folds between them, a fold drawn in the style of the
    // member before it: (μ, shape, stable).
    let mut points: Vec<(f64, &[f64], bool)> = vec![];
    let folds_before = |k: usize| family.folds.iter().filter(move |f| f.next_member == k);
    for (k, (m, value)) in family.members.iter().zip(&values).enumerate() {
        for fold in folds_before(k) {
            let stable = points.last().is_none_or(|p| p.2);
            points.push((fold.momentum, &fold.shape, stable));
        }
        points.push((*value, &m.shape, m.stable));
    }
    for fold in folds_before(family.members.len()) {
        points.push((fold.momentum, &fold.shape, points.last().is_none_or(|p| p.2)));
    }
    let n = points.len();
    let names = family.members.first().map(|m| m.shape_names.clone()).unwrap_or_default();
    let panels = names
        .iter()
        .enumerate()
        .map(|(j, name)| {
            let mut series = vec![];
            let mut labelled = [false, false];
            let mut start = 0;
            for k in 1..=n {
                if k == n || points[k].2 != points[start].2 {
                    // The stretch start..k, joined to the next point so that the line is unbroken.
                    let line = (start..(k + 1).min(n)).map(|i| (points[i].0, points[i].1[j])).collect();
                    let stable = points[start].2;
                    let mut line = Series::line(line);
                    line.dashed = !stable;
                    line.markers = true;
                    if !labelled[usize::from(stable)] {
                        line.name = Some(if stable { "stable" } else { "unstable" }.to_owned());
                        labelled[usize::from(stable)] = true;
                    }
                    series.push(line);
                    start = k;
                }
            }
            Panel::new(format!("momentum p_{}", family.along), name.clone(), series)
                .caption(format!("{name} of the relative equilibria along p_{}", family.along))
        })
        .collect();
    Figure::new("family", format!("Relative equilibria of {system} along p_{}", family.along), panels)
        .subtitle("stable solid, unstable dashed; one marker per member and per fold")
}

/// The printed table of a family.
fn family_table(system: &str, family: &Family, dir: &Path) -> String {
    let values = family.values();
    let names = family.members.first().map(|m| m.shape_names.clone()).unwrap_or_default();
    let mut text = format!(
        "family of relative equilibria of {system} along p_{}: {} members → {}\n",
        family.along,
        family.members.len(),
        dir.display()
    );
    let mut header = format!("  {:>14}", format!("p_{}", family.along));
    for name in &names {
        header.push_str(&format!(" {name:>18}"));
    }
    header.push_str("  verdict     max |λ| − 1");
    text.push_str(&header);
    text.push('\n');
    for (k, (value, member)) in values.iter().zip(&family.members).enumerate() {
        for fold in family.folds.iter().filter(|f| f.next_member == k) {
            let mut line = format!("  {:>14.6}", fold.momentum);
            for s in &fold.shape {
                line.push_str(&format!(" {s:>18.12}"));
            }
            line.push_str("  fold: the family turns back");
            text.push_str(&line);
            text.push('\n');
        }
        let mut line = format!("  {value:>14.6}");
        for s in &member.shape {
            line.push_str(&format!(" {s:>18.12}"));
        }
        let largest = member.multipliers.iter().map(|(re, im)| re.hypot(*im)).fold(0.0, f64::max);
        let verdict = if member.stable { "stable" } else { "unstable" };
        line.push_str(&format!("  {verdict:<10} {:>10.1e}", largest - 1.0));
        text.push_str(&line);
        text.push('\n');
    }
    for fold in &family.folds {
        text.push_str(&format!(
            "  the family turns back at a fold at p_{} = {:.10}: it continues on another branch\n",
            family.along, fold.momentum
        ));
    }
    for (a, b) in family.stability_changes() {
        text.push_str(&format!("  the stability changes between p_{} = {a} and {b}\n", family.along));
    }
    if let Some((at, why)) = &family.ended {
        text.push_str(&format!("  the family ends before p_{} = {at}: {why}\n", family.along));
    }
    text.trim_end().to_owned()
}
