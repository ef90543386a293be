//! Native code for a [`Program`], generated with Cranelift.
//!
//! A program becomes one straight-line function `fn(inputs: *const f64, outputs: *mut f64)`: each
//! instruction is one SSA value, each output is stored as soon as its register is computed.
//!
//! - `+ − × ÷`, −x, 1/x, √x and |x| are single IEEE instructions, so their results equal
//!   [`Program::eval`]'s bit for bit;
//! - the sign of x is a comparison and a select, with [`Unary::Signum`]'s values (0 at ±0, NaN at NaN),
//!   and so are min, max, the indicator x < y and the gate x ≠ 0 ? y : 0;
//! - xⁿ multiplies by repeated squaring, unrolled for the program's n: the same products in the same
//!   order as the runtime routine behind [`f64::powi`] (`__powidf2`), then 1/· for n < 0;
//! - every other function calls, through an `extern "C"` wrapper, the very [`Unary::apply`] or
//!   [`Binary::apply`] the interpreter calls, so its result is the interpreter's.
//!
//! Results therefore equal the interpreter's to the last bit, except for the payload of a NaN.

use std::fmt;
use std::sync::Mutex;

use cranelift_codegen::ir::condcodes::FloatCC;
use cranelift_codegen::ir::immediates::Ieee64;
use cranelift_codegen::ir::{types, AbiParam, InstBuilder, MemFlagsData, SigRef, Signature, Type, Value};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_codegen::Context;
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{default_libcall_names, Module};

use super::program::{Binary, Instruction, MalformedProgram, Program, Register, Unary};

/// Why a program could not be compiled to native code. Unless it is malformed, the program can still be
/// evaluated by [`Program::eval`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum JitError {
    /// Cranelift has no code generator for this processor or operating system.
    #[error("native code is not available on this host ({reason}); the program can only be interpreted")]
    UnsupportedHost {
        /// Cranelift's reason.
        reason: String,
    },
    /// Cranelift failed while generating or loading the code (a defect: please report it with the
    /// program that caused it).
    #[error("native code generation failed while {stage}: {message}")]
    Codegen {
        /// What was being done.
        stage: &'static str,
        /// Cranelift's message.
        message: String,
    },
    /// The program reads a register, input or output it does not have.
    #[error(transparent)]
    Malformed(#[from] MalformedProgram),
}

impl JitError {
    fn codegen(stage: &'static str, error: impl fmt::Display) -> Self {
        JitError::Codegen { stage, message: error.to_string() }
    }
}

/// The compiled function: reads `inputs` numbers from the first pointer, writes `outputs` numbers
/// through the second.
type Entry = unsafe extern "C" fn(*const f64, *mut f64);

/// A [`Program`] compiled to native code. It owns its executable memory and frees it on drop.
///
/// `NativeProgram` is `Send` and `Sync`: the code touches nothing but the slices given to
/// [`NativeProgram::call`] (the functions it calls are pure), and nothing but `drop` touches the
/// memory that holds the code.
///
/// ```
/// use ddirac::compiled::{Binary, Instruction, NativeProgram, Program, Unary};
///
/// // f(x, y) = sin(x)·y, and x itself
/// let program = Program {
///     inputs: 2,
///     instructions: vec![
///         Instruction::Input(0),
///         Instruction::Input(1),
///         Instruction::Unary(Unary::Sin, 0),
///         Instruction::Binary(Binary::Mul, 2, 1),
///     ],
///     outputs: vec![3, 0],
/// };
/// let native = NativeProgram::compile(&program)?;
/// let mut out = [0.0; 2];
/// native.call(&[0.5, 3.0], &mut out);
/// assert_eq!(out, [0.5f64.sin() * 3.0, 0.5]);
/// # Ok::<(), ddirac::compiled::JitError>(())
/// ```
pub struct NativeProgram {
    entry: Entry,
    inputs: usize,
    outputs: usize,
    /// The owner of the memory `entry` points into; taken by `drop` only. The mutex is never
    /// locked: it only makes the owner (`Send` but not `Sync`) shareable.
    module: Option<Mutex<JITModule>>,
}

