//! Per-step diagnostics and their summary: the Hamiltonian from the Legendre transform, the paper's
//! discrete energy L_d(q_k, q_{k+1}) (§7.2), the momentum map J(q, p) = p_g (Lemma 2.1) and Newton
//! statistics.

/// The error type an output consumer (the observer of [`crate::integrate`], a watch) may return.
pub type OutputError = Box<dyn std::error::Error + Send + Sync>;

/// One reported row of a trajectory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row<'a> {
    /// Step index k.
    pub k: usize,
    /// Time t_k = k h.
    pub t: f64,
    /// Configuration q_k (angles unwrapped unless asked otherwise).
    pub q: &'a [f64],
    /// Canonical momenta p_k.
    pub p: &'a [f64],
    /// The Hamiltonian H(q_k, p_k).
    pub energy: f64,
    /// L_d(q_k, q_{k+1}); `None` on the last row.
    pub discrete_energy: Option<f64>,
    /// The momentum map J(q_k, p_k) = p_g, one entry per group coordinate.
    pub momentum_map: &'a [f64],
    /// The chart of the atlas the step was in (0: the main chart, in which q and p are reported).
    pub chart: usize,
}

/// Minimum, maximum and mean of a quantity, with its first value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stats {
    /// First value.
    pub initial: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Arithmetic mean.
    pub mean: f64,
}

#[derive(Debug, Clone, Copy)]
pub(crate) struct Accumulator {
    first: Option<f64>,
    min: f64,
    max: f64,
    sum: f64,
    count: usize,
}

impl Default for Accumulator {
    fn default() -> Self {
        Self { first: None, min: f64::INFINITY, max: f64::NEG_INFINITY, sum: 0.0, count: 0 }
    }
}

impl Accumulator {
    pub fn push(&mut self, value: f64) {
        self.first.get_or_insert(value);
        self.min = self.min.min(value);
        self.max = self.max.max(value);
        self.sum += value;
        self.count += 1;
    }

    pub fn stats(&self) -> Stats {
        Stats {
            initial: self.first.unwrap_or(f64::NAN),
            min: self.min,
            max: self.max,
            mean: self.sum / self.count.max(1) as f64,
        }
    }
}

/// The momentum map's first value and its largest deviation from it.
///
/// The deviation is measured against the size of the momenta it is computed from: J is a sum of
/// momenta, so its round-off is relative to them, and a conserved J_0 = 0 among momenta of size 10⁵
/// is kept to within 10⁵ ε, not to within a relative error of J_0.
#[derive(Debug, Clone, PartialEq)]
pub struct MomentumMapDrift {
    /// J(q0, p0).
    pub initial: Vec<f64>,
    /// max_k ‖J_k − J_0‖∞ over all steps.
    pub max_drift: f64,
    /// The size the drift is measured against: the larger of ‖J_0‖∞ and the largest momentum |p_i|
    /// of any step (of the momenta the scheme carries, (μ, w) for a reduced run, when the energy is
    /// not watched: `on_energy_jump = "ignore"`).
    pub scale: f64,
    /// `max_drift / scale`; `None` when every momentum of the run is 0.
    pub max_relative_drift: Option<f64>,
}

/// Newton statistics over all steps.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NewtonSummary {
    /// Sum of Newton corrections over all steps.
    pub total_iterations: usize,
    /// Sum of Jacobian evaluations over all steps (one per correction with classical Newton, far
    /// fewer with a kept Jacobian; see [`crate::NewtonOptions::reuse_jacobian`]).
    pub total_jacobians: usize,
    /// Largest number of corrections in one step.
    pub max_iterations: usize,
    /// Largest accepted residual norm.
    pub max_residual: f64,
    /// Steps that failed and were taken as equal sub-steps instead.
    pub subdivided_steps: usize,
    /// The largest number of sub-steps such a step took (0 when none).
    pub max_subdivision: usize,
}

/// How a run evaluated the derivatives of its step equations.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum DerivativePath {
    /// Programs compiled from the Lagrangian ([`crate::compiled`]; native code with the `jit` feature,
    /// interpreted without it), with the instruction counts of its two programs (residual, and
    /// residual with the Jacobian).
    Compiled {
        /// Instructions of the program without the mixed block.
        residual: usize,
        /// Instructions of the program with the mixed block.
        jacobian: usize,
        /// Instructions of the closed-form step ([`crate::compiled::LinearStep`]), when the step
        /// equations are linear in the unknowns (after eliminating γ): each step is then one
        /// evaluation of it, with Newton's method only as a fallback.
        closed_form: Option<usize>,
    },
    /// Dual numbers ([`crate::ad`]), and why compiled derivatives were not used when they were
    /// allowed.
    Dual {
        /// Why the run did not compile its derivatives; `None` when it was asked not to.
        reason: Option<String>,
    },
}

