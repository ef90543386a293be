//! The recording scalar [`Traced`]: running generic code on it once writes the code's arithmetic into
//! a graph of operations, instead of computing numbers.
//!
//! A [`Traced`] is the index of a node in a thread-local graph of operations. Every operator and
//! elementary function of num-dual's [`num_dual::DualNum`] appends (or finds) one node. Operations on numbers
//! that do not depend on the inputs fold to constants on the spot, so a Lagrangian's parameters and
//! their combinations cost nothing in the recorded graph.
//!
//! A recording is valid for every input only if the code does the same operations everywhere. Code
//! that looks at a value ([`num_dual::DualStruct::re`], comparisons, `is_positive`, …) may branch
//! on it; on an input-dependent value this makes the trace fail with [`NotCompiled::ValueInspected`]
//! (the value at the trace point is still returned, so the code runs on). On constants it is
//! harmless and allowed. Operations without an instruction in [`super::program`] (`%`, which
//! truncates, and the spherical Bessel functions) fail with [`NotCompiled::Unsupported`] on
//! input-dependent numbers.

mod arithmetic;

use std::cell::{Cell, RefCell};

use super::graph::{Graph, Node};
use super::program::{Binary, Unary};

/// Why a function could not be compiled (then the caller keeps dual numbers).
///
/// ```
/// use ddirac::compiled::{pair_programs, NotCompiled, Traced};
/// use num_dual::DualStruct;
/// // `max` by hand: which branch runs depends on the point.
/// let max = |_: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| if a[0].re() > b[0].re() { a[0] } else { b[0] };
/// assert_eq!(pair_programs(max, &[0.0], &[1.0]), Err(NotCompiled::ValueInspected { operation: "re" }));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum NotCompiled {
    /// The function looked at the value of an input-dependent number, so the operations it does may
    /// depend on the point.
    #[error("the function inspects the value of an input-dependent number (`{operation}`)")]
    ValueInspected {
        /// The inspecting operation.
        operation: &'static str,
    },
    /// The function used an operation that has no compiled form.
    #[error("`{operation}` has no compiled form")]
    Unsupported {
        /// The operation.
        operation: &'static str,
    },
    /// The function or one of its derivatives is not finite at the point of the trace.
    #[error("the {what} is not finite at the trace point ({value})")]
    NonFinite {
        /// `value`, `first derivative` or `mixed derivative`.
        what: &'static str,
        /// The value found.
        value: f64,
    },
    /// A traced number was used outside the trace that made it.
    #[error("a traced number was used outside the trace that made it")]
    ForeignValue,
}

/// A number recorded as a node of a graph of operations: the scalar that generic code runs on to be
/// compiled. [`super::pair_programs`] runs the code on it.
///
/// It implements [`num_dual::DualNum`] like the dual numbers of [`crate::ad`]; see the module
/// documentation for what a trace cannot record. Outside a trace, operations on it record into an idle
/// graph that nothing reads.
///
/// ```
/// use ddirac::compiled::{pair_programs, Traced};
/// use num_dual::DualNum;
/// let f = |base: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| (base[0] + a[0]) * (base[0] + b[0]).sin();
/// let programs = pair_programs(f, &[1.0], &[0.5]).unwrap();
/// // Inputs (base, b); outputs f, ∂f/∂a, ∂f/∂b at a = 0.
/// let mut out = [0.0; 3];
/// programs.first.eval(&[2.0, 0.25], &mut Vec::new(), &mut out);
/// assert_eq!(out, [2.0 * 2.25f64.sin(), 2.25f64.sin(), 2.0 * 2.25f64.cos()]);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Traced {
    node: Node,
    trace: u32,
}

/// The graph being recorded on this thread, and the first reason it cannot be compiled.
struct Recording {
    graph: Graph,
    trace: u32,
    failure: Option<NotCompiled>,
}

impl Recording {
    fn new(trace: u32) -> Self {
        Self { graph: Graph::new(), trace, failure: None }
    }