impl NativeProgram {
    /// Compiles `program` for the host processor.
    ///
    /// Fails when the host has no code generator, when the program reads a register or input it
    /// does not define, or (a defect) when Cranelift fails.
    pub fn compile(program: &Program) -> Result<Self, JitError> {
        program.validate()?;
        let mut module = host_module()?;
        let pointer = module.target_config().pointer_type();
        let mut context = module.make_context();
        context.func.signature.params.push(AbiParam::new(pointer));
        context.func.signature.params.push(AbiParam::new(pointer));
        let id = module
            .declare_anonymous_function(&context.func.signature)
            .map_err(|e| JitError::codegen("declaring the function", e))?;
        emit(program, &module, &mut context);
        module.define_function(id, &mut context).map_err(|e| JitError::codegen("compiling the function", e))?;
        module.clear_context(&mut context);
        module.finalize_definitions().map_err(|e| JitError::codegen("loading the code", e))?;
        let code = module.get_finalized_function(id);
        // SAFETY: `code` is the finalized function declared above with the signature
        // (pointer, pointer) -> () in the host's default calling convention, which is "C".
        let entry = unsafe { std::mem::transmute::<*const u8, Entry>(code) };
        Ok(NativeProgram {
            entry,
            inputs: program.inputs,
            outputs: program.outputs.len(),
            module: Some(Mutex::new(module)),
        })
    }

    /// How many numbers [`NativeProgram::call`] reads.
    pub fn inputs(&self) -> usize {
        self.inputs
    }

    /// How many numbers [`NativeProgram::call`] writes.
    pub fn outputs(&self) -> usize {
        self.outputs
    }

    /// Evaluates the program: reads `inputs`, writes every entry of `outputs`.
    ///
    /// # Panics
    ///
    /// If `inputs.len() != self.inputs()` or `outputs.len() != self.outputs()` (a programming error:
    /// the sizes come from the program, not from the user).
    #[inline]
    pub fn call(&self, inputs: &[f64], outputs: &mut [f64]) {
        assert_eq!(inputs.len(), self.inputs, "wrong number of inputs for a compiled program");
        assert_eq!(outputs.len(), self.outputs, "wrong number of outputs for a compiled program");
        // SAFETY: the code reads `self.inputs` numbers from its first argument and writes
        // `self.outputs` numbers through its second (see `emit`), the lengths just checked; the slices
        // cannot overlap. The code lives as long as `self.module`.
        unsafe { (self.entry)(inputs.as_ptr(), outputs.as_mut_ptr()) }
    }
}

impl Drop for NativeProgram {
    fn drop(&mut self) {
        if let Some(module) = self.module.take() {
            let module = module.into_inner().unwrap_or_else(|poisoned| poisoned.into_inner());
            // SAFETY: `entry`, the only pointer into the module's memory, dies with `self`, and no
            // call can be running: it would borrow `self`.
            unsafe { module.free_memory() }
        }
    }
}

impl fmt::Debug for NativeProgram {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("NativeProgram").field("inputs", &self.inputs).field("outputs", &self.outputs).finish()
    }
}

/// A JIT module for the host processor, optimizing for speed. Cranelift's IR verifier is off: the
/// emitter writes one block of straight-line arithmetic, and verifying it took about a quarter of a
/// compiled run's set-up (callgrind, charged particle).
fn host_module() -> Result<JITModule, JitError> {
    let mut flags = settings::builder();
    let options = [
        ("opt_level", "speed"),
        ("use_colocated_libcalls", "false"),
        ("is_pic", "false"),
        ("enable_verifier", "false"),
    ];
    for (name, value) in options {
        flags.set(name, value).map_err(|e| JitError::codegen("configuring the code generator", e))?;
    }
    let isa = cranelift_native::builder()
        .map_err(|reason| JitError::UnsupportedHost { reason: reason.to_string() })?
        .finish(settings::Flags::new(flags))
        .map_err(|e| JitError::UnsupportedHost { reason: e.to_string() })?;
    Ok(JITModule::new(JITBuilder::with_isa(isa, default_libcall_names())))
}

