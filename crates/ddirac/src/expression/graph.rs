//! The expression as a graph of operations in evaluation order, built with constant folding,
//! merging of identical operations, and a few exact algebraic rewrites that move constant factors and
//! terms outward (so that `2*l1*l2*a*b` becomes one product a·b times the folded constant 2·l1·l2, and
//! `l1^2*a^2*b^2` shares a²·b² with `a^2*b^2`) and signs into subtractions.

use std::collections::HashMap;

use super::functions::{Binary, Scalar, Unary};

/// The largest |n| for which `x^n` of a variable is `powi`. num-dual's `powi` multiplies the factors
/// n(n−1) and n(n−1)(n−2) of the second and third derivatives as i32, which overflows beyond
/// |n| = 1290; larger exponents take `powf`, which forms those factors in floating point.
const MAX_POWI: f64 = 1024.0;

/// The index of a node.
pub(super) type Value = u32;

/// An operand: a folded constant or a node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Operand {
    Const(f64),
    Value(Value),
}

/// An operation; f64 constants are stored as bits so that nodes can be merged by hashing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Node {
    /// The i-th variable.
    Var(u32),
    /// A constant as a (dual) number, for operations without a scalar path.
    Const(u64),
    Unary(Unary, Value),
    Binary(Binary, Value, Value),
    Scalar(Scalar, Value, u64),
}

impl Node {
    /// The nodes this one reads.
    pub(super) fn operands(self) -> impl Iterator<Item = Value> {
        let (a, b) = match self {
            Node::Var(_) | Node::Const(_) => (None, None),
            Node::Unary(_, a) | Node::Scalar(_, a, _) => (Some(a), None),
            Node::Binary(_, a, b) => (Some(a), Some(b)),
        };
        a.into_iter().chain(b)
    }
}

/// The nodes built so far, each distinct operation once.
#[derive(Debug, Default)]
pub(super) struct Graph {
    pub(super) nodes: Vec<Node>,
    memo: HashMap<Node, Value>,
}

impl Graph {
    fn intern(&mut self, node: Node) -> Operand {
        Operand::Value(self.intern_value(node))
    }

    fn intern_value(&mut self, node: Node) -> Value {
        let next = self.nodes.len() as Value;
        let value = *self.memo.entry(node).or_insert(next);
        if value == next {
            self.nodes.push(node);
        }
        value
    }

    fn node(&self, value: Value) -> Node {
        self.nodes[value as usize]
    }

    /// The i-th variable.
    pub(super) fn var(&mut self, index: usize) -> Operand {
        self.intern(Node::Var(index as u32))
    }

    fn materialize(&mut self, operand: Operand) -> Value {
        match operand {
            Operand::Value(v) => v,
            Operand::Const(c) => self.intern_value(Node::Const(c.to_bits())),
        }
    }

    pub(super) fn unary(&mut self, op: Unary, a: Operand) -> Operand {
        match (op, a) {
            (_, Operand::Const(c)) => Operand::Const(op.apply(c)),
            (Unary::Neg, Operand::Value(v)) => self.neg(v),
            (Unary::Square, _) => self.mul(a, a),
            (_, Operand::Value(v)) => self.intern(Node::Unary(op, v)),
        }
    }

    pub(super) fn binary(&mut self, op: Binary, a: Operand, b: Operand) -> Operand {
        match (op, a, b) {
            (Binary::Pow, _, _) => self.pow(a, b),
            (_, Operand::Const(x), Operand::Const(y)) => Operand::Const(op.apply(x, &y)),
            (Binary::Add, _, _) => self.add(a, b),
            (Binary::Sub, _, _) => self.sub(a, b),
            (Binary::Mul, _, _) => self.mul(a, b),
            (Binary::Div, _, _) => self.div(a, b),
            _ => {
                let (a, b) = (self.materialize(a), self.materialize(b));
                self.intern(Node::Binary(op, a, b))
            }
        }
    }

    fn commutative(&mut self, op: Binary, x: Value, y: Value) -> Operand {
        self.intern(Node::Binary(op, x.min(y), x.max(y)))
    }

    fn neg(&mut self, v: Value) -> Operand {
        match self.node(v) {
            Node::Unary(Unary::Neg, u) => Operand::Value(u),
            Node::Scalar(Scalar::Mul, u, c) => self.mul_const(u, -f64::from_bits(c)),
            Node::Scalar(Scalar::Add, u, c) => self.sub_from(-f64::from_bits(c), u),
            Node::Scalar(Scalar::SubFrom, u, c) => self.add_const(u, -f64::from_bits(c)),
            Node::Binary(Binary::Sub, a, b) => self.intern(Node::Binary(Binary::Sub, b, a)),
            _ => self.intern(Node::Unary(Unary::Neg, v)),
        }
    }

