//! The expression language: values against hand-computed numbers, derivatives against the same
//! Lagrangians written in Rust (paper §7.1 and §7.2), the paper's Table 1 through a Lagrangian given
//! as text, and errors with their exact spans and messages (round trips: `expression_round_trips.rs`).

use ddirac::expression::{
    parse, ExpressionError, ExpressionSpec, ExpressionSystem, Origin, Scope, Span, SyntaxError, FUNCTIONS,
};
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, TABLE_1};
use ddirac::{solve, Coordinate, DiscreteLagrangian, Method, OutputOptions, Rule, System};
use nalgebra::SVector;
use num_dual::{hessian, Dual2SVec64, DualNum};

use crate::pendulum_text;
use pendulum_text::double_spherical_pendulum_spec;

fn assert_close(computed: f64, expected: f64, relative: f64, what: &str) {
    let tolerance = relative * expected.abs().max(1.0);
    assert!((computed - expected).abs() <= tolerance, "{what}: computed {computed:e}, expected {expected:e}");
}

/// Variables x, y, z and constants a = 2, b = 0.5.
fn scope() -> Scope {
    Scope::new().variable("x").variable("y").variable("z").constant("a", 2.0).constant("b", 0.5)
}

const AT: [f64; 3] = [0.7, -1.3, 2.0];

#[test]
fn values_match_hand_computed_numbers() {
    let (x, y, z) = (AT[0], AT[1], AT[2]);
    let cases: &[(&str, f64)] = &[
        ("1", 1.0),
        ("1.5", 1.5),
        (".5", 0.5),
        ("1e-3", 0.001),
        ("2.5E+4", 25000.0),
        ("3.", 3.0),
        ("-x^2", -0.49),
        ("-2^2", -4.0),
        ("(-2)^2", 4.0),
        ("2^3^2", 512.0),
        ("2^-1", 0.5),
        ("1 - 2 - 3", -4.0),
        ("8 / 4 / 2", 1.0),
        ("2 + 3 * 4", 14.0),
        ("+x - -y", -0.6),
        ("a*x^2 + b*y", 0.33),
        ("x/2", 0.35),
        ("2/x", 2.0 / 0.7),
        ("x^3", 0.343),
        ("x^-2", 1.0 / 0.49),
        ("x^1.5", 0.7f64.powf(1.5)),
        ("x^z", 0.49),
        ("pow(x, z)", 0.49),
        ("z^x", 2f64.powf(0.7)),
        ("atan2(y, x)", y.atan2(x)),
        ("min(x, y)", -1.3),
        ("max(x, y)", 0.7),
        ("abs(y)", 1.3),
        ("ln(z) - log(z)", 0.0),
        ("ln(z)", std::f64::consts::LN_2),
        ("sqrt(z)", std::f64::consts::SQRT_2),
        ("exp(x)", x.exp()),
        ("sin(x)*cos(y) - tan(x)", x.sin() * y.cos() - x.tan()),
        ("asin(x) + acos(x)", std::f64::consts::FRAC_PI_2),
        ("atan(y)", y.atan()),
        ("sinh(x) + cosh(y) + tanh(z)", x.sinh() + y.cosh() + z.tanh()),
        ("sin(x)^2 + cos(x)^2", 1.0),
    ];
    for &(source, expected) in cases {
        let program = scope().compile_expression(source).unwrap_or_else(|e| panic!("{source}: {e}"));
        assert_close(program.eval(&AT), expected, 4.0 * f64::EPSILON, source);
    }
}

#[test]
fn constant_subexpressions_are_folded() {
    let program = scope().compile_expression("2*a + sin(0) - b^2").unwrap();
    assert_eq!(program.constant(), Some(3.75));
    assert_eq!(program.instructions(), 0);
    assert_eq!(program.eval(&AT), 3.75);
    // x·(2·a·b) is one scalar product: a load and a multiplication by 2.
    assert_eq!(scope().compile_expression("2*x*a*b").unwrap().instructions(), 2);
}

#[test]
fn repeated_subexpressions_and_definitions_are_computed_once() {
    let scope = scope().definition("s", "sin(x)*y");
    let once = scope.compile_expression("s").unwrap();
    let thrice = scope.compile_expression("s + s*cos(x) + s^2 + (y*sin(x))*z").unwrap();
    // load x, load y, sin_cos(x), product; then ·cos, square, load z, ·z and three sums.
    assert_eq!(once.instructions(), 4);
    assert_eq!(thrice.instructions(), 4 + 7);
    let s = AT[0].sin() * AT[1];
    assert_close(thrice.eval(&AT), s + s * AT[0].cos() + s * s + s * AT[2], 1e-15, "shared");
}

