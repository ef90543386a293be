//! Native code for straight-line programs: the time to compile a program of 300 and of 3000
//! instructions with [`ddirac::compiled::NativeProgram::compile`], and the time to evaluate it natively
//! and with the interpreter [`ddirac::compiled::Program::eval`].
//!
//! The programs are synthetic, shaped like derivative code: mostly products and sums of recent
//! registers, a tenth sines and cosines, a few quotients, squares and constants; 8 inputs, 40 outputs.
//!
//! `cargo bench -p ddirac --bench jit -- --noplot`

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use ddirac::compiled::{Binary, Instruction, NativeProgram, Program, Unary};

const INPUTS: usize = 8;

/// A program of `len` instructions drawn by a fixed xorshift sequence.
fn program(len: usize) -> Program {
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let mut instructions: Vec<Instruction> = (0..INPUTS as u32).map(Instruction::Input).collect();
    while instructions.len() < len {
        let k = instructions.len() as u64;
        let recent = (k - 1 - next() % k.min(20)) as u32;
        let any = (next() % k) as u32;
        instructions.push(match next() % 20 {
            0..=5 => Instruction::Binary(Binary::Mul, recent, any),
            6..=10 => Instruction::Binary(Binary::Add, recent, any),
            11..=13 => Instruction::Binary(Binary::Sub, recent, any),
            14 => Instruction::Binary(Binary::Div, recent, any),
            15 => Instruction::Unary(Unary::Sin, recent),
            16 => Instruction::Unary(Unary::Cos, recent),
            17 => Instruction::constant((next() % 1000) as f64 / 300.0),
            18 => Instruction::Unary(Unary::Neg, recent),
            _ => Instruction::Powi(recent, 2),
        });
    }
    let outputs = (INPUTS as u32..len as u32).step_by(len / 40).take(40).collect();
    Program { inputs: INPUTS, instructions, outputs }
}

fn jit(c: &mut Criterion) {
    let inputs = [0.1, 0.2, -0.3, 0.4, 0.5, -0.6, 0.7, 0.8];
    let mut group = c.benchmark_group("jit");
    group.sample_size(20);
    for len in [300, 3000] {
        let program = program(len);
        group.bench_with_input(BenchmarkId::new("compile", len), &program, |b, program| {
            b.iter(|| NativeProgram::compile(black_box(program)).expect("the host has native code"))
        });
        let native = NativeProgram::compile(&program).expect("the host has native code");
        let mut outputs = vec![0.0; program.outputs.len()];
        group.bench_with_input(BenchmarkId::new("call", len), &native, |b, native| {
            b.iter(|| native.call(black_box(&inputs), black_box(&mut outputs)))
        });
        let mut registers = Vec::new();
        group.bench_with_input(BenchmarkId::new("interpret", len), &program, |b, program| {
            b.iter(|| program.eval(black_box(&inputs), &mut registers, black_box(&mut outputs)))
        });
    }
    group.finish();
}

criterion_group!(benches, jit);
criterion_main!(benches);
