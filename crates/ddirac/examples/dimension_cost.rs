//! Time per step of the built-in chain of pendula in a fixed dimension (`Fixed<links>`, as a spec
//! runs it) or in a dimension chosen at run time (`Dynamic(links)`): the measurement behind
//! BENCHMARKS.md's "One engine for every size".
//!
//! ```text
//! cargo run --release -p ddirac --example dimension_cost -- LINKS fixed|dynamic dual|compiled STEPS
//! ```
//!
//! Prints the nanoseconds per step and the final state (the two dimensions give the same bits).

use ddirac::systems::DynamicPendulumChain;
use ddirac::{Differentiation, DynSystem, InitialMomentum, Method, Problem, Rule};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: dimension_cost LINKS fixed|dynamic dual|compiled STEPS";
    let [_, links, dimension, derivatives, steps] = args.as_slice() else {
        return Err(usage.into());
    };
    let (links, steps): (usize, usize) = (links.parse()?, steps.parse()?);
    let system: Box<dyn DynSystem> = match dimension.as_str() {
        "dynamic" => DynamicPendulumChain::new(links).erased(),
        "fixed" => {
            let chain = ddirac::systems::find("pendulum_chain").ok_or("no built-in chain")?;
            (chain.build)(&[("links".to_string(), links as f64)])?
        }
        _ => return Err(usage.into()),
    };
    let differentiation = match derivatives.as_str() {
        "dual" => Differentiation::Dual,
        "compiled" => Differentiation::Compiled,
        _ => return Err(usage.into()),
    };
    let arch = |i: usize| 0.5 * (std::f64::consts::PI * i as f64 / (links + 1) as f64).sin();
    let q0 = (1..=links).map(arch).collect();
    let problem = Problem::new(0.005, steps, q0, InitialMomentum::Momentum(vec![0.0; links]));
    let method = Method { rule: Rule::Midpoint, differentiation, ..Method::default() };
    let start = std::time::Instant::now();
    let mut stepper = system.stepper(&problem, &method)?;
    while !stepper.is_finished() {
        stepper.step()?;
    }
    let per_step = start.elapsed().as_nanos() as f64 / steps as f64;
    let state = stepper.state();
    println!("{per_step:.0} ns/step; q = {:?}; p = {:?}", state.q(), state.p());
    Ok(())
}
