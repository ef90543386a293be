//! The public stepper: a run over the charts of the system's atlas (paper §6; [`crate::atlas`]).
//!
//! Each chart has its own [`ChartStepper`] (its scheme, derivatives, predictor and Newton memory),
//! prepared when the run first enters the chart. A step where one chart alone has weight is taken with
//! that chart's scheme, one where charts overlap with the glued discrete Lagrangian ([`crate::blend`])
//! in the chart preferred at its midpoint ([`SWITCH_BELOW`]); compositions of order 6 and 8 take
//! every step with the scheme of the chart preferred at its midpoint ([`atlas::glues`]). The run moves
//! the state to another chart by the cotangent lift
//! ([`atlas::transition`]) and continues from a first step, with the run's record and energy watch
//! carried over.
//! Rows, states and the summary are given in the main chart, with continuous angles. A run without
//! an atlas, or with `method.atlas = false`, is its main chart's stepper alone, step for step.

use super::progress::{Progress, Record};
use super::{ChartStepper, OwnedRowIn, StateIn, StepReport};
use crate::atlas::{self, InChart, SWITCH_BELOW};
use crate::diagnostics::OutputError;
use crate::diagnostics::{Row, Summary};
use crate::dim::{Dim, Fixed};
use crate::mechanics::lagrangian::SystemIn;
use crate::{CoordinateKind, Differentiation, Error, InitialMomentum, Method, Problem, Split};

/// A run of a [`Problem`] for a [`System`](crate::System) with a [`Method`], one step at a time.
///
/// [`Stepper::new`](crate::StepperIn::new) does what a run does before its first step: it checks the input and the
/// hypotheses of the method ([`crate::check`]), chooses the unreduced or the reduced equations and
/// prepares their derivatives. Then [`Stepper::step`](crate::StepperIn::step) advances from step k to k + 1,
/// [`Stepper::row`](crate::StepperIn::row) reports the current state, and [`Stepper::finish`](crate::StepperIn::finish) gives the run's summary.
/// [`Stepper::state`](crate::StepperIn::state) saves the state of step k with everything that influences later steps (the
/// predictor's memory, the kept Newton Jacobian, the energy watch) and the run's record so far;
/// [`Stepper::restart`](crate::StepperIn::restart) continues from it bit for bit. [`State::new`](crate::StateIn::new) gives a cold state from q and p
/// alone, for starting a prepared stepper from other initial data (an ensemble).
///
/// ```
/// use ddirac::{solve, Method, OutputOptions, Rule, Stepper, systems::ChargedParticle};
/// let (system, problem) = (ChargedParticle::default(), ChargedParticle::paper_problem(200));
/// let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
///
/// let mut stepper = Stepper::new(&system, &problem, &method).unwrap();
/// for _ in 0..120 {
///     stepper.step().unwrap();
/// }
/// let saved = stepper.state();
/// while !stepper.is_finished() {
///     stepper.step().unwrap();
/// }
/// let q_end = stepper.row().q;
///
/// // Another stepper continues from the saved state as the first one did, bit for bit ...
/// let mut again = Stepper::new(&system, &problem, &method).unwrap();
/// again.restart(&saved).unwrap();
/// assert_eq!(again.k(), 120);
/// while !again.is_finished() {
///     again.step().unwrap();
/// }
/// assert_eq!(again.row().q, q_end);
/// // ... and both end where `solve` ends.
/// let solution = solve(&system, &problem, &method, &OutputOptions::default()).unwrap();
/// assert_eq!(solution.q.last().unwrap().as_slice(), q_end.as_slice());
/// // Paper, Table 1: N = 200 → 0.01664
/// assert!((again.finish().unwrap().reference_error.unwrap() - 0.01664).abs() < 5e-6);
/// ```
pub struct StepperIn<S, Dm: Dim> {
    system: S,
    dim: Dm,
    problem: Problem,
    method: Method,
    /// The stepper of each chart the run has entered (index: the chart; 0 is the main chart), then
    /// those of the charts' glued steps ([`crate::blend`]; index: the number of charts + the chart).
    charts: Vec<Option<ChartStepper<InChart<S, Dm>, Dm>>>,
    /// The number of charts of the atlas.
    count: usize,
    current: usize,
    /// Whether the current stepper takes glued steps.
    glued: bool,
    /// The chart alone with weight at the current point, if known ([`atlas::sole_chart`]): (k, chart).
    sole_here: Option<(usize, Option<usize>)>,
    /// Whether the run switches charts: the system has an atlas and the method asks for it.
    switching: bool,
    /// The current point in the main chart, followed step by step outside it (continuous angles).
    near: Dm::Array<f64>,
    split: Split,
    /// The kinds of the main chart's coordinates.
    kinds: Dm::Array<CoordinateKind>,
    /// Whether the momentum map is p_g in each chart: it has the main chart's number of group
    /// coordinates (else it is measured in the main chart after each step there).
    carries_momentum: Vec<bool>,
    wrap_angles: bool,
    switches: usize,
    /// The progress of the current chart before its last step, kept to take the step again in
    /// another chart (one buffer, refilled at every step).
    before: Option<Progress<Dm>>,
}

