//! `charged-particle`: one scheme, the reduced (+) left-rule equations of the charged particle
//! (paper eq. `reduceddiscreteequationsem`, §7.1), computed by the generic engine (automatic
//! differentiation and Newton's method) and by the hand-written step
//! (`baselines::charged_particle_step`), against the Boris pusher (`baselines::boris`), a different
//! second-order scheme of the same motion.

use std::hint::black_box;

use ddirac::baselines::boris::Boris;
use ddirac::baselines::charged_particle_step::{ChargedParticleStep, ReducedState};
use ddirac::systems::ChargedParticle;
use ddirac::{Differentiation, DynSystem, Method, Problem, Rule, Variant};
use serde::Serialize;
use serde_json::Value;

use super::harness::{compare, Comparison, Contender, Pair, Target};
use super::{built_in, engine, integrate_once, max_difference, method, print, to_json, Settings};

/// The generic engine.
pub const ENGINE: &str = "engine";
/// The hand-written step.
pub const SPECIALISED: &str = "specialised";
/// The Boris pusher.
pub const BORIS: &str = "boris";

/// The engine should cost at most this many hand-written steps.
const ENGINE_TARGET: Target = Target::AtMost(5.0);
/// The hand-written step should cost at most this many Boris steps.
const SPECIALISED_TARGET: Target = Target::AtMost(3.0);

/// The three integrators of one problem with the final positions they reach.
pub struct Contenders<'a> {
    /// Engine, specialised step, Boris, in this order.
    pub contenders: Vec<Contender<'a>>,
    /// The final position q_N of each, in the same order.
    pub finals: [[f64; 3]; 3],
}

/// The engine (reduced (+), left rule), the hand-written step and Boris for `problem`, the paper's
/// initial data with any step and number of steps.
pub fn contenders<'a>(system: &'a dyn DynSystem, problem: &'a Problem) -> Result<Contenders<'a>, miette::Report> {
    let steps = problem.steps;
    let h = problem.step;
    // The compiled closed-form step at every N (under `auto` a run of fewer than 5000 steps would
    // use dual numbers and Newton's method: another path, not another size).
    let reduced = Method { differentiation: Differentiation::Compiled, ..method(Rule::Left, true, Variant::Plus) };
    let what = format!("charged particle, left, reduced (+), compiled closed form, N = {steps}, h = {h}");
    let summary = integrate_once(&what, system, problem, &reduced)?;
    let engine_q = [summary.final_q[0], summary.final_q[1], summary.final_q[2]];
    let stepper = ChargedParticleStep { m: 1.0, b0: 1.0, h };
    let start = ReducedState { q: [0.0; 3], theta: 0.0, w: [1.0, 0.0, 1.0], mu: 1.0 };
    let boris = Boris { e: 1.0, m: 1.0, b0: 1.0 };
    let finals = [engine_q, stepper.run(start, steps).q, boris.run(h, steps, [0.0; 3], [1.0, 0.0, 1.0]).position];
    let contenders = vec![
        engine(ENGINE, &what, system, problem, reduced)?,
        Contender::new(SPECIALISED, steps, move || {
            black_box(black_box(&stepper).run(black_box(start), steps));
            Ok(())
        }),
        Contender::new(BORIS, steps, move || {
            black_box(black_box(&boris).run(black_box(h), steps, black_box([0.0; 3]), black_box([1.0, 0.0, 1.0])));
            Ok(())
        }),
    ];
    Ok(Contenders { contenders, finals })
}

/// The ratios between the three, with the targets.
pub fn pairs() -> [Pair<'static>; 3] {
    [
        Pair::new(ENGINE, SPECIALISED).target(ENGINE_TARGET),
        Pair::new(ENGINE, BORIS),
        Pair::new(SPECIALISED, BORIS).target(SPECIALISED_TARGET),
    ]
}

#[derive(Serialize)]
struct Report {
    comparison: Comparison,
    /// max_i |q_N,i| difference between the engine and the hand-written step (the same scheme).
    engine_vs_specialised: f64,
}

/// Runs the group.
pub fn run(settings: &Settings) -> Result<Value, miette::Report> {
    // Long enough that the engine's set-up (tracing and compiling its closed-form step, ≈ 3 ms) is a
    // few per cent of the run, as in the long runs the engine is meant for.
    let steps = if settings.quick { 200 } else { 1_000_000 };
    print::heading("charged-particle", "generic engine (compiled closed-form step), hand-written step and Boris");
    let system = built_in("charged_particle")?;
    // The paper's problem with h = 0.02 (T = 20 for 1000 steps).
    let problem = Problem { steps, ..ChargedParticle::paper_problem(1000) };
    let Contenders { contenders, finals } = contenders(system.as_ref(), &problem)?;
    let title = format!("charged particle (paper §7.1), left rule, reduced (+), h = 0.02, {steps} steps");
    let comparison = compare(title, settings.schedule, contenders, &pairs())?;
    print::comparison(&comparison);
    let difference = max_difference(&finals[..1], &finals[1..2]);
    println!("    engine and specialised step, max |q_N difference| (one scheme): {difference:.2e}");
    to_json(&Report { comparison, engine_vs_specialised: difference })
}
