//! What a program that defines and runs its own system needs, in one import.
//!
//! ```
//! use ddirac::prelude::*;
//!
//! /// A free particle on a line, translation-invariant in `x`.
//! struct Free;
//!
//! impl System<1> for Free {
//!     fn coordinates(&self) -> [Coordinate; 1] {
//!         [Coordinate::group("x")]
//!     }
//!     fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, _q: &[D; 1], v: &[D; 1]) -> D {
//!         v[0] * v[0] * 0.5
//!     }
//! }
//!
//! let problem = Problem::new(0.1, 10, vec![0.0], InitialMomentum::Momentum(vec![2.0]));
//! let run = solve(&Free, &problem, &Method::default(), &OutputOptions::default()).unwrap();
//! assert!((run.summary.final_q[0] - 2.0).abs() < 1e-12);
//! ```

pub use crate::num_dual::DualNum;
pub use crate::{
    check, integrate, solve, Connection, Coordinate, Error, InitialMomentum, Method, OutputOptions, Problem, Role,
    Rule, Solution, State, Stepper, System, Variant,
};