    fn fail(&mut self, failure: NotCompiled) {
        self.failure.get_or_insert(failure);
    }

    /// The node of `x`, if it belongs to this recording.
    fn operand(&mut self, x: Traced) -> Node {
        if x.trace == self.trace {
            x.node
        } else {
            self.fail(NotCompiled::ForeignValue);
            self.graph.constant(f64::NAN)
        }
    }
}

thread_local! {
    /// The current recording; outside [`trace`] an idle one that nothing reads.
    static RECORDING: RefCell<Recording> = RefCell::new(Recording::new(0));
    /// How many traces this thread has started, to tell their numbers apart.
    static TRACES: Cell<u32> = const { Cell::new(0) };
}

/// Puts the enclosing recording back, also when the traced code panics.
struct Restore(Option<Recording>);

impl Drop for Restore {
    fn drop(&mut self) {
        if let Some(outer) = self.0.take() {
            RECORDING.set(outer);
        }
    }
}

/// Runs `f` on one traced input per entry of `point` (recorded with that value) and returns the
/// graph with the node of the result, or why it cannot be compiled. The inputs are the graph's first
/// nodes, in order.
pub(super) fn trace(point: &[f64], f: impl FnOnce(&[Traced]) -> Traced) -> Result<(Graph, Node), NotCompiled> {
    let id = TRACES.with(|count| {
        count.set(count.get().wrapping_add(1).max(1));
        count.get()
    });
    let _restore = Restore(Some(RECORDING.replace(Recording::new(id))));
    let inputs: Vec<Traced> = point.iter().map(|&value| record([], |g, []| g.input(value))).collect();
    let y = f(&inputs);
    let node = RECORDING.with_borrow_mut(|r| r.operand(y));
    let recording = RECORDING.replace(Recording::new(0));
    match recording.failure {
        Some(failure) => Err(failure),
        None => Ok((recording.graph, node)),
    }
}

/// Appends the node `f` builds from the operands' nodes.
fn record<const K: usize>(operands: [Traced; K], f: impl FnOnce(&mut Graph, [Node; K]) -> Node) -> Traced {
    RECORDING.with_borrow_mut(|r| {
        let nodes = operands.map(|x| r.operand(x));
        Traced { node: f(&mut r.graph, nodes), trace: r.trace }
    })
}

impl Traced {
    fn constant(c: f64) -> Self {
        record([], |g, []| g.constant(c))
    }

    fn unary(self, op: Unary) -> Self {
        record([self], |g, [x]| g.unary(op, x))
    }

    fn binary(self, op: Binary, other: Self) -> Self {
        record([self, other], |g, [x, y]| g.binary(op, x, y))
    }

    /// The value at the trace point; on an input-dependent number the trace fails.
    fn inspect(self, operation: &'static str) -> f64 {
        RECORDING.with_borrow_mut(|r| {
            let n = r.operand(self);
            if r.graph.constant_of(n).is_none() {
                r.fail(NotCompiled::ValueInspected { operation });
            }
            r.graph.value(n)
        })
    }

    /// f(operands) for an operation without a compiled form: folded on constants, a failed trace
    /// otherwise.
    fn unsupported<const K: usize>(
        operands: [Self; K],
        operation: &'static str,
        f: impl FnOnce([f64; K]) -> f64,
    ) -> Self {
        RECORDING.with_borrow_mut(|r| {
            let nodes = operands.map(|x| r.operand(x));
            if nodes.iter().any(|&n| r.graph.constant_of(n).is_none()) {
                r.fail(NotCompiled::Unsupported { operation });
            }
            let value = f(nodes.map(|n| r.graph.value(n)));
            Traced { node: r.graph.constant(value), trace: r.trace }
        })
    }

    /// x mod y, which truncates x / y.
    fn remainder(self, other: Self) -> Self {
        Self::unsupported([self, other], "%", |[x, y]| x % y)
    }
}