/// Writes the program's function into `context`: one block, one value per register.
fn emit(program: &Program, module: &JITModule, context: &mut Context) {
    let pointer = module.target_config().pointer_type();
    let mut builder_context = FunctionBuilderContext::new();
    let mut b = FunctionBuilder::new(&mut context.func, &mut builder_context);
    let block = b.create_block();
    b.append_block_params_for_function_params(block);
    b.switch_to_block(block);
    b.seal_block(block);
    let (inputs, outputs) = (b.block_params(block)[0], b.block_params(block)[1]);

    let mut e = Emitter {
        pointer,
        unary: b.import_signature(wrapper_signature(module, 1)),
        binary: b.import_signature(wrapper_signature(module, 2)),
        b,
    };
    // Outputs by register, so that each is stored as soon as it is known.
    let mut stores: Vec<(Register, usize)> = program.outputs.iter().enumerate().map(|(k, &r)| (r, k)).collect();
    stores.sort_unstable();
    let mut stores = stores.into_iter().peekable();
    let mut registers: Vec<Value> = Vec::with_capacity(program.instructions.len());
    for (index, &instruction) in program.instructions.iter().enumerate() {
        let value = match instruction {
            Instruction::Input(i) => e.load(inputs, i as usize),
            Instruction::Const(bits) => e.constant(f64::from_bits(bits)),
            Instruction::Unary(op, x) => e.unary(op, registers[x as usize]),
            Instruction::Binary(op, x, y) => e.binary(op, registers[x as usize], registers[y as usize]),
            Instruction::Powi(x, n) => e.powi(registers[x as usize], n),
        };
        registers.push(value);
        while let Some((_, output)) = stores.next_if(|&(r, _)| r as usize == index) {
            e.store(value, outputs, output);
        }
    }
    e.b.ins().return_(&[]);
    e.b.finalize(module.target_config());
}

/// The signature of an `extern "C" fn(f64, …) -> f64` with `arity` arguments.
fn wrapper_signature(module: &JITModule, arity: usize) -> Signature {
    let mut signature = module.make_signature();
    signature.params.extend(std::iter::repeat_n(AbiParam::new(types::F64), arity));
    signature.returns.push(AbiParam::new(types::F64));
    signature
}

/// Emits the instructions of one program into a function builder.
struct Emitter<'a> {
    b: FunctionBuilder<'a>,
    pointer: Type,
    /// The signature of the one-argument wrappers.
    unary: SigRef,
    /// The signature of the two-argument wrappers.
    binary: SigRef,
}