    fn neg_operand(&mut self, a: Operand) -> Operand {
        self.unary(Unary::Neg, a)
    }

    fn add(&mut self, a: Operand, b: Operand) -> Operand {
        let (x, y) = match (a, b) {
            (Operand::Const(x), Operand::Const(y)) => return Operand::Const(x + y),
            (Operand::Value(v), Operand::Const(c)) | (Operand::Const(c), Operand::Value(v)) => {
                return self.add_const(v, c)
            }
            (Operand::Value(x), Operand::Value(y)) => (x, y),
        };
        match (self.node(x), self.node(y)) {
            (Node::Scalar(Scalar::Add, u, c), _) => {
                let sum = self.add(Operand::Value(u), b);
                self.add(sum, Operand::Const(f64::from_bits(c)))
            }
            (_, Node::Scalar(Scalar::Add, w, c)) => {
                let sum = self.add(a, Operand::Value(w));
                self.add(sum, Operand::Const(f64::from_bits(c)))
            }
            (_, Node::Unary(Unary::Neg, w)) => self.sub(a, Operand::Value(w)),
            (Node::Unary(Unary::Neg, u), _) => self.sub(b, Operand::Value(u)),
            _ => self.commutative(Binary::Add, x, y),
        }
    }

    fn add_const(&mut self, v: Value, c: f64) -> Operand {
        if c == 0.0 {
            return Operand::Value(v);
        }
        match self.node(v) {
            Node::Scalar(Scalar::Add, u, k) => self.add_const(u, f64::from_bits(k) + c),
            Node::Scalar(Scalar::SubFrom, u, k) => self.sub_from(f64::from_bits(k) + c, u),
            _ => self.intern(Node::Scalar(Scalar::Add, v, c.to_bits())),
        }
    }

    fn sub(&mut self, a: Operand, b: Operand) -> Operand {
        let (x, y) = match (a, b) {
            (Operand::Const(x), Operand::Const(y)) => return Operand::Const(x - y),
            (Operand::Value(v), Operand::Const(c)) => return self.add_const(v, -c),
            (Operand::Const(c), Operand::Value(v)) => return self.sub_from(c, v),
            (Operand::Value(x), Operand::Value(y)) => (x, y),
        };
        match (self.node(x), self.node(y)) {
            (Node::Scalar(Scalar::Add, u, c), _) => {
                let difference = self.sub(Operand::Value(u), b);
                self.add(difference, Operand::Const(f64::from_bits(c)))
            }
            (_, Node::Scalar(Scalar::Add, w, c)) => {
                let difference = self.sub(a, Operand::Value(w));
                self.add(difference, Operand::Const(-f64::from_bits(c)))
            }
            (_, Node::Unary(Unary::Neg, w)) => self.add(a, Operand::Value(w)),
            (Node::Unary(Unary::Neg, u), _) => {
                let sum = self.add(Operand::Value(u), b);
                self.neg_operand(sum)
            }
            _ => self.intern(Node::Binary(Binary::Sub, x, y)),
        }
    }

    /// c − v
    fn sub_from(&mut self, c: f64, v: Value) -> Operand {
        match self.node(v) {
            Node::Unary(Unary::Neg, u) => self.add_const(u, c),
            Node::Scalar(Scalar::Add, u, k) => self.sub_from(c - f64::from_bits(k), u),
            Node::Scalar(Scalar::SubFrom, u, k) => self.add_const(u, c - f64::from_bits(k)),
            _ if c == 0.0 => self.neg(v),
            _ => self.intern(Node::Scalar(Scalar::SubFrom, v, c.to_bits())),
        }
    }

    fn mul(&mut self, a: Operand, b: Operand) -> Operand {
        let (x, y) = match (a, b) {
            (Operand::Const(x), Operand::Const(y)) => return Operand::Const(x * y),
            (Operand::Value(v), Operand::Const(c)) | (Operand::Const(c), Operand::Value(v)) => {
                return self.mul_const(v, c)
            }
            (Operand::Value(x), Operand::Value(y)) => (x, y),
        };
        match (self.node(x), self.node(y)) {
            (Node::Scalar(Scalar::Mul, u, c), _) => {
                let product = self.mul(Operand::Value(u), b);
                self.mul(product, Operand::Const(f64::from_bits(c)))
            }
            (_, Node::Scalar(Scalar::Mul, w, c)) => {
                let product = self.mul(a, Operand::Value(w));
                self.mul(product, Operand::Const(f64::from_bits(c)))
            }
            (Node::Unary(Unary::Neg, u), _) => {
                let product = self.mul(Operand::Value(u), b);
                self.neg_operand(product)
            }
            (_, Node::Unary(Unary::Neg, w)) => {
                let product = self.mul(a, Operand::Value(w));
                self.neg_operand(product)
            }
            _ if x == y => self.intern(Node::Unary(Unary::Square, x)),
            _ => self.commutative(Binary::Mul, x, y),
        }
    }

