//! Work–precision of three integrators of the charged particle (paper §7.1, T = 20), and the
//! reduced/unreduced time ratios of the step benchmarks measured side by side.
//!
//! 1. The generic engine (reduced (+), left rule), the same scheme written out by hand
//!    (`baselines::charged_particle_step`) and the Boris pusher (`baselines::boris`): for each N,
//!    the wall time of one run and the error ‖q(T) − q_N‖ against the exact motion
//!    (sin t, cos t − 1, t).
//! 2. The engine runs of `benches/steps.rs` (1000 steps each), reduced and unreduced, so that the
//!    ratios do not depend on how the load of a shared machine changed between two criterion
//!    benchmarks; with the mean number of Newton iterations per step of each.
//!
//! All runs of one table are timed in the same process, alternating, in several rounds; each time
//! is the smallest over the rounds of the mean over a batch of runs.
//!
//! `cargo run --release -p ddirac --example work_precision`

use std::hint::black_box;
use std::time::{Duration, Instant};

use ddirac::baselines::boris::Boris;
use ddirac::baselines::charged_particle_step::{ChargedParticleStep, ReducedState};
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, HeavyTop, Kepler};
use ddirac::{integrate, InitialMomentum, Method, OutputOptions, Problem, Rule, System, Variant};

const T: f64 = 20.0;
const ROUNDS: usize = 15;
/// Each round runs a method for about this long.
const BATCH: Duration = Duration::from_millis(20);
const LAST_ROW_ONLY: OutputOptions = OutputOptions { every: 1_000_000, wrap_angles: false };

fn error(q: &[f64]) -> f64 {
    let exact = [T.sin(), T.cos() - 1.0, T];
    (0..3).map(|i| (q[i] - exact[i]).powi(2)).sum::<f64>().sqrt()
}

fn method(rule: Rule, reduced: bool, variant: Variant) -> Method {
    Method { rule, variant, reduced, ..Method::default() }
}

/// One engine run; returns the final configuration.
fn run<S: System<N>, const N: usize>(system: &S, problem: &Problem, method: &Method) -> Vec<f64> {
    integrate(system, problem, method, &LAST_ROW_ONLY, &mut |_| Ok(())).expect("the run succeeds").final_q
}

/// Smallest over [`ROUNDS`] rounds of the mean seconds per call, the calls alternating round by round.
fn interleaved(calls: &[&dyn Fn()]) -> Vec<f64> {
    let batch = |f: &dyn Fn(), reps: usize| {
        let started = Instant::now();
        for _ in 0..reps {
            f();
        }
        started.elapsed().as_secs_f64() / reps as f64
    };
    let reps: Vec<usize> =
        calls.iter().map(|f| ((BATCH.as_secs_f64() / batch(*f, 1).max(1e-9)) as usize).clamp(1, 1_000_000)).collect();
    let mut best = vec![f64::INFINITY; calls.len()];
    for _ in 0..ROUNDS {
        for ((f, &r), b) in calls.iter().zip(&reps).zip(&mut best) {
            *b = b.min(batch(*f, r));
        }
    }
    best
}