impl Emitter<'_> {
    fn constant(&mut self, c: f64) -> Value {
        self.b.ins().f64const(Ieee64::with_bits(c.to_bits()))
    }

    /// The address `base + 8·index`, as a base and an offset.
    fn element(&mut self, base: Value, index: usize) -> (Value, i32) {
        let bytes = 8 * index as i64;
        match i32::try_from(bytes) {
            Ok(offset) => (base, offset),
            Err(_) => (self.b.ins().iadd_imm_s(base, bytes), 0),
        }
    }

    fn load(&mut self, inputs: Value, index: usize) -> Value {
        let (base, offset) = self.element(inputs, index);
        self.b.ins().load(types::F64, MemFlagsData::trusted(), base, offset)
    }

    fn store(&mut self, value: Value, outputs: Value, index: usize) {
        let (base, offset) = self.element(outputs, index);
        self.b.ins().store(MemFlagsData::trusted(), value, base, offset);
    }

    fn call(&mut self, signature: SigRef, function: *const u8, args: &[Value]) -> Value {
        let callee = self.b.ins().iconst(self.pointer, function as i64);
        let call = self.b.ins().call_indirect(signature, callee, args);
        self.b.inst_results(call)[0]
    }

    fn unary(&mut self, op: Unary, x: Value) -> Value {
        let function: extern "C" fn(f64) -> f64 = match op {
            Unary::Neg => return self.b.ins().fneg(x),
            Unary::Recip => {
                let one = self.constant(1.0);
                return self.b.ins().fdiv(one, x);
            }
            Unary::Sqrt => return self.b.ins().sqrt(x),
            Unary::Abs => return self.b.ins().fabs(x),
            Unary::Signum => return self.signum(x),
            Unary::Cbrt => wrappers::cbrt,
            Unary::Exp => wrappers::exp,
            Unary::ExpM1 => wrappers::exp_m1,
            Unary::Ln => wrappers::ln,
            Unary::Ln1p => wrappers::ln_1p,
            Unary::Sin => wrappers::sin,
            Unary::Cos => wrappers::cos,
            Unary::Tan => wrappers::tan,
            Unary::Asin => wrappers::asin,
            Unary::Acos => wrappers::acos,
            Unary::Atan => wrappers::atan,
            Unary::Sinh => wrappers::sinh,
            Unary::Cosh => wrappers::cosh,
            Unary::Tanh => wrappers::tanh,
            Unary::Asinh => wrappers::asinh,
            Unary::Acosh => wrappers::acosh,
            Unary::Atanh => wrappers::atanh,
        };
        self.call(self.unary, function as *const u8, &[x])
    }

    fn binary(&mut self, op: Binary, x: Value, y: Value) -> Value {
        let function: extern "C" fn(f64, f64) -> f64 = match op {
            Binary::Add => return self.b.ins().fadd(x, y),
            Binary::Sub => return self.b.ins().fsub(x, y),
            Binary::Mul => return self.b.ins().fmul(x, y),
            Binary::Div => return self.b.ins().fdiv(x, y),
            Binary::Pow => wrappers::pow,
            Binary::Atan2 => wrappers::atan2,
            Binary::Min | Binary::Max | Binary::Less | Binary::Gate => return self.select(op, x, y),
        };
        self.call(self.binary, function as *const u8, &[x, y])
    }

    /// The operations that pick one of two values by a comparison, as [`Binary::apply`] does:
    /// min(x, y) = y < x ? y : x, max(x, y) = y > x ? y : x, x < y ? 1 : 0, and x ≠ 0 ? y : 0
    /// (ordered comparisons, false with a NaN; ≠ is true with a NaN, as in Rust).
    fn select(&mut self, op: Binary, x: Value, y: Value) -> Value {
        let (condition, a, b, then, otherwise) = match op {
            Binary::Min => (FloatCC::LessThan, y, x, y, x),
            Binary::Max => (FloatCC::GreaterThan, y, x, y, x),
            Binary::Less => (FloatCC::LessThan, x, y, self.constant(1.0), self.constant(0.0)),
            _ => (FloatCC::NotEqual, x, self.constant(0.0), y, self.constant(0.0)),
        };
        let holds = self.b.ins().fcmp(condition, a, b);
        self.b.ins().select(holds, then, otherwise)
    }

    /// [`Unary::Signum`]: 0 at ±0, NaN at NaN, ±1 with the sign of x otherwise.
    fn signum(&mut self, x: Value) -> Value {
        let (zero, one, nan) = (self.constant(0.0), self.constant(1.0), self.constant(f64::NAN));
        let unit = self.b.ins().fcopysign(one, x);
        let is_nan = self.b.ins().fcmp(FloatCC::Unordered, x, x);
        let nonzero = self.b.ins().select(is_nan, nan, unit);
        let is_zero = self.b.ins().fcmp(FloatCC::Equal, x, zero);
        self.b.ins().select(is_zero, zero, nonzero)
    }

    /// xⁿ by repeated squaring, as `__powidf2` computes it: for each bit of |n| from the lowest,
    /// multiply the product by the current square if the bit is set, then square; 1/· for n < 0.
    fn powi(&mut self, x: Value, n: i32) -> Value {
        let mut bits = n.unsigned_abs();
        let mut square = x;
        let mut product = None;
        loop {
            if bits & 1 == 1 {
                product = Some(match product {
                    Some(p) => self.b.ins().fmul(p, square),
                    None => square,
                });
            }
            bits >>= 1;
            if bits == 0 {
                break;
            }
            square = self.b.ins().fmul(square, square);
        }
        let product = match product {
            Some(p) => p,
            None => self.constant(1.0),
        };
        if n < 0 {
            let one = self.constant(1.0);
            self.b.ins().fdiv(one, product)
        } else {
            product
        }
    }
}

