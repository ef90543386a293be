//! The compiled derivatives against the dual numbers of [`crate::ad`], which compute the same
//! numbers by a different method: both run the same generic code, at random points.

use crate::dim::Fixed;
use crate::Scalar;
use std::cell::Cell;

use num_dual::{DualNum, DualStruct};

use super::graph::Graph;
use super::{pair_programs, Instruction, NotCompiled, PairPrograms, Program, Traced};
use crate::dim::{self, PairFunction};
use crate::expression::{ExpressionSpec, ExpressionSystem};
use crate::systems::{ChargedParticle, DoubleSphericalPendulum, HeavyTop, Kepler, PendulumChain, TwoBody};
use crate::{Coordinate, DiscreteLagrangian, Rule, System};

/// A pair function f(base, a, b), generic over the scalar.
trait Generic<const N: usize> {
    fn eval<D: Scalar>(&self, base: &[D; N], a: &[D; N], b: &[D; N]) -> D;
}

/// f(base, ·, ·) at a fixed base, for the dual numbers.
struct AtBase<'f, G, const N: usize> {
    f: &'f G,
    base: [f64; N],
}

impl<G: Generic<N>, const N: usize> PairFunction<Fixed<N>> for AtBase<'_, G, N> {
    fn eval<D: Scalar>(&self, a: &[D; N], b: &[D; N]) -> D {
        self.f.eval(&self.base.map(D::from), a, b)
    }
}

/// A small deterministic generator of numbers in [−1, 1) (xorshift64*).
struct Random(u64);

impl Random {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        bits as f64 / (1u64 << 52) as f64 - 1.0
    }

    fn point<const N: usize>(&mut self, centre: &[f64; N], radius: f64) -> [f64; N] {
        std::array::from_fn(|i| centre[i] + radius * self.next())
    }
}

fn run(program: &Program, inputs: &[f64]) -> Vec<f64> {
    let mut outputs = vec![0.0; program.outputs.len()];
    program.eval(inputs, &mut Vec::new(), &mut outputs);
    outputs
}

/// Every entry of `compiled` within `tolerance` of `dual`, relative to the largest entry of the block.
fn assert_block_close(what: &str, compiled: &[f64], dual: &[f64], tolerance: f64) {
    let scale = dual.iter().fold(f64::MIN_POSITIVE, |m, x| m.max(x.abs()));
    for (k, (c, d)) in compiled.iter().zip(dual).enumerate() {
        assert!((c - d).abs() <= tolerance * scale, "{what}[{k}]: compiled {c:e}, dual numbers {d:e}");
    }
}

/// Traces `f` at (`base`, `b`), then compares both programs with [`dim::mixed`] at `points` random
/// points within `radius` of it. Returns the programs.
fn compare<G: Generic<N>, const N: usize>(f: &G, base: [f64; N], b: [f64; N], radius: f64) -> PairPrograms {
    let programs = pair_programs(Fixed, |base, a, b| f.eval(base, a, b), &base, &b).expect("the function compiles");
    assert_eq!((programs.first.inputs, programs.mixed.inputs), (2 * N, 2 * N));
    assert_eq!((programs.first.outputs.len(), programs.mixed.outputs.len()), (1 + 2 * N, 1 + 2 * N + N * N));
    let mut random = Random(0x9e37_79b9_7f4a_7c15);
    for _ in 0..8 {
        let (base, b) = (random.point(&base, radius), random.point(&b, radius));
        let inputs: Vec<f64> = base.iter().chain(&b).copied().collect();
        let (first, mixed) = (run(&programs.first, &inputs), run(&programs.mixed, &inputs));
        let dual = dim::mixed(Fixed, &AtBase { f, base }, &[0.0; N], &b);
        assert_eq!(first[..], mixed[..1 + 2 * N], "both programs compute f, ∂f/∂a, ∂f/∂b alike");
        assert_block_close("value", &first[..1], &[dual.value], 1e-13);
        assert_block_close("∂f/∂a", &first[1..1 + N], dual.da.as_slice(), 1e-12);
        assert_block_close("∂f/∂b", &first[1 + N..], dual.db.as_slice(), 1e-12);
        let dadb: Vec<f64> = (0..N * N).map(|k| dual.dadb[(k / N, k % N)]).collect();
        assert_block_close("∂²f/∂a∂b", &mixed[1 + 2 * N..], &dadb, 1e-12);
    }
    programs
}

/// A function that uses every operation a trace records, on arguments inside their domains.
struct EveryOperation;

