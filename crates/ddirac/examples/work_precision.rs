//! Work–precision of three integrators of the charged particle (paper §7.1, T = 20): the generic
//! engine (reduced (+), left rule), the same scheme written out by hand
//! (`baselines::charged_particle_step`) and the Boris pusher (`baselines::boris`).
//!
//! For each N it prints the wall time of one run and the error ‖q(T) − q_N‖ against the exact
//! motion (sin t, cos t − 1, t). The three are timed in the same process, alternating, in several
//! rounds; each time is the smallest over the rounds of the mean over a batch of runs.
//!
//! `cargo run --release -p ddirac --example work_precision`

use std::hint::black_box;
use std::time::{Duration, Instant};

use ddirac::baselines::boris::Boris;
use ddirac::baselines::charged_particle_step::{ChargedParticleStep, ReducedState};
use ddirac::systems::ChargedParticle;
use ddirac::{integrate, Method, OutputOptions, Rule, Variant};

const T: f64 = 20.0;
/// An integrator: N steps over T from the paper's initial data to the final position.
type Integrator = fn(usize) -> [f64; 3];
const ROUNDS: usize = 15;
/// Each round runs a method for about this long.
const BATCH: Duration = Duration::from_millis(20);

fn error(q: &[f64]) -> f64 {
    let exact = [T.sin(), T.cos() - 1.0, T];
    (0..3).map(|i| (q[i] - exact[i]).powi(2)).sum::<f64>().sqrt()
}

/// One run of each integrator with N steps: returns the final position.
fn engine(steps: usize) -> [f64; 3] {
    let method = Method { rule: Rule::Left, variant: Variant::Plus, reduced: true, ..Method::default() };
    let output = OutputOptions { every: 1_000_000, wrap_angles: false };
    let problem = ChargedParticle::paper_problem(steps);
    let s =
        integrate(&ChargedParticle::default(), &problem, &method, &output, &mut |_| Ok(())).expect("the run succeeds");
    [s.final_q[0], s.final_q[1], s.final_q[2]]
}

fn specialised(steps: usize) -> [f64; 3] {
    let stepper = ChargedParticleStep { m: 1.0, b0: 1.0, h: T / steps as f64 };
    let start = ReducedState { q: [0.0; 3], theta: 0.0, w: [1.0, 0.0, 1.0], mu: 1.0 };
    stepper.run(black_box(start), steps).q
}

fn boris(steps: usize) -> [f64; 3] {
    Boris { e: 1.0, m: 1.0, b0: 1.0 }
        .run(T / steps as f64, steps, black_box([0.0; 3]), black_box([1.0, 0.0, 1.0]))
        .position
}

/// Mean seconds per run over a batch of `reps` runs.
fn time(run: Integrator, steps: usize, reps: usize) -> f64 {
    let started = Instant::now();
    for _ in 0..reps {
        black_box(run(black_box(steps)));
    }
    started.elapsed().as_secs_f64() / reps as f64
}

fn main() {
    let methods: [(&str, Integrator); 3] = [("engine", engine), ("specialised", specialised), ("boris", boris)];
    println!("charged particle, T = 20; time per run [s] (time per step [ns]) and ‖q(T) − q_N‖");
    println!(
        "{:>6}  {:>24} {:>10}  {:>24} {:>10}  {:>24} {:>10}",
        "N", "engine", "error", "specialised", "error", "boris", "error"
    );
    for steps in [50, 100, 200, 400, 800, 1600, 3200, 6400, 12800] {
        // Batch sizes from one calibration run each.
        let reps = methods.map(|(_, run)| {
            let once = time(run, steps, 1).max(1e-9);
            ((BATCH.as_secs_f64() / once) as usize).clamp(1, 1_000_000)
        });
        let mut best = [f64::INFINITY; 3];
        for _ in 0..ROUNDS {
            for (i, (_, run)) in methods.iter().enumerate() {
                best[i] = best[i].min(time(*run, steps, reps[i]));
            }
        }
        let mut line = format!("{steps:>6}");
        for (i, (_, run)) in methods.iter().enumerate() {
            let per_step_ns = best[i] / steps as f64 * 1e9;
            line += &format!("  {:>11.4e} ({:>8.1} ns) {:>10.3e}", best[i], per_step_ns, error(&run(steps)));
        }
        println!("{line}");
    }
}
