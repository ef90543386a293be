//! A system defined in Rust by its user: a particle in the plane in polar coordinates (r, φ) under a
//! central potential V(r) = −k/r + ε/r², which is invariant under rotations (φ is the group
//! coordinate). The reduced run conserves the angular momentum p_φ to round-off and agrees with the
//! unreduced run.
//!
//! `cargo run --release -p ddirac --example user_system`

use ddirac::prelude::*;

/// L = ½ m (ṙ² + r² φ̇²) + k/r − ε/r².
struct Central {
    m: f64,
    k: f64,
    eps: f64,
}

impl System<2> for Central {
    fn coordinates(&self) -> [Coordinate; 2] {
        [Coordinate::shape("r"), Coordinate::group("phi").angle()]
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; 2], v: &[D; 2]) -> D {
        let r = q[0];
        (v[0] * v[0] + r * r * v[1] * v[1]) * (0.5 * self.m) + r.recip() * self.k - (r * r).recip() * self.eps
    }
}

fn main() -> Result<(), Error> {
    let system = Central { m: 1.0, k: 1.0, eps: 0.05 };
    let problem = Problem::new(0.01, 20_000, vec![1.0, 0.0], InitialMomentum::Velocity(vec![0.0, 1.2]));
    let every = OutputOptions { every: 20_000, ..OutputOptions::default() };
    for reduced in [true, false] {
        let method = Method { reduced, ..Method::default() };
        let run = solve(&system, &problem, &method, &every)?;
        let s = &run.summary;
        println!(
            "reduced = {reduced:<5}  q_N = ({:.12}, {:.12})  p_phi drift {:.1e}  energy [{:.12}, {:.12}]  warnings {}",
            s.final_q[0],
            s.final_q[1],
            s.momentum_map.max_drift,
            s.energy.min,
            s.energy.max,
            s.warnings.len()
        );
    }
    Ok(())
}
