//! Name resolution against a [`Scope`] and lowering of the syntax tree into the graph of the
//! compiled IR ([`crate::compiled`]): variables are its inputs, in order, and every operation is
//! interned with the graph's constant folding and merging of identical nodes.

use std::collections::HashMap;

use super::ast::{BinaryOp, Expr, ExprKind, UnaryOp};
use super::functions::{Function, FUNCTIONS};
use super::scope::{Entry, Scope};
use super::{definitions, parse, CompiledExpression, ExpressionError, Origin, Span};
use crate::compiled::graph::{Graph, Node};
use crate::compiled::Binary;

impl Scope {
    /// Compiles `source`, reporting its errors as belonging to `origin` (errors inside a definition
    /// are reported with [`Origin::Definition`]). Every definition of the scope is checked, whether
    /// the expression uses it or not.
    pub fn compile(&self, origin: Origin, source: &str) -> Result<CompiledExpression, ExpressionError> {
        let (graph, root) = self.lower(origin, source)?;
        Ok(CompiledExpression::new(graph.program(&[root])))
    }

    /// Compiles a standalone expression ([`Origin::Expression`]).
    pub fn compile_expression(&self, source: &str) -> Result<CompiledExpression, ExpressionError> {
        self.compile(Origin::Expression, source)
    }

    /// The graph of `source` and its root node; input k of the graph is the k-th variable.
    pub(super) fn lower(&self, origin: Origin, source: &str) -> Result<(Graph, Node), ExpressionError> {
        let expr = parse(source).map_err(|error| ExpressionError::Syntax { origin: origin.clone(), error })?;
        let mut graph = Graph::new();
        let inputs = (0..self.variables).map(|_| graph.input(0.0)).collect();
        let mut compiler = Compiler { scope: self, graph, inputs, done: HashMap::new() };
        for (name, definition) in definitions::in_order(self)? {
            let node = compiler.lower(&definition, &Origin::Definition(name.to_owned()))?;
            compiler.done.insert(name, node);
        }
        let root = compiler.lower(&expr, &origin)?;
        Ok((compiler.graph, root))
    }
}

struct Compiler<'s> {
    scope: &'s Scope,
    graph: Graph,
    /// The node of each variable.
    inputs: Vec<Node>,
    /// Definitions already lowered: all those an expression being lowered uses
    /// ([`definitions::in_order`]).
    done: HashMap<&'s str, Node>,
}

impl Compiler<'_> {
    fn lower(&mut self, expr: &Expr, origin: &Origin) -> Result<Node, ExpressionError> {
        Ok(match &expr.kind {
            ExprKind::Number(value) => self.graph.constant(*value),
            ExprKind::Name(name) => self.name(name, expr.span, origin)?,
            ExprKind::Unary { op, operand } => {
                let operand = self.lower(operand, origin)?;
                match op {
                    UnaryOp::Neg => self.graph.neg(operand),
                    UnaryOp::Plus => operand,
                }
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let (a, b) = (self.lower(lhs, origin)?, self.lower(rhs, origin)?);
                self.graph.binary(binary(*op), a, b)
            }
            ExprKind::Chain { first, rest } => {
                let mut value = self.lower(first, origin)?;
                for (op, operand) in rest {
                    let b = self.lower(operand, origin)?;
                    value = self.graph.binary(binary(*op), value, b);
                }
                value
            }
            ExprKind::Call { name, name_span, args } => {
                let Some(function) = Function::named(name) else {
                    let origin = origin.clone();
                    if self.scope.entries.contains_key(name.as_str()) {
                        return Err(ExpressionError::NotAFunction { origin, span: *name_span, name: name.clone() });
                    }
                    let suggestion = closest(name, FUNCTIONS.iter().copied());
                    return Err(ExpressionError::UnknownFunction {
                        origin,
                        span: *name_span,
                        name: name.clone(),
                        suggestion,
                    });
                };
                if args.len() != function.arity() {
                    return Err(ExpressionError::Arity {
                        origin: origin.clone(),
                        span: expr.span,
                        function: name.clone(),
                        expected: function.arity(),
                        found: args.len(),
                    });
                }
                let args = args.iter().map(|arg| self.lower(arg, origin)).collect::<Result<Vec<_>, _>>()?;
                match function {
                    Function::Unary(op) => self.graph.unary(op, args[0]),
                    Function::Binary(op) => self.graph.binary(op, args[0], args[1]),
                }
            }
        })
    }

    fn name(&mut self, name: &str, span: Span, origin: &Origin) -> Result<Node, ExpressionError> {
        let scope = self.scope;
        match scope.entries.get_key_value(name) {
            Some((_, Entry::Variable(index))) => Ok(self.inputs[*index]),
            Some((_, Entry::Constant(value))) => Ok(self.graph.constant(*value)),
            Some((key, Entry::Definition(_))) => {
                Ok(*self.done.get(key.as_str()).expect("definitions are lowered after the definitions they use"))
            }
            Some((_, Entry::Unavailable(reason))) => Err(ExpressionError::Unavailable {
                origin: origin.clone(),
                span,
                name: name.to_owned(),
                reason: reason.clone(),
            }),
            None if Function::named(name).is_some() => {
                Err(ExpressionError::FunctionWithoutCall { origin: origin.clone(), span, name: name.to_owned() })
            }
            None => {
                let known = scope
                    .order
                    .iter()
                    .filter(|n| !matches!(scope.entries.get(n.as_str()), Some(Entry::Unavailable(_))))
                    .map(String::as_str);
                let suggestion = closest(name, known);
                Err(ExpressionError::UnknownName { origin: origin.clone(), span, name: name.to_owned(), suggestion })
            }
        }
    }
}

/// The operation of a binary operator.
fn binary(op: BinaryOp) -> Binary {
    match op {
        BinaryOp::Add => Binary::Add,
        BinaryOp::Sub => Binary::Sub,
        BinaryOp::Mul => Binary::Mul,
        BinaryOp::Div => Binary::Div,
        BinaryOp::Pow => Binary::Pow,
    }
}

/// The candidate closest to `name`, if it is within a third of the name's length (at least one
/// edit): closest by edit distance ignoring case, then by edit distance, then first given. A name
/// that differs only in case (`K` for `k`) is therefore always the suggestion.
pub(super) fn closest<'a>(name: &str, candidates: impl Iterator<Item = &'a str>) -> Option<String> {
    let limit = (name.chars().count() / 3).max(1);
    let lower = name.to_lowercase();
    candidates
        .map(|c| ((edit_distance(&lower, &c.to_lowercase()), edit_distance(name, c)), c))
        .filter(|((folded, _), _)| *folded <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c.to_owned())
}

/// Levenshtein distance, counting in characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let next = (row[j + 1] + 1).min(row[j] + 1).min(diagonal + usize::from(ca != cb));
            diagonal = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}