/// A run of a system of `N` coordinates ([`StepperIn`] in a fixed dimension).
pub type Stepper<S, const N: usize> = StepperIn<S, Fixed<N>>;

impl<S: SystemIn<Dm> + Clone, Dm: Dim> StepperIn<S, Dm> {
    /// Checks `problem` and `method` for `system` as [`crate::integrate`] does, and prepares the
    /// first step: an error for input that a run refuses, or for a hypothesis that fails
    /// ([`crate::CheckReport::verdict`]; the warnings it allows go into the summary). With an atlas,
    /// the run starts in the best chart at the initial point.
    pub fn new(system: S, problem: &Problem, method: &Method) -> Result<Self, Error> {
        crate::stack::enough(system.dim(), || Self::new_here(system, problem, method))
    }

    fn new_here(system: S, problem: &Problem, method: &Method) -> Result<Self, Error> {
        let mut main = ChartStepper::new(InChart::new(system.clone(), 0), problem, method, true)?;
        main.add_check_warnings(crate::check::atlas_verdict(&system, problem, method)?);
        let extra = system.charts().len();
        let near = main.progress.config.unwrapped();
        let dim = system.dim();
        let coordinates = system.coordinates();
        let split = Split::new(coordinates.as_ref());
        let kinds = dim.array(|i| coordinates[i].kind);
        let carries_momentum =
            atlas::all_charts(&system).iter().map(|c| Split::new(c.as_ref()).n_g() == split.n_g()).collect();
        let mut charts = vec![Some(main)];
        charts.resize_with(2 * (extra + 1), || None);
        let switching = method.atlas && extra > 0;
        let mut stepper = Self {
            system,
            dim,
            problem: problem.clone(),
            method: method.clone(),
            charts,
            count: extra + 1,
            current: 0,
            glued: false,
            sole_here: None,
            switching,
            near,
            split,
            kinds,
            carries_momentum,
            wrap_angles: false,
            switches: 0,
            before: None,
        };
        if switching {
            stepper.choose_chart()?;
        }
        Ok(stepper)
    }

    /// The index in `charts` of the stepper of chart `chart`, plain or glued.
    fn slot(&self, chart: usize, glued: bool) -> usize {
        chart + if glued { self.count } else { 0 }
    }

    fn chart(&self) -> &ChartStepper<InChart<S, Dm>, Dm> {
        self.charts[self.slot(self.current, self.glued)].as_ref().expect("the current chart has a stepper")
    }

    fn chart_mut(&mut self) -> &mut ChartStepper<InChart<S, Dm>, Dm> {
        let slot = self.slot(self.current, self.glued);
        self.charts[slot].as_mut().expect("the current chart has a stepper")
    }

