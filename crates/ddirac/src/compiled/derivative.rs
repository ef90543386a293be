//! The derivatives a step needs of a pair function f(base, a, b), differentiated symbolically on its
//! traced graph, and the two programs that compute them.
//!
//! With base, a and b blocks of N numbers, the schemes need at a = 0
//!
//! - the *first* program: f, ∂f/∂a_i, ∂f/∂b_j (1 + 2N outputs);
//! - the *mixed* program: the same and ∂²f/∂a_i∂b_j, row-major at i·N + j (1 + 2N + N² outputs);
//!
//! both as functions of the inputs (base_0 … base_{N−1}, b_0 … b_{N−1}).
//!
//! 1. f is traced once ([`super::trace`]) with base, a and b as inputs.
//! 2. Reverse mode over the graph gives the gradient: the adjoint ū = ∂f/∂u of each node, seeded with
//!    f̄ = 1 and accumulated from the users of a node, x̄ += ū · ∂u/∂x, over the nodes that depend on
//!    a or b. The adjoints are new nodes of the same graph.
//! 3. The value and gradient are rebuilt with a := 0, which folds what a = 0 makes constant.
//! 4. Forward mode along each b_j gives the mixed block: the tangent u̇ = Σ ∂u/∂x · ẋ, seeded with
//!    ḃ_j = 1, of the nodes ∂f/∂a_i read; nodes that do not depend on b_j have no tangent, so zeros
//!    cost nothing. Substituting a = 0 before differentiating along b is exact, since setting a = 0
//!    and differentiating in b commute.
//!
//! The local derivatives ∂u/∂x are the textbook ones, written with the node u = op(x) where that
//! saves work (∂eˣ = u, ∂tan = 1 + u², ∂(x/y)/∂y = −u/y); atan2(x, y) = atan(x/y) has
//! ∂/∂x = y/(x² + y²), ∂/∂y = −x/(x² + y²); xʸ with a variable exponent has ∂/∂x = y·u/x and
//! ∂/∂y = u·ln x; |x| has sign(x), and sign(x) has 0.
//!
//! min(x, y) and max(x, y) have the one-sided derivatives of the operand they pick: ∂/∂y is the
//! indicator s = [y < x] (for max [x < y], `Binary::Less`, whose own derivative is 0) and ∂/∂x is
//! 1 − s. An adjoint or tangent is *gated* by the indicator (`Binary::Gate`: v where s ≠ 0, else 0)
//! rather than multiplied by it, so that an infinite or NaN derivative of the operand not picked
//! does not turn 0 · ∞ into NaN; a gated value has the derivative of the gate's value operand, and a
//! gated adjoint or tangent keeps its gate outside the factors it meets later (∂ min(a, √b)/∂b at
//! b = 0 is 0 where a is picked, in reverse mode as in forward mode).

use super::graph::{Graph, Node};
use super::program::{Binary, Instruction, Program, Unary};
use super::trace::{self, NotCompiled, Traced};
use crate::dim::Dim;
use crate::RuntimeInput;

/// The two programs of a pair function: inputs (base, b), outputs at a = 0 as in the module
/// documentation.
#[derive(Debug, Clone, PartialEq)]
pub struct PairPrograms {
    /// f, ∂f/∂a, ∂f/∂b.
    pub first: Program,
    /// f, ∂f/∂a, ∂f/∂b and ∂²f/∂a∂b (row-major).
    pub mixed: Program,
    /// The operations of f itself as traced (with a as an input, before differentiation): what one
    /// evaluation of f by dual numbers computes.
    pub operations: usize,
    /// The guards of the trace ([`super::trace`]): each program ends with one output per guard, the
    /// sign of a difference, valid where it is one of the signs allowed here (bits of `Sign`).
    pub guards: Vec<u8>,
    /// The runtime inputs of the programs, after (base, b), with their values for the run that traced
    /// them ([`crate::Scalar::runtime_input`]).
    pub runtime: Vec<(RuntimeInput, f64)>,
}

impl PairPrograms {
    /// Whether the guard outputs `signs` (the programs' last outputs) allow the point they were
    /// computed at.
    pub fn holds(guards: &[u8], signs: &[f64]) -> bool {
        guards.iter().zip(signs).all(|(&allowed, &s)| allowed & trace::Sign::of(s) as u8 != 0)
    }
}