type H3 = Dual2SVec64<3>;

fn compare_hessians(source: &str, reference: impl Fn(H3, H3, H3) -> H3) {
    let program = scope().compile_expression(source).unwrap();
    for at in [AT, [1.1, 0.4, 0.9], [0.3, 2.2, -0.8]] {
        let point = SVector::from(at);
        let (v1, g1, h1) = hessian(|v: SVector<H3, 3>| program.eval(&[v[0], v[1], v[2]]), &point);
        let (v2, g2, h2) = hessian(|v: SVector<H3, 3>| reference(v[0], v[1], v[2]), &point);
        assert_close(v1, v2, 1e-13, source);
        for i in 0..3 {
            assert_close(g1[i], g2[i], 1e-13, source);
            for j in 0..3 {
                assert_close(h1[(i, j)], h2[(i, j)], 1e-12, source);
            }
        }
    }
}

#[test]
fn gradients_and_hessians_match_rust() {
    compare_hessians("x^3*y - sin(x*y)/z", |x, y, z| x.powi(3) * y - (x * y).sin() / z);
    compare_hessians("atan2(y, x) + sqrt(x^2 + y^2)", |x, y, _| y.atan2(x) + (x * x + y * y).sqrt());
    compare_hessians("exp(-x^2/2)*cosh(z) - 3/y", |x, y, z| (-(x * x) * 0.5).exp() * z.cosh() - y.recip() * 3.0);
    let abs = |v: H3| if v.re < 0.0 { -v } else { v };
    compare_hessians("abs(x)^z + 2^y + abs(y)^2.5", |x, y, z| {
        abs(x).powd(z) + (y * 2f64.ln()).exp() + abs(y).powf(2.5)
    });
    compare_hessians("min(x, y)*max(y, z) + tanh(x) - sinh(y)", |x, y, z| {
        let min = if y < x { y } else { x };
        let max = if z > y { z } else { y };
        min * max + x.tanh() - y.sinh()
    });
    compare_hessians("atan(x) + asin(x/4) - acos(y/5) + ln(z^2) + tan(x)", |x, y, z| {
        x.atan() + (x * 0.25).asin() - (y * 0.2).acos() + (z * z).ln() + x.tan()
    });
    compare_hessians("a*(x - b)^4 - (x*y - z)/(a + x^2)", |x, y, z| {
        (x - 0.5).powi(4) * 2.0 - (x * y - z) / (x * x + 2.0)
    });
}

fn charged_particle_spec(m: f64, b0: f64) -> ExpressionSpec {
    let string = |s: &str| s.to_owned();
    ExpressionSpec {
        coordinates: vec![
            Coordinate::shape("x"),
            Coordinate::shape("y"),
            Coordinate::shape("z"),
            Coordinate::group("theta").angle(),
        ],
        lagrangian: string("0.5*m*(x_dot^2 + y_dot^2 + z_dot^2) + 0.5*(Ax*x_dot + Ay*y_dot + theta_dot)^2"),
        definitions: vec![(string("Ax"), string("-B0/2*y")), (string("Ay"), string("B0/2*x"))],
        parameters: vec![(string("m"), m), (string("B0"), b0)],
        exact_solution: vec![
            (string("x"), string("sin(t)")),
            (string("y"), string("cos(t) - 1")),
            (string("z"), string("t")),
        ],
        ..ExpressionSpec::default()
    }
}

/// L, and L_d with D1, D2 and D1D2 for `rule`, agree between two systems at (q0, q1).
fn compare_systems<A: System<4>, B: System<4>>(a: &A, b: &B, rule: Rule, step: f64, q0: [f64; 4], q1: [f64; 4]) {
    let v: [f64; 4] = std::array::from_fn(|i| (q1[i] - q0[i]) / step);
    assert_close(a.lagrangian(&q0, &v), b.lagrangian(&q0, &v), 1e-12, "L");
    let (da, db) = (DiscreteLagrangian::new(a, rule, step), DiscreteLagrangian::new(b, rule, step));
    let (da, db) = (da.derivatives(&q0, &q1), db.derivatives(&q0, &q1));
    let scale = db.d1d2.amax().max(1.0);
    assert_close(da.value, db.value, 1e-12, "L_d");
    for i in 0..4 {
        assert_close(da.d1[i], db.d1[i], 1e-12, "D1 L_d");
        assert_close(da.d2[i], db.d2[i], 1e-12, "D2 L_d");
        for j in 0..4 {
            let (x, y) = (da.d1d2[(i, j)], db.d1d2[(i, j)]);
            assert!((x - y).abs() <= 1e-12 * scale, "D1D2 L_d ({i}, {j}): {x:e} vs {y:e}");
        }
    }
}