    /// Report angles wrapped to (−π, π] (in [`Stepper::row`](crate::StepperIn::row) and the summary's final q) instead of
    /// continuous; the default is continuous.
    pub fn set_wrap_angles(&mut self, wrap: bool) {
        self.wrap_angles = wrap;
        let glued_main = self.count;
        for main in [0, glued_main] {
            if let Some(main) = &mut self.charts[main] {
                main.set_wrap_angles(wrap);
            }
        }
    }

    /// The current step index k.
    pub fn k(&self) -> usize {
        self.chart().k()
    }

    /// The current time t_k = k h.
    pub fn t(&self) -> f64 {
        self.chart().t()
    }

    /// The dimension: the number of coordinates.
    pub fn dim(&self) -> Dm {
        self.dim
    }

    /// The number of steps N of the problem.
    pub fn steps(&self) -> usize {
        self.problem.steps
    }

    /// Whether all N steps are taken.
    pub fn is_finished(&self) -> bool {
        self.chart().is_finished()
    }

    /// The chart of the atlas the run is in (0: the main chart).
    pub fn current_chart(&self) -> usize {
        self.current
    }

    /// Takes step k → k + 1: solves the step equations, checks the new state, watches the energy;
    /// with an atlas, in the chart preferred at the step's midpoint.
    ///
    /// Returns [`Error::Interrupted`] when a stop was requested ([`crate::interrupt`]) and an error
    /// when the run is finished, Newton's method fails, the state becomes non-finite or the energy
    /// jumps under [`crate::JumpAction::Fail`]. A failed solve or a non-finite state leaves the
    /// stepper at step k (only its kept Newton Jacobian is dropped; restarting from a saved state
    /// retries the step bit for bit); an energy jump is reported once the step that shows it is taken.
    #[inline]
    pub fn step(&mut self) -> Result<StepReport, Error> {
        crate::stack::enough(self.dim, || self.step_here())
    }

    fn step_here(&mut self) -> Result<StepReport, Error> {
        if !self.switching {
            return self.chart_mut().step();
        }
        if !atlas::glues(&self.method) {
            return self.switched_step();
        }
        // Where one chart alone has weight at both ends of the step (of each sub-step), the glued
        // discrete Lagrangian is that chart's: the step is taken with its own scheme, and again
        // glued if the step taken reaches where another chart has weight too.
        let k = self.k();
        let (q, dim) = (self.chart().progress.config.unwrapped(), self.dim);
        let predicted = self.chart().predicted_increment();
        let sole = self.sole_at(k, &q);
        if let Some(chart) = sole.filter(|_| self.sole_anywhere(&dim.array(|i| q[i] + predicted[i])) == sole) {
            if (chart, false) != (self.current, self.glued) {
                self.switch_to(chart, false)?;
            }
            self.keep_before();
            let start = self.chart().progress.config.unwrapped();
            let report = self.chart_mut().step()?;
            let taken = self.chart().progress.config.unwrapped();
            // A composition's sub-steps go beyond the step's ends: each of their ends counts.
            let sole_throughout =
                self.chart().all_stage_ends(&start, &mut |end| self.sole_anywhere(end) == Some(chart));
            if sole_throughout && self.sole_at(k + 1, &taken) == Some(chart) {
                self.follow();
                return Ok(report);
            }
            self.take_back();
        }
        // A glued step, in the chart preferred at the step's predicted midpoint (a choice of
        // coordinates alone: the glued L_d is the same function in every chart).
        self.move_to_preferred(true)?;
        self.sole_here = None;
        let report = self.chart_mut().step()?;
        self.follow();
        Ok(report)
    }

    /// A step of a method that switches charts at a step ([`atlas::glues`]): in the chart preferred at
    /// the step's predicted midpoint, with that chart's own scheme.
    fn switched_step(&mut self) -> Result<StepReport, Error> {
        self.move_to_preferred(false)?;
        let report = self.chart_mut().step()?;
        self.follow();
        Ok(report)
    }

