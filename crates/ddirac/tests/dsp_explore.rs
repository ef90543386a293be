use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{Method, Stepper};

#[test]
fn explore() {
    let steps: usize = std::env::var("STEPS").map(|s| s.parse().unwrap()).unwrap_or(10_000);
    let system = DoubleSphericalPendulum::default();
    let mut problem = DoubleSphericalPendulum::paper_problem(10_000);
    problem.steps = steps;
    for reduced in [true, false] {
        let method = Method { reduced, ..Method::default() };
        let t0 = std::time::Instant::now();
        let mut stepper = Stepper::new(&system, &problem, &method).unwrap();
        let h0 = stepper.row().energy;
        let mut worst = 0.0f64;
        let mut last = [0.0; 4];
        while !stepper.is_finished() {
            stepper.step().unwrap();
            if stepper.k() % 10 == 0 || stepper.is_finished() {
                let row = stepper.row();
                worst = worst.max(((row.energy - h0) / h0).abs());
                last = row.q;
            }
        }
        let s = stepper.finish().unwrap();
        println!("reduced {reduced}: worst {worst:.3e} switches {} subdiv {} q {:?} {:.2}s warnings {:?}", s.chart_switches, s.newton.subdivided_steps, last, t0.elapsed().as_secs_f64(), s.warnings.iter().map(|w| w.message.clone()).collect::<Vec<_>>());
    }
}
