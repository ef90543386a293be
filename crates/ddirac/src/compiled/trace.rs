//! The recording scalar [`Traced`]: running generic code on it once writes the code's arithmetic into
//! a graph of operations, instead of computing numbers.
//!
//! A [`Traced`] is the index of a node in a thread-local graph of operations. Every operator and
//! elementary function of num-dual's [`num_dual::DualNum`] appends (or finds) one node. Operations on numbers
//! that do not depend on the inputs fold to constants on the spot, so a Lagrangian's parameters and
//! their combinations cost nothing in the recorded graph.
//!
//! A recording is valid for every input only if the code does the same operations everywhere. Code
//! that compares numbers (`<`, `==`, `partial_cmp`, `is_positive`, … — what `min`, `max` and
//! piecewise functions do) may branch on the answer. A comparison of input-dependent numbers is
//! answered for the trace point and *guarded*: the recording keeps sign(x − y) as a `Guard` with
//! the signs that give the same answer, and a program evaluated where a guard's sign is another one
//! is not valid there (the caller then uses dual numbers for that point). Within its guards a
//! program is the branch the trace took, with that branch's (one-sided) derivatives. The choices of
//! [`crate::Scalar::min_of`] and [`crate::Scalar::max_of`] (which text Lagrangians use) are not
//! comparisons but operations of the program ([`Binary::Min`], [`Binary::Max`]), valid on both
//! sides and without a guard. Code that reads
//! the value itself ([`num_dual::DualStruct::re`]) may do anything with it; on an input-dependent
//! number this makes the trace fail with [`NotCompiled::ValueInspected`] (the value at the trace point
//! is still returned, so the code runs on). On constants both are harmless and allowed. Operations without an instruction in [`super::program`] (`%`, which
//! truncates, and the spherical Bessel functions) fail with [`NotCompiled::Unsupported`] on
//! input-dependent numbers.

mod arithmetic;

use std::cell::{Cell, RefCell};

use super::graph::{Graph, Node};
use super::program::{Binary, Unary};
use crate::RuntimeInput;

/// Why a function could not be compiled (then the caller keeps dual numbers).
///
/// ```
/// use ddirac::compiled::{pair_programs, NotCompiled, Traced};
/// use ddirac::dim::Fixed;
/// use num_dual::DualStruct;
/// // `max` by hand: which branch runs depends on the point.
/// let max = |_: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| if a[0].re() > b[0].re() { a[0] } else { b[0] };
/// assert_eq!(pair_programs(Fixed, max, &[0.0], &[1.0]), Err(NotCompiled::ValueInspected { operation: "re" }));
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
/// use ddirac::dim::Fixed;
/// use num_dual::DualNum;
/// let f = |base: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| (base[0] + a[0]) * (base[0] + b[0]).sin();
/// let programs = pair_programs(Fixed, f, &[1.0], &[0.5]).unwrap();
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

/// A comparison the traced code made, kept as the sign of a difference and the signs for which the
/// comparison gives the answer it gave at the trace point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Guard {
    /// The node of sign(x − y).
    pub node: Node,
    /// The allowed signs, a set of [`Sign`]s as bits.
    pub allowed: u8,
}

/// The sign of a difference x − y: which way a comparison of x and y goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Sign {
    Negative = 1,
    Zero = 2,
    Positive = 4,
    /// x or y is NaN (or x − y is ∞ − ∞, which the guard treats as unknown).
    Unordered = 8,
}

impl Sign {
    const ALL: [Sign; 4] = [Sign::Negative, Sign::Zero, Sign::Positive, Sign::Unordered];

    /// The class of a value of sign(x − y).
    pub(super) fn of(s: f64) -> Sign {
        if s < 0.0 {
            Sign::Negative
        } else if s > 0.0 {
            Sign::Positive
        } else if s == 0.0 {
            Sign::Zero
        } else {
            Sign::Unordered
        }
    }

    /// Whether the guard allows this sign.
    pub(super) fn allowed_by(self, guard: &Guard) -> bool {
        guard.allowed & self as u8 != 0
    }
}

/// A comparison of two numbers, as the operators ask it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Comparison {
    Less,
    LessOrEqual,
    Greater,
    GreaterOrEqual,
    Equal,
}

impl Comparison {
    /// The answer for two numbers whose difference has the sign `sign`.
    fn holds(self, sign: Sign) -> bool {
        matches!(
            (self, sign),
            (Comparison::Less | Comparison::LessOrEqual, Sign::Negative)
                | (Comparison::Greater | Comparison::GreaterOrEqual, Sign::Positive)
                | (Comparison::LessOrEqual | Comparison::GreaterOrEqual | Comparison::Equal, Sign::Zero)
        )
    }
}

/// The graph being recorded on this thread, the comparisons it is guarded by, and the first reason it
/// cannot be compiled.
struct Recording {
    graph: Graph,
    trace: u32,
    guards: Vec<Guard>,
    /// The runtime inputs made so far with their nodes and values, when the trace keeps them as
    /// inputs ([`crate::Scalar::runtime_input`]); `None` when it folds them in.
    runtime: Option<Vec<(RuntimeInput, Node, f64)>>,
    failure: Option<NotCompiled>,
}

impl Recording {
    fn new(trace: u32) -> Self {
        Self { graph: Graph::new(), trace, guards: Vec::new(), runtime: None, failure: None }
    }

