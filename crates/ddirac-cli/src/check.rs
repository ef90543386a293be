//! `ddirac check SPEC`: everything a run checks before its first step, without integrating — the
//! spec (parse, validation, the Lagrangian's expressions), the invariance of L_d under each group
//! translation (the hypothesis of reduction, paper §4), the connection axioms (Definition 2.1), the
//! regularity of the Legendre transform and whether p0 lies on the primary constraint p = ∂L/∂v, and
//! for an atlas each chart's maps, Legendre map, group coordinates and angles.
//!
//! The report goes to stdout. The verdict is the library's ([`ddirac::CheckReport::verdict`]), the
//! one a run applies before its first step: the exit status is 0 exactly when a run of the spec's
//! method would be accepted, and a refusal is the error the run would report. Warnings a run would
//! carry (a reduction with `check_invariance = false` of an L_d that fails the check) are printed
//! too.

use std::path::PathBuf;

use ddirac::{CheckReport, Finding, InitialMomentum, Role};

use crate::diagnostics::CliError;
use crate::run::{self, Loaded};
use crate::spec::Plan;

/// Options of `ddirac check`.
pub struct CheckOptions {
    /// The spec file.
    pub spec: PathBuf,
    /// `--set KEY=VALUE` arguments, in order.
    pub set: Vec<String>,
}

/// Checks a spec, prints the report, and fails when a run would be refused.
pub fn check(options: &CheckOptions) -> Result<(), CliError> {
    let spec_text = run::read(&options.spec)?;
    if crate::rigid::names_rigid_body(&spec_text, &options.set) {
        return crate::rigid::check::check(&options.spec, &options.set, spec_text);
    }
    let loaded = run::load_text(&options.spec, spec_text, &options.set)?;
    loaded.print_notes();
    let Loaded { source, plan, .. } = loaded;
    let located = |error: ddirac::Error| match plan.spans.diagnostic(&source, &error) {
        Some(diagnostic) => CliError::Spec(diagnostic),
        None => CliError::Integration(error),
    };
    let report = plan.system.check(&plan.problem, &plan.method).map_err(located)?;
    let verdict = report.verdict(&plan.method);
    println!("{}", text(&plan, &report, &verdict));
    match verdict {
        Ok(warnings) => {
            crate::report::print_warnings(&warnings);
            Ok(())
        }
        Err(error) => Err(located(error)),
    }
}

/// One line of a hypothesis tested per coordinate.
fn finding_line(heading: &str, f: &Finding, tolerance: f64, holds: &str, fails: &str) -> String {
    let verdict = if f.holds(tolerance) {
        holds.to_owned()
    } else if f.decided() {
        fails.to_owned()
    } else {
        format!("UNDECIDED: L_d is finite at only {} pairs near the initial data", f.samples)
    };
    format!(
        "  {heading:<16}  {}: deviation {:.2e} (tolerance {tolerance:.0e}, {} samples): {verdict}",
        f.coordinate, f.deviation, f.samples
    )
}

/// The lines of the atlas's charts: each chart's maps there and back, the Legendre map where its
/// quality is high, its group coordinates and angles.
fn chart_lines(report: &CheckReport, m: &ddirac::Method) -> Vec<String> {
    let mut lines = vec![];
    let used = if m.atlas { "" } else { " (not used: `method.atlas = false`)" };
    for (i, c) in report.charts.iter().enumerate() {
        let heading = if i == 0 { "charts" } else { "" };
        let maps = if c.points == 0 {
            "UNTESTED: no sampled point falls where its quality is positive".to_owned()
        } else if c.inverse() {
            format!("maps inverse on {} sampled points (largest round trip {:.1e})", c.points, c.round_trip)
        } else {
            format!(
                "maps NOT inverse: a round trip lands {:.2e} (relative) away, at ({}); tolerance {:.0e}",
                c.round_trip,
                c.worst.iter().map(|x| format!("{x:.4}")).collect::<Vec<_>>().join(", "),
                ddirac::ROUND_TRIP_TOLERANCE
            )
        };
        lines.push(format!("  {heading:<16}  `{}`{used}: {maps}", c.name));
        if let Some((at, quality)) = &c.singular_where_good {
            let at = at.iter().map(|x| format!("{x:.4}")).collect::<Vec<_>>().join(", ");
            lines.push(format!("  {:<16}    quality {quality:.3} at ({at}), where its Legendre map is SINGULAR", ""));
        }
        let not_invariant = if m.reduced { "NOT invariant" } else { "NOT invariant (unreduced: not needed)" };
        for f in &c.invariance {
            lines.push(finding_line("", f, report.invariance_tolerance, "invariant", not_invariant));
        }
        for f in &c.periodicity {
            lines.push(finding_line("", f, report.periodicity_tolerance, "2π-periodic", "NOT 2π-periodic"));
        }
    }
    lines
}