    /// Moves to the chart preferred at the coming step's predicted midpoint ([`Self::preferred_chart`]),
    /// in its glued or its own steps.
    fn move_to_preferred(&mut self, glued: bool) -> Result<(), Error> {
        let (q, dim) = (self.chart().progress.config.unwrapped(), self.dim);
        let predicted = self.chart().predicted_increment();
        let target = self.preferred_chart(&dim.array(|i| q[i] + 0.5 * predicted[i]));
        if (target, glued) != (self.current, self.glued) {
            self.switch_to(target, glued)?;
        }
        Ok(())
    }

    /// Keeps the current stepper's progress before a step, to take the step back.
    fn keep_before(&mut self) {
        let slot = self.slot(self.current, self.glued);
        let progress = &self.charts[slot].as_ref().expect("the current chart has a stepper").progress;
        match &mut self.before {
            Some(saved) => saved.clone_from(progress),
            None => self.before = Some(progress.clone()),
        }
    }

    /// Takes back the step taken since [`Self::keep_before`].
    fn take_back(&mut self) {
        let slot = self.slot(self.current, self.glued);
        let chart = self.charts[slot].as_mut().expect("the current chart has a stepper");
        std::mem::swap(&mut chart.progress, self.before.as_mut().expect("kept before the step"));
    }

    /// The chart alone with weight ([`atlas::sole_chart`]) at the current point `q` of step `k`,
    /// remembered for the step.
    fn sole_at(&mut self, k: usize, q: &Dm::Array<f64>) -> Option<usize> {
        if let Some((known, sole)) = self.sole_here {
            if known == k {
                return sole;
            }
        }
        let sole = self.sole_anywhere(q);
        self.sole_here = Some((k, sole));
        sole
    }

    /// The chart alone with weight ([`atlas::sole_chart`]) at the point `q` of the current chart.
    fn sole_anywhere(&self, q: &Dm::Array<f64>) -> Option<usize> {
        let main = atlas::point(&self.system, self.current, 0, q);
        atlas::sole_chart(&self.system, &self.kinds, self.count, &main)
    }

    /// After a step in another chart: the main-chart point followed, and the momentum map measured
    /// where the chart does not carry it.
    fn follow(&mut self) {
        if self.current == 0 {
            return;
        }
        let (q, p) = self.chart_state();
        let raw = atlas::point(&self.system, self.current, 0, &q);
        self.near = self.system.nearest_in_main(raw, &self.near, &self.kinds);
        if !self.carries_momentum[self.current] {
            if let Some((_, p_main)) = atlas::transition(&self.system, self.current, 0, &q, &p) {
                let slot = self.slot(self.current, self.glued);
                let chart = self.charts[slot].as_mut().expect("the current chart has a stepper");
                chart.progress.record.drift(&self.split, &p_main, &p_main);
            }
        }
    }

    /// The configuration (unwrapped) and canonical momenta of the current chart.
    fn chart_state(&self) -> (Dm::Array<f64>, Dm::Array<f64>) {
        let chart = self.chart();
        let p = chart.p();
        (chart.progress.config.unwrapped(), p)
    }

    /// The chart for a step whose midpoint is `q` (in the current chart), a function of the point
    /// alone: the main chart where its measure is at least [`SWITCH_BELOW`]; else the chart with the
    /// largest measure among those that carry the momentum map (have the main chart's group
    /// coordinates), if that is at least [`SWITCH_BELOW`]; else the chart with the largest measure.
    fn preferred_chart(&self, q: &Dm::Array<f64>) -> usize {
        let main = if self.current == 0 { q.clone() } else { atlas::point(&self.system, self.current, 0, q) };
        let qualities = (0..self.count)
            .filter_map(|c| atlas::measure_at(&self.system, &self.kinds, c, &main).map(|quality| (c, quality)));
        let (mut carrying, mut any) = (None::<(usize, f64)>, None::<(usize, f64)>);
        for (chart, quality) in qualities {
            if chart == 0 && quality >= SWITCH_BELOW {
                return 0;
            }
            if self.carries_momentum[chart] && carrying.is_none_or(|(_, best)| quality > best) {
                carrying = Some((chart, quality));
            }
            if any.is_none_or(|(_, best)| quality > best) {
                any = Some((chart, quality));
            }
        }
        match (carrying, any) {
            (Some((chart, quality)), _) if quality >= SWITCH_BELOW => chart,
            (_, Some((chart, _))) => chart,
            _ => self.current,
        }
    }