    fn fail(&mut self, failure: NotCompiled) {
        self.failure.get_or_insert(failure);
    }

    /// The sign of x − y at the trace point. When it depends on the inputs, a guard allows the signs
    /// `same(sign)` gives (those for which the caller's answer is the same); a trace point whose own
    /// sign the guard would not allow (∞ − ∞ for equal infinities) fails the trace.
    fn guard<'s, I: Iterator<Item = &'s Sign>>(&mut self, x: Traced, y: Traced, same: impl FnOnce(Sign) -> I) -> Sign {
        let (x, y) = (self.operand(x), self.operand(y));
        let (vx, vy) = (self.graph.value(x), self.graph.value(y));
        let sign = match vx.partial_cmp(&vy) {
            Some(std::cmp::Ordering::Less) => Sign::Negative,
            Some(std::cmp::Ordering::Equal) => Sign::Zero,
            Some(std::cmp::Ordering::Greater) => Sign::Positive,
            None => Sign::Unordered,
        };
        let difference = self.graph.sub(x, y);
        let node = self.graph.unary(Unary::Signum, difference);
        if self.graph.constant_of(node).is_none() {
            let allowed = same(sign).fold(0, |bits, s| bits | *s as u8);
            let guard = Guard { node, allowed };
            if !Sign::of(self.graph.value(node)).allowed_by(&guard) {
                self.fail(NotCompiled::ValueInspected { operation: "comparison" });
            }
            self.guards.push(guard);
        }
        sign
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

/// A recorded function: its graph, the node of its result, the guards it holds under and its runtime
/// inputs.
pub(super) struct Recorded {
    pub graph: Graph,
    pub result: Node,
    pub guards: Vec<Guard>,
    /// The runtime inputs the function asked for, in the order of their inputs (after those of
    /// `point`), with their values at the trace.
    pub runtime: Vec<(RuntimeInput, f64)>,
}

/// Runs `f` on one traced input per entry of `point` (recorded with that value) and returns the
/// recording, or why it cannot be compiled. The inputs are the graph's first nodes, in order; with
/// `runtime`, the runtime inputs `f` asks for ([`crate::Scalar::runtime_input`]) are inputs too,
/// numbered after them, and are folded in as constants otherwise.
pub(super) fn trace(
    point: &[f64],
    runtime: bool,
    f: impl FnOnce(&[Traced]) -> Traced,
) -> Result<Recorded, NotCompiled> {
    let id = TRACES.with(|count| {
        count.set(count.get().wrapping_add(1).max(1));
        count.get()
    });
    let mut recording = Recording::new(id);
    recording.runtime = runtime.then(Vec::new);
    let _restore = Restore(Some(RECORDING.replace(recording)));
    let inputs: Vec<Traced> = point.iter().map(|&value| record([], |g, []| g.input(value))).collect();
    let y = f(&inputs);
    let node = RECORDING.with_borrow_mut(|r| r.operand(y));
    let recording = RECORDING.replace(Recording::new(0));
    match recording.failure {
        Some(failure) => Err(failure),
        None => Ok(Recorded {
            graph: recording.graph,
            result: node,
            guards: recording.guards,
            runtime: recording
                .runtime
                .unwrap_or_default()
                .into_iter()
                .map(|(input, _, value)| (input, value))
                .collect(),
        }),
    }
}

/// In a trace that keeps runtime inputs, the input standing for `input` (made on first use with the
/// value given then); min and max as operations of the program.
impl crate::Scalar for Traced {
    fn runtime_input(input: RuntimeInput, value: f64) -> Option<Self> {
        RECORDING.with_borrow_mut(|r| {
            let Recording { graph, trace, runtime, .. } = r;
            let runtime = runtime.as_mut()?;
            let node = match runtime.iter().find(|(made, _, _)| *made == input) {
                Some(&(_, node, _)) => node,
                None => {
                    let node = graph.input(value);
                    runtime.push((input, node, value));
                    node
                }
            };
            Some(Traced { node, trace: *trace })
        })
    }

    /// One [`Binary::Min`] node, valid on both sides of x = y.
    fn min_of(self, other: Self) -> Self {
        self.binary(Binary::Min, other)
    }

    /// One [`Binary::Max`] node, valid on both sides of x = y.
    fn max_of(self, other: Self) -> Self {
        self.binary(Binary::Max, other)
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

    /// Compares `self` with `other` at the trace point and guards the answer when it depends on the
    /// inputs.
    fn compare(self, other: Self, comparison: Comparison) -> bool {
        RECORDING.with_borrow_mut(|r| {
            let sign = r.guard(self, other, |sign| {
                Sign::ALL.iter().filter(move |s| comparison.holds(**s) == comparison.holds(sign))
            });
            comparison.holds(sign)
        })
    }

    /// The ordering of `self` and `other` at the trace point, guarded when it depends on the inputs.
    fn ordering(self, other: Self) -> Option<std::cmp::Ordering> {
        RECORDING.with_borrow_mut(|r| {
            let sign = r.guard(self, other, |sign| Sign::ALL.iter().filter(move |s| **s == sign));
            match sign {
                Sign::Negative => Some(std::cmp::Ordering::Less),
                Sign::Zero => Some(std::cmp::Ordering::Equal),
                Sign::Positive => Some(std::cmp::Ordering::Greater),
                Sign::Unordered => None,
            }
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