/// Traces f(base, a, b) at (base, 0, b) and returns its programs, with the step size and the
/// parameters folded in ([`pair_programs_with_runtime_inputs`] keeps them as inputs).
///
/// The point only matters for what the trace can check there: values that code inspects, and that
/// f and its derivatives are finite.
///
/// ```
/// use ddirac::compiled::pair_programs;
/// use num_dual::DualNum;
/// // f = (base + a)² · eᵇ
/// use ddirac::dim::Fixed;
/// let programs = pair_programs(Fixed, |base, a, b| (base[0] + a[0]).powi(2) * b[0].exp(), &[1.0], &[0.0]).unwrap();
/// let mut out = [0.0; 4];
/// programs.mixed.eval(&[3.0, 0.0], &mut Vec::new(), &mut out);
/// assert_eq!(out, [9.0, 6.0, 9.0, 6.0]); // f, ∂f/∂a, ∂f/∂b, ∂²f/∂a∂b
/// ```
pub fn pair_programs<Dm: Dim, F>(
    dim: Dm,
    f: F,
    base: &Dm::Array<f64>,
    b: &Dm::Array<f64>,
) -> Result<PairPrograms, NotCompiled>
where
    F: Fn(&Dm::Array<Traced>, &Dm::Array<Traced>, &Dm::Array<Traced>) -> Traced,
{
    programs(pair_graph(dim, f, base, b, false)?)
}

/// [`pair_programs`] with the runtime inputs f asks for (the step size, a text Lagrangian's
/// parameters) kept as inputs of the programs, after (base, b): one compiled program then serves
/// every value of them.
///
/// ```
/// use ddirac::compiled::pair_programs_with_runtime_inputs;
/// use ddirac::{dim::Fixed, RuntimeInput, Scalar};
/// // f = h · b², with h a runtime input.
/// let f = |_: &[_; 1], _: &[_; 1], b: &[ddirac::compiled::Traced; 1]| {
///     let h = ddirac::compiled::Traced::runtime_input(RuntimeInput::Step, 0.1).unwrap();
///     b[0] * b[0] * h
/// };
/// let programs = pair_programs_with_runtime_inputs(Fixed, f, &[0.0], &[3.0]).unwrap();
/// assert_eq!(programs.runtime, vec![(RuntimeInput::Step, 0.1)]);
/// let mut out = [0.0; 3];
/// programs.first.eval(&[0.0, 3.0, 0.5], &mut Vec::new(), &mut out); // h = 0.5 now
/// assert_eq!(out, [4.5, 0.0, 3.0]);
/// ```
pub fn pair_programs_with_runtime_inputs<Dm: Dim, F>(
    dim: Dm,
    f: F,
    base: &Dm::Array<f64>,
    b: &Dm::Array<f64>,
) -> Result<PairPrograms, NotCompiled>
where
    F: Fn(&Dm::Array<Traced>, &Dm::Array<Traced>, &Dm::Array<Traced>) -> Traced,
{
    programs(pair_graph(dim, f, base, b, true)?)
}

/// The two programs of a differentiated pair graph.
fn programs(pair: PairGraph) -> Result<PairPrograms, NotCompiled> {
    let n = pair.da.len();
    let PairGraph { mut graph, value, da, db, operations, guards, runtime } = pair;
    let columns: Vec<Vec<Node>> = (0..n)
        .map(|j| match graph.input_node(n + j) {
            Some(b_j) => directional(&mut graph, b_j, &da),
            None => vec![graph.constant(0.0); n],
        })
        .collect();
    let mut roots: Vec<Node> = std::iter::once(value).chain(da).chain(db).collect();
    let mut outputs = roots.clone();
    outputs.extend((0..n * n).map(|k| columns[k % n][k / n]));
    check_finite(&graph, &outputs, n)?;
    let signs = guards.iter().map(|(node, _)| *node);
    roots.extend(signs.clone());
    outputs.extend(signs);
    let guards = guards.iter().map(|(_, allowed)| *allowed).collect();
    Ok(PairPrograms { first: graph.program(&roots), mixed: graph.program(&outputs), operations, guards, runtime })
}