    /// Moves to the chart alone with weight at the current point, else to the preferred chart there
    /// (before a first step).
    fn choose_chart(&mut self) -> Result<(), Error> {
        let q = self.chart().progress.config.unwrapped();
        let k = self.k();
        let sole = if atlas::glues(&self.method) { self.sole_at(k, &q) } else { None };
        let target = sole.unwrap_or_else(|| self.preferred_chart(&q));
        if (target, false) != (self.current, self.glued) {
            self.switch_to(target, false)?;
        }
        Ok(())
    }

    /// Moves the state of step k to chart `to` by the cotangent lift and continues there from a
    /// first step, with the run's record and energy watch, in glued steps if `glued`.
    fn switch_to(&mut self, to: usize, glued: bool) -> Result<(), Error> {
        let k = self.k();
        let (q, p) = self.chart_state();
        let Some((mut q_to, p_to)) = atlas::transition(&self.system, self.current, to, &q, &p) else {
            return Ok(());
        };
        if to == 0 {
            q_to = self.system.nearest_in_main(q_to, &self.near, &self.kinds);
        } else {
            self.inverse_at(to, &q_to)?;
        }
        let slot = self.slot(to, glued);
        if self.charts[slot].is_none() {
            self.charts[slot] = Some(self.prepare(to, &q_to, &p_to, glued)?);
        }
        // The run's diagnostics span the whole run: its record, and the energy watch with the
        // energy of the last step (H is a function on T*Q, and each chart's discrete energy follows it
        // to O(h²)), so that a jump or a drift is measured against the run before the switch.
        let from = &self.chart().progress;
        let (mut record, monitor, last_energy) = (from.record.clone(), from.monitor.clone(), from.last_energy);
        if record.tangent.is_some() && to != self.current {
            let map = self.switch_map(self.current, to, &q, &p, &q_to);
            record.compose_tangent(&map, (k, self.t()), "chart switch");
        }
        let stepper = self.charts[slot].as_mut().expect("prepared");
        stepper.restart(&StateIn::new(k, q_to, p_to))?;
        let progress = &mut stepper.progress;
        (progress.record, progress.monitor, progress.last_energy) = (record, monitor, last_energy);
        progress.monitor.rebase();
        if self.current == 0 {
            self.near = q;
        }
        if to != self.current {
            self.switches += 1;
        }
        (self.current, self.glued) = (to, glued);
        Ok(())
    }

    /// The Jacobian of the switch from chart `from` to chart `to` at (q, p) of chart `from`, landing
    /// at `q_to` ([`crate::tangent_map::switch`]); NaN where the maps have none.
    fn switch_map(
        &self,
        from: usize,
        to: usize,
        q: &Dm::Array<f64>,
        p: &Dm::Array<f64>,
        q_to: &Dm::Array<f64>,
    ) -> nalgebra::DMatrix<f64> {
        let n = 2 * self.dim.n();
        crate::tangent_map::switch(&self.system, (from, to), q, p, q_to)
            .unwrap_or_else(|| nalgebra::DMatrix::from_element(n, n, f64::NAN))
    }

    /// An error unless the maps of chart `chart` are inverse at its point `q` (to
    /// [`crate::ROUND_TRIP_TOLERANCE`]), where the run is about to step in it: the check tested them
    /// on points sampled over the chart's domain, and this is the point the run relies on.
    fn inverse_at(&self, chart: usize, q: &Dm::Array<f64>) -> Result<(), Error> {
        let coordinates = atlas::all_charts(&self.system).swap_remove(chart);
        let kinds = self.dim.array(|i| coordinates[i].kind);
        let there = atlas::point(&self.system, chart, 0, q);
        let back = crate::chart::nearest_turns(atlas::point(&self.system, 0, chart, &there), q, &kinds);
        let apart = atlas::round_trip_distance(q.as_ref(), back.as_ref());
        if apart <= crate::ROUND_TRIP_TOLERANCE {
            return Ok(());
        }
        let chart_name = self.system.charts().swap_remove(chart - 1).0;
        let problem = crate::ChartProblem::NotInverse {
            deviation: apart,
            at: q.as_ref().to_vec(),
            tolerance: crate::ROUND_TRIP_TOLERANCE,
        };
        Err(Error::Chart { chart: chart_name, problem })
    }

