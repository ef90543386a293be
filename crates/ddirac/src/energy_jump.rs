//! A watch on the energy of each step: a step whose energy changes far more than the run's typical
//! step-to-step change has crossed a singularity of the Lagrangian (a `1/x` potential stepped over)
//! or Newton's method converged to another root. The integrators conserve a modified energy, so on a
//! smooth trajectory the energy of consecutive steps changes smoothly and by little; a jump is the
//! mark of a result that cannot be trusted.
//!
//! The energy of step k is E_k = ⟨(p_k + p_{k+1})/2, (q_{k+1} − q_k)/h⟩ − L_d(q_k, q_{k+1})/h, the
//! discrete counterpart of H = ⟨p, v⟩ − L at the middle of the step (the generalized energies of the
//! paper's eqs. `Ed`, `Edminus` averaged and divided by h), from quantities every step has anyway; it
//! follows H to O(h²), also through the transient errors near a pole of spherical coordinates. An excursion starts at step k when
//!
//! |E_k − E_{k−1}| > `threshold` · scale  and  |E_k − E_{k−1}| > 100 · typical,
//!
//! where scale is the largest of |E| and |⟨p, Δq/h⟩| seen before, and typical the running mean of
//! the earlier steps' changes (an excursion is not folded into it); over the first 3 steps, before
//! the mean means anything, a change must exceed max(0.5, 100 · `threshold`) · scale. The excursion
//! is a *spike* and ends as soon as the energy is back within `threshold` · scale of its level
//! before it (the transient error of passing close to a pole of spherical coordinates, say). It is a
//! *jump* when the energy stays away and the changes are calm again (within 10 · typical, or
//! `threshold` · scale / 10) for as many steps in a row as the excursion took to calm down, and at
//! least 8 — a new level, as after a singular potential stepped over or a wrong Newton root — or
//! when the run ends while it is still away.
//!
//! A slow departure has no jump: the energy of a run whose step does not resolve the motion (a
//! gyration that speeds up as the particle enters a stronger field, say) can wander by any amount in
//! changes each of which looks ordinary. So the watch also looks at the energy H(q_k, p_k) of the
//! state (a function on T*Q, the same in every chart of an atlas; evaluated only at these looks, every
//! 16th ordinary step and at most 64 times in a run) and reports a *drift*, once, when it differs from
//! the first step's by more than [`ENERGY_DRIFT`] of the drift scale — the larger of the first step's
//! scale and the mean over the looks of max(|E_k|, |⟨p, Δq/h⟩|), which a wandering energy cannot
//! inflate in a few steps as it inflates the largest value seen — or, relative to what the run
//! resolves, at two looks in a row, by more than [`DRIFT_BAND`] times the band |H_k − H_first| of the
//! looks in the run's first eighth of steps (the bounded oscillation of a symplectic method's energy at
//! this step) and more than [`DRIFT_FLOOR`] of the drift scale (a spike, the transient error of passing
//! near a pole of spherical coordinates, is not a drift).

/// What a run does when a step's energy jumps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum JumpAction {
    /// Go on, with a warning in the summary.
    #[default]
    Warn,
    /// Fail with [`crate::Error::EnergyJump`].
    Fail,
    /// Do not watch.
    Ignore,
}

impl JumpAction {
    /// All actions, in spec order.
    pub const ALL: [JumpAction; 3] = [JumpAction::Warn, JumpAction::Fail, JumpAction::Ignore];

    /// The name in specs: `warn`, `error` or `ignore`.
    pub fn name(self) -> &'static str {
        match self {
            JumpAction::Warn => "warn",
            JumpAction::Fail => "error",
            JumpAction::Ignore => "ignore",
        }
    }

    /// Parses a name.
    ///
    /// ```
    /// use ddirac::JumpAction;
    /// assert_eq!(JumpAction::from_name("error"), Some(JumpAction::Fail));
    /// assert_eq!(JumpAction::from_name("panic"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|a| a.name() == name)
    }
}

/// The energy watch of a method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyJump {
    /// Smallest change, relative to the energy scale, that may count as a jump (default 1e-3).
    pub threshold: f64,
    /// What to do on a jump.
    pub action: JumpAction,
}

impl Default for EnergyJump {
    fn default() -> Self {
        Self { threshold: 1e-3, action: JumpAction::Warn }
    }
}

