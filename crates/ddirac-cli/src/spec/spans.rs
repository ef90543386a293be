//! Where the spec wrote the values that the library's errors can concern, to point those errors at
//! them.

use std::ops::Range;

use miette::LabeledSpan;

use crate::diagnostics::{SpecError, SpecSource};

/// Spans of the spec values that library errors can concern.
#[derive(Debug, Default)]
pub struct Spans {
    /// Each parameter override's value.
    pub parameters: Vec<(String, Range<usize>)>,
    /// `initial.q`.
    pub q: Option<Range<usize>>,
    /// `initial.p` or `initial.v`.
    pub momentum: Option<Range<usize>>,
    /// `method.connection`.
    pub connection: Option<Range<usize>>,
    /// `method.reduced`.
    pub reduced: Option<Range<usize>>,
    /// The `[time]` table.
    pub time: Option<Range<usize>>,
    /// `output.every`.
    pub every: Option<Range<usize>>,
    /// The `system` value (name or table).
    pub system: Option<Range<usize>>,
    /// The declaration of each group coordinate in `system.group`, by name (`[system]` tables only).
    pub group: Vec<(String, Range<usize>)>,
    /// Each entry of `system.angles`, by name (`[system]` tables only).
    pub angles: Vec<(String, Range<usize>)>,
    /// `method.tolerance`.
    pub tolerance: Option<Range<usize>>,
    /// `method.on_energy_jump`.
    pub energy_jump: Option<Range<usize>>,
    /// `method.composition`, else `method.order`.
    pub composition: Option<Range<usize>>,
    /// Whether the system is a built-in one (named) rather than a `[system]` table.
    pub built_in: bool,
}

impl Spans {
    /// The span and label of the spec value a library error is about, if any.
    pub fn locate(&self, error: &ddirac::Error) -> Option<(Range<usize>, &'static str)> {
        use ddirac::{Error as E, Hypothesis, Input};
        let what = match error {
            E::Size { what, .. } | E::NonFinite { what, .. } | E::Invalid { what, .. } => what,
            E::Undecided { hypothesis: Hypothesis::Periodicity, coordinate, .. } => {
                return match self.angles.iter().find(|(n, _)| n == coordinate) {
                    Some((_, span)) => Some((span.clone(), "this angle")),
                    None => self.system.clone().map(|s| (s, "this system")),
                }
            }
            E::NotInvariant { .. } | E::NoSymmetry | E::Undecided { .. } => {
                return self.reduced.clone().map(|s| (s, "reduction asked here"))
            }
            E::OffPrimaryConstraint { .. } => return self.momentum.clone().map(|s| (s, "off the primary constraint")),
            E::Chart { .. } => return self.system.clone().map(|s| (s, "the atlas of this system")),
            E::Undetermined { .. } => return self.system.clone().map(|s| (s, "this system")),
            E::Newton { .. } | E::Diverged { .. } | E::EnergyJump { .. } => {
                return self.time.clone().map(|s| (s, "this time grid"))
            }
            _ => return None,
        };
        match what {
            Input::Parameter(name) => {
                self.parameters.iter().find(|(n, _)| n == name).map(|(_, span)| (span.clone(), "this parameter"))
            }
            Input::InitialConfiguration => self.q.clone().map(|s| (s, "initial configuration")),
            Input::InitialMomentum | Input::InitialVelocity | Input::MomentumFromVelocity => {
                self.momentum.clone().map(|s| (s, "initial data"))
            }
            Input::Connection => self.connection.clone().map(|s| (s, "this connection")),
            Input::Composition => self.composition.clone().map(|s| (s, "this composition")),
            Input::Every => self.every.clone().map(|s| (s, "this value")),
            Input::Step | Input::Steps => self.time.clone().map(|s| (s, "this time grid")),
            _ => None,
        }
    }

