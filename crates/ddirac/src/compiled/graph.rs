//! A hash-consed graph of [`Instruction`]s (node k is register k), built with constant folding and
//! a few algebraic rewrites, from which straight-line [`Program`]s are cut.
//!
//! Every node is interned: an instruction that already exists returns the existing node, so a
//! subexpression computed twice is computed once. Before interning, an instruction is simplified:
//!
//! - operations on constants are folded with the program's own [`Unary::apply`], [`Binary::apply`]
//!   and `powi`, so a folded constant equals what the program would compute;
//! - x + 0, x − 0, x · 1, x / 1, x⁰, x¹ and −(−x) drop the operation; x · 0, 0 / x, x − x become 0;
//! - signs move outward: x · (−1), 0 − x, (−x) · y, x / (−y) become negations, x + (−y) becomes
//!   x − y and x − (−y) becomes x + y, and −(c · y) for a constant c becomes (−c) · y;
//! - exact scalings merge into constant factors: x + x is 2 · x, k · (c · y) is (k·c) · y when k or
//!   c is a power of two, x / 2ᵏ is x · 2⁻ᵏ;
//! - operands of + and × are ordered, so that a · b and b · a are one node;
//! - xⁿ for a small integer n is expanded into the products of binary exponentiation (the same
//!   products, in the same order, as `f64::powi`), a constant small integer power
//!   xᶜ becomes that product too, another constant integer power up to 1024 is `powi`, x^½ is √x;
//! - min(x, x) and max(x, x) are x; a gate by a constant indicator is its operand or 0.
//!
//! The rewrites that drop a term (x · 0 = 0, x − x = 0) differ from IEEE arithmetic only where x is
//! infinite or NaN, the merged scalings only where a product overflows or underflows. A node that does not depend on the inputs is always a constant after folding.
//!
//! Each node also carries its value at the point the graph was built at (the inputs' values), so that
//! a trace can answer what a value is where that is harmless.

use super::program::{Binary, Instruction, Program, Unary};
use rustc_hash::FxHashMap;

/// The index of a node, which is also its register in an extracted program.
pub(crate) type Node = u32;

/// Powers xⁿ with |n| up to this are expanded into multiplications.
const MAX_EXPANDED_POWER: i32 = 16;

/// A constant integer exponent with |n| up to this is [`Instruction::Powi`], a larger one
/// [`Binary::Pow`]. num-dual's `powi` forms the factors n(n−1) and n(n−1)(n−2) of the second and third
/// derivatives in i32, which overflows beyond |n| = 1290; its `powf` forms them in floating point.
const MAX_POWI: f64 = 1024.0;

/// The graph: instructions in evaluation order, each with its value at the build point.
#[derive(Debug, Clone, Default)]
pub(crate) struct Graph {
    nodes: Vec<Instruction>,
    values: Vec<f64>,
    inputs: Vec<f64>,
    interned: FxHashMap<Instruction, Node>,
}

impl Graph {
    /// An empty graph.
    pub(crate) fn new() -> Self {
        Self::default()
    }

    /// How many nodes the graph has.
    pub(crate) fn len(&self) -> usize {
        self.nodes.len()
    }

    /// The instruction of node `n`.
    pub(crate) fn instruction(&self, n: Node) -> Instruction {
        self.nodes[n as usize]
    }

    /// The inputs' values at the build point.
    pub(crate) fn point(&self) -> &[f64] {
        &self.inputs
    }

    /// The value of node `n` at the build point.
    pub(crate) fn value(&self, n: Node) -> f64 {
        self.values[n as usize]
    }