impl Generic<3> for EveryOperation {
    fn eval<D: Scalar>(&self, base: &[D; 3], a: &[D; 3], b: &[D; 3]) -> D {
        let x: [D; 3] = std::array::from_fn(|i| base[i] + a[i]);
        let y: [D; 3] = std::array::from_fn(|i| base[i] - b[i] * 0.5);
        let p = x[0] * y[1] - y[0] / (x[1] * x[1] + 2.0) + x[2].mul_add(y[2], x[0]);
        let q = (x[0] * x[1] + 1.5).powi(3) + y[2].powi(2) + x[1].powi(-2).recip() + (y[0] + 2.0).powi(-3);
        let r = (x[2] * x[2] + 1.0).powf(2.5) + (y[1] * y[1] + 1.0).powf(0.5) + (x[0] * x[0] + 0.5).powf(3.0);
        let s = (x[1] * x[1] + 1.0).powd(y[0]) + y[1].exp2() + (x[2] * y[0]).exp_m1() + (-x[0]).exp();
        let t = (y[2] * y[2] + 2.0).ln()
            + (x[0] * x[0] + 1.0).log(3.0)
            + (y[1] * y[1] + 0.1).log2()
            + (x[2] * x[2] + 1.0).log10()
            + (y[0] * y[0]).ln_1p();
        let (sin, cos) = (x[1] + y[2]).sin_cos();
        let u = x[0].sin() * y[1].cos() + (x[2] * 0.3).tan() + sin * cos * 2.0;
        let bounded = (x[1] * y[2]).tanh() * 0.9;
        let v = bounded.asin() + bounded.acos() * x[0] + (bounded * 0.5).atan() + x[1].atan2(y[2] + 3.0);
        let w = (x[0] * 0.5).sinh() * y[0].cosh() + bounded.asinh() + (x[2] * x[2] + 1.5).acosh() + bounded.atanh();
        let z = (x[1] * x[1] + 0.3).sqrt()
            + (x[2] * 2.0 + 5.0).cbrt()
            + (y[1] - 4.0).abs() * x[0]
            + (y[2] + 7.0).signum() * y[1];
        let mut acc = [p, q, r, s, t, u, v, w, z].into_iter().sum::<D>() * 0.25;
        acc += [x[0] + 2.0, y[1] + 3.0, x[2] * x[2] + 1.0].into_iter().product::<D>();
        acc -= num_traits::Inv::inv(x[2] * x[2] + 4.0);
        acc *= 1.5;
        acc /= 3.0;
        acc * 2.0 + D::from(10.0) / (y[0] * y[0] + 1.0) - 1.0
    }
}

#[test]
fn every_operation_matches_dual_numbers() {
    compare(&EveryOperation, [0.3, -0.4, 0.5], [0.2, 0.6, -0.3], 0.3);
}

/// L_d(base + a, base + b) of a system.
struct Local<S>(DiscreteLagrangian<S>);

impl<S: System<N>, const N: usize> Generic<N> for Local<S> {
    fn eval<D: Scalar>(&self, base: &[D; N], a: &[D; N], b: &[D; N]) -> D {
        self.0.eval_local(base, a, b)
    }
}

/// Compares `system`'s discrete Lagrangian for `rule` near (q, q + h v) and returns the programs.
fn compare_system<S: System<N>, const N: usize>(system: &S, rule: Rule, step: f64, q: [f64; N]) -> PairPrograms {
    let ld = Local(DiscreteLagrangian::new(system, rule, step));
    let offset = std::array::from_fn(|i| step * (0.3 + 0.1 * i as f64));
    compare(&ld, q, offset, 0.05)
}

#[test]
fn built_in_systems_match_dual_numbers() {
    for rule in Rule::ALL {
        compare_system(&ChargedParticle::default_parameters(), rule, 0.1, [0.3, -0.2, 1.0, 0.5]);
        compare_system(&DoubleSphericalPendulum::default_parameters(), rule, 0.01, [0.0, 2.25, 2.0, 3.0]);
        compare_system(&Kepler::default_parameters(), rule, 0.05, [1.2, 0.4]);
        compare_system(&HeavyTop::default_parameters(), rule, 0.05, [0.1, 0.7, -0.3]);
        compare_system(&TwoBody::default_parameters(), rule, 0.05, [1.0, 0.2, -0.5, 0.3]);
        compare_system(&PendulumChain::<6>::default_parameters(), rule, 0.02, [0.1, -0.2, 0.3, 0.2, -0.1, 0.4]);
    }
}

