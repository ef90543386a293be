//! An ensemble over initial data with one stepper: the charged particle of the paper (§7.1) started
//! with several velocities along the field. `Stepper::new` checks the problem and prepares the step's
//! derivatives once; each member restarts it from a cold state (q0, p0) and steps to the end. A
//! checkpoint halfway shows a restart from a saved state, which continues bit for bit.
//!
//! `cargo run --release -p ddirac --example ensemble`

use ddirac::prelude::*;
use ddirac::systems::ChargedParticle;

fn main() -> Result<(), Error> {
    let system = ChargedParticle::default();
    let problem = ChargedParticle::paper_problem(2000);
    let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
    let mut stepper = Stepper::new(&system, &problem, &method)?;
    for vz in [0.0, 0.5, 1.0, 2.0] {
        stepper.restart(&State::new(0, [0.0; 4], [1.0, 0.0, vz, 1.0]))?;
        let mut halfway = None;
        while !stepper.is_finished() {
            if stepper.k() == problem.steps / 2 {
                halfway = Some(stepper.state());
            }
            stepper.step()?;
        }
        let end = stepper.row();
        // Continue once more from the checkpoint: the same end, bit for bit.
        stepper.restart(&halfway.expect("the run passes halfway"))?;
        while !stepper.is_finished() {
            stepper.step()?;
        }
        assert_eq!(stepper.row().q, end.q);
        println!(
            "v_z = {vz:.1}: q(T) = ({:+.6}, {:+.6}, {:+.6}), p_theta = {}",
            end.q[0], end.q[1], end.q[2], end.p[3]
        );
    }
    let summary = stepper.finish()?;
    println!("last member: ‖q(T) − q_N‖ = {:.3e} against the exact helix", summary.reference_error.unwrap_or(f64::NAN));
    Ok(())
}