    /// The constant of node `n`, if it is one.
    pub(crate) fn constant_of(&self, n: Node) -> Option<f64> {
        match self.instruction(n) {
            Instruction::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    /// Whether node `n` is the constant `c` (compared by value, so 0 and −0 are both zero).
    fn is(&self, n: Node, c: f64) -> bool {
        self.constant_of(n) == Some(c)
    }

    /// The operand of a negation.
    fn negated(&self, n: Node) -> Option<Node> {
        match self.instruction(n) {
            Instruction::Unary(Unary::Neg, x) => Some(x),
            _ => None,
        }
    }

    /// (c, y) if node `n` is the product of a constant c and a node y.
    fn scaled(&self, n: Node) -> Option<(f64, Node)> {
        match self.instruction(n) {
            Instruction::Binary(Binary::Mul, a, b) => match (self.constant_of(a), self.constant_of(b)) {
                (Some(c), None) => Some((c, b)),
                (None, Some(c)) => Some((c, a)),
                _ => None,
            },
            _ => None,
        }
    }

    /// (k·c, z) if x is a constant k, y = c · z, and k · (c · z) = (k·c) · z exactly because k or c is
    /// a power of two (and k·c a normal number).
    fn merged_factors(&self, x: Node, y: Node) -> Option<(f64, Node)> {
        let k = self.constant_of(x)?;
        let (c, z) = self.scaled(y)?;
        let kc = k * c;
        ((is_power_of_two(k) || is_power_of_two(c)) && kc.is_normal()).then_some((kc, z))
    }

    /// The existing node of `instruction`, or a new one.
    fn intern(&mut self, instruction: Instruction) -> Node {
        if let Some(&n) = self.interned.get(&instruction) {
            return n;
        }
        let n = Node::try_from(self.nodes.len()).expect("graphs stay below 2³² nodes");
        self.values.push(instruction.apply(&self.inputs, &self.values));
        self.nodes.push(instruction);
        self.interned.insert(instruction, n);
        n
    }

    /// A new input with value `value` at the build point; inputs are numbered in creation order.
    pub(crate) fn input(&mut self, value: f64) -> Node {
        let index = u32::try_from(self.inputs.len()).expect("inputs stay below 2³²");
        self.inputs.push(value);
        self.intern(Instruction::Input(index))
    }

    /// The node of input k, if the graph has it.
    pub(crate) fn input_node(&self, k: usize) -> Option<Node> {
        self.interned.get(&Instruction::Input(u32::try_from(k).ok()?)).copied()
    }

    /// The constant c.
    pub(crate) fn constant(&mut self, c: f64) -> Node {
        self.intern(Instruction::constant(c))
    }

    /// op(x), simplified.
    pub(crate) fn unary(&mut self, op: Unary, x: Node) -> Node {
        if let Some(c) = self.constant_of(x) {
            return self.constant(op.apply(c));
        }
        if let (Unary::Neg, Some((c, y))) = (op, self.scaled(x)) {
            let minus_c = self.constant(-c);
            return self.mul(minus_c, y);
        }
        match (op, self.negated(x)) {
            (Unary::Neg, Some(y)) => y,
            (Unary::Abs, Some(y)) => self.unary(Unary::Abs, y),
            _ => self.intern(Instruction::Unary(op, x)),
        }
    }

    /// −x.
    pub(crate) fn neg(&mut self, x: Node) -> Node {
        self.unary(Unary::Neg, x)
    }

    /// x + y.
    pub(crate) fn add(&mut self, x: Node, y: Node) -> Node {
        self.binary(Binary::Add, x, y)
    }

    /// x − y.
    pub(crate) fn sub(&mut self, x: Node, y: Node) -> Node {
        self.binary(Binary::Sub, x, y)
    }

    /// x · y.
    pub(crate) fn mul(&mut self, x: Node, y: Node) -> Node {
        self.binary(Binary::Mul, x, y)
    }

    /// x / y.
    pub(crate) fn div(&mut self, x: Node, y: Node) -> Node {
        self.binary(Binary::Div, x, y)
    }

    /// op(x, y), simplified.
    pub(crate) fn binary(&mut self, op: Binary, x: Node, y: Node) -> Node {
        if let (Some(a), Some(b)) = (self.constant_of(x), self.constant_of(y)) {
            return self.constant(op.apply(a, b));
        }
        let (nx, ny) = (self.negated(x), self.negated(y));
        match op {
            Binary::Add if self.is(x, 0.0) => y,
            Binary::Add if self.is(y, 0.0) => x,
            Binary::Add => match (nx, ny) {
                (_, Some(v)) => self.sub(x, v),
                (Some(u), None) => self.sub(y, u),
                (None, None) if x == y => {
                    let two = self.constant(2.0);
                    self.mul(two, x)
                }
                (None, None) => self.intern(Instruction::Binary(op, x.min(y), x.max(y))),
            },
            Binary::Sub if self.is(y, 0.0) => x,
            Binary::Sub if self.is(x, 0.0) => self.neg(y),
            Binary::Sub if x == y => self.constant(0.0),
            Binary::Sub => match (nx, ny) {
                (_, Some(v)) => self.add(x, v),
                (Some(u), None) => {
                    let sum = self.add(u, y);
                    self.neg(sum)
                }
                (None, None) => self.intern(Instruction::Binary(op, x, y)),
            },
            Binary::Mul if self.is(x, 0.0) || self.is(y, 0.0) => self.constant(0.0),
            Binary::Mul if self.is(x, 1.0) => y,
            Binary::Mul if self.is(y, 1.0) => x,
            Binary::Mul if self.is(x, -1.0) => self.neg(y),
            Binary::Mul if self.is(y, -1.0) => self.neg(x),
            Binary::Div if self.is(x, 0.0) => self.constant(0.0),
            Binary::Div if self.is(y, 1.0) => x,
            Binary::Div if self.is(y, -1.0) => self.neg(x),
            Binary::Div if self.constant_of(y).is_some_and(is_power_of_two) => {
                let reciprocal = self.unary(Unary::Recip, y);
                self.mul(x, reciprocal)
            }
            Binary::Mul | Binary::Div if nx.is_some() || ny.is_some() => {
                let inner = self.binary(op, nx.unwrap_or(x), ny.unwrap_or(y));
                if nx.is_some() == ny.is_some() {
                    inner
                } else {
                    self.neg(inner)
                }
            }
            Binary::Mul => match self.merged_factors(x, y).or_else(|| self.merged_factors(y, x)) {
                Some((c, z)) => {
                    let c = self.constant(c);
                    self.mul(c, z)
                }
                None => self.intern(Instruction::Binary(op, x.min(y), x.max(y))),
            },
            Binary::Pow => match self.constant_of(y) {
                Some(p) => self.constant_power(x, p),
                None if self.is(x, 1.0) => x,
                None => self.intern(Instruction::Binary(op, x, y)),
            },
            Binary::Min | Binary::Max if x == y => x,
            Binary::Less if x == y => self.constant(0.0),
            Binary::Gate => match self.constant_of(x) {
                Some(c) if c != 0.0 => y,
                Some(_) => self.constant(0.0),
                None if self.is(y, 0.0) => y,
                None => self.intern(Instruction::Binary(op, x, y)),
            },
            Binary::Div | Binary::Atan2 | Binary::Min | Binary::Max | Binary::Less => {
                self.intern(Instruction::Binary(op, x, y))
            }
        }
    }

    /// xᵖ for a constant p: xⁿ for an integer p with |p| ≤ [`MAX_POWI`], √x for p = ½.
    fn constant_power(&mut self, x: Node, p: f64) -> Node {
        if p == p.trunc() && p.abs() <= MAX_POWI {
            // `as` is exact: p is an integer of at most 1024.
            self.powi(x, p as i32)
        } else if p == 0.5 {
            self.unary(Unary::Sqrt, x)
        } else {
            let p = self.constant(p);
            self.intern(Instruction::Binary(Binary::Pow, x, p))
        }
    }

    /// xⁿ, expanded into multiplications for small |n| as `f64::powi` computes it: binary
    /// exponentiation over the bits of |n|, then a reciprocal for negative n.
    pub(crate) fn powi(&mut self, x: Node, n: i32) -> Node {
        if let Some(c) = self.constant_of(x) {
            return self.constant(c.powi(n));
        }
        match n {
            0 => self.constant(1.0),
            1 => x,
            -1 => self.unary(Unary::Recip, x),
            _ if n.abs() <= MAX_EXPANDED_POWER => {
                let (mut bits, mut square, mut product) = (n.unsigned_abs(), x, None);
                loop {
                    if bits & 1 == 1 {
                        product = Some(product.map_or(square, |p| self.mul(p, square)));
                    }
                    bits >>= 1;
                    if bits == 0 {
                        break;
                    }
                    square = self.mul(square, square);
                }
                let power = product.unwrap_or(x);
                if n < 0 {
                    self.unary(Unary::Recip, power)
                } else {
                    power
                }
            }
            _ => self.intern(Instruction::Powi(x, n)),
        }
    }

    /// `instruction` with its operands in this graph, simplified (inputs are not rebuilt here).
    fn rebuild(&mut self, instruction: Instruction) -> Node {
        match instruction {
            Instruction::Input(_) | Instruction::Const(_) => self.intern(instruction),
            Instruction::Unary(op, x) => self.unary(op, x),
            Instruction::Binary(op, x, y) => self.binary(op, x, y),
            Instruction::Powi(x, n) => self.powi(x, n),
        }
    }

    /// Which nodes the `roots` read, directly or not (the roots included).
    pub(crate) fn live(&self, roots: &[Node]) -> Vec<bool> {
        let mut live = vec![false; self.len()];
        for &r in roots {
            live[r as usize] = true;
        }
        for n in (0..self.len()).rev() {
            if live[n] {
                for operand in self.nodes[n].operands() {
                    live[operand as usize] = true;
                }
            }
        }
        live
    }

    /// The part of the graph the `roots` read, rebuilt in a new graph with input k replaced by the
    /// constant `replace[k]` where that is given. The kept inputs are renumbered in order. Returns
    /// the new graph and the roots' nodes in it.
    pub(crate) fn substitute(&self, roots: &[Node], replace: &[Option<f64>]) -> (Graph, Vec<Node>) {
        let mut out = Graph::new();
        let sources: Vec<Node> = self
            .inputs
            .iter()
            .zip(replace)
            .map(|(&value, replacement)| match *replacement {
                Some(c) => out.constant(c),
                None => out.input(value),
            })
            .collect();
        let live = self.live(roots);
        let mut map = vec![0; self.len()];
        for (n, instruction) in self.nodes.iter().enumerate() {
            if !live[n] {
                continue;
            }
            let moved = |r: Node| map[r as usize];
            map[n] = match *instruction {
                Instruction::Input(k) => sources[k as usize],
                Instruction::Const(_) => out.intern(*instruction),
                Instruction::Unary(op, x) => out.rebuild(Instruction::Unary(op, moved(x))),
                Instruction::Binary(op, x, y) => out.rebuild(Instruction::Binary(op, moved(x), moved(y))),
                Instruction::Powi(x, n) => out.rebuild(Instruction::Powi(moved(x), n)),
            };
        }
        let roots = roots.iter().map(|&r| map[r as usize]).collect();
        (out, roots)
    }

    /// The `roots` rebuilt in this graph with input k replaced by node `replace[k]` where that is
    /// given, simplified anew (what a constant replacement makes constant folds). Nodes that read no
    /// replaced input stay as they are.
    pub(crate) fn replace_inputs(&mut self, roots: &[Node], replace: &[Option<Node>]) -> Vec<Node> {
        let live = self.live(roots);
        let mut map: Vec<Node> = (0..live.len() as Node).collect();
        for (n, &is_live) in live.iter().enumerate() {
            if !is_live {
                continue;
            }
            let moved = |r: Node| map[r as usize];
            map[n] = match self.nodes[n] {
                Instruction::Input(k) => replace.get(k as usize).copied().flatten().unwrap_or(n as Node),
                Instruction::Const(_) => n as Node,
                Instruction::Unary(op, x) => self.rebuild(Instruction::Unary(op, moved(x))),
                Instruction::Binary(op, x, y) => self.rebuild(Instruction::Binary(op, moved(x), moved(y))),
                Instruction::Powi(x, k) => self.rebuild(Instruction::Powi(moved(x), k)),
            };
        }
        roots.iter().map(|&r| map[r as usize]).collect()
    }

    /// How many operations (nodes that are neither inputs nor constants) `root` reads, itself
    /// included.
    pub(crate) fn operations(&self, root: Node) -> usize {
        let live = self.live(&[root]);
        let operation = |n: usize| !matches!(self.nodes[n], Instruction::Input(_) | Instruction::Const(_));
        (0..self.len()).filter(|&n| live[n] && operation(n)).count()
    }

    /// Whether any of `roots` reads any of the nodes `sources`, directly or not.
    pub(crate) fn reads(&self, roots: &[Node], sources: &[Node]) -> bool {
        let live = self.live(roots);
        sources.iter().any(|&s| live.get(s as usize).copied().unwrap_or(false))
    }

    /// The straight-line program computing `outputs`: the nodes they read, in order, renumbered.
    /// It reads as many inputs as the graph has.
    pub(crate) fn program(&self, outputs: &[Node]) -> Program {
        let live = self.live(outputs);
        let mut register = vec![0; self.len()];
        let mut instructions = Vec::new();
        for (n, instruction) in self.nodes.iter().enumerate() {
            if live[n] {
                let r = |x: Node| register[x as usize];
                let renumbered = match *instruction {
                    Instruction::Unary(op, x) => Instruction::Unary(op, r(x)),
                    Instruction::Binary(op, x, y) => Instruction::Binary(op, r(x), r(y)),
                    Instruction::Powi(x, k) => Instruction::Powi(r(x), k),
                    leaf => leaf,
                };
                register[n] = instructions.len() as Node;
                instructions.push(renumbered);
            }
        }
        let outputs = outputs.iter().map(|&o| register[o as usize]).collect();
        Program { inputs: self.inputs.len(), instructions, outputs }
    }
}

/// Whether c = ±2ᵏ, a normal number, so that scaling by it is exact.
fn is_power_of_two(c: f64) -> bool {
    c.is_normal() && c.to_bits() & ((1 << 52) - 1) == 0
}
