//! A compiled expression: its program in the compiled IR and the interpreter that evaluates it over
//! any scalar.

use crate::compiled::{Interpreter, Program};

/// A compiled expression: the straight-line [`Program`] of the compiled IR (one output, the scope's
/// variables as inputs, in order) and its [`Interpreter`], which evaluates it generically over the
/// scalar (f64 or any num-dual number, so that automatic differentiation gives every derivative).
/// The same program compiles to native code (`compiled::NativeProgram`, with the `jit` feature).
///
/// ```
/// use ddirac::expression::Scope;
/// use num_dual::first_derivative;
/// let compiled = Scope::new().variable("x").compile_expression("x^3 + sin(x)").unwrap();
/// let (value, derivative) = first_derivative(|x| compiled.eval(&[x]), 0.5);
/// assert!((value - (0.125 + 0.5f64.sin())).abs() < 1e-15);
/// assert!((derivative - (0.75 + 0.5f64.cos())).abs() < 1e-15);
/// assert_eq!(compiled.program().inputs, 1);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct CompiledExpression {
    program: Program,
    interpreter: Interpreter,
}

impl CompiledExpression {
    /// The expression computed by `program`'s one output.
    ///
    /// # Panics
    ///
    /// If the program has another number of outputs than one.
    pub fn new(program: Program) -> Self {
        let interpreter = Interpreter::new(&program);
        Self { program, interpreter }
    }

    /// The program in the compiled IR.
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// Number of variables `eval` expects.
    pub fn variables(&self) -> usize {
        self.program.inputs
    }

    /// Number of registers the interpreter uses.
    pub fn registers(&self) -> usize {
        self.interpreter.registers()
    }

    /// Number of the interpreter's steps (loads, operations, in-place updates, `sin_cos` pairs).
    pub fn instructions(&self) -> usize {
        self.interpreter.steps()
    }

    /// The value, if the expression depends on no variable.
    pub fn constant(&self) -> Option<f64> {
        self.interpreter.constant()
    }

    /// The value at `vars` (in the order of the scope's variables).
    ///
    /// # Panics
    ///
    /// If `vars.len()` differs from [`CompiledExpression::variables`].
    pub fn eval<D: crate::Scalar>(&self, vars: &[D]) -> D {
        assert_eq!(vars.len(), self.variables(), "the program has {} variables", self.variables());
        self.eval_with(|i| vars[i])
    }

    /// The value with the i-th variable given by `load(i)`, called once for each variable the
    /// expression uses (i < [`CompiledExpression::variables`]).
    #[inline]
    pub fn eval_with<D: crate::Scalar>(&self, load: impl Fn(usize) -> D) -> D {
        self.interpreter.eval_with(load)
    }
}
