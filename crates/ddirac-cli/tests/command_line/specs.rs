//! Specs with a `[system]` table: errors in the Lagrangian, the definitions, the exact solution and
//! the coordinate lists are reported at the characters they concern (the tests read the underlined
//! characters back from the report), and initial values may be given by coordinate name.

use crate::common;

use common::{assert_fails, example, run, succeed, underlined, TempDir};

/// A small system: a particle on a line in a potential well, with one definition.
const WELL: &str = r#"
[system]
name = "well"
shape = ["x"]
group = ["y"]
lagrangian = "0.5*m*(x_dot^2 + y_dot^2) - V"
[system.definitions]
V = "0.5*k*x^2"
[parameters]
m = 2.0
k = 8.0
[method]
rule = "midpoint"
[time]
steps = 100
duration = 1.0
[initial]
q = { x = 1.0, y = 0.0 }
p = { x = 0.0, y = 2.0 }
"#;

/// `WELL` with `from` replaced by `to`, written to `dir`.
fn well(dir: &TempDir, from: &str, to: &str) -> String {
    assert!(WELL.contains(from), "WELL has no `{from}`");
    dir.file("spec.toml", &WELL.replacen(from, to, 1))
}

#[test]
fn the_well_runs_and_follows_its_exact_solution() {
    let dir = TempDir::new("well");
    let exact = "[system.exact]\nx = \"cos(2*t)\"\ny = \"t\"\n[parameters]";
    let finished = succeed(&well(&dir, "[parameters]", exact), &[], &dir);
    // ω = sqrt(k/m) = 2, x(t) = cos 2t, y(t) = p_y t / m = t; midpoint error O(h²) with h = 0.01.
    let error = finished.summary["reference_error"].as_f64().unwrap();
    assert!(error > 1e-7 && error < 1e-4, "{error}");
    assert_eq!(finished.summary["system"], "well");
    assert_eq!(finished.summary["parameters"]["k"], 8.0);
}

#[test]
fn a_syntax_error_is_underlined_in_the_lagrangian() {
    let dir = TempDir::new("syntax");
    let spec = well(&dir, "y_dot^2) - V", "y_dot^2) - * V");
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["invalid `[system]`: in the Lagrangian: unexpected `*`"]);
    assert_eq!(underlined(&stderr, "lagrangian = "), ["*"]);
    assert!(!stderr.contains(" at 3"), "byte offsets leak into the message:\n{stderr}");
}

#[test]
fn an_unknown_name_is_underlined_in_its_definition() {
    let dir = TempDir::new("unknown");
    let spec = well(&dir, "0.5*k*x^2", "0.5*kappa*x^2");
    let stderr = assert_fails(
        &run(&spec, &[], &dir),
        &dir,
        &["in definition `V`: unknown name `kappa`", "the parameters (m, k)", "the definitions (V)"],
    );
    assert_eq!(underlined(&stderr, "V = "), ["kappa"]);
}

#[test]
fn a_cycle_of_definitions_underlines_each_reference() {
    let dir = TempDir::new("cycle");
    let spec = well(&dir, "V = \"0.5*k*x^2\"", "V = \"0.5*k*x^2 + W\"\nW = \"V/2\"");
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["definitions refer to each other in a cycle"]);
    assert_eq!(underlined(&stderr, "V = "), ["W"]);
    assert_eq!(underlined(&stderr, "W = "), ["V"]);
}

#[test]
fn errors_in_multi_line_and_literal_strings_are_exact_and_escaped_strings_are_labelled_whole() {
    let dir = TempDir::new("strings");
    let spec = well(
        &dir,
        "lagrangian = \"0.5*m*(x_dot^2 + y_dot^2) - V\"",
        "lagrangian = '''\n0.5*m*x_dot^2\n  - sin(x, y)'''",
    );
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["`sin` takes 1 argument, but 2 were given"]);
    assert_eq!(underlined(&stderr, "  - sin"), ["sin(x, y)"]);

    let spec = well(&dir, "0.5*k*x^2", "0.5*k*x^2 + \\u0062ad");
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["unknown name `bad`"]);
    assert_eq!(underlined(&stderr, "V = "), ["\"0.5*k*x^2 + \\u0062ad\""]);
    assert!(stderr.contains("bytes 12..15 of this string"), "{stderr}");
}

#[test]
fn the_exact_solution_may_use_time_and_parameters_only() {
    let dir = TempDir::new("exact");
    let spec = well(&dir, "[parameters]", "[system.exact]\nx = \"cos(2*t) + y\"\n[parameters]");
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["in the exact solution for `x`: `y` is not available"]);
    assert_eq!(underlined(&stderr, "x = \"cos"), ["y"]);

    let spec = well(&dir, "[parameters]", "[system.exact]\nz = \"t\"\n[parameters]");
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["`z` is not a coordinate"]);
    assert_eq!(underlined(&stderr, "z = \"t\""), ["z"]);
}

#[test]
fn a_coordinate_in_two_lists_is_refused_at_both() {
    let dir = TempDir::new("two-lists");
    let spec = well(&dir, "group = [\"y\"]", "group = [\"y\", \"x\"]");
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["coordinate `x` is listed in both `shape` and `group`"]);
    assert_eq!(underlined(&stderr, "shape = "), ["\"x\""]);
    assert_eq!(underlined(&stderr, "group = "), ["\"x\""]);
}