impl std::fmt::Display for DerivativePath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DerivativePath::Compiled { residual, jacobian, closed_form } => {
                write!(f, "compiled ({residual} instructions for a residual, {jacobian} with the Jacobian")?;
                match closed_form {
                    Some(n) => write!(f, "; linear step equations, solved in closed form by {n} instructions)"),
                    None => f.write_str(")"),
                }
            }
            DerivativePath::Dual { reason: None } => f.write_str("dual numbers"),
            DerivativePath::Dual { reason: Some(reason) } => write!(f, "dual numbers (not compiled: {reason})"),
        }
    }
}

/// What a warning is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum WarningKind {
    /// A reduced run with `check_invariance` off, of an L_d that fails the invariance check.
    NotInvariant,
    /// A reduced run with `check_invariance` off, of an L_d whose invariance could not be tested.
    InvarianceUndecided,
    /// A step whose energy changed far more than the run's typical step-to-step change: a singularity
    /// of the Lagrangian crossed, or Newton's method converged to another root.
    EnergyJump,
    /// The closed-form step failed its residual test and the step was solved by Newton's method.
    NewtonFallback,
    /// An angle's advance in one step was not resolved — more than [`crate::MAX_ANGLE_STEP`], or a
    /// kick of more than [`crate::KICK`] times its typical advance with its rate changing by more than
    /// half within the step — where the Legendre map is not near-singular: the step does not resolve
    /// the motion.
    UnderResolved,
    /// An angle's advance in one step was not resolved (as for [`WarningKind::UnderResolved`], or
    /// a soft kick of more than [`crate::SOFT_KICK`] times its typical advance) where the Legendre map
    /// ∂²L/∂v² has become near-singular, or a step needed sub-steps there: the
    /// coordinates are singular there (a pole of spherical coordinates), and the trajectory near it
    /// cannot be trusted.
    SingularChart,
    /// The energy moved away from its initial value by more than [`crate::ENERGY_DRIFT`] of its scale:
    /// far more than the bounded error of a step that resolves the motion.
    EnergyDrift,
    /// A step failed (Newton's method, a non-finite state) and was taken as equal sub-steps instead
    /// (up to [`crate::MAX_SUBDIVISION`]): the run went on, with the same structure, through motion
    /// the step size does not resolve there.
    Subdivided,
    /// The Newton tolerance allows each step an error larger than the step's own truncation error,
    /// estimated from how much the increments change from step to step
    /// ([`crate::LOOSE_TOLERANCE_MARGIN`]): the result may be no more accurate than the tolerance,
    /// whatever the order of the method.
    LooseTolerance,
    /// The Legendre transform cannot be inverted at the initial data (a degenerate Lagrangian of a
    /// rigid system): the energy is not reported.
    NoEnergy,
    /// With [`crate::Method::sensitivities`]: the tangent map could not be carried through a step (the
    /// mixed Hessian of its generating function is singular or not finite there) or a chart switch
    /// (the maps have no derivative there): the run's tangent map is not finite from that step on.
    SensitivityLost,
}

impl WarningKind {
    /// The name written in `summary.json`: `not_invariant`, `invariance_undecided`, `energy_jump`,
    /// `newton_fallback`, `under_resolved`, `singular_chart`, `energy_drift`, `subdivided`,
    /// `loose_tolerance`, `no_energy`, `sensitivity_lost`.
    pub fn name(self) -> &'static str {
        match self {
            WarningKind::NotInvariant => "not_invariant",
            WarningKind::InvarianceUndecided => "invariance_undecided",
            WarningKind::EnergyJump => "energy_jump",
            WarningKind::NewtonFallback => "newton_fallback",
            WarningKind::UnderResolved => "under_resolved",
            WarningKind::SingularChart => "singular_chart",
            WarningKind::EnergyDrift => "energy_drift",
            WarningKind::Subdivided => "subdivided",
            WarningKind::LooseTolerance => "loose_tolerance",
            WarningKind::NoEnergy => "no_energy",
            WarningKind::SensitivityLost => "sensitivity_lost",
        }
    }
}