#[test]
fn charged_particle_matches_rust() {
    for (m, b0) in [(1.0, 1.0), (1.7, -0.6)] {
        let text = ExpressionSystem::<4>::new(&charged_particle_spec(m, b0)).unwrap();
        let rust = ChargedParticle { m, b0 };
        for rule in [Rule::Left, Rule::Midpoint, Rule::Trapezoid] {
            compare_systems(&text, &rust, rule, 0.1, [0.3, -0.2, 1.0, 0.5], [0.35, -0.1, 1.1, 0.7]);
            compare_systems(&text, &rust, rule, 0.2, [-1.3, 0.8, 0.0, 2.0], [-1.0, 0.6, 0.3, 2.4]);
        }
    }
}

#[test]
fn double_spherical_pendulum_matches_rust() {
    let text = ExpressionSystem::<4>::new(&double_spherical_pendulum_spec()).unwrap();
    let rust = DoubleSphericalPendulum::default();
    assert_eq!(text.coordinates(), rust.coordinates());
    let q0 = [0.0, 2.25, 2.0, 3.0];
    compare_systems(&text, &rust, Rule::Midpoint, 0.01, q0, [0.001, 2.251, 2.0005, 3.002]);
    compare_systems(&text, &rust, Rule::Midpoint, 0.01, [0.4, 1.0, -0.3, 2.0], [0.41, 1.02, -0.29, 1.97]);
    compare_systems(&text, &rust, Rule::Left, 0.05, [-1.0, 0.5, 0.7, 1.5], [-0.9, 0.6, 0.65, 1.45]);
}

#[test]
fn table_1_through_a_lagrangian_given_as_text() {
    let text = ExpressionSystem::<4>::new(&charged_particle_spec(1.0, 1.0)).unwrap();
    let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
    for (steps, printed) in TABLE_1 {
        let (problem, output) =
            (ChargedParticle::paper_problem(steps), OutputOptions { every: steps, wrap_angles: false });
        let from_text = solve(&text, &problem, &method, &output).unwrap().summary;
        let built_in = solve(&ChargedParticle::default(), &problem, &method, &output).unwrap().summary;
        let (e_text, e_rust) = (from_text.reference_error.unwrap(), built_in.reference_error.unwrap());
        assert!((e_text - e_rust).abs() <= 1e-12, "N = {steps}: {e_text} vs {e_rust}");
        assert!((e_text - printed).abs() <= 5e-5 * printed.max(0.1), "N = {steps}: {e_text} vs printed {printed}");
        for (a, b) in from_text.final_q.iter().zip(&built_in.final_q) {
            assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0));
        }
    }
}

#[test]
fn type_erased_system_runs_like_the_built_in_one() {
    let text = double_spherical_pendulum_spec().into_dyn().unwrap();
    let built_in = (ddirac::systems::find("double_spherical_pendulum").unwrap().build)(&[]).unwrap();
    let problem = DoubleSphericalPendulum::paper_problem(10_000);
    let problem = ddirac::Problem { steps: 50, ..problem };
    // The text system declares no atlas: compare in the main chart.
    let method = Method { reduced: true, atlas: false, ..Method::default() };
    let run = |system: &dyn ddirac::DynSystem| {
        system.integrate(&problem, &method, &OutputOptions { every: 50, wrap_angles: false }, &mut |_| Ok(())).unwrap()
    };
    let (a, b) = (run(text.as_ref()), run(built_in.as_ref()));
    assert_eq!(text.coordinates(), built_in.coordinates());
    for (x, y) in a.final_q.iter().zip(&b.final_q).chain(a.final_p.iter().zip(&b.final_p)) {
        assert!((x - y).abs() <= 1e-9 * y.abs().max(1.0), "{x} vs {y}");
    }
}