    /// The stepper of chart `chart`, prepared at (q, p) of that chart: the method of the run, without
    /// the main chart's connection, and unreduced in a chart without group coordinates. The stepper of
    /// glued steps ([`crate::blend`]) is unreduced and takes dual numbers (which charts have weight
    /// changes from step to step, which a compiled program cannot follow).
    fn prepare(
        &self,
        chart: usize,
        q: &Dm::Array<f64>,
        p: &Dm::Array<f64>,
        glued: bool,
    ) -> Result<ChartStepper<InChart<S, Dm>, Dm>, Error> {
        let in_chart =
            if glued { InChart::glued(self.system.clone(), chart) } else { InChart::new(self.system.clone(), chart) };
        let has_group = Split::new(in_chart.coordinates().as_ref()).n_g() > 0;
        let mut method =
            Method { connection: None, reduced: self.method.reduced && has_group && !glued, ..self.method.clone() };
        if glued {
            method.differentiation = Differentiation::Dual;
        }
        let (q0, p0) = (q.as_ref().to_vec(), p.as_ref().to_vec());
        let problem = Problem { q0, initial: InitialMomentum::Momentum(p0), ..self.problem.clone() };
        let mut stepper = ChartStepper::new(in_chart, &problem, &method, false)?;
        if chart == 0 {
            stepper.set_wrap_angles(self.wrap_angles);
        }
        Ok(stepper)
    }

    /// The row of the current step k in the main chart: q_k, p_k, the Hamiltonian, the momentum map
    /// and the chart the step is in (the discrete energy of step k is known once it is taken:
    /// [`StepReport::discrete_energy`]). The summary's energy statistics are over the rows taken.
    pub fn row(&mut self) -> OwnedRowIn<Dm> {
        crate::stack::enough(self.dim, || self.row_here())
    }

    fn row_here(&mut self) -> OwnedRowIn<Dm> {
        let current = self.current;
        let mut row = self.chart_mut().row();
        if current == 0 {
            return row;
        }
        let (q, p) = self.chart_state();
        if let Some((_, p_main)) = atlas::transition(&self.system, current, 0, &q, &p) {
            row.p = p_main;
        }
        row.q = if self.wrap_angles { wrapped(&self.kinds, self.near.clone()) } else { self.near.clone() };
        row.momentum_map = self.dim.array(|_| 0.0);
        let j = self.split.momentum_map(row.p.as_ref());
        row.momentum_map.as_mut().iter_mut().zip(j).for_each(|(slot, j)| *slot = j);
        row.n_g = self.split.n_g();
        row.chart = current;
        row
    }

    /// Steps to the end, handing the rows of every `every`-th step and of the last to `observer`
    /// (what [`crate::integrate`] reports), each with the discrete energy of its step. The same
    /// steps and rows as [`Stepper::step`](crate::StepperIn::step) and [`Stepper::row`](crate::StepperIn::row). `watch` is called with k every
    /// [`crate::WATCH_STEPS`] steps (from k = 0). After an error the stepper stays at the step that
    /// failed, as after [`Stepper::step`](crate::StepperIn::step).
    pub fn run_to_end(
        &mut self,
        every: usize,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
        watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
    ) -> Result<(), Error> {
        crate::stack::enough(self.dim, || self.run_to_end_here(every, observer, watch))
    }

