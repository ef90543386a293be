//! The names an expression may use, and what each stands for.

use std::collections::HashMap;

/// What a name stands for.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Entry {
    Variable(usize),
    Constant(f64),
    Definition(String),
    Unavailable(String),
}

/// The names an expression may use: variables (in the order of the values given to
/// [`CompiledExpression::eval`](super::CompiledExpression::eval)), constants, definitions and names reserved with a reason.
///
/// Names should be distinct; when one is declared twice, the later declaration wins (the variable
/// count still includes every variable declared).
///
/// ```
/// use ddirac::expression::{ExpressionError, Scope};
/// let scope = Scope::new().variable("x").constant("k", 3.0).definition("f", "k*x^2").unavailable("t", "no time");
/// assert_eq!(scope.compile_expression("f/2").unwrap().eval(&[2.0]), 6.0);
/// assert!(matches!(scope.compile_expression("t"), Err(ExpressionError::Unavailable { .. })));
/// ```
#[derive(Debug, Clone, Default)]
pub struct Scope {
    pub(super) entries: HashMap<String, Entry>,
    /// Declaration order, for deterministic suggestions and definition checks.
    pub(super) order: Vec<String>,
    pub(super) variables: usize,
}

impl Scope {
    /// A scope with no names.
    pub fn new() -> Self {
        Self::default()
    }

    fn declare(mut self, name: &str, entry: Entry) -> Self {
        if self.entries.insert(name.to_owned(), entry).is_none() {
            self.order.push(name.to_owned());
        }
        self
    }

    /// Adds the next variable.
    pub fn variable(mut self, name: &str) -> Self {
        self.variables += 1;
        let index = self.variables - 1;
        self.declare(name, Entry::Variable(index))
    }

    /// Adds a named constant.
    pub fn constant(self, name: &str, value: f64) -> Self {
        self.declare(name, Entry::Constant(value))
    }

    /// Adds a named definition: an expression that may use every name of the scope, including other
    /// definitions, as long as no definition depends on itself.
    pub fn definition(self, name: &str, source: &str) -> Self {
        self.declare(name, Entry::Definition(source.to_owned()))
    }

    /// Reserves a name that expressions in this scope may not use, with the reason given in the error.
    pub fn unavailable(self, name: &str, reason: &str) -> Self {
        self.declare(name, Entry::Unavailable(reason.to_owned()))
    }

    /// Number of variables.
    pub fn variables(&self) -> usize {
        self.variables
    }
}