/// The double spherical pendulum as text (examples/double_spherical_pendulum_expression.toml).
fn double_spherical_pendulum_spec() -> ExpressionSpec {
    let pairs = |list: &[(&str, &str)]| list.iter().map(|&(n, s)| (n.to_owned(), s.to_owned())).collect();
    let angles = ["vartheta1", "phi1", "vartheta2", "phi2"].map(|n| Coordinate::shape(n).angle());
    ExpressionSpec {
        coordinates: angles.to_vec(),
        lagrangian: "0.5*l1^2*m1*(phi1_dot^2 + theta1_dot^2*sin(phi1)^2) + T2 \
                     - g*m1*l1*cos(phi1) - g*m2*(l1*cos(phi1) + l2*cos(phi2))"
            .into(),
        definitions: pairs(&[
            ("theta1", "vartheta1 - vartheta2"),
            ("theta2", "vartheta1 + vartheta2"),
            ("theta1_dot", "vartheta1_dot - vartheta2_dot"),
            ("theta2_dot", "vartheta1_dot + vartheta2_dot"),
            (
                "T2",
                "0.5*m2*(l1^2*phi1_dot^2 + l2^2*phi2_dot^2 + l1^2*theta1_dot^2*sin(phi1)^2 \
                 + l2^2*theta2_dot^2*sin(phi2)^2 + 2*l1*l2*cross)",
            ),
            (
                "cross",
                "phi1_dot*phi2_dot*sin(phi1)*sin(phi2) + phi1_dot*phi2_dot*cos(phi1)*cos(phi2)*cos(theta1 - theta2) \
                 + phi1_dot*theta2_dot*sin(phi2)*sin(theta1 - theta2)*cos(phi1) \
                 - phi2_dot*theta1_dot*sin(phi1)*sin(theta1 - theta2)*cos(phi2) \
                 + theta1_dot*theta2_dot*sin(phi1)*sin(phi2)*cos(theta1 - theta2)",
            ),
        ]),
        parameters: [("m1", 20.0), ("m2", 35.0), ("l1", 500.0), ("l2", 800.0), ("g", 9.8)]
            .map(|(n, v)| (n.to_owned(), v))
            .to_vec(),
        ..ExpressionSpec::default()
    }
}

#[test]
fn expression_system_matches_dual_numbers() {
    let system = ExpressionSystem::<4>::new(&double_spherical_pendulum_spec()).expect("the spec compiles");
    for rule in [Rule::Midpoint, Rule::Trapezoid] {
        compare_system(&system, rule, 0.01, [0.0, 2.25, 2.0, 3.0]);
    }
}

#[test]
fn program_sizes_of_the_paper_systems() {
    // Instructions in all, and those that compute (not inputs or constants).
    let count = |p: &Program| {
        let computing = p.instructions.iter().filter(|i| !matches!(i, Instruction::Input(_) | Instruction::Const(_)));
        (p.instructions.len(), computing.count())
    };
    let sizes = |p: &PairPrograms| (count(&p.first), count(&p.mixed));
    let particle = compare_system(&ChargedParticle::default_parameters(), Rule::Left, 0.1, [0.3, -0.2, 1.0, 0.5]);
    let pendulum =
        compare_system(&DoubleSphericalPendulum::default_parameters(), Rule::Midpoint, 0.01, [0.0, 2.25, 2.0, 3.0]);
    eprintln!("charged particle, left: (first, mixed) = {:?} (instructions, operations)", sizes(&particle));
    eprintln!(
        "double spherical pendulum, midpoint: (first, mixed) = {:?} (instructions, operations)",
        sizes(&pendulum)
    );
}

#[test]
fn branching_on_an_input_dependent_value_is_detected() {
    let branch = |_: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| if a[0].re() > 0.0 { a[0] } else { b[0] };
    assert_eq!(pair_programs(Fixed, branch, &[1.0], &[2.0]), Err(NotCompiled::ValueInspected { operation: "re" }));
}

/// A comparison is answered for the trace point and guarded: the programs report, through their guard
/// outputs, whether a point lies on the branch that was traced.
#[test]
fn comparisons_are_guarded() {
    let larger = |base: &[Traced; 1], _: &[Traced; 1], b: &[Traced; 1]| if base[0] < b[0] { b[0] } else { base[0] };
    let programs = pair_programs(Fixed, larger, &[1.0], &[2.0]).unwrap();
    assert_eq!(programs.guards.len(), 1);
    let at = |base: f64, b: f64| {
        let mut out = [0.0; 4];
        programs.first.eval(&[base, b], &mut Vec::new(), &mut out);
        (out, PairPrograms::holds(&programs.guards, &out[3..]))
    };
    // On the traced branch (base < b): f = b, ∂f/∂a = 0, ∂f/∂b = 1.
    assert_eq!(at(0.5, 3.0), ([3.0, 0.0, 1.0, -1.0], true));
    // Off it (base ≥ b) the guard fails.
    assert!(!at(3.0, 0.5).1);
    assert!(!at(2.0, 2.0).1);
    // A comparison of constants needs no guard.
    let constant = |_: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| {
        if Traced::from(1.0) < Traced::from(2.0) {
            a[0] * b[0]
        } else {
            b[0]
        }
    };
    assert!(pair_programs(Fixed, constant, &[1.0], &[2.0]).unwrap().guards.is_empty());
}

