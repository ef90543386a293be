//! Compiled derivatives: a Lagrangian traced once into a graph of operations, differentiated
//! symbolically, simplified, and turned into straight-line native code.

mod cache;
mod cost;
mod derivative;
pub(crate) mod graph;
mod interpreter;
pub mod jit;
mod linear_step;
mod pair;
pub mod program;
pub mod trace;

pub use cache::{native, native_compilations};
pub use cost::CompileCost;
pub use derivative::{pair_programs, pair_programs_with_runtime_inputs, PairPrograms};
pub use interpreter::Interpreter;
pub use jit::{JitError, NativeProgram};
pub use linear_step::{LinearSolution, LinearStep};
pub use pair::{CompileError, CompiledPair};
pub use program::{Binary, Instruction, Program, Register, Unary};
pub use trace::{NotCompiled, Traced};

#[cfg(test)]
mod tests;