/// `extern "C"` entry points to [`Unary::apply`] and [`Binary::apply`], one per function.
mod wrappers {
    use super::{Binary, Unary};

    macro_rules! unary {
        ($($name:ident: $op:ident),* $(,)?) => {$(
            pub(super) extern "C" fn $name(x: f64) -> f64 {
                Unary::$op.apply(x)
            }
        )*};
    }

    macro_rules! binary {
        ($($name:ident: $op:ident),* $(,)?) => {$(
            pub(super) extern "C" fn $name(x: f64, y: f64) -> f64 {
                Binary::$op.apply(x, y)
            }
        )*};
    }

    unary!(
        cbrt: Cbrt, exp: Exp, exp_m1: ExpM1, ln: Ln, ln_1p: Ln1p, sin: Sin, cos: Cos, tan: Tan, asin: Asin,
        acos: Acos, atan: Atan, sinh: Sinh, cosh: Cosh, tanh: Tanh, asinh: Asinh, acosh: Acosh, atanh: Atanh,
    );
    binary!(pow: Pow, atan2: Atan2);
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    const UNARY: [Unary; 22] = {
        use Unary::*;
        [
            Neg, Recip, Sqrt, Cbrt, Abs, Signum, Exp, ExpM1, Ln, Ln1p, Sin, Cos, Tan, Asin, Acos, Atan, Sinh, Cosh,
            Tanh, Asinh, Acosh, Atanh,
        ]
    };
    const BINARY: [Binary; 10] = [
        Binary::Add,
        Binary::Sub,
        Binary::Mul,
        Binary::Div,
        Binary::Pow,
        Binary::Atan2,
        Binary::Min,
        Binary::Max,
        Binary::Less,
        Binary::Gate,
    ];

    /// Numbers that exercise signs, zeros, infinities, NaN, subnormals and domain edges.
    fn special() -> impl Iterator<Item = f64> {
        let finite = [0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 2.0, -3.7, 0.999, 1.001, 1e-300, -5e-324, 1e300, -1e300, 710.0];
        finite.into_iter().chain([-745.5, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, std::f64::consts::PI])
    }

    /// Bit-equal, or both NaN (the payload of a NaN is not specified).
    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    /// Runs the program natively and interpreted on `inputs`, and checks that all outputs agree.
    fn check(program: &Program, inputs: &[f64]) {
        let native = NativeProgram::compile(program).unwrap();
        assert_eq!((native.inputs(), native.outputs()), (program.inputs, program.outputs.len()));
        let mut expected = vec![0.0; program.outputs.len()];
        program.eval(inputs, &mut Vec::new(), &mut expected);
        let mut actual = vec![f64::NAN; program.outputs.len()];
        native.call(inputs, &mut actual);
        for (k, (&a, &e)) in actual.iter().zip(&expected).enumerate() {
            assert!(same(a, e), "output {k} at {inputs:?}: native {a:e} ({:#x}), interpreted {e:e}", a.to_bits());
        }
    }

    #[test]
    fn every_unary_operation_matches_the_interpreter_bit_for_bit() {
        let instructions = std::iter::once(Instruction::Input(0)).chain(UNARY.map(|op| Instruction::Unary(op, 0)));
        let program = Program { inputs: 1, instructions: instructions.collect(), outputs: (1..=22).collect() };
        for x in special().chain((-40..=40).map(|k| f64::from(k) * 0.173)) {
            check(&program, &[x]);
        }
    }