    fn mul_const(&mut self, v: Value, c: f64) -> Operand {
        if c == 1.0 {
            return Operand::Value(v);
        }
        if c == -1.0 {
            return self.neg(v);
        }
        match self.node(v) {
            Node::Scalar(Scalar::Mul, u, k) => self.mul_const(u, f64::from_bits(k) * c),
            Node::Scalar(Scalar::DivInto, u, k) => self.div_into(f64::from_bits(k) * c, u),
            Node::Unary(Unary::Neg, u) => self.mul_const(u, -c),
            _ => self.intern(Node::Scalar(Scalar::Mul, v, c.to_bits())),
        }
    }

    fn div(&mut self, a: Operand, b: Operand) -> Operand {
        let (x, y) = match (a, b) {
            (Operand::Const(x), Operand::Const(y)) => return Operand::Const(x / y),
            (Operand::Value(v), Operand::Const(c)) => return self.mul_const(v, c.recip()),
            (Operand::Const(c), Operand::Value(v)) => return self.div_into(c, v),
            (Operand::Value(x), Operand::Value(y)) => (x, y),
        };
        match (self.node(x), self.node(y)) {
            (Node::Scalar(Scalar::Mul, u, c), _) => {
                let quotient = self.div(Operand::Value(u), b);
                self.mul(quotient, Operand::Const(f64::from_bits(c)))
            }
            (_, Node::Scalar(Scalar::Mul, w, c)) => {
                let quotient = self.div(a, Operand::Value(w));
                self.mul(quotient, Operand::Const(f64::from_bits(c).recip()))
            }
            (Node::Unary(Unary::Neg, u), _) => {
                let quotient = self.div(Operand::Value(u), b);
                self.neg_operand(quotient)
            }
            (_, Node::Unary(Unary::Neg, w)) => {
                let quotient = self.div(a, Operand::Value(w));
                self.neg_operand(quotient)
            }
            _ => self.intern(Node::Binary(Binary::Div, x, y)),
        }
    }

    /// c / v
    fn div_into(&mut self, c: f64, v: Value) -> Operand {
        match self.node(v) {
            Node::Scalar(Scalar::Mul, u, k) => self.div_into(c / f64::from_bits(k), u),
            Node::Unary(Unary::Neg, u) => self.div_into(-c, u),
            _ if c == 1.0 => self.intern(Node::Unary(Unary::Recip, v)),
            _ => self.intern(Node::Scalar(Scalar::DivInto, v, c.to_bits())),
        }
    }

    /// a^b: `powi` for an integer constant exponent with |b| ≤ [`MAX_POWI`], `powf` for another
    /// constant exponent, exp(b ln a) otherwise.
    fn pow(&mut self, a: Operand, b: Operand) -> Operand {
        let integer = |n: f64| n.fract() == 0.0 && n.abs() <= i32::MAX as f64;
        match (a, b) {
            (Operand::Const(x), Operand::Const(n)) if integer(n) => Operand::Const(x.powi(n as i32)),
            (Operand::Const(x), Operand::Const(n)) => Operand::Const(x.powf(n)),
            (Operand::Value(v), Operand::Const(n)) if integer(n) && n.abs() <= MAX_POWI => match n as i32 {
                0 => Operand::Const(1.0),
                1 => a,
                2 => self.mul(a, a),
                -1 => self.div_into(1.0, v),
                _ => self.intern(Node::Scalar(Scalar::Powi, v, n.to_bits())),
            },
            (Operand::Value(v), Operand::Const(n)) => self.intern(Node::Scalar(Scalar::Powf, v, n.to_bits())),
            (Operand::Const(x), Operand::Value(_)) => {
                let exponent = self.mul(b, Operand::Const(x.ln()));
                self.unary(Unary::Exp, exponent)
            }
            (Operand::Value(x), Operand::Value(y)) => self.intern(Node::Binary(Binary::Pow, x, y)),
        }
    }
}
