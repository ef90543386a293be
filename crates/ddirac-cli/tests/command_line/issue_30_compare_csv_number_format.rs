//! `compare.csv` wrote its numbers with Rust's `{}` (a difference of 1e-17 as `0.00000000000000001`,
//! thousands of numbers longer than 24 characters) instead of the documented format of the CSV files
//! (README, "Output files"): the shortest text that reads back as the same f64, positional between
//! 10⁻⁴ and 10¹⁶ and with an exponent outside, at most 24 characters.

use crate::common;

use common::{ddirac, example, stderr, TempDir};

/// Checks one field against the documented format: it reads back as an f64, whose own shortest
/// text it is, in positional notation exactly for 0 and 10⁻⁴ ≤ |v| < 10¹⁶, in at most 24 characters.
fn documented(field: &str, at: &str) -> f64 {
    assert!(field.len() <= 24, "{at}: `{field}` has {} characters", field.len());
    let v: f64 = field.parse().unwrap_or_else(|e| panic!("{at}: `{field}` is not a number: {e}"));
    let magnitude = v.abs();
    let positional = magnitude == 0.0 || (1e-4..1e16).contains(&magnitude);
    // Rust's `{}` and `{:e}` print the fewest significant digits that read back exactly.
    let shortest = if positional { format!("{v}") } else { format!("{v:e}") };
    assert_eq!(field, shortest, "{at}: `{field}` is not the shortest text of {v:e} in its notation");
    assert_eq!(shortest.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{at}");
    v
}

#[test]
fn every_number_of_compare_csv_has_the_documented_format() {
    let dir = TempDir::new("compare-format");
    let out = dir.out();
    // The double spherical pendulum: its reduced and unreduced runs differ by round-off, differences
    // far below 10⁻⁴ that `{}` writes out in full.
    let spec = example("double_spherical_pendulum.toml");
    let args = [
        "run",
        &spec,
        "--compare",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--set",
        "time.steps=400",
        "--set",
        "time.duration=4.0",
        "--set",
        "output.every=1",
        // The paper's chart, where the two runs differ by round-off (with the atlas both take the same
        // glued steps here).
        "--set",
        "method.atlas=false",
    ];
    let output = ddirac(&args, &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = std::fs::read_to_string(out.join("compare.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[0], "t");
    let (mut numbers, mut tiny, mut empty) = (0, 0, 0);
    for (k, line) in lines.enumerate() {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), header.len(), "row {k}");
        for (name, field) in header.iter().zip(&fields) {
            if field.is_empty() {
                // The last row has no discrete energy.
                assert_eq!(*name, "d_discrete_energy", "row {k}");
                empty += 1;
                continue;
            }
            let v = documented(field, &format!("row {k}, {name}"));
            numbers += 1;
            if v != 0.0 && v.abs() < 1e-4 {
                tiny += 1;
            }
        }
    }
    assert_eq!(empty, 1);
    // The file holds the numbers the old format wrote longest: the test can fail.
    assert!(tiny > 100, "only {tiny} of {numbers} numbers are below 1e-4 in magnitude");
}
