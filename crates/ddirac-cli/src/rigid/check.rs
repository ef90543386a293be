//! `ddirac check` of a rigid body's spec: the spec's values, the initial attitude, the declared
//! symmetry tested (ℓ(g R, Ω) = ℓ(R, Ω) for rotations g of the group, at attitudes spread over SO(3)),
//! whether the method may reduce by it, the Legendre transform at the initial data, and the verdict a
//! run would reach before its first step (the exit status is 0 exactly when it would be accepted).

use ddirac::rigid::{so3, test_symmetry, RigidInitial, RigidStepper, Symmetry, INVARIANCE_TOLERANCE};

use super::plan;
use crate::diagnostics::CliError;

/// Checks the rigid body's spec whose text is `text`, prints the report, and fails when a run would
/// be refused.
pub fn check(path: &std::path::Path, set: &[String], text: String) -> Result<(), CliError> {
    let super::LoadedRigid { source, spec, plan } = super::load_text(path, text, set)?;
    let located = |e: ddirac::Error| plan::refusal(&source, &spec, e);
    let (problem, method) = (&plan.problem, &plan.method);
    let r0 = problem.r0;
    let omega0 = match &problem.initial {
        RigidInitial::Velocity { omega, .. } => *omega,
        // The samples spread about Ω0 by its size: about 0, of size 1, without Ω0 at hand.
        RigidInitial::Momentum { .. } => [0.0; 3],
    };
    let symmetry = ddirac::rigid::RigidSystem::symmetry(&plan.body);
    let mut lines = vec![format!(
        "{}: the attitude R on SO(3), rule {}, {}{}",
        plan.name,
        method.rule.name(),
        if method.reduced { "reduced by SO(3)" } else { "unreduced" },
        crate::report::composition(method.composition)
    )];
    lines.push(format!(
        "  attitude R0       |RᵀR − I| = {:.1e}, det R − 1 = {:.1e} (tolerance {:.0e}): a rotation",
        so3::orthogonality_error(&r0),
        so3::determinant(&r0) - 1.0,
        ddirac::rigid::ROTATION_TOLERANCE
    ));
    let v0 = match &problem.initial {
        RigidInitial::Velocity { v, .. } => v.clone(),
        RigidInitial::Momentum { p, .. } => vec![0.0; p.len()],
    };
    let tested = test_symmetry(&plan.body, &r0, &omega0, &problem.s0, &v0);
    lines.push(match (&tested, symmetry) {
        (_, Symmetry::None) => "  symmetry          none declared: nothing to test or reduce".to_owned(),
        (Ok(deviation), _) => format!(
            "  symmetry          {}: ℓ(g R, Ω) = ℓ(R, Ω) to {deviation:.1e} relative (tolerance {INVARIANCE_TOLERANCE:.0e}): \
             holds",
            describe(symmetry)
        ),
        (Err(e), _) => format!("  symmetry          {}: {e}", describe(symmetry)),
    });
    let reduction = match (symmetry, method.reduced) {
        (Symmetry::Rotations, true) => "by SO(3): the Euler–Poincaré equations on Π, R reconstructed",
        (Symmetry::Rotations, false) => "possible (`method.reduced = true`): the Lagrangian is invariant under SO(3)",
        (_, true) => "REFUSED: the Lagrangian is not invariant under every rotation",
        (_, false) => "not possible by all of SO(3) (not needed: unreduced)",
    };
    lines.push(format!("  reduction         {reduction}"));
    let verdict = RigidStepper::new(&plan.body, problem.clone(), method).map(|mut stepper| stepper.summary());
    if let Ok(summary) = &verdict {
        let energy = summary.energy.initial;
        lines.push(if energy.is_nan() {
            "  Legendre          ∂ℓ/∂Ω cannot be inverted at the initial data: the energy is not reported".to_owned()
        } else {
            format!("  Legendre          regular at the initial data: energy H0 = {energy:.10e}")
        });
        let j = &summary.momentum_map.initial;
        lines.push(format!(
            "  momentum          R0 Π0 = ({:.6e}, {:.6e}, {:.6e}), |Π0| = {:.6e}",
            j[0], j[1], j[2], summary.casimir.initial
        ));
    }
    lines.push(format!(
        "  verdict           {}",
        match &verdict {
            Ok(s) if s.warnings.is_empty() => "a run would be accepted".to_owned(),
            Ok(s) => format!("a run would be accepted with {} warning(s)", s.warnings.len()),
            Err(_) => "a run would be refused".to_owned(),
        }
    ));
    println!("{}", lines.join("\n"));
    match verdict {
        Ok(summary) => {
            crate::report::print_warnings(&summary.warnings);
            Ok(())
        }
        Err(e) => Err(located(e)),
    }
}

/// The symmetry in words.
fn describe(symmetry: Symmetry) -> &'static str {
    match symmetry {
        Symmetry::Rotations => "SO(3), every rotation of space",
        Symmetry::Vertical => "rotations about the vertical e3",
        Symmetry::None => "none",
    }
}