    fn run_to_end_here(
        &mut self,
        every: usize,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
        watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
    ) -> Result<(), Error> {
        if !self.switching {
            return self.chart_mut().run_to_end(every, observer, watch);
        }
        let (mut until_report, mut until_watch) = (0, 0);
        while !self.is_finished() {
            if until_watch == 0 {
                watch(self.k()).map_err(Error::Output)?;
                until_watch = super::WATCH_STEPS;
            }
            until_watch -= 1;
            let row = (until_report == 0).then(|| self.row());
            until_report = if until_report == 0 { every - 1 } else { until_report - 1 };
            let step = self.step()?;
            if let Some(mut row) = row {
                row.discrete_energy = Some(step.discrete_energy);
                observer(&row.as_row()).map_err(Error::Output)?;
            }
        }
        let row = self.row();
        observer(&row.as_row()).map_err(Error::Output)
    }

    /// The state of step k in the main chart, with all that a stepper of the same system, method and
    /// step needs to continue from it bit for bit (the chart it is in too).
    pub fn state(&self) -> StateIn<Dm> {
        let mut state = self.chart().state();
        if self.current != 0 {
            let (q, p) = self.chart_state();
            if let Some((_, p_main)) = atlas::transition(&self.system, self.current, 0, &q, &p) {
                state.p = p_main;
            }
            state.q = self.near.clone();
        }
        if let Some(memory) = &mut state.memory {
            memory.chart = self.current;
            memory.glued = self.glued;
            memory.near = self.near.clone();
        }
        state
    }

    /// Continues from `state`: from a state taken from a stepper of the same system, method and step
    /// exactly as that stepper would have continued (its record too, so that the summary covers the
    /// whole run); from a cold state as on a first step from (q, p), with a new record (and, with an
    /// atlas, in the best chart there). The derivatives prepared by [`Stepper::new`](crate::StepperIn::new) are kept. A
    /// compiled closed-form step holds the conserved momenta μ of the problem as constants: from a
    /// state with another μ the steps are solved by Newton's method on the same equations instead.
    ///
    /// An error for a state beyond the problem's last step, a warm state from another method or
    /// step (restart from its [`State::cold`](crate::StateIn::cold) form instead), or a cold state with a non-finite
    /// entry or, for a degenerate Lagrangian, with p off the primary constraint p = ∂L/∂v. The other
    /// hypotheses [`Stepper::new`](crate::StepperIn::new) tested near the problem's initial data (invariance, periodicity)
    /// are not tested again for a cold state.
    pub fn restart(&mut self, state: &StateIn<Dm>) -> Result<(), Error> {
        crate::stack::enough(self.dim, || self.restart_here(state))
    }

    fn restart_here(&mut self, state: &StateIn<Dm>) -> Result<(), Error> {
        let Some(memory) = &state.memory else {
            self.charts[0].as_mut().expect("the main chart has a stepper").restart(state)?;
            (self.current, self.glued, self.near, self.sole_here) = (0, false, state.q.clone(), None);
            return if self.switching { self.choose_chart() } else { Ok(()) };
        };
        let (chart, glued) = (memory.chart, memory.glued);
        if chart >= self.count {
            return Err(Error::Invalid { what: crate::Input::State, why: crate::Reason::NoSuchChart { chart } });
        }
        let slot = self.slot(chart, glued);
        if self.charts[slot].is_none() {
            let Some((q, p)) = atlas::transition(&self.system, 0, chart, &state.q, &state.p) else {
                let why = crate::Reason::OutsideChart { chart };
                return Err(Error::Invalid { what: crate::Input::State, why });
            };
            self.charts[slot] = Some(self.prepare(chart, &q, &p, glued)?);
        }
        self.charts[slot].as_mut().expect("prepared").restart(state)?;
        (self.current, self.glued, self.near, self.sole_here) = (chart, glued, memory.near.clone(), None);
        Ok(())
    }