    #[test]
    fn signum_is_zero_at_zero_nan_at_nan_and_a_unit_otherwise() {
        let program = Program {
            inputs: 1,
            instructions: vec![Instruction::Input(0), Instruction::Unary(Unary::Signum, 0)],
            outputs: vec![1],
        };
        let native = NativeProgram::compile(&program).unwrap();
        let mut out = [0.0];
        for (x, expected) in [(0.0, 0.0f64), (-0.0, 0.0), (-5e-324, -1.0), (3.0, 1.0), (f64::NEG_INFINITY, -1.0)] {
            native.call(&[x], &mut out);
            assert_eq!(out[0].to_bits(), expected.to_bits(), "signum({x})");
        }
        native.call(&[f64::NAN], &mut out);
        assert!(out[0].is_nan());
    }

    #[test]
    fn every_binary_operation_matches_the_interpreter_bit_for_bit() {
        let instructions = [Instruction::Input(0), Instruction::Input(1)]
            .into_iter()
            .chain(BINARY.map(|op| Instruction::Binary(op, 0, 1)));
        let program = Program { inputs: 2, instructions: instructions.collect(), outputs: (2..12).collect() };
        for x in special() {
            for y in special() {
                check(&program, &[x, y]);
            }
        }
    }

    /// The native xⁿ repeats the products of `__powidf2`, the routine [`f64::powi`] calls when n is
    /// not a compile-time constant (as in the interpreter), so the results are equal bit for bit.
    #[test]
    fn powi_matches_the_interpreter_bit_for_bit() {
        let exponents = [-3, -2, -1, 0, 1, 2, 3, 4, 5, 7, 13, -17, 64, 1000, -1023, i32::MAX, i32::MIN];
        let instructions = std::iter::once(Instruction::Input(0)).chain(exponents.map(|n| Instruction::Powi(0, n)));
        let program = Program {
            inputs: 1,
            instructions: instructions.collect(),
            outputs: (1..=exponents.len() as u32).collect(),
        };
        for x in special().chain((-60..=60).map(|k| 1.0 + f64::from(k) * 0.0371)) {
            check(&program, &[x]);
        }
    }

    #[test]
    fn constants_and_inputs_can_be_outputs() {
        let program = Program {
            inputs: 3,
            instructions: vec![
                Instruction::constant(-2.5),
                Instruction::Input(2),
                Instruction::Input(0),
                Instruction::constant(f64::INFINITY),
            ],
            outputs: vec![0, 1, 2, 3, 1, 0],
        };
        let native = NativeProgram::compile(&program).unwrap();
        let mut out = [0.0; 6];
        native.call(&[1.0, 2.0, 3.0], &mut out);
        assert_eq!(out, [-2.5, 3.0, 1.0, f64::INFINITY, 3.0, -2.5]);
    }

    #[test]
    fn a_program_without_instructions_reads_nothing_and_writes_nothing() {
        let program = Program { inputs: 2, instructions: vec![], outputs: vec![] };
        let native = NativeProgram::compile(&program).unwrap();
        native.call(&[1.0, 2.0], &mut []);
        assert_eq!((native.inputs(), native.outputs()), (2, 0));
    }

    #[test]
    #[should_panic(expected = "wrong number of inputs")]
    fn calling_with_the_wrong_number_of_inputs_panics() {
        let program = Program { inputs: 2, instructions: vec![Instruction::Input(1)], outputs: vec![0] };
        NativeProgram::compile(&program).unwrap().call(&[1.0], &mut [0.0]);
    }

    #[test]
    fn malformed_programs_are_rejected() {
        let forward = Program {
            inputs: 1,
            instructions: vec![Instruction::Input(0), Instruction::Binary(Binary::Add, 0, 1)],
            outputs: vec![],
        };
        assert_eq!(
            NativeProgram::compile(&forward).unwrap_err(),
            JitError::Malformed(MalformedProgram::UndefinedRegister { instruction: 1, register: 1 })
        );
        let input = Program { inputs: 1, instructions: vec![Instruction::Input(1)], outputs: vec![] };
        assert_eq!(
            NativeProgram::compile(&input).unwrap_err(),
            JitError::Malformed(MalformedProgram::UndefinedInput { instruction: 0, input: 1, inputs: 1 })
        );
        let output = Program { inputs: 1, instructions: vec![Instruction::Input(0)], outputs: vec![0, 1] };
        assert_eq!(
            NativeProgram::compile(&output).unwrap_err(),
            JitError::Malformed(MalformedProgram::UndefinedOutput { output: 1, register: 1, registers: 1 })
        );
    }