fn compile_error(source: &str) -> ExpressionError {
    scope().compile_expression(source).expect_err(source)
}

#[test]
fn syntax_errors_have_exact_spans_and_messages() {
    let cases: &[(&str, Span, &str)] = &[
        (
            "1 +",
            Span::new(3, 3),
            "unexpected end of expression; expected an expression (a number, a name, a function call, `(` or a sign)",
        ),
        ("(x", Span::new(2, 2), "missing `)` to close the `(` at 0..1; expected `)` before the end of the expression"),
        (
            "x y",
            Span::new(2, 3),
            "unexpected name `y` after a complete expression; expected an operator or the end of the expression",
        ),
        (
            "2 $ 3",
            Span::new(2, 3),
            "unexpected character `$`; expected a number, a name, an operator, a parenthesis or a comma",
        ),
        ("", Span::new(0, 0), "empty expression; expected a number, a name, a function call or `(`"),
        ("  ", Span::new(0, 2), "empty expression; expected a number, a name, a function call or `(`"),
        ("sin(x y)", Span::new(6, 7), "unexpected name `y`; expected `,`, `)` or an operator"),
        (
            "(x))",
            Span::new(3, 4),
            "unexpected `)` after a complete expression; expected an operator or the end of the expression",
        ),
        ("2e+", Span::new(0, 3), "malformed number `2e+`: expected digits after the exponent marker"),
        (
            "x * é",
            Span::new(4, 6),
            "unexpected character `é`; expected a number, a name, an operator, a parenthesis or a comma",
        ),
    ];
    for &(source, span, message) in cases {
        let ExpressionError::Syntax { origin, error } = compile_error(source) else { panic!("{source}") };
        assert_eq!(origin, Origin::Expression);
        assert_eq!((error.span(), error.to_string().as_str()), (span, message), "{source:?}");
    }
    assert_eq!(
        compile_error("1 +").to_string(),
        "in the expression at 3..3: unexpected end of expression; expected an expression (a number, a name, a \
         function call, `(` or a sign)"
    );
}

#[test]
fn name_errors_have_exact_spans_and_messages() {
    let cases: &[(&str, Span, &str)] = &[
        ("sin(x, y)", Span::new(0, 9), "in the expression at 0..9: `sin` takes 1 argument, but 2 were given"),
        ("atan2(x)", Span::new(0, 8), "in the expression at 0..8: `atan2` takes 2 arguments, but 1 was given"),
        ("foo(x)", Span::new(0, 3), "in the expression at 0..3: unknown function `foo`"),
        ("1 + sinn(x)", Span::new(4, 8), "in the expression at 4..8: unknown function `sinn` (did you mean `sin`?)"),
        ("unknown_var", Span::new(0, 11), "in the expression at 0..11: unknown name `unknown_var`"),
        ("2*x + xx", Span::new(6, 8), "in the expression at 6..8: unknown name `xx` (did you mean `x`?)"),
        ("x(2)", Span::new(0, 1), "in the expression at 0..1: `x` is not a function and cannot be called"),
        ("cos + 1", Span::new(0, 3), "in the expression at 0..3: `cos` is a function; call it as `cos(...)`"),
    ];
    for &(source, span, message) in cases {
        let error = compile_error(source);
        assert_eq!((error.span(), error.to_string().as_str()), (Some(span), message), "{source:?}");
        assert_eq!(error.origin(), Some(&Origin::Expression));
    }
}

#[test]
fn errors_in_definitions_name_the_definition() {
    let mut spec = charged_particle_spec(1.0, 1.0);
    spec.definitions[1].1 = "B1/2*x".into();
    let error = ExpressionSystem::<4>::new(&spec).unwrap_err();
    assert_eq!(error.origin(), Some(&Origin::Definition("Ay".into())));
    assert_eq!(error.span(), Some(Span::new(0, 2)));
    assert_eq!(error.to_string(), "in definition `Ay` at 0..2: unknown name `B1` (did you mean `B0`?)");

    spec.definitions[1].1 = "B0/2*(x".into();
    let error = ExpressionSystem::<4>::new(&spec).unwrap_err();
    assert!(
        matches!(&error, ExpressionError::Syntax { origin: Origin::Definition(d), error: SyntaxError::MissingParen { .. } } if d == "Ay")
    );

    let mut spec = charged_particle_spec(1.0, 1.0);
    spec.lagrangian = "0.5*m*x_dot^2*t".into();
    assert_eq!(
        ExpressionSystem::<4>::new(&spec).unwrap_err().to_string(),
        "in the Lagrangian at 14..15: `t` is not available here: a Lagrangian does not depend on time (`t` is for \
         exact solutions)"
    );
    let mut spec = charged_particle_spec(1.0, 1.0);
    spec.exact_solution[2].1 = "t + x".into();
    let error = ExpressionSystem::<4>::new(&spec).unwrap_err();
    assert_eq!(error.origin(), Some(&Origin::ExactSolution("z".into())));
    assert_eq!(error.span(), Some(Span::new(4, 5)));
}

