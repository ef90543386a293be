//! A flat sum of about a thousand terms was refused as "nested too deeply", and the report quoted the
//! whole line of the spec (92 KB for a generated Lagrangian). A spec with a long sum now runs, and a
//! report about a long line quotes a window of it, with the line and column of the place. (The
//! library's side, a sum of 10⁵ terms, is tested in the crate ddirac.)

use crate::common;

use common::{assert_fails, check, succeed, TempDir};

/// x_dot^2 + x + x + … + x with `terms` terms x.
fn flat_sum(terms: usize) -> String {
    format!("x_dot^2 + {}", vec!["x"; terms].join(" + "))
}

/// A spec whose Lagrangian is `lagrangian`, on one line.
fn spec(lagrangian: &str) -> String {
    format!(
        "[system]\nshape = [\"x\"]\nlagrangian = \"{lagrangian}\"\n[parameters]\n[time]\nsteps = 10\nstep = 0.01\n\
         [initial]\nq = [0.0]\np = [0.0]\n"
    )
}

#[test]
fn a_spec_with_a_sum_of_five_thousand_terms_runs() {
    let dir = TempDir::new("flat-sum");
    let finished = succeed(&dir.file("spec.toml", &spec(&flat_sum(5000))), &[], &dir);
    // L = ẋ² + 5000 x: the force 5000 accelerates the mass 2 at 2500, x(0.1) = 1250 · 0.01.
    let x = finished.final_q()[0];
    assert!((x - 12.5).abs() < 1e-9, "{x}");
}

#[test]
fn an_error_in_a_long_line_is_shown_in_a_window_of_it() {
    let dir = TempDir::new("long-line");
    let mut terms = vec!["x"; 20_000];
    terms[12_345] = "y";
    let lagrangian = format!("x_dot^2 + {}", terms.join(" + "));
    let text = spec(&lagrangian);
    let line = text.lines().nth(2).unwrap();
    assert!(line.len() > 80_000);
    let column = line.find(" y ").unwrap() + 2;

    let stderr = assert_fails(&check(&dir.file("spec.toml", &text), &[], &dir), &dir, &["unknown name `y`"]);
    assert!(stderr.len() < 2000, "the report is {} bytes long:\n{}", stderr.len(), &stderr[..2000]);
    let place = format!("at line 3, column {column} of {} characters", line.chars().count());
    let lines: Vec<&str> = stderr.lines().collect();
    let at = lines.iter().position(|l| l.contains(&place)).unwrap_or_else(|| panic!("no `{place}`:\n{stderr}"));
    // The excerpt, and `^` under the `y` in it.
    let (excerpt, marks): (Vec<char>, Vec<char>) = (lines[at + 1].chars().collect(), lines[at + 2].chars().collect());
    assert!((60..=120).contains(&excerpt.len()), "{}", lines[at + 1]);
    let first = marks.iter().position(|&c| c == '^').expect("a mark");
    let count = marks.iter().filter(|&&c| c == '^').count();
    assert_eq!((excerpt[first], count), ('y', 1), "{stderr}");
}
