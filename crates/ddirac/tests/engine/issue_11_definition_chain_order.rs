//! A chain of definitions, each using the previous one, overflowed the stack and aborted the process
//! when the definitions were declared last first (4000 of them in a spec): each definition was
//! lowered inside the lowering of the one that uses it. Definitions are now ordered, dependencies
//! first, by a search without recursion, and lowered one after the other.

use ddirac::expression::{ExpressionError, Origin, Scope, Span};

const LENGTH: usize = 20_000;

/// x, with the definitions a1 = x, a_k = a_{k−1}² − a_{k−1}, declared from a_LENGTH down to a1.
fn reversed_chain() -> Scope {
    let mut scope = Scope::new().variable("x");
    for k in (2..=LENGTH).rev() {
        scope = scope.definition(&format!("a{k}"), &format!("a{p}*a{p} - a{p}", p = k - 1));
    }
    scope.definition("a1", "x")
}

/// Runs in the test's own thread, whose stack is the default one (2 MiB).
#[test]
fn a_long_chain_declared_last_first_compiles() {
    let program = reversed_chain().compile_expression(&format!("a{LENGTH} + 1")).unwrap();
    let x = 0.3;
    let mut a = x;
    for _ in 2..=LENGTH {
        a = a * a - a;
    }
    assert_eq!(program.eval(&[x]), a + 1.0);
    // Each definition is computed once: two operations per link of the chain.
    assert!(program.instructions() <= 2 * LENGTH + 2, "{}", program.instructions());
}

#[test]
fn a_long_cycle_names_every_reference() {
    // a1 uses a2, …, a_n uses a1; declared in order.
    let n = 5000;
    let mut scope = Scope::new().variable("x");
    for k in 1..=n {
        scope = scope.definition(&format!("a{k}"), &format!("x + a{}", k % n + 1));
    }
    let Err(ExpressionError::Cycle { origin, span, cycle }) = scope.compile_expression("a1") else { panic!("a cycle") };
    assert_eq!((origin, span), (Origin::Definition(format!("a{n}")), Span::new(4, 6)));
    assert_eq!(cycle.len(), n);
    for (k, step) in cycle.iter().enumerate() {
        assert_eq!(step.origin, Origin::Definition(format!("a{}", k + 1)));
        assert_eq!(step.name, format!("a{}", (k + 1) % n + 1));
    }
    // The message shows the ends of the cycle.
    let message = scope.compile_expression("a1").unwrap_err().to_string();
    let ends = "a1 → a2 → a3 → a4 → a5 → a6 → a7 → a8 → … (4985 more) → a4994 → a4995 → a4996 → a4997 → a4998 → a4999 \
                → a5000 → a1";
    assert!(message.ends_with(ends), "{message}");
}

#[test]
fn errors_inside_the_chain_name_their_definition() {
    let scope = reversed_chain().definition("a777", "a776*b");
    let Err(ExpressionError::UnknownName { origin, name, .. }) = scope.compile_expression("a10") else {
        panic!("an unknown name")
    };
    assert_eq!((origin, name.as_str()), (Origin::Definition("a777".into()), "b"));
}
