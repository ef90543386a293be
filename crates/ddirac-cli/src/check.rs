//! `ddirac check SPEC`: everything a run checks before its first step, without integrating — the
//! spec (parse, validation, the Lagrangian's expressions), the invariance of L_d under each group
//! translation (the hypothesis of reduction, paper §4), the connection axioms (Definition 2.1), the
//! regularity of the Legendre transform and whether p0 lies on the primary constraint p = ∂L/∂v.
//!
//! The report goes to stdout. The exit status is 0 when a run of the spec's method would be
//! accepted, and non-zero when it would be refused or could not be trusted: a reduced method with a
//! Lagrangian that is not invariant (even with `check_invariance = false`), a reduced method without
//! group coordinates, or a degenerate Lagrangian with a p0 off the primary constraint.

use std::path::PathBuf;

use ddirac::{CheckReport, InitialMomentum, Role};
use miette::LabeledSpan;

use crate::diagnostics::{CliError, SpecError, SpecSource};
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
    let Loaded { source, plan, .. } = run::load(&options.spec, &options.set)?;
    let report = plan.system.check(&plan.problem, &plan.method).map_err(|error| {
        match plan.spans.diagnostic(&source, &error) {
            Some(diagnostic) => CliError::Spec(diagnostic),
            None => CliError::Integration(error),
        }
    })?;
    let findings = Findings::new(&plan, &report);
    let refusal = findings.refusal(&source, &plan, &report);
    println!("{}", findings.text(&plan, &report, refusal.is_some()));
    match refusal {
        Some(error) => Err(CliError::Spec(error)),
        None => Ok(()),
    }
}

/// What the report means for a run of the spec's method.
struct Findings {
    /// The first group coordinate under whose translation L_d changes, with its deviation.
    not_invariant: Option<(String, f64)>,
    /// p0 given as momenta, its largest entry.
    p0_scale: Option<f64>,
    /// Whether p0 satisfies the primary constraint.
    consistent: bool,
}

impl Findings {
    fn new(plan: &Plan, report: &CheckReport) -> Self {
        let not_invariant =
            report.invariance.iter().find(|(_, d)| *d > report.invariance_tolerance).map(|(n, d)| (n.clone(), *d));
        let p0_scale = match &plan.problem.initial {
            InitialMomentum::Momentum(p) => Some(p.iter().fold(0.0f64, |m, v| m.max(v.abs()))),
            InitialMomentum::Velocity(_) => None,
        };
        let consistent = match p0_scale {
            Some(scale) => report.momentum_consistent(scale),
            None => true,
        };
        Self { not_invariant, p0_scale, consistent }
    }

    /// Why a run would be refused, as a diagnostic pointing at the spec values concerned.
    fn refusal(&self, source: &SpecSource, plan: &Plan, report: &CheckReport) -> Option<Box<SpecError>> {
        let reduced = plan.method.reduced;
        if reduced && report.invariance.is_empty() {
            return plan.spans.diagnostic(source, &ddirac::Error::NoSymmetry).or_else(|| {
                Some(source.error(None, "a run would be refused: reduction needs at least one group coordinate", ""))
            });
        }
        if let (true, Some((coordinate, deviation))) = (reduced, &self.not_invariant) {
            let error = ddirac::Error::NotInvariant {
                coordinate: coordinate.clone(),
                deviation: *deviation,
                tolerance: report.invariance_tolerance,
            };
            return Some(plan.spans.diagnostic(source, &error).unwrap_or_else(|| {
                source
                    .error(None, format!("a run would be refused: {error}"), "")
                    .with_help("run the unreduced equations (`reduced = false`); reduction needs an invariant L_d")
            }));
        }
        if !report.regular() && !self.consistent {
            let labels = plan
                .spans
                .momentum
                .clone()
                .map(|span| LabeledSpan::new_with_span(Some("off the primary constraint".into()), span))
                .into_iter()
                .collect();
            return Some(
                source
                    .error_with(
                        format!(
                            "the Lagrangian is degenerate (rank {} of {}) and p0 does not satisfy the primary \
                             constraint p = ∂L/∂v(q0, v): mismatch {:.3e}",
                            report.legendre_rank, report.coordinates, report.constraint_mismatch
                        ),
                        labels,
                    )
                    .with_help(
                        "for a degenerate Lagrangian p0 is fixed by q0 where L is linear in the velocities: give \
                         p0 = ∂L/∂v(q0, v0), or give the velocities `v` instead of `p`",
                    ),
            );
        }
        None
    }

    /// The report printed on stdout.
    fn text(&self, plan: &Plan, report: &CheckReport, refused: bool) -> String {
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
        for (i, (name, deviation)) in report.invariance.iter().enumerate() {
            let verdict = if *deviation <= report.invariance_tolerance {
                "invariant"
            } else {
                "NOT invariant: reduction refused"
            };
            lines.push(format!(
                "  {:<16}  {name}: deviation {deviation:.2e} (tolerance {:.0e}): {verdict}",
                if i == 0 { "invariance" } else { "" },
                report.invariance_tolerance
            ));
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
        let momentum = match self.p0_scale {
            None => "given as a velocity: p0 = ∂L/∂v(q0, v0) lies on the primary constraint".to_owned(),
            Some(_) if self.consistent => format!(
                "consistent with the primary constraint p = ∂L/∂v (mismatch {:.2e})",
                report.constraint_mismatch
            ),
            Some(_) => format!(
                "NOT consistent with the primary constraint p = ∂L/∂v (mismatch {:.2e})",
                report.constraint_mismatch
            ),
        };
        lines.push(format!("  initial momentum  {momentum}"));
        let verdict = if refused {
            "a run would be refused"
        } else if m.reduced {
            "a run would be accepted (reduced equations)"
        } else {
            "a run would be accepted (unreduced equations)"
        };
        lines.push(format!("  verdict           {verdict}"));
        lines.join("\n")
    }
}