#[test]
fn cycles_between_definitions_are_reported_with_every_reference() {
    let scope = scope().definition("a1", "b1").definition("b1", "2*a1");
    let ExpressionError::Cycle { origin, span, cycle } = scope.compile_expression("x").unwrap_err() else {
        panic!("expected a cycle")
    };
    assert_eq!((origin, span), (Origin::Definition("b1".into()), Span::new(2, 4)));
    let steps: Vec<_> = cycle.iter().map(|s| (s.origin.clone(), s.name.as_str(), s.span)).collect();
    assert_eq!(
        steps,
        [
            (Origin::Definition("a1".into()), "b1", Span::new(0, 2)),
            (Origin::Definition("b1".into()), "a1", Span::new(2, 4))
        ]
    );
    assert_eq!(
        scope.compile_expression("x").unwrap_err().to_string(),
        "in definition `b1` at 2..4: definitions refer to each other in a cycle: a1 → b1 → a1"
    );
    let error = Scope::new().definition("a", "b").definition("b", "a").compile_expression("1").unwrap_err();
    assert_eq!(error.to_string(), "in definition `b` at 0..1: definitions refer to each other in a cycle: a → b → a");
    let error = Scope::new().definition("s", "s + 1").compile_expression("1").unwrap_err();
    assert_eq!(error.to_string(), "in definition `s` at 0..1: definitions refer to each other in a cycle: s → s");
}

#[test]
fn system_declarations_are_checked() {
    let base = charged_particle_spec(1.0, 1.0);
    let with = |f: &dyn Fn(&mut ExpressionSpec)| {
        let mut spec = base.clone();
        f(&mut spec);
        ExpressionSystem::<4>::new(&spec).unwrap_err().to_string()
    };
    assert_eq!(
        with(&|s| s.coordinates[2] = Coordinate::shape("x_dot")),
        "the name `x_dot` is declared twice: as coordinate `x_dot` and as the velocity of coordinate `x`"
    );
    assert_eq!(
        with(&|s| s.parameters[0].0 = "y".into()),
        "the name `y` is declared twice: as coordinate `y` and as parameter `y`"
    );
    assert_eq!(
        with(&|s| s.coordinates[3] = Coordinate::group("t")),
        "the name `t` is declared twice: as the time `t` (reserved) and as coordinate `t`"
    );
    assert_eq!(
        with(&|s| s.definitions[0].0 = "exp".into()),
        "definition `exp`: invalid name `exp`: it is the name of a function"
    );
    assert_eq!(
        with(&|s| s.coordinates[0] = Coordinate::shape("2x")),
        "coordinate `2x`: invalid name `2x`: a name is a letter or `_` followed by letters, digits and `_`"
    );
    assert_eq!(with(&|s| s.parameters[1].1 = f64::NAN), "parameter `B0` is not finite (NaN)");
    assert_eq!(
        with(&|s| s.exact_solution[0].0 = "thetaa".into()),
        "the exact solution for `thetaa`: `thetaa` is not a coordinate (did you mean `theta`?)"
    );
    assert_eq!(
        with(&|s| s.exact_solution[1].0 = "x".into()),
        "the name `x` is declared twice: as an exact solution for `x` and as an exact solution for `x`"
    );
    assert!(matches!(ExpressionSystem::<3>::new(&base), Err(ExpressionError::Dimension { expected: 3, found: 4 })));
    let empty = ExpressionSpec { lagrangian: "1".into(), ..ExpressionSpec::default() };
    assert!(matches!(empty.into_dyn().err(), Some(ExpressionError::NoCoordinates)));
    // More coordinates than the largest engine size run in a dynamic dimension.
    let many = ExpressionSpec {
        coordinates: (0..101).map(|i| Coordinate::shape(&format!("q{i}"))).collect(),
        lagrangian: "q0_dot^2".into(),
        ..ExpressionSpec::default()
    };
    assert_eq!(many.into_dyn().unwrap().coordinates().len(), 101);
    let sixteen = ExpressionSpec {
        coordinates: (0..16).map(|i| Coordinate::shape(&format!("q{i}"))).collect(),
        lagrangian: "q15_dot^2".into(),
        ..ExpressionSpec::default()
    };
    assert_eq!(sixteen.into_dyn().unwrap().coordinates().len(), 16);
}