fn work_precision() {
    println!("charged particle, T = 20: time per run [s] (per step [ns]) and ‖q(T) − q_N‖; Newton iterations per step");
    println!(
        "{:>6}  {:>24} {:>10} {:>5}  {:>24} {:>10}  {:>24} {:>10}",
        "N", "engine", "error", "it.", "specialised", "error", "boris", "error"
    );
    let system = ChargedParticle::default();
    let engine = method(Rule::Left, true, Variant::Plus);
    for steps in [50, 100, 200, 400, 800, 1600, 3200, 6400, 12800] {
        let h = T / steps as f64;
        let problem = ChargedParticle::paper_problem(steps);
        let stepper = ChargedParticleStep { m: 1.0, b0: 1.0, h };
        let start = ReducedState { q: [0.0; 3], theta: 0.0, w: [1.0, 0.0, 1.0], mu: 1.0 };
        let boris = Boris { e: 1.0, m: 1.0, b0: 1.0 };
        let finals = [
            run(&system, &problem, &engine)[..3].to_vec(),
            stepper.run(start, steps).q.to_vec(),
            boris.run(h, steps, [0.0; 3], [1.0, 0.0, 1.0]).position.to_vec(),
        ];
        let times = interleaved(&[
            &|| {
                black_box(run(&system, black_box(&problem), &engine));
            },
            &|| {
                black_box(black_box(&stepper).run(black_box(start), steps));
            },
            &|| {
                black_box(black_box(&boris).run(h, steps, black_box([0.0; 3]), black_box([1.0, 0.0, 1.0])));
            },
        ]);
        let summary = integrate(&system, &problem, &engine, &LAST_ROW_ONLY, &mut |_| Ok(())).expect("the run succeeds");
        let iterations = summary.newton.total_iterations as f64 / steps as f64;
        let mut line = format!("{steps:>6}");
        for (i, (time, q)) in times.iter().zip(&finals).enumerate() {
            line += &format!("  {:>11.4e} ({:>8.1} ns) {:>10.3e}", time, time / steps as f64 * 1e9, error(q));
            if i == 0 {
                line += &format!(" {iterations:>5.2}");
            }
        }
        println!("{line}");
    }
}

/// Reduced (+), reduced (−) where given, and unreduced, alternating; prints ns per step and ratios.
fn compare<S: System<N>, const N: usize>(name: &str, system: &S, problem: &Problem, rule: Rule, minus: bool) {
    let mut methods = vec![("reduced (+)", method(rule, true, Variant::Plus))];
    if minus {
        methods.push(("reduced (−)", method(rule, true, Variant::Minus)));
    }
    methods.push(("unreduced", method(rule, false, Variant::Plus)));
    let calls: Vec<Box<dyn Fn()>> = methods
        .iter()
        .map(|(_, m)| -> Box<dyn Fn()> {
            Box::new(move || {
                black_box(run(system, black_box(problem), m));
            })
        })
        .collect();
    let times = interleaved(&calls.iter().map(|c| c.as_ref()).collect::<Vec<_>>());
    let unreduced = times[times.len() - 1];
    let mut line = format!("{name:<36}");
    for ((label, m), t) in methods.iter().zip(&times) {
        let summary = integrate(system, problem, m, &LAST_ROW_ONLY, &mut |_| Ok(())).expect("the run succeeds");
        let iterations = summary.newton.total_iterations as f64 / problem.steps as f64;
        line += &format!("  {label} {:>7.1} ns ({iterations:.2} Newton it.)", t / problem.steps as f64 * 1e9);
    }
    for ((label, _), t) in methods.iter().zip(&times).take(times.len() - 1) {
        line += &format!("  {label}/unreduced {:.3}", t / unreduced);
    }
    println!("{line}");
}

fn reduced_vs_unreduced() {
    println!("\nengine runs of benches/steps.rs (1000 steps), time per step, interleaved");
    let steps = 1000;
    let cp = ChargedParticle::default();
    let cp_problem = ChargedParticle::paper_problem(steps);
    compare("charged particle, left", &cp, &cp_problem, Rule::Left, true);
    compare("charged particle, midpoint", &cp, &cp_problem, Rule::Midpoint, true);
    let dsp_problem = Problem { steps, ..DoubleSphericalPendulum::paper_problem(10_000) };
    compare(
        "double spherical pendulum, midpoint",
        &DoubleSphericalPendulum::default(),
        &dsp_problem,
        Rule::Midpoint,
        true,
    );
    let kepler_problem = Problem::new(0.01, steps, vec![1.0, 0.3], InitialMomentum::Momentum(vec![0.2, 1.2]));
    compare("Kepler, midpoint", &Kepler::default(), &kepler_problem, Rule::Midpoint, false);
    let top_problem = Problem::new(1e-3, steps, vec![0.0, 0.6, 0.0], InitialMomentum::Velocity(vec![0.4, 0.0, 30.0]));
    compare("heavy top, midpoint", &HeavyTop::default(), &top_problem, Rule::Midpoint, false);
}

fn main() {
    work_precision();
    reduced_vs_unreduced();
}