/// Something a user should know about a run that still completed. Repeated events of one kind make
/// one warning: the first event's step and message, and how many there were.
#[derive(Debug, PartialEq)]
pub struct Warning {
    /// What it is about.
    pub kind: WarningKind,
    /// The step k of the first event (`None` for a finding before the first step).
    pub step: Option<usize>,
    /// The time t_k of the first event.
    pub t: Option<f64>,
    /// What happened and what it means.
    pub message: String,
    /// How many events of this kind the run had (1 for a finding before the first step).
    pub count: usize,
}

impl Clone for Warning {
    fn clone(&self) -> Self {
        Self { message: self.message.clone(), ..*self }
    }

    /// Reuses the message's memory.
    fn clone_from(&mut self, source: &Self) {
        self.message.clone_from(&source.message);
        (self.kind, self.step, self.t, self.count) = (source.kind, source.step, source.t, source.count);
    }
}

impl Warning {
    /// A warning about step `at = Some((k, t_k))`, or about the run before its first step.
    pub fn new(kind: WarningKind, at: Option<(usize, f64)>, message: String) -> Self {
        Self { kind, step: at.map(|(k, _)| k), t: at.map(|(_, t)| t), message, count: 1 }
    }
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if let (Some(k), Some(t)) = (self.step, self.t) {
            write!(f, "step {k} (t = {}): ", crate::error::Time(t))?;
        }
        f.write_str(&self.message)?;
        if self.count > 1 {
            write!(f, " ({} steps in all; the first is reported)", self.count)?;
        }
        Ok(())
    }
}

/// Collects a run's warnings, one per kind.
#[derive(Debug, Clone, Default)]
pub(crate) struct Warnings(pub Vec<Warning>);

impl Warnings {
    /// Records an event: a new warning, or one more count of the kind's first.
    pub fn push(&mut self, warning: Warning) {
        match self.0.iter_mut().find(|w| w.kind == warning.kind) {
            Some(first) => first.count += 1,
            None => self.0.push(warning),
        }
    }
}

/// What a run reports at its end.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Coordinate names, in order.
    pub coordinates: Vec<String>,
    /// Number of steps the summary covers: N for a whole run (see [`crate::Stepper::finish`]).
    pub steps: usize,
    /// Step size h.
    pub step: f64,
    /// q_N (angles unwrapped unless asked otherwise).
    pub final_q: Vec<f64>,
    /// p_N.
    pub final_p: Vec<f64>,
    /// The Hamiltonian over the reported rows (the rows taken with [`crate::Stepper::row`]).
    pub energy: Stats,
    /// L_d(q_k, q_{k+1}) over all steps.
    pub discrete_energy: Stats,
    /// The momentum map over all steps.
    pub momentum_map: MomentumMapDrift,
    /// Newton statistics over all steps.
    pub newton: NewtonSummary,
    /// How the step derivatives were evaluated.
    pub derivatives: DerivativePath,
    /// Wall-clock time from the preparation of the derivatives to the summary.
    pub wall_seconds: f64,
    /// ‖q(T) − q_N‖ on the coordinates the exact solution gives, when the system has one.
    pub reference_error: Option<f64>,
    /// How many times the run switched between the charts of the system's atlas.
    pub chart_switches: usize,
    /// What the user should know about the run (see [`Warning`]), in the order first seen.
    pub warnings: Vec<Warning>,
    /// With [`crate::Method::sensitivities`]: the tangent map d(q_N, p_N)/d(q_0, p_0), 2n rows of 2n
    /// entries, q then p in the order of [`Summary::coordinates`] (main chart).
    pub sensitivity: Option<Vec<Vec<f64>>>,
}

/// A trajectory kept in memory: the reported rows and the summary.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Times of the reported rows.
    pub t: Vec<f64>,
    /// Configurations of the reported rows.
    pub q: Vec<Vec<f64>>,
    /// Momenta of the reported rows.
    pub p: Vec<Vec<f64>>,
    /// Hamiltonian of the reported rows.
    pub energy: Vec<f64>,
    /// L_d(q_k, q_{k+1}) of the reported rows (NaN on the last).
    pub discrete_energy: Vec<f64>,
    /// Momentum map of the reported rows.
    pub momentum_map: Vec<Vec<f64>>,
    /// The run's summary.
    pub summary: Summary,
}