#[test]
fn every_function_compiles_with_its_arity() {
    for name in FUNCTIONS {
        let two = matches!(*name, "atan2" | "pow" | "min" | "max");
        let source = if two { format!("{name}(x, 0.5)") } else { format!("{name}(0.5*x)") };
        let program = scope().compile_expression(&source).unwrap_or_else(|e| panic!("{source}: {e}"));
        assert!(program.eval(&AT).is_finite(), "{source}");
    }
}

#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let deep = format!("{}x{}", "(".repeat(5000), ")".repeat(5000));
    assert!(matches!(parse(&deep), Err(SyntaxError::TooDeep { .. })));
    let long = vec!["x"; 5000].join(" + ");
    assert_close(scope().compile_expression(&long).unwrap().eval(&AT), 5000.0 * 0.7, 1e-12, "flat sum");
    let fine = vec!["x"; 900].join(" + ");
    assert_close(scope().compile_expression(&fine).unwrap().eval(&AT), 900.0 * 0.7, 1e-13, "long sum");
    let minus = format!("{}x", "-".repeat(999));
    assert_eq!(scope().compile_expression(&minus).unwrap().eval(&AT), -0.7);
}

/// num-dual's `powi` forms the factors n(n−1) and n(n−1)(n−2) of the second and third derivatives
/// in i32, which 50000·49999 overflows (a panic with overflow checks, a wrong derivative without);
/// such exponents go through `powf`.
#[test]
fn large_integer_exponents_have_exact_derivatives() {
    let program = Scope::new().variable("x").compile_expression("x^50000 - pow(x, -2000) + x^1024").unwrap();
    let (n, m, k) = (50000.0f64, -2000.0f64, 1024.0f64);
    // At x = 1 every derivative is an exact integer.
    let (value, d1, d2, d3) = num_dual::third_derivative(|x| program.eval(&[x]), 1.0);
    assert_eq!(value, 1.0);
    assert_eq!(d1, n - m + k);
    assert_eq!(d2, n * (n - 1.0) - m * (m - 1.0) + k * (k - 1.0));
    assert_eq!(d3, n * (n - 1.0) * (n - 2.0) - m * (m - 1.0) * (m - 2.0) + k * (k - 1.0) * (k - 2.0));
    // Elsewhere, against the closed forms.
    let x = 1.00001f64;
    let (value, d1, d2) = num_dual::second_derivative(|x| program.eval(&[x]), x);
    let term = |n: f64, order: i32| (0..order).map(|j| n - j as f64).product::<f64>() * x.powf(n - order as f64);
    assert_close(value, term(n, 0) - term(m, 0) + term(k, 0), 1e-12, "value");
    assert_close(d1, term(n, 1) - term(m, 1) + term(k, 1), 1e-12, "first derivative");
    assert_close(d2, term(n, 2) - term(m, 2) + term(k, 2), 1e-12, "second derivative");
}

#[test]
fn pi_is_predefined_and_no_declaration_may_take_its_name() {
    use ddirac::expression::{ExpressionSpec, ExpressionSystem};
    use ddirac::{Coordinate, System};
    let spec = |parameters: Vec<(String, f64)>| ExpressionSpec {
        coordinates: vec![Coordinate::shape("x")],
        lagrangian: "pi * x_dot^2".into(),
        definitions: vec![],
        parameters,
        exact_solution: vec![],
        ..ExpressionSpec::default()
    };
    let system = ExpressionSystem::<1>::new(&spec(vec![])).unwrap();
    assert_eq!(system.lagrangian(&[0.0], &[1.0]), std::f64::consts::PI);
    let refused = ExpressionSystem::<1>::new(&spec(vec![("pi".into(), 3.0)]));
    assert!(matches!(refused.err(), Some(ddirac::expression::ExpressionError::InvalidName { .. })));
}