    #[test]
    fn programs_are_freed_on_drop() {
        let program = Program {
            inputs: 1,
            instructions: vec![Instruction::Input(0), Instruction::Unary(Unary::Sin, 0)],
            outputs: vec![1],
        };
        let mut out = [0.0];
        for k in 0..1000 {
            let native = NativeProgram::compile(&program).unwrap();
            native.call(&[f64::from(k)], &mut out);
            assert_eq!(out[0], f64::from(k).sin());
        }
    }

    #[test]
    fn native_programs_can_be_shared_between_threads() {
        fn send_sync<T: Send + Sync>(_: &T) {}
        let program = Program {
            inputs: 1,
            instructions: vec![Instruction::Input(0), Instruction::Unary(Unary::Exp, 0)],
            outputs: vec![1],
        };
        let native = NativeProgram::compile(&program).unwrap();
        send_sync(&native);
        std::thread::scope(|scope| {
            for k in 0..2 {
                let native = &native;
                scope.spawn(move || {
                    let mut out = [0.0];
                    native.call(&[f64::from(k)], &mut out);
                    assert_eq!(out[0], f64::from(k).exp());
                });
            }
        });
    }

    /// One random instruction: an operation and two operands, chosen modulo the registers before it.
    type Gene = (u8, u32, u32, f64);

    /// A program over `inputs` inputs whose instructions follow `genes`, outputting every fourth
    /// register and the last.
    fn random_program(inputs: usize, genes: &[Gene]) -> Program {
        let mut instructions: Vec<Instruction> = (0..inputs as u32).map(Instruction::Input).collect();
        for &(op, a, b, c) in genes {
            let k = instructions.len() as u32;
            let (a, b) = (a % k, b % k);
            instructions.push(match op % 16 {
                0 => Instruction::constant(c),
                1..=4 => Instruction::Binary(BINARY[(op % 16 - 1) as usize], a, b),
                5 => Instruction::Binary(BINARY[(b % 10) as usize], b, a),
                6 => Instruction::Powi(a, b as i32 % 7 - 3),
                7 => Instruction::Unary(Unary::Sin, a),
                8 => Instruction::Unary(Unary::Cos, a),
                9 => Instruction::Unary(Unary::Neg, a),
                10 => Instruction::Unary(Unary::Sqrt, a),
                11 => Instruction::Unary(Unary::Exp, a),
                12 => Instruction::Unary(Unary::Tanh, a),
                13 => Instruction::Unary(Unary::Signum, a),
                _ => Instruction::Unary(UNARY[(b % 22) as usize], a),
            });
        }
        let registers = instructions.len() as u32;
        let outputs = (0..registers).step_by(4).chain(std::iter::once(registers - 1)).collect();
        Program { inputs, instructions, outputs }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn random_programs_match_the_interpreter_bit_for_bit(
            inputs in prop::collection::vec(-3.0..3.0f64, 1..6),
            genes in prop::collection::vec((any::<u8>(), any::<u32>(), any::<u32>(), -4.0..4.0f64), 1..200),
        ) {
            check(&random_program(inputs.len(), &genes), &inputs);
        }
    }

    #[test]
    fn large_programs_compile() {
        let genes: Vec<Gene> = (0..3000u32)
            .map(|k| ((k.wrapping_mul(2654435761) >> 7) as u8, k.wrapping_mul(40503), k ^ 0x5bd1e995, 0.25))
            .collect();
        check(&random_program(8, &genes), &[0.1, -0.2, 0.3, 0.4, -0.5, 0.6, 0.7, 0.8]);
    }
}