/// The report printed on stdout.
fn text(plan: &Plan, report: &CheckReport, verdict: &Result<Vec<ddirac::Warning>, ddirac::Error>) -> String {
    let coordinates = plan.system.coordinates();
    let listed: Vec<String> = coordinates
        .iter()
        .map(|c| if c.role == Role::Group { format!("{} [group]", c.name) } else { c.name.clone() })
        .collect();
    let m = &plan.method;
    let mut lines = vec![format!(
        "{}: {} coordinates ({}), rule {}, variant {}, {}",
        plan.name,
        coordinates.len(),
        listed.join(", "),
        m.rule.name(),
        m.variant.name(),
        if m.reduced { "reduced" } else { "unreduced" }
    )];
    if report.invariance.is_empty() {
        lines.push("  invariance        no group coordinates: nothing to reduce".into());
    }
    let not_invariant = match (m.reduced, m.check_invariance) {
        (true, true) => "NOT invariant: reduction refused",
        (true, false) => "NOT invariant: reduced anyway (check_invariance = false), with a warning",
        (false, _) => "NOT invariant: the unreduced equations do not need it",
    };
    for (i, f) in report.invariance.iter().enumerate() {
        let heading = if i == 0 { "invariance" } else { "" };
        lines.push(finding_line(heading, f, report.invariance_tolerance, "invariant", not_invariant));
    }
    for (i, f) in report.periodicity.iter().enumerate() {
        let heading = if i == 0 { "angles" } else { "" };
        let fails = "NOT 2π-periodic: the chart may not wrap it";
        lines.push(finding_line(heading, f, report.periodicity_tolerance, "2π-periodic", fails));
    }
    let n_g = report.invariance.len();
    let n_x = coordinates.len() - n_g;
    let connection = if m.connection.is_some() { "K as given" } else { "K = 0" };
    let axioms = if report.connection_axioms { "axioms hold" } else { "axioms fail" };
    lines.push(format!("  connection        {connection} ({n_g} × {n_x}): {axioms}"));
    let legendre = if report.regular() { "regular" } else { "degenerate" };
    lines.push(format!(
        "  Legendre          {legendre} (rank {} of {}) at (q0, v0)",
        report.legendre_rank, report.coordinates
    ));
    let momentum = match &plan.problem.initial {
        InitialMomentum::Velocity(_) => {
            "given as a velocity: p0 = ∂L/∂v(q0, v0) lies on the primary constraint".to_owned()
        }
        InitialMomentum::Momentum(_) if report.momentum_consistent() => {
            format!("consistent with the primary constraint p = ∂L/∂v (mismatch {:.2e})", report.constraint_mismatch)
        }
        InitialMomentum::Momentum(_) => format!(
            "NOT consistent with the primary constraint p = ∂L/∂v (mismatch {:.2e})",
            report.constraint_mismatch
        ),
    };
    lines.push(format!("  initial momentum  {momentum}"));
    lines.extend(chart_lines(report, m));
    let equations = if m.reduced { "reduced equations" } else { "unreduced equations" };
    let verdict = match verdict {
        Err(_) => "a run would be refused".to_owned(),
        Ok(w) if w.is_empty() => format!("a run would be accepted ({equations})"),
        Ok(w) => format!("a run would be accepted ({equations}) with {} warning(s)", w.len()),
    };
    lines.push(format!("  verdict           {verdict}"));
    lines.join("\n")
}