/// A pair function's value and gradient at a = 0, as nodes of a graph whose inputs are (base, b).
pub(super) struct PairGraph {
    pub graph: Graph,
    pub value: Node,
    pub da: Vec<Node>,
    pub db: Vec<Node>,
    /// The operations of f as traced ([`PairPrograms::operations`]).
    pub operations: usize,
    /// The guards: the node of each sign and its allowed signs ([`PairPrograms::guards`]).
    pub guards: Vec<(Node, u8)>,
    /// The runtime inputs, after (base, b) ([`PairPrograms::runtime`]).
    pub runtime: Vec<(RuntimeInput, f64)>,
}

/// Traces f(base, a, b) at (base, 0, b) and differentiates it once: steps 1 to 3 above. With
/// `runtime`, the runtime inputs f asks for are inputs after (base, b).
pub(super) fn pair_graph<Dm: Dim, F>(
    dim: Dm,
    f: F,
    base: &Dm::Array<f64>,
    b: &Dm::Array<f64>,
    runtime: bool,
) -> Result<PairGraph, NotCompiled>
where
    F: Fn(&Dm::Array<Traced>, &Dm::Array<Traced>, &Dm::Array<Traced>) -> Traced,
{
    let n = dim.n();
    let zeros = vec![0.0; n];
    let point: Vec<f64> = base.as_ref().iter().chain(&zeros).chain(b.as_ref()).copied().collect();
    let trace::Recorded { mut graph, result: y, guards, runtime } = trace::trace(&point, runtime, |x| {
        let block = |k: usize| dim.array(|i| x[k * n + i]);
        f(&block(0), &block(1), &block(2))
    })?;
    let operations = graph.operations(y);
    // The trace's inputs are its first nodes: base, a, b.
    let wrt: Vec<Node> = (n..3 * n).map(|k| k as Node).collect();
    let mut roots = vec![y];
    roots.extend(gradient(&mut graph, y, &wrt));
    roots.extend(guards.iter().map(|g| g.node));
    let inputs = 3 * n + runtime.len();
    let a_is_zero: Vec<Option<f64>> = (0..inputs).map(|k| (n..2 * n).contains(&k).then_some(0.0)).collect();
    let (graph, roots) = graph.substitute(&roots, &a_is_zero);
    let guards = guards.iter().zip(&roots[1 + 2 * n..]).map(|(g, &node)| (node, g.allowed)).collect();
    Ok(PairGraph {
        graph,
        value: roots[0],
        da: roots[1..=n].to_vec(),
        db: roots[1 + n..1 + 2 * n].to_vec(),
        operations,
        guards,
        runtime,
    })
}

/// `NotCompiled::NonFinite` unless every output is finite at the graph's build point; outputs are
/// the value, 2n first derivatives and then second derivatives.
pub(super) fn check_finite(graph: &Graph, outputs: &[Node], n: usize) -> Result<(), NotCompiled> {
    for (k, &node) in outputs.iter().enumerate() {
        let value = graph.value(node);
        if !value.is_finite() {
            let what = ["value", "first derivative", "mixed derivative"][usize::from(k > 0) + usize::from(k > 2 * n)];
            return Err(NotCompiled::NonFinite { what, value });
        }
    }
    Ok(())
}

/// A local derivative ∂u/∂x: a factor, the reciprocal of a divisor (so that ū · 1/d is one
/// division), or an indicator (1 where u is x, 0 elsewhere) that gates v instead of multiplying it.
#[derive(Debug, Clone, Copy)]
enum Partial {
    Times(Node),
    Over(Node),
    Where(Node),
}

impl Partial {
    /// v · ∂u/∂x. A gated v stays gated: the gate goes outside the factor, so that the factor of a
    /// branch not taken (∂√x = ∞ at 0) meets the gated-off 0 as 0 rather than as 0 · ∞ = NaN.
    fn scale(self, g: &mut Graph, v: Node) -> Node {
        if let (Partial::Times(_) | Partial::Over(_), Instruction::Binary(Binary::Gate, indicator, inner)) =
            (self, g.instruction(v))
        {
            let scaled = self.scale(g, inner);
            return g.binary(Binary::Gate, indicator, scaled);
        }
        match self {
            Partial::Times(d) => g.mul(v, d),
            Partial::Over(d) => g.div(v, d),
            Partial::Where(indicator) => g.binary(Binary::Gate, indicator, v),
        }
    }
}