#[test]
fn inspecting_constants_is_allowed() {
    let f = |_: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| {
        let c = Traced::from(2.0).sqrt();
        let scale = if c.re() > 1.0 && c > 1.0 { c.re() } else { 0.0 };
        a[0] * b[0] * scale
    };
    let programs = pair_programs(Fixed, f, &[0.0], &[3.0]).expect("only a constant is inspected");
    assert_eq!(run(&programs.mixed, &[0.0, 3.0]), [0.0, 3.0 * 2f64.sqrt(), 0.0, 2f64.sqrt()]);
}

#[test]
fn unsupported_operations_and_non_finite_values_are_reported() {
    let bessel = |_: &[Traced; 1], a: &[Traced; 1], _: &[Traced; 1]| a[0].sph_j0();
    assert_eq!(pair_programs(Fixed, bessel, &[0.0], &[0.0]), Err(NotCompiled::Unsupported { operation: "sph_j0" }));
    let remainder = |_: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| a[0] % b[0];
    assert_eq!(pair_programs(Fixed, remainder, &[0.0], &[1.0]), Err(NotCompiled::Unsupported { operation: "%" }));
    let constant_bessel = |_: &[Traced; 1], a: &[Traced; 1], _: &[Traced; 1]| a[0] * Traced::from(0.0).sph_j0();
    assert!(pair_programs(Fixed, constant_bessel, &[0.0], &[0.0]).is_ok());
    let root = |_: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| (a[0] + b[0]).sqrt();
    assert!(matches!(pair_programs(Fixed, root, &[0.0], &[-1.0]), Err(NotCompiled::NonFinite { what: "value", .. })));
    assert!(matches!(
        pair_programs(Fixed, root, &[0.0], &[0.0]),
        Err(NotCompiled::NonFinite { what: "first derivative", value }) if value == f64::INFINITY
    ));
}

#[test]
fn a_traced_number_kept_from_another_trace_is_reported() {
    let kept = Cell::new(None);
    let keep = |_: &[Traced; 1], a: &[Traced; 1], _: &[Traced; 1]| {
        let old = kept.get().unwrap_or(a[0]);
        kept.set(Some(a[0]));
        a[0] * old
    };
    assert!(pair_programs(Fixed, keep, &[0.0], &[1.0]).is_ok());
    assert_eq!(pair_programs(Fixed, keep, &[0.0], &[1.0]), Err(NotCompiled::ForeignValue));
}

#[test]
fn equal_expressions_share_nodes_and_trivial_ones_fold() {
    let mut g = Graph::new();
    let (x, y) = (g.input(0.5), g.input(-2.0));
    assert_eq!(g.mul(x, y), g.mul(y, x));
    assert_eq!(g.add(x, y), g.add(y, x));
    let (zero, one) = (g.constant(0.0), g.constant(1.0));
    assert_eq!((g.sub(x, x), g.mul(x, zero), g.div(zero, y)), (zero, zero, zero));
    assert_eq!((g.add(x, zero), g.mul(one, x), g.div(x, one), g.powi(x, 1)), (x, x, x, x));
    let minus_x = g.neg(x);
    assert_eq!((g.neg(minus_x), g.sub(zero, x)), (x, minus_x));
    assert_eq!(g.add(y, minus_x), g.sub(y, x));
    let (two, minus_two) = (g.constant(2.0), g.constant(-2.0));
    let folded = g.binary(super::Binary::Pow, two, minus_two);
    assert_eq!(g.constant_of(folded), Some(0.25));
    let (min, max) = (super::Binary::Min, super::Binary::Max);
    assert_eq!((g.binary(min, x, x), g.binary(max, y, y)), (x, y));
    let (smaller, larger) = (g.binary(min, two, minus_two), g.binary(max, two, minus_two));
    assert_eq!((g.constant_of(smaller), g.constant_of(larger)), (Some(-2.0), Some(2.0)));
}

#[test]
fn expanded_powers_equal_powi_to_the_last_bit() {
    let mut random = Random(42);
    for n in -20..=20 {
        let mut g = Graph::new();
        let x = g.input(0.0);
        let power = g.powi(x, n);
        let program = g.program(&[power]);
        for _ in 0..20 {
            let value = 3.0 * random.next();
            assert_eq!(run(&program, &[value])[0].to_bits(), value.powi(n).to_bits(), "x = {value}, n = {n}");
        }
    }
}
