//! Runs the paper's two experiments (§7) reduced and unreduced and prints what they report.
//!
//! `cargo run --release -p ddirac --example paper_runs`

use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, TABLE_1};
use ddirac::{solve, Error, Method, OutputOptions, Rule};

fn main() -> Result<(), Error> {
    println!("Charged particle (left rule, T = 20): N, ‖q(T) − q_N‖ reduced, unreduced, paper");
    for (steps, printed) in TABLE_1 {
        let run = |reduced| -> Result<f64, Error> {
            let method = Method { rule: Rule::Left, reduced, ..Method::default() };
            let s =
                solve(&ChargedParticle::default(), &ChargedParticle::paper_problem(steps), &method, &last_only(steps))?;
            Ok(s.summary.reference_error.unwrap_or(f64::NAN))
        };
        println!("{steps:>5}  {:.6}  {:.6}  {printed}", run(true)?, run(false)?);
    }

    println!("\nDouble spherical pendulum (midpoint, T = 100, N = 10⁴)");
    let steps = 10_000;
    let problem = DoubleSphericalPendulum::paper_problem(steps);
    let system = DoubleSphericalPendulum::default();
    let mut finals = vec![];
    for reduced in [true, false] {
        let method = Method { rule: Rule::Midpoint, reduced, ..Method::default() };
        let s = solve(&system, &problem, &method, &last_only(steps))?.summary;
        println!(
            "reduced = {reduced:<5}  q_N = {:?}\n  discrete energy [{:.6e}, {:.6e}], Newton {} iterations (max {}), {:.3} s",
            s.final_q, s.discrete_energy.min, s.discrete_energy.max, s.newton.total_iterations, s.newton.max_iterations,
            s.wall_seconds
        );
        finals.push(s.final_q);
    }
    let diff = finals[0].iter().zip(&finals[1]).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    println!("max |q_N reduced − q_N unreduced| = {diff:.3e}");
    Ok(())
}

fn last_only(steps: usize) -> OutputOptions {
    OutputOptions { every: steps, wrap_angles: false }
}
