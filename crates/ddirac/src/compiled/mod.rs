//! Compiled derivatives: a Lagrangian traced once into a graph of operations, differentiated
//! symbolically, simplified, and turned into straight-line programs, which run as native code
//! (Cranelift, the default feature `jit`) or, without that feature, on their interpreter
//! ([`Program::eval`]).

mod cache;
mod cost;
mod derivative;
mod error;
mod executable;
pub(crate) mod graph;
mod interpreter;
#[cfg(feature = "jit")]
pub mod jit;
mod linear_step;
mod pair;
pub mod program;
pub mod trace;

pub use cache::native_compilations;
pub use cost::CompileCost;
pub use derivative::{pair_programs, pair_programs_with_runtime_inputs, PairPrograms};
pub use error::CompileError;
pub use interpreter::Interpreter;
#[cfg(feature = "jit")]
pub use jit::{JitError, NativeProgram};
pub(crate) use linear_step::{known_not_affine, remember_not_affine};
pub use linear_step::{LinearSolution, LinearStep, Refusal};
pub use pair::CompiledPair;
pub use program::{Binary, Instruction, MalformedProgram, Program, Register, Unary};
pub use trace::{NotCompiled, Traced};

#[cfg(test)]
mod tests;