/// ∂f/∂w for each w in `wrt`, by reverse mode over the nodes up to f.
fn gradient(g: &mut Graph, f: Node, wrt: &[Node]) -> Vec<Node> {
    let end = f as usize + 1;
    let mut active = vec![false; end];
    for &w in wrt.iter().filter(|&&w| (w as usize) < end) {
        active[w as usize] = true;
    }
    for n in 0..end {
        active[n] = active[n] || g.instruction(n as Node).operands().any(|x| active[x as usize]);
    }
    let mut adjoint: Vec<Option<Node>> = vec![None; end];
    if active[f as usize] {
        adjoint[f as usize] = Some(g.constant(1.0));
    }
    for u in (0..end).rev() {
        let Some(bar) = adjoint[u] else { continue };
        for (x, partial) in partials(g, u as Node, |x| active[x as usize]).into_iter().flatten() {
            let term = partial.scale(g, bar);
            adjoint[x as usize] = Some(match adjoint[x as usize] {
                Some(sum) => g.add(sum, term),
                None => term,
            });
        }
    }
    wrt.iter().map(|&w| adjoint.get(w as usize).copied().flatten().unwrap_or_else(|| g.constant(0.0))).collect()
}

/// The derivatives of `roots` along the input node `x`, by forward mode over the nodes they read.
pub(super) fn directional(g: &mut Graph, x: Node, roots: &[Node]) -> Vec<Node> {
    let end = roots.iter().map(|&r| r as usize + 1).max().unwrap_or(0);
    let needed = g.live(roots);
    let mut tangent: Vec<Option<Node>> = vec![None; end.max(x as usize + 1)];
    tangent[x as usize] = Some(g.constant(1.0));
    for u in x as usize + 1..end {
        if !needed[u] {
            continue;
        }
        let mut sum = None;
        for (v, partial) in partials(g, u as Node, |v| tangent[v as usize].is_some()).into_iter().flatten() {
            if let Some(dv) = tangent[v as usize] {
                let term = partial.scale(g, dv);
                sum = Some(sum.map_or(term, |s| g.add(s, term)));
            }
        }
        tangent[u] = sum;
    }
    roots.iter().map(|&r| tangent[r as usize].unwrap_or_else(|| g.constant(0.0))).collect()
}

/// ∂u/∂x for the operands x of node u that `active` selects.
fn partials(g: &mut Graph, u: Node, active: impl Fn(Node) -> bool) -> [Option<(Node, Partial)>; 2] {
    match g.instruction(u) {
        Instruction::Input(_) | Instruction::Const(_) => [None, None],
        Instruction::Unary(op, x) => [active(x).then(|| (x, unary(g, op, x, u))), None],
        Instruction::Powi(x, n) => [active(x).then(|| (x, power(g, x, n, u))), None],
        Instruction::Binary(op, x, y) => [
            active(x).then(|| (x, first_operand(g, op, x, y, u))),
            active(y).then(|| (y, second_operand(g, op, x, y, u))),
        ],
    }
}

/// d(xⁿ)/dx = n xⁿ⁻¹ (n u / x for the one n whose n − 1 is not an i32).
fn power(g: &mut Graph, x: Node, n: i32, u: Node) -> Partial {
    let factor = g.constant(f64::from(n));
    match n.checked_sub(1) {
        Some(m) => {
            let p = g.powi(x, m);
            Partial::Times(g.mul(factor, p))
        }
        None => {
            let nu = g.mul(factor, u);
            Partial::Times(g.div(nu, x))
        }
    }
}

