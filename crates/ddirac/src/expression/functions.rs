//! The functions of the language, by name, and the operations of the compiled program
//! ([`crate::compiled::Unary`], [`crate::compiled::Binary`]) they stand for.

use crate::compiled::{Binary, Unary};

/// The functions of the language, by name.
pub const FUNCTIONS: &[&str] = &[
    "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "exp", "ln", "log", "sqrt", "abs",
    "pow", "min", "max",
];

/// The constants of the language, by name, with their values: every expression may use them, so no
/// coordinate, parameter or definition may take their names.
pub const CONSTANTS: &[(&str, f64)] = &[("pi", std::f64::consts::PI)];

/// Why `name` cannot be declared, if it names a constant of the language.
pub(super) fn constant(name: &str) -> Option<String> {
    CONSTANTS
        .iter()
        .find(|(c, _)| *c == name)
        .map(|(c, value)| format!("it is the constant `{c}` = {value} of the language, which every expression may use"))
}

/// A function of the language: an operation of one or two operands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Function {
    Unary(Unary),
    Binary(Binary),
}

impl Function {
    pub(super) fn named(name: &str) -> Option<Function> {
        use Function::{Binary as B, Unary as U};
        Some(match name {
            "sin" => U(Unary::Sin),
            "cos" => U(Unary::Cos),
            "tan" => U(Unary::Tan),
            "asin" => U(Unary::Asin),
            "acos" => U(Unary::Acos),
            "atan" => U(Unary::Atan),
            "sinh" => U(Unary::Sinh),
            "cosh" => U(Unary::Cosh),
            "tanh" => U(Unary::Tanh),
            "exp" => U(Unary::Exp),
            "ln" | "log" => U(Unary::Ln),
            "sqrt" => U(Unary::Sqrt),
            "abs" => U(Unary::Abs),
            "atan2" => B(Binary::Atan2),
            "pow" => B(Binary::Pow),
            "min" => B(Binary::Min),
            "max" => B(Binary::Max),
            _ => return None,
        })
    }

    pub(super) fn arity(self) -> usize {
        match self {
            Function::Unary(_) => 1,
            Function::Binary(_) => 2,
        }
    }
}

#[cfg(test)]
mod tests {
    use num_dual::Dual64;

    use super::FUNCTIONS;
    use crate::compiled::{pair_programs, CompiledPair, Traced};
    use crate::dim::Fixed;
    use crate::expression::Scope;

    /// Every function gives the same value and first derivatives through the interpreter on dual
    /// numbers and through the compiled programs of one trace (native code with the `jit` feature) (at x < y, x > 0), also on the other
    /// side of the kinks of `abs`, `min` and `max`.
    #[test]
    fn every_function_agrees_on_both_back_ends() {
        let scope = Scope::new().variable("x").variable("y");
        let points = [(0.3, 0.7), (0.7, 0.3), (-0.4, 0.2), (0.5, -0.6), (-0.8, -0.1)];
        for name in FUNCTIONS {
            let binary = matches!(*name, "atan2" | "pow" | "min" | "max");
            let source = if binary { format!("{name}(x, y)") } else { format!("{name}(x)") };
            let compiled = scope.compile_expression(&source).unwrap();
            let f = |base: &[Traced; 2], a: &[Traced; 2], _: &[Traced; 2]| compiled.eval_with(|i| base[i] + a[i]);
            let programs = pair_programs(Fixed, f, &[0.3, 0.7], &[0.0; 2]).unwrap_or_else(|e| panic!("{source}: {e}"));
            assert!(programs.guards.is_empty(), "{source}");
            let native = CompiledPair::from_programs(Fixed::<2>, &programs).unwrap();
            let mut checked = 0;
            for (x, y) in points {
                let dual = |dx, dy| compiled.eval(&[Dual64::new(x, dx), Dual64::new(y, dy)]);
                let (along_x, along_y) = (dual(1.0, 0.0), dual(0.0, 1.0));
                let expected = [along_x.re, along_x.eps, along_y.eps];
                if expected.iter().any(|v| !v.is_finite()) {
                    continue;
                }
                let (first, _) = native.first_or_mixed(&[x, y], &[0.0; 2], false).unwrap();
                let out = [first.value, first.da[0], first.da[1]];
                for (k, (&c, &d)) in out.iter().zip(&expected).enumerate() {
                    let what = ["value", "∂/∂x", "∂/∂y"][k];
                    assert!(
                        (c - d).abs() <= 1e-14 * d.abs().max(1.0),
                        "{source} at ({x}, {y}), {what}: native {c}, dual {d}"
                    );
                }
                checked += 1;
            }
            assert!(checked >= 2, "{source}: {checked} points in the domain");
        }
    }
}
