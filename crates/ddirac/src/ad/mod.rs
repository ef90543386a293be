//! Forward-mode automatic differentiation for the step equations: the dual numbers that carry the
//! derivative blocks of a function f(a, b) of two argument blocks that a step needs, and nothing
//! more. How they are seeded and run in a dimension, fixed or chosen at run time, is
//! [`crate::dim`]'s ([`crate::dim::mixed`], [`crate::dim::first`]).
//!
//! A step of every scheme differentiates one scalar function of two blocks: L_d(q0, q1) for the
//! discrete Euler–Lagrange map (paper §2.3.2), l̂(a, b) for the reduced equations (§4.3–4.4). It needs
//!
//! - for the Newton Jacobian, the value, ∂f/∂a, ∂f/∂b and the mixed block ∂²f/∂a∂b ([`Mixed`]);
//! - for a residual alone, the value, ∂f/∂a and ∂f/∂b ([`Gradient`]), a small fraction of the cost.
//!
//! Both are dual numbers over plain fixed-size arrays, so their arithmetic compiles to straight-line
//! code without branches or copies of optional parts. They implement num-dual's [`DualNum`](num_dual::DualNum), so a
//! user's Lagrangian, generic over `D: DualNum<Primitive = f64> + Copy`, runs on them unchanged.
//!
//! For many coordinates a single [`Mixed`] pass carries n² second-derivative entries per
//! intermediate value; [`crate::dim::mixed`] then computes the mixed block in column chunks of [`crate::dim::CHUNK`] so that
//! the intermediate values stay small (see BENCHMARKS.md for the measured crossover). In a dimension
//! chosen at run time ([`crate::dim::Dynamic`]) the dual numbers keep their fixed width: the
//! derivatives are computed in blocks of [`crate::dim::BLOCK`] arguments, so that no dual number
//! lives on the heap.

mod gradient;
mod jet;
mod mixed;

pub use gradient::Gradient;
pub use mixed::Mixed;