    /// Prepares this stepper for `problem` as [`Stepper::new`](crate::StepperIn::new) prepares a new stepper of the same
    /// system and method, keeping the derivatives when they serve the problem unchanged (an
    /// ensemble's members that differ in initial data trace and compile once): `Ok(true)` then, and
    /// the run that follows is that of a new stepper, bit for bit. `Ok(false)` when a new stepper
    /// might differ — another step size or number of steps, a compiled closed-form step (it holds the
    /// first step's conserved momenta), a trace with guards, compiled programs that fail their check
    /// against dual numbers at the new first step, dual numbers chosen at the first step — and the
    /// caller makes a new stepper. An error is the one [`Stepper::new`](crate::StepperIn::new) gives for `problem` (its input
    /// and the check of the method's hypotheses near its initial data are tested anew). The main
    /// chart's derivatives are what is kept; the other charts are prepared anew when entered.
    pub fn renew(&mut self, problem: &Problem) -> Result<bool, Error> {
        crate::stack::enough(self.dim, || self.renew_here(problem))
    }

    fn renew_here(&mut self, problem: &Problem) -> Result<bool, Error> {
        let main = self.charts[0].as_mut().expect("the main chart has a stepper");
        if !main.renew(problem)? {
            return Ok(false);
        }
        main.add_check_warnings(crate::check::atlas_verdict(&self.system, problem, &self.method)?);
        self.near = main.progress.config.unwrapped();
        self.problem = problem.clone();
        self.charts.iter_mut().skip(1).for_each(|chart| *chart = None);
        (self.current, self.glued, self.switches, self.sole_here) = (0, false, 0, None);
        if self.switching {
            self.choose_chart()?;
        }
        Ok(true)
    }

    /// The summary of the run up to the current step: the energy watch's last verdict (an error
    /// under [`crate::JumpAction::Fail`] when the energy jumped and did not come back), final state
    /// in the main chart, statistics, Newton counts, chart switches and warnings.
    pub fn finish(mut self) -> Result<Summary, Error> {
        self.summary()
    }

    /// What [`Stepper::finish`](crate::StepperIn::finish) gives, leaving the stepper to be renewed ([`Stepper::renew`](crate::StepperIn::renew)) or
    /// restarted.
    pub fn summary(&mut self) -> Result<Summary, Error> {
        crate::stack::enough(self.dim, || self.summary_here())
    }

    fn summary_here(&mut self) -> Result<Summary, Error> {
        let mut summary = self.chart_mut().summary()?;
        summary.chart_switches = self.switches;
        // The derivatives of the run are the main chart's (glued steps take dual numbers).
        if let Some(main) = &self.charts[0] {
            summary.derivatives = main.derivative_path.clone();
        }
        if self.current != 0 {
            let (q, p) = self.chart_state();
            let tangent = &self.chart().progress.record.tangent;
            if let (Some(tangent), Some((q_main, _))) =
                (tangent, atlas::transition(&self.system, self.current, 0, &q, &p))
            {
                let to_main = self.switch_map(self.current, 0, &q, &p, &q_main) * tangent;
                summary.sensitivity = Some(super::rows(&to_main));
            }
            let state = self.state();
            summary.coordinates = self.system.coordinates().as_ref().iter().map(|c| c.name.clone()).collect();
            let final_q = if self.wrap_angles { wrapped(&self.kinds, state.q.clone()) } else { state.q.clone() };
            summary.final_q = final_q.as_ref().to_vec();
            summary.final_p = state.p.as_ref().to_vec();
            let Record { start: (k0, q0, p0), .. } = &self.chart().progress.record;
            let t = (state.k - k0) as f64 * self.problem.step;
            summary.reference_error = self
                .system
                .exact_solution(q0, p0, t)
                .and_then(|exact| super::reference_error(exact.as_ref(), state.q.as_ref()));
        }
        Ok(summary)
    }
}

/// A main-chart configuration with its angles wrapped to (−π, π].
fn wrapped<A: AsMut<[f64]>>(kinds: &impl AsRef<[CoordinateKind]>, mut q: A) -> A {
    for (q, kind) in q.as_mut().iter_mut().zip(kinds.as_ref()) {
        if *kind == CoordinateKind::Angle {
            *q = crate::chart::wrap(*q);
        }
    }
    q
}