/// Steps over which the first changes are averaged before the ratio test applies.
const WARM_UP: usize = 3;
/// How many times the typical change starts an excursion.
const RATIO: f64 = 100.0;
/// Calm steps in a row that end an excursion.
const CALM_STEPS: usize = 8;

/// The departure of the energy from its first step's value, relative to the energy scale, that the
/// watch reports as a drift (10 %): a symplectic integrator whose step resolves the motion keeps its
/// energy error bounded and small (the examples' runs stay below 2 % even through pole passages).
pub const ENERGY_DRIFT: f64 = 0.1;

/// How many times the band of the energy's departure over the first eighth of a run its departure
/// must exceed later to count as a drift (with [`DRIFT_FLOOR`]).
pub const DRIFT_BAND: f64 = 4.0;

/// The smallest departure, relative to the drift scale, that counts as a drift measured against
/// the band ([`DRIFT_BAND`]).
pub const DRIFT_FLOOR: f64 = 1e-2;

/// The drift is looked at every this many ordinary steps (a drift builds up over many steps; a
/// look at every step showed as 4 % of the charged particle's closed-form step).
const DRIFT_EVERY: usize = 16;

/// A drift found by [`Monitor::push`]: the energy of step `at` is `energy`, that of the first step
/// `first`, and `scale` the energy scale then.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drift {
    /// The step k, and t_k.
    pub at: (usize, f64),
    /// The first step's energy.
    pub first: f64,
    /// This step's energy.
    pub energy: f64,
    /// The energy scale.
    pub scale: f64,
    /// The band of the departure over the run's first steps, when that is what the drift exceeds.
    pub band: Option<f64>,
}

impl Drift {
    /// The sentence a warning says.
    pub fn describe(&self) -> String {
        let band = match self.band {
            Some(band) => format!(
                ", {:.1} times its largest departure {band:.2e} over the run's first steps",
                (self.energy - self.first).abs() / band
            ),
            None => String::new(),
        };
        format!(
            "the energy has drifted from {:.6e} to {:.6e} ({:.1} % of its scale {:.3e}{band}): far more than the \
             bounded error of a step that resolves the motion; the step is too large for the motion here (a fast \
             oscillation or gyration, say) or the coordinates degenerate, and the trajectory from here on cannot \
             be trusted (try a smaller step)",
            self.first,
            self.energy,
            100.0 * (self.energy - self.first).abs() / self.scale,
            self.scale
        )
    }
}

/// A jump found by [`Monitor::push`] or [`Monitor::finish`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jump {
    /// The step k where the excursion started, and t_k.
    pub at: (usize, f64),
    /// The energy before the excursion.
    pub before: f64,
    /// The energy after it (at the run's end when it never calmed down).
    pub after: f64,
    /// The typical step-to-step change before it (`None` during the warm-up).
    pub typical: Option<f64>,
}

impl Jump {
    /// The sentence a warning or an error says.
    pub fn describe(&self) -> String {
        let change = (self.after - self.before).abs();
        let against = match self.typical {
            Some(t) if t > 0.0 => format!("{:.1e} times the typical step-to-step change {t:.2e}", change / t),
            _ => "in the first steps".into(),
        };
        format!(
            "the energy jumped from {:.6e} to {:.6e} ({against}) and did not come back: a singularity of the \
             Lagrangian was crossed or Newton's method converged to another root; the trajectory after it \
             cannot be trusted (try a smaller step)",
            self.before, self.after
        )
    }
}

/// An excursion under way: where it started, the level before it, its length in steps and its
/// last run of calm steps.
#[derive(Debug, Clone, Copy)]
struct Excursion {
    at: (usize, f64),
    level: f64,
    steps: usize,
    calm: usize,
}