/// f′(x) for u = f(x).
fn unary(g: &mut Graph, op: Unary, x: Node, u: Node) -> Partial {
    let one = g.constant(1.0);
    let square = |g: &mut Graph, v: Node| g.mul(v, v);
    match op {
        Unary::Neg => Partial::Times(g.constant(-1.0)),
        Unary::Recip => {
            let uu = square(g, u);
            Partial::Times(g.neg(uu))
        }
        Unary::Sqrt => Partial::Over(g.add(u, u)),
        Unary::Cbrt => {
            let three = g.constant(3.0);
            let three_x = g.mul(three, x);
            Partial::Times(g.div(u, three_x))
        }
        Unary::Abs => Partial::Times(g.unary(Unary::Signum, x)),
        Unary::Signum => Partial::Times(g.constant(0.0)),
        Unary::Exp => Partial::Times(u),
        Unary::ExpM1 => Partial::Times(g.add(u, one)),
        Unary::Ln => Partial::Over(x),
        Unary::Ln1p => Partial::Over(g.add(x, one)),
        Unary::Sin => Partial::Times(g.unary(Unary::Cos, x)),
        Unary::Cos => {
            let s = g.unary(Unary::Sin, x);
            Partial::Times(g.neg(s))
        }
        Unary::Tan => {
            let uu = square(g, u);
            Partial::Times(g.add(one, uu))
        }
        Unary::Tanh => {
            let uu = square(g, u);
            Partial::Times(g.sub(one, uu))
        }
        Unary::Sinh => Partial::Times(g.unary(Unary::Cosh, x)),
        Unary::Cosh => Partial::Times(g.unary(Unary::Sinh, x)),
        Unary::Asin | Unary::Acos | Unary::Atan | Unary::Asinh | Unary::Acosh | Unary::Atanh => {
            let xx = square(g, x);
            let denominator = match op {
                Unary::Asin | Unary::Acos => {
                    let d = g.sub(one, xx);
                    g.unary(Unary::Sqrt, d)
                }
                Unary::Asinh => {
                    let d = g.add(xx, one);
                    g.unary(Unary::Sqrt, d)
                }
                Unary::Acosh => {
                    let d = g.sub(xx, one);
                    g.unary(Unary::Sqrt, d)
                }
                Unary::Atan => g.add(one, xx),
                _ => g.sub(one, xx),
            };
            Partial::Over(if op == Unary::Acos { g.neg(denominator) } else { denominator })
        }
    }
}

/// ∂u/∂x for u = op(x, y).
fn first_operand(g: &mut Graph, op: Binary, x: Node, y: Node, u: Node) -> Partial {
    match op {
        Binary::Add | Binary::Sub => Partial::Times(g.constant(1.0)),
        Binary::Mul => Partial::Times(y),
        Binary::Div => Partial::Over(y),
        Binary::Pow => match g.constant_of(y) {
            Some(p) => {
                let (factor, exponent) = (g.constant(p), g.constant(p - 1.0));
                let lowered = g.binary(Binary::Pow, x, exponent);
                Partial::Times(g.mul(factor, lowered))
            }
            None => {
                let yu = g.mul(y, u);
                Partial::Times(g.div(yu, x))
            }
        },
        Binary::Atan2 => {
            let r = squared_norm(g, x, y);
            Partial::Times(g.div(y, r))
        }
        Binary::Min | Binary::Max => {
            let one = g.constant(1.0);
            let second = picks_second(g, op, x, y);
            Partial::Where(g.sub(one, second))
        }
        // piecewise constant in x (for a gate, its indicator)
        Binary::Less | Binary::Gate => Partial::Times(g.constant(0.0)),
    }
}

/// 1 where min(x, y) or max(x, y) is y, else 0 (y < x, y > x: [`Binary::apply`]).
fn picks_second(g: &mut Graph, op: Binary, x: Node, y: Node) -> Node {
    match op {
        Binary::Min => g.binary(Binary::Less, y, x),
        _ => g.binary(Binary::Less, x, y),
    }
}

/// ∂u/∂y for u = op(x, y).
fn second_operand(g: &mut Graph, op: Binary, x: Node, y: Node, u: Node) -> Partial {
    let negated = match op {
        Binary::Add => return Partial::Times(g.constant(1.0)),
        Binary::Sub => return Partial::Times(g.constant(-1.0)),
        Binary::Mul => return Partial::Times(x),
        Binary::Pow => {
            let ln = g.unary(Unary::Ln, x);
            return Partial::Times(g.mul(u, ln));
        }
        Binary::Div => g.div(u, y),
        Binary::Min | Binary::Max => return Partial::Where(picks_second(g, op, x, y)),
        Binary::Less => return Partial::Times(g.constant(0.0)),
        Binary::Gate => return Partial::Where(x),
        Binary::Atan2 => {
            let r = squared_norm(g, x, y);
            g.div(x, r)
        }
    };
    Partial::Times(g.neg(negated))
}

/// x² + y².
fn squared_norm(g: &mut Graph, x: Node, y: Node) -> Node {
    let (xx, yy) = (g.mul(x, x), g.mul(y, y));
    g.add(xx, yy)
}