#[test]
fn angles_order_and_duplicates_are_checked_against_the_coordinates() {
    let dir = TempDir::new("lists");
    let spec = well(&dir, "group = [\"y\"]", "group = [\"y\"]\nangles = [\"z\"]");
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["`z` in `system.angles` is not a coordinate"]);
    assert_eq!(underlined(&stderr, "angles = "), ["\"z\""]);

    let spec = well(&dir, "group = [\"y\"]", "group = [\"y\"]\norder = [\"y\"]");
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["not a permutation of the coordinates: it misses x"]);
    assert_eq!(underlined(&stderr, "order = "), ["[\"y\"]"]);

    let spec = well(&dir, "group = [\"y\"]", "group = [\"y\", \"y\"]");
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["`y` appears twice in `system.group`"]);
    assert_eq!(underlined(&stderr, "group = "), ["\"y\"", "\"y\""]);

    let spec = well(&dir, "shape = [\"x\"]", "shape = []");
    let spec_text = std::fs::read_to_string(&spec).unwrap();
    let spec = dir.file("spec.toml", &spec_text.replace("group = [\"y\"]", "group = []"));
    assert_fails(&run(&spec, &[], &dir), &dir, &["the `[system]` table declares no coordinates"]);
}

#[test]
fn the_order_key_reorders_the_coordinates() {
    let dir = TempDir::new("order");
    let spec = well(&dir, "group = [\"y\"]", "group = [\"y\"]\norder = [\"y\", \"x\"]");
    let finished = succeed(&spec, &[], &dir);
    assert_eq!(finished.summary["coordinates"], serde_json::json!(["y", "x"]));
    // By name, the initial data do not depend on the order: y(1) = p_y / m = 1, x(1) ≈ cos 2.
    let q = finished.final_q();
    assert!((q[0] - 1.0).abs() < 1e-12, "{q:?}");
    assert!((q[1] - 2f64.cos()).abs() < 1e-3, "{q:?}");
}

#[test]
fn declaration_clashes_and_reserved_names_point_at_the_declaration() {
    let dir = TempDir::new("clash");
    let spec = well(&dir, "k = 8.0", "x_dot = 8.0");
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["the name `x_dot` is declared twice"]);
    assert_eq!(underlined(&stderr, "x_dot = 8.0"), ["x_dot"]);
    let spec = well(&dir, "- V\"", "- V + t\"");
    let stderr = assert_fails(&run(&spec, &[], &dir), &dir, &["a Lagrangian does not depend on time"]);
    assert_eq!(underlined(&stderr, "lagrangian = "), ["t"]);
}

#[test]
fn initial_values_by_name_equal_the_arrays_in_coordinate_order() {
    let (by_name, in_order) = (TempDir::new("by-name"), TempDir::new("in-order"));
    let spec = example("charged_particle.toml");
    let named =
        ["initial.q={ theta = 0.0, q3 = 0.0, q2 = 0.0, q1 = 0.0 }", "initial.p={ q1 = 1, q2 = 0, q3 = 1, theta = 1 }"];
    let a = succeed(&spec, &named, &by_name);
    let b = succeed(&spec, &[], &in_order);
    assert_eq!(a.final_q(), b.final_q());
    assert_eq!(a.summary["initial"]["p"], serde_json::json!([1.0, 0.0, 1.0, 1.0]));
}

#[test]
fn missing_and_unknown_names_in_initial_values_are_listed() {
    let dir = TempDir::new("initial-names");
    let stderr = assert_fails(
        &run(&example("charged_particle.toml"), &["initial.p={ q1 = 1, theta = 1 }"], &dir),
        &dir,
        &["`initial.p` has no value for `q2`, `q3`", "give one value per coordinate: q1, q2, q3, theta"],
    );
    assert!(stderr.contains("missing `q2`, `q3`"), "{stderr}");
    let spec = well(&dir, "p = { x = 0.0, y = 2.0 }", "p = { x = 0.0, y = 2.0, z = 1.0 }");
    let stderr =
        assert_fails(&run(&spec, &[], &dir), &dir, &["`initial.p` gives a value for `z`, which is not a coordinate"]);
    assert_eq!(underlined(&stderr, "p = {"), ["z"]);
}

/// `method.order` and `method.composition`: an order that does not exist, a set without the order
/// it needs, a set of another order, and a composition of a rule that is not symmetric are spec
/// errors pointing at the key.
#[test]
fn compositions_that_do_not_exist_are_refused_at_their_key() {
    let dir = TempDir::new("composition-errors");
    let spec = common::example("charged_particle.toml");
    for (sets, expected) in [
        (vec!["method.order=5"], "there is no method of order 5"),
        (vec!["method.rule=\"midpoint\"", "method.composition=\"kahan-li\""], "has several orders"),
        (vec!["method.rule=\"midpoint\"", "method.order=4", "method.composition=\"kahan-li\""], "order 4 has `suzuki`"),
        (vec!["method.rule=\"midpoint\"", "method.composition=\"yoshida\""], "unknown composition `yoshida`"),
        (vec!["method.order=4"], "needs a symmetric rule"),
    ] {
        let output = run(&spec, &sets, &dir);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{sets:?}: {stderr}");
        assert!(stderr.contains(expected), "{sets:?}: expected {expected:?} in {stderr}");
        assert!(stderr.contains("order =") || stderr.contains("composition ="), "{sets:?}: the key is shown: {stderr}");
        assert!(!dir.out().exists(), "{sets:?}: nothing is written");
    }
}