/// The watch over a run's steps.
#[derive(Debug, Clone)]
pub(crate) struct Monitor {
    options: EnergyJump,
    /// E_{k−1} (NaN before the first step).
    previous: f64,
    /// The energy scale, and `threshold` times it.
    scale: f64,
    threshold: f64,
    /// Sum and number of the ordinary changes so far.
    sum: f64,
    count: usize,
    excursion: Option<Excursion>,
    /// The first step's energy (NaN before it) and scale.
    first: f64,
    first_scale: f64,
    /// Sum of max(|E_k|, |⟨p, Δq/h⟩|) over the steps the drift was looked at, and their number.
    scale_sum: f64,
    steps: f64,
    /// Ordinary steps until the drift is looked at again.
    until_drift: usize,
    /// The drift found, until taken ([`Monitor::take_drift`]); `drifted` once one was found.
    drift: Option<Drift>,
    drifted: bool,
    /// Steps left in the window of the run's first steps, and the band max |H_k − H_first| over the
    /// drift looks in it.
    window: usize,
    band: f64,
    /// Ordinary steps between drift looks.
    every: usize,
    /// Whether the last look found the energy beyond the band (a drift against the band must be
    /// found at two looks in a row: a spike, the transient error of passing near a pole, is not one).
    beyond_band: bool,
    /// Changes still to be taken as the new level without the jump test ([`Monitor::rebase`]).
    rebased: u8,
}

impl Monitor {
    pub fn new(options: EnergyJump) -> Self {
        let (previous, scale, threshold) = (f64::NAN, 0.0, 0.0);
        let (first, first_scale, scale_sum, steps, drift, drifted) = (f64::NAN, 0.0, 0.0, 0.0, None, false);
        Self {
            options,
            previous,
            scale,
            threshold,
            sum: 0.0,
            count: 0,
            excursion: None,
            first,
            first_scale,
            scale_sum,
            steps,
            until_drift: 1,
            drift,
            drifted,
            window: 0,
            band: 0.0,
            every: DRIFT_EVERY,
            beyond_band: false,
            rebased: 0,
        }
    }

    /// After a switch to another chart of an atlas: the discrete energy E_k is the chart's own (each
    /// chart's method conserves its own modified energy, which differ by O(h²)), so the changes of the
    /// step that switches and of the next are taken as the new level (as no change), not tested as
    /// jumps. The drift is still measured from the run's first step, so a level that moves at
    /// switches over the run is reported as one.
    pub fn rebase(&mut self) {
        self.rebased = 2;
    }

    /// Sets the drift looks for a run of `steps` steps: at least every [`DRIFT_EVERY`] ordinary
    /// steps and at most 64 per run, with the band of the departure measured over its first eighth.
    pub fn set_window(&mut self, steps: usize) {
        self.window = (steps / 8).max(16);
        self.every = (steps / 64).max(DRIFT_EVERY);
    }

    /// Whether the next [`Monitor::push`] wants the energy H(q, p) of the state the step reached: at
    /// the first step and at the drift looks.
    #[inline(always)]
    pub fn wants_state_energy(&self) -> bool {
        self.until_drift <= 1 || self.previous.is_nan()
    }

    fn typical(&self) -> f64 {
        self.sum / self.count.max(1) as f64
    }

    /// Takes step k's energy `energy` (at `at` = (k, t_k)), the size |⟨p, Δq/h⟩| of its kinetic
    /// part and, when [`Monitor::wants_state_energy`], the energy H of the state it reached (the
    /// drift is measured on H, a function on T*Q, the same in every chart of an atlas); returns a jump
    /// when an excursion ends away from its level.
    #[inline(always)]
    pub fn push(&mut self, at: (usize, f64), energy: f64, kinetic: f64, state: Option<f64>) -> Option<Jump> {
        let before = std::mem::replace(&mut self.previous, energy);
        // A change across a switch of charts is the new level's, not a jump (see `rebase`).
        let rebased = self.rebased > 0 && !before.is_nan();
        self.rebased -= u8::from(rebased);
        let change = if rebased { 0.0 } else { (energy - before).abs() };
        // An ordinary step, by the test below written without a division.
        let ordinary = change <= self.threshold || change * self.count as f64 <= RATIO * self.sum;
        self.window = self.window.saturating_sub(1);
        if ordinary && self.excursion.is_none() && self.count >= WARM_UP {
            self.until_drift -= 1;
            if let (0, Some(state)) = (self.until_drift, state) {
                self.watch_drift(at, state, kinetic);
            }
            self.sum += change;
            self.count += 1;
            if energy.abs().max(kinetic) > self.scale {
                self.rescale(energy.abs().max(kinetic));
            }
            return None;
        }
        self.unusual(at, energy, before, change, kinetic, state)
    }

