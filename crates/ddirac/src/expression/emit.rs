//! From the operation graph to a flat program: dead operations are dropped, `sin` and `cos` of one
//! argument become one `sin_cos`, and registers are allocated by linear scan, so that the register
//! count is the largest number of values alive at once. A register is free again after the last
//! instruction that reads it; a result takes the register of its first operand when that operand dies
//! there (sums, differences, negations and scalar updates are then made in place, without copying
//! the number), and otherwise the lowest free register.

use super::eval::{Inst, Program, Result as ProgramResult};
use super::functions::{Binary, Scalar, Unary};
use super::graph::{Node, Operand, Value};

/// The program computing `result` from `nodes`, with `variables` variables.
pub(super) fn program(nodes: &[Node], result: Operand, variables: usize) -> Program {
    let result = match result {
        Operand::Const(c) => {
            return Program { instructions: Vec::new(), registers: 0, variables, result: ProgramResult::Const(c) }
        }
        Operand::Value(v) => v as usize,
    };
    let n = nodes.len();
    let mut live = vec![false; n];
    live[result] = true;
    for i in (0..=result).rev() {
        if live[i] {
            nodes[i].operands().for_each(|o| live[o as usize] = true);
        }
    }

    // sin and cos of one argument: both are computed at the first of the two positions.
    let mut partner: Vec<Option<usize>> = vec![None; n];
    let mut sines = std::collections::HashMap::new();
    for (i, node) in nodes.iter().enumerate().filter(|(i, _)| live[*i]) {
        if let Node::Unary(Unary::Sin, a) = node {
            sines.insert(*a, i);
        }
    }
    for (i, node) in nodes.iter().enumerate().filter(|(i, _)| live[*i]) {
        if let Node::Unary(Unary::Cos, a) = node {
            if let Some(&s) = sines.get(a) {
                (partner[s], partner[i]) = (Some(i), Some(s));
            }
        }
    }
    let position = |i: usize| partner[i].map_or(i, |p| p.min(i));

    let mut last_use = vec![0usize; n];
    for i in (0..n).filter(|&i| live[i]) {
        nodes[i].operands().for_each(|o| last_use[o as usize] = last_use[o as usize].max(position(i)));
    }
    last_use[result] = usize::MAX;

    let mut allocator = Allocator::default();
    let mut register = vec![0u32; n];
    let mut instructions = Vec::new();
    for i in (0..n).filter(|&i| live[i]) {
        if position(i) != i {
            continue;
        }
        let mut operands: Vec<Value> = nodes[i].operands().collect();
        if matches!(nodes[i], Node::Binary(Binary::Add | Binary::Mul, ..))
            && last_use[operands[0] as usize] != i
            && last_use[operands[1] as usize] == i
        {
            operands.swap(0, 1);
        }
        let read: Vec<u32> = operands.iter().map(|&o| register[o as usize]).collect();
        let mut freed = Vec::with_capacity(2);
        for &o in &operands {
            if last_use[o as usize] == i && !freed.contains(&o) {
                allocator.free(register[o as usize]);
                freed.push(o);
            }
        }
        // A result overwrites its first operand's register when that operand dies here, so that
        // updates can be made in place.
        let dst = allocator.take(freed.first().filter(|&&o| o == operands[0]).map(|&o| register[o as usize]));
        register[i] = dst;
        let in_place = read.first() == Some(&dst);
        instructions.push(match nodes[i] {
            Node::Var(var) => Inst::Load { dst, var },
            Node::Const(bits) => Inst::Const { dst, value: f64::from_bits(bits) },
            Node::Unary(op @ (Unary::Sin | Unary::Cos), _) if partner[i].is_some() => {
                let second = allocator.take(None);
                register[partner[i].unwrap_or(i)] = second;
                let (sin, cos) = if op == Unary::Sin { (dst, second) } else { (second, dst) };
                Inst::SinCos { sin, cos, a: read[0] }
            }
            Node::Unary(Unary::Neg, _) if in_place => Inst::ScalarUpdate { op: Scalar::Mul, dst, c: -1.0 },
            Node::Unary(op, _) => Inst::Unary { op, dst, a: read[0] },
            Node::Binary(op @ (Binary::Add | Binary::Sub), _, _) if in_place => Inst::Update { op, dst, b: read[1] },
            Node::Binary(op, _, _) => Inst::Binary { op, dst, a: read[0], b: read[1] },
            Node::Scalar(op @ (Scalar::Add | Scalar::Mul | Scalar::SubFrom), _, c) if in_place => {
                Inst::ScalarUpdate { op, dst, c: f64::from_bits(c) }
            }
            Node::Scalar(op, _, c) => Inst::Scalar { op, dst, a: read[0], c: f64::from_bits(c) },
        });
    }
    Program {
        instructions,
        registers: allocator.in_use.len(),
        variables,
        result: ProgramResult::Register(register[result]),
    }
}

/// Registers in use.
#[derive(Default)]
struct Allocator {
    in_use: Vec<bool>,
}

impl Allocator {
    /// Takes `preferred` if it is free, else the lowest free register.
    fn take(&mut self, preferred: Option<u32>) -> u32 {
        if let Some(r) = preferred.filter(|&r| !self.in_use[r as usize]) {
            self.in_use[r as usize] = true;
            return r;
        }
        match self.in_use.iter().position(|used| !used) {
            Some(r) => {
                self.in_use[r] = true;
                r as u32
            }
            None => {
                self.in_use.push(true);
                (self.in_use.len() - 1) as u32
            }
        }
    }

    fn free(&mut self, register: u32) {
        self.in_use[register as usize] = false;
    }
}
