//! The order in which a scope's definitions are lowered: each after the definitions it uses, found
//! without recursion from one definition to the next, so that a chain of thousands of definitions
//! declared in any order needs no more stack than a chain of two; a cycle is an error naming every
//! reference in it.

use std::collections::HashMap;

use super::ast::{Expr, ExprKind};
use super::scope::{Entry, Scope};
use super::{parse, CycleStep, ExpressionError, Origin};

/// A definition being visited: its tree, the references to definitions in it (in source order), how
/// many of them have been followed, and the reference that led to it.
struct Visit<'s> {
    name: &'s str,
    expr: Expr,
    references: Vec<CycleStep>,
    next: usize,
    reached_by: Option<CycleStep>,
}

/// Every definition of `scope`, parsed, dependencies first: a depth-first search from each
/// definition in declaration order, following references in source order. A definition that does
/// not parse is a syntax error when the search reaches it; a reference back to a definition still
/// being visited is an [`ExpressionError::Cycle`] listing the references from that definition round
/// to itself.
pub(super) fn in_order(scope: &Scope) -> Result<Vec<(&str, Expr)>, ExpressionError> {
    let mut visited: HashMap<&str, bool> = HashMap::new(); // false while being visited
    let mut order = Vec::new();
    for root in scope.order.iter().map(String::as_str) {
        if visited.contains_key(root) {
            continue;
        }
        let Some(first) = visit(scope, root, None)? else { continue };
        visited.insert(root, false);
        let mut stack = vec![first];
        while let Some(top) = stack.last_mut() {
            let Some(reference) = top.references.get(top.next).cloned() else {
                let done = stack.pop().expect("the stack has a top");
                visited.insert(done.name, true);
                order.push((done.name, done.expr));
                continue;
            };
            top.next += 1;
            let Some((name, _)) = scope.entries.get_key_value(reference.name.as_str()) else { continue };
            match visited.get(name.as_str()) {
                Some(true) => {}
                Some(false) => {
                    let start = stack.iter().position(|v| v.name == name).unwrap_or(0);
                    let cycle: Vec<CycleStep> =
                        stack[start + 1..].iter().filter_map(|v| v.reached_by.clone()).chain([reference]).collect();
                    let last = cycle.last().expect("the closing reference");
                    return Err(ExpressionError::Cycle { origin: last.origin.clone(), span: last.span, cycle });
                }
                None => {
                    if let Some(next) = visit(scope, name, Some(reference))? {
                        visited.insert(name, false);
                        stack.push(next);
                    }
                }
            }
        }
    }
    Ok(order)
}

/// The visit of definition `name`, parsed, or `None` if the name is not a definition.
fn visit<'s>(
    scope: &'s Scope,
    name: &'s str,
    reached_by: Option<CycleStep>,
) -> Result<Option<Visit<'s>>, ExpressionError> {
    let Some(Entry::Definition(source)) = scope.entries.get(name) else { return Ok(None) };
    let origin = Origin::Definition(name.to_owned());
    let expr = parse(source).map_err(|error| ExpressionError::Syntax { origin: origin.clone(), error })?;
    let mut references = Vec::new();
    collect(scope, &expr, &origin, &mut references);
    Ok(Some(Visit { name, expr, references, next: 0, reached_by }))
}

/// The references to definitions in `expr`, in source order.
fn collect(scope: &Scope, expr: &Expr, origin: &Origin, out: &mut Vec<CycleStep>) {
    match &expr.kind {
        ExprKind::Number(_) => {}
        ExprKind::Name(name) => {
            if let Some(Entry::Definition(_)) = scope.entries.get(name.as_str()) {
                out.push(CycleStep { origin: origin.clone(), name: name.clone(), span: expr.span });
            }
        }
        ExprKind::Unary { operand, .. } => collect(scope, operand, origin, out),
        ExprKind::Binary { lhs, rhs, .. } => {
            collect(scope, lhs, origin, out);
            collect(scope, rhs, origin, out);
        }
        ExprKind::Chain { first, rest } => {
            collect(scope, first, origin, out);
            rest.iter().for_each(|(_, operand)| collect(scope, operand, origin, out));
        }
        ExprKind::Call { args, .. } => args.iter().for_each(|arg| collect(scope, arg, origin, out)),
    }
}
