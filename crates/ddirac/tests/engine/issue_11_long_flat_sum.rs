//! A flat sum of about a thousand terms was refused as "nested too deeply". Chains of `+ -` and
//! `* /` are now read in a loop into one node, so their length costs no depth in the parser nor in
//! any pass over the tree (compiling, evaluating, tracing, differentiating), while real nesting is
//! still refused cleanly. The report of the command line is tested in the crate ddirac-cli.

use ddirac::compiled::{pair_programs, Traced};
use ddirac::dim::Fixed;
use ddirac::dim::{self, PairFunction};
use ddirac::expression::{parse, CompiledExpression, ExprKind, ExpressionSpec, ExpressionSystem, Scope, SyntaxError};
use ddirac::{solve, Coordinate, Differentiation, InitialMomentum, Method, OutputOptions, Problem};

const TERMS: usize = 100_000;

/// x_dot^2 + x + x + … + x with `terms` terms x.
fn flat_sum(terms: usize) -> String {
    format!("x_dot^2 + {}", vec!["x"; terms].join(" + "))
}

/// L(x, ẋ) as a function of the two blocks (x) and (ẋ).
struct Lagrangian<'p>(&'p CompiledExpression);

impl PairFunction<Fixed<1>> for Lagrangian<'_> {
    fn eval<D: ddirac::Scalar>(&self, a: &[D; 1], b: &[D; 1]) -> D {
        self.0.eval(&[a[0], b[0]])
    }
}

/// Runs in the test's own thread, whose stack is the default one (2 MiB).
#[test]
fn a_sum_of_a_hundred_thousand_terms_parses_compiles_and_differentiates() {
    let source = flat_sum(TERMS);
    let expr = parse(&source).unwrap();
    let ExprKind::Chain { rest, .. } = &expr.kind else { panic!("a sum is one chain") };
    assert_eq!(rest.len(), TERMS);
    // The printed tree reads back to the same text.
    assert_eq!(parse(&expr.to_string()).unwrap().to_string(), expr.to_string());

    let program = Scope::new().variable("x").variable("x_dot").compile_expression(&source).unwrap();
    let (x, v) = (0.7, 0.3);
    let expected = v * v + TERMS as f64 * x;
    assert!((program.eval(&[x, v]) - expected).abs() <= 1e-9 * expected);
    // By dual numbers: ∂L/∂x = n, ∂L/∂ẋ = 2ẋ.
    let d = dim::first(Fixed, &Lagrangian(&program), &[x], &[v]);
    assert!((d.value - expected).abs() <= 1e-9 * expected);
    assert!((d.da[0] - TERMS as f64).abs() <= 1e-9 * TERMS as f64);
    assert!((d.db[0] - 2.0 * v).abs() <= 1e-12);

    // Traced and differentiated symbolically: f(base, a, b) = L(base + a, b − a).
    let f = |base: &[Traced; 1], a: &[Traced; 1], b: &[Traced; 1]| {
        program.eval_with(|i| if i == 0 { base[0] + a[0] } else { b[0] - a[0] })
    };
    let programs = pair_programs(Fixed, f, &[x], &[v]).unwrap();
    let mut out = [0.0; 3];
    programs.first.eval(&[x, v], &mut Vec::new(), &mut out);
    // f = (b − a)² + n (base + a) at a = 0: value, ∂f/∂a = n − 2b, ∂f/∂b = 2b.
    let n = TERMS as f64;
    for (computed, exact) in out.iter().zip([expected, n - 2.0 * v, 2.0 * v]) {
        assert!((computed - exact).abs() <= 1e-9 * exact.abs(), "{out:?}");
    }
}

#[test]
fn a_system_with_a_long_sum_integrates() {
    // L = ½ ẋ² − k x with the force k written as a sum of a thousand terms 0.001: free fall.
    let force = vec!["0.001*x"; 1000].join(" + ");
    let spec = ExpressionSpec {
        coordinates: vec![Coordinate::shape("x")],
        lagrangian: format!("0.5*x_dot^2 - ({force})"),
        ..Default::default()
    };
    let system = ExpressionSystem::<1>::new(&spec).unwrap();
    let problem = Problem::new(0.1, 10, vec![0.0], InitialMomentum::Momentum(vec![0.0]));
    let method = Method { differentiation: Differentiation::Dual, ..Method::default() };
    let solution = solve(&system, &problem, &method, &OutputOptions::default()).unwrap();
    // Constant force 1: x(t) = −t²/2, which the midpoint rule follows exactly.
    let q = solution.summary.final_q[0];
    assert!((q + 0.5).abs() < 1e-12, "{q}");
}

#[test]
fn ten_thousand_parentheses_are_an_error_not_a_crash() {
    let deep = format!("{}x{}", "(".repeat(10_000), ")".repeat(10_000));
    assert!(matches!(parse(&deep), Err(SyntaxError::TooDeep { .. })));
    let powers = vec!["x"; 10_000].join("^");
    assert!(matches!(parse(&powers), Err(SyntaxError::TooDeep { .. })));
    assert!(Scope::new().variable("x").compile_expression(&deep).is_err());
}