    /// Reports a drift at step `at` (an ordinary step: a jump is reported as one, and the energy's
    /// level after it is the new reference). Called at the looks (every [`DRIFT_EVERY`] ordinary
    /// steps or more, see [`Monitor::set_window`]), whose scales make the mean.
    #[cold]
    fn watch_drift(&mut self, at: (usize, f64), energy: f64, kinetic: f64) {
        self.until_drift = self.every;
        if self.first.is_nan() {
            // The first look after a jump: the new reference.
            self.first = energy;
            return;
        }
        if self.window > 0 {
            self.band = self.band.max((energy - self.first).abs());
        }
        self.scale_sum += energy.abs().max(kinetic);
        self.steps += 1.0;
        // |E − E_first| > ENERGY_DRIFT · max(first scale, mean scale), without a division; or more
        // than DRIFT_BAND times the band of the first steps, and DRIFT_FLOOR of the scale.
        let departure = (energy - self.first).abs();
        let scale = (self.first_scale * self.steps).max(self.scale_sum);
        let beyond_scale = departure * self.steps > ENERGY_DRIFT * scale;
        let beyond_band =
            self.window == 0 && departure > DRIFT_BAND * self.band && departure * self.steps > DRIFT_FLOOR * scale;
        let persistent = std::mem::replace(&mut self.beyond_band, beyond_band) && beyond_band;
        if (beyond_scale || persistent) && !self.drifted {
            self.drifted(at, energy, !beyond_scale);
        }
    }

    /// Records the drift of step `at`, found against the band of the first steps or the scale.
    #[cold]
    fn drifted(&mut self, at: (usize, f64), energy: f64, against_band: bool) {
        self.drifted = true;
        let scale = self.first_scale.max(self.scale_sum / self.steps);
        let band = against_band.then_some(self.band);
        self.drift = Some(Drift { at, first: self.first, energy, scale, band });
    }

    /// The drift found since the last call, if any (at most one per run).
    #[inline]
    pub fn take_drift(&mut self) -> Option<Drift> {
        self.drift.take()
    }

    fn rescale(&mut self, scale: f64) {
        self.scale = scale;
        self.threshold = self.options.threshold * scale;
    }

    /// [`Monitor::push`] for the first steps, an excursion, or a step that may start one.
    #[cold]
    fn unusual(
        &mut self,
        at: (usize, f64),
        energy: f64,
        before: f64,
        change: f64,
        kinetic: f64,
        state: Option<f64>,
    ) -> Option<Jump> {
        if before.is_nan() && self.count == 0 && self.excursion.is_none() {
            self.first = state.unwrap_or(energy);
            self.first_scale = energy.abs().max(kinetic);
            self.rescale(energy.abs().max(kinetic));
            return None;
        }
        let (typical, threshold) = (self.typical(), self.threshold);
        if let Some(excursion) = &mut self.excursion {
            if (energy - excursion.level).abs() <= threshold {
                self.excursion = None;
                return None;
            }
            excursion.steps += 1;
            let calm = change <= (10.0 * typical).max(0.1 * threshold);
            excursion.calm = if calm { excursion.calm + 1 } else { 0 };
            if excursion.calm < CALM_STEPS.max(excursion.steps - excursion.calm) {
                return None;
            }
            let excursion = self.excursion.take().expect("under way");
            // The jump is reported; a later drift is measured from the level after it (the next
            // look's H).
            self.first = f64::NAN;
            return Some(self.jump(excursion, energy));
        }
        let starts = if self.count < WARM_UP {
            change > (0.5f64).max(RATIO * self.options.threshold) * self.scale
        } else {
            change > threshold && change > RATIO * typical
        };
        if starts || !change.is_finite() {
            self.excursion = Some(Excursion { at, level: before, steps: 0, calm: 0 });
        } else {
            if let (true, Some(state)) = (self.count >= WARM_UP, state) {
                self.watch_drift(at, state, kinetic);
            }
            self.sum += change;
            self.count += 1;
            self.rescale(self.scale.max(energy.abs()).max(kinetic));
        }
        None
    }

    /// The jump of an excursion still under way when the run ends, if the energy is then away
    /// from its level.
    pub fn finish(&mut self) -> Option<Jump> {
        let excursion = self.excursion.take()?;
        let last = self.previous;
        let jumped = (last - excursion.level).abs() > self.threshold || last.is_nan();
        jumped.then(|| self.jump(excursion, last))
    }

    fn jump(&self, excursion: Excursion, after: f64) -> Jump {
        let typical = (self.count >= WARM_UP).then(|| self.typical());
        Jump { at: excursion.at, before: excursion.level, after, typical }
    }
}