    /// A library error as a diagnostic pointing at the spec values it concerns, if it concerns any.
    ///
    /// A refused reduction points at `reduced = true` and, for a `[system]` table, at the group
    /// coordinate whose translation changes L_d.
    pub fn diagnostic(&self, source: &SpecSource, error: &ddirac::Error) -> Option<Box<SpecError>> {
        let mut labels: Vec<LabeledSpan> = self
            .locate(error)
            .map(|(span, label)| LabeledSpan::new_with_span(Some(label.into()), span))
            .into_iter()
            .collect();
        let help = match error {
            ddirac::Error::NotInvariant { coordinate, tolerance, .. } => {
                if let Some((_, span)) = self.group.iter().find(|(n, _)| n == coordinate) {
                    let label = format!("L_d is not invariant under translations of `{coordinate}`");
                    labels.push(LabeledSpan::new_with_span(Some(label), span.clone()));
                }
                Some(format!(
                    "reduction needs L_d(q0 + a, q1 + a) = L_d(q0, q1) for translations a of every group coordinate \
                     (relative tolerance {tolerance:.0e}); run the unreduced equations (`reduced = false`), or \
                     choose group coordinates that the Lagrangian does not depend on"
                ))
            }
            ddirac::Error::NotPeriodic { coordinate, .. } => {
                if let Some((_, span)) = self.angles.iter().find(|(n, _)| n == coordinate) {
                    let label = format!("L is not 2π-periodic in `{coordinate}`");
                    labels.push(LabeledSpan::new_with_span(Some(label), span.clone()));
                }
                Some(format!(
                    "the chart of an angle wraps it to (−π, π], which changes the motion unless L(q + 2π e, v) = \
                     L(q, v); remove `{coordinate}` from `angles` if it is not an angle on the circle"
                ))
            }
            ddirac::Error::Undecided { hypothesis: ddirac::Hypothesis::Periodicity, .. } => Some(
                "L_d is not finite near the initial data, so the hypothesis could not be tested: check the initial \
                 data and where the Lagrangian is defined; remove the coordinate from `angles` if it is not an angle \
                 on the circle"
                    .into(),
            ),
            ddirac::Error::Undecided { .. } => Some(
                "L_d is not finite near the initial data, so the hypothesis could not be tested: check the initial \
                 data and where the Lagrangian is defined; `check_invariance = false` reduces anyway, with a warning"
                    .into(),
            ),
            ddirac::Error::Undetermined { .. } => Some(
                "every velocity must enter the Lagrangian so that the step equations fix the next configuration \
                 (for a Lagrangian linear in the velocities, as point vortices', their coefficients must make \
                 D1D2 L_d invertible): check its terms and parameters"
                    .into(),
            ),
            ddirac::Error::OffPrimaryConstraint { .. } => Some(
                "for a degenerate Lagrangian p0 is fixed by q0 where L is linear in the velocities: give p0 = \
                 ∂L/∂v(q0, v0), or give the velocities `v` instead of `p`"
                    .into(),
            ),
            ddirac::Error::Newton { .. } | ddirac::Error::Diverged { .. } | ddirac::Error::EnergyJump { .. } => {
                if let Some(span) = self.tolerance.clone() {
                    labels.push(LabeledSpan::new_with_span(Some("Newton tolerance".into()), span));
                }
                if let (ddirac::Error::EnergyJump { .. }, Some(span)) = (error, self.energy_jump.clone()) {
                    labels.push(LabeledSpan::new_with_span(Some("a jump is an error here".into()), span));
                }
                Some(
                    "a smaller step (`time.step`, or more `time.steps`) resolves the motion better; near a \
                     singularity of the coordinates or of the Lagrangian no step may suffice"
                        .into(),
                )
            }
            ddirac::Error::Chart { .. } => Some(
                "a run through an atlas steps in each chart with the Lagrangian carried there by `to_main`, and moves \
                 between charts by `from_main`: both must be exact inverses on the chart's domain (where its \
                 `quality` is positive), its `quality` high only where the chart is regular, and its group \
                 coordinates symmetries of L; `method.atlas = false` runs in the main chart alone"
                    .into(),
            ),
            ddirac::Error::NoSymmetry => {
                if let Some(span) = self.system.clone().filter(|_| labels.is_empty()) {
                    labels.push(LabeledSpan::new_with_span(Some("no group coordinate".into()), span));
                }
                Some(if self.built_in {
                    "this system has no symmetry to reduce by: run the unreduced equations (`reduced = false`)".into()
                } else {
                    "list the coordinates translated by the symmetry in `system.group`".into()
                })
            }
            _ => None,
        };
        if labels.is_empty() {
            return None;
        }
        let message = match error {
            ddirac::Error::Newton { .. } | ddirac::Error::Diverged { .. } | ddirac::Error::EnergyJump { .. } => {
                format!("the integration failed: {error}")
            }
            _ => error.to_string(),
        };
        let diagnostic = source.error_with(message, labels);
        Some(match help {
            Some(help) => diagnostic.with_help(help),
            None => diagnostic,
        })
    }
}
