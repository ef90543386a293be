//! `ddirac bench --quick`: every group prints its tables, every ratio is a finite positive number
//! formed round by round, the JSON file holds the measurements, and the numbers the groups compute
//! besides times agree with independent references (the paper's Table 1, order 2 of both schemes,
//! the reduced and unreduced trajectories, one scheme computed two ways). Timings themselves are not
//! checked against any value: they depend on the machine and its load.

use crate::common;

use std::process::Output;

use serde_json::Value;

use common::{ddirac, numbers, TempDir};

const GROUPS: [&str; 7] =
    ["reduction", "charged-particle", "work-precision", "expression", "linearity", "scaling", "dimension"];

fn stdout(output: &Output) -> String {
    assert!(output.status.success(), "bench failed:\n{}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The numbers after the name of every `ratio NAME: MEDIAN [IQR Q1 – Q3, range MIN – MAX]` line.
fn printed_ratios(text: &str) -> Vec<(String, Vec<f64>)> {
    text.lines()
        .filter_map(|line| line.trim_start().strip_prefix("ratio "))
        .map(|rest| {
            let (name, values) = rest.split_once(": ").unwrap_or_else(|| panic!("malformed ratio line `{rest}`"));
            let numbers = values
                .split_whitespace()
                .filter_map(|token| token.trim_matches(|c| matches!(c, '[' | ']' | ',' | ':')).parse::<f64>().ok())
                .collect();
            (name.to_owned(), numbers)
        })
        .collect()
}

/// Every object with a `ratios` array, anywhere in `value`, with its path.
fn comparisons<'a>(value: &'a Value, path: String, found: &mut Vec<(String, &'a Value)>) {
    match value {
        Value::Object(map) => {
            if map.contains_key("ratios") && map.contains_key("timings") {
                found.push((path.clone(), value));
            }
            for (key, child) in map {
                comparisons(child, format!("{path}.{key}"), found);
            }
        }
        Value::Array(items) => {
            for (i, child) in items.iter().enumerate() {
                comparisons(child, format!("{path}[{i}]"), found);
            }
        }
        _ => {}
    }
}

fn spread_is_ordered(spread: &Value, what: &str) {
    let s = |key: &str| spread[key].as_f64().unwrap_or_else(|| panic!("{what}: no `{key}`"));
    let (min, q1, median, q3, max) = (s("min"), s("q1"), s("median"), s("q3"), s("max"));
    assert!(min.is_finite() && min > 0.0, "{what}: min {min}");
    assert!(min <= q1 && q1 <= median && median <= q3 && q3 <= max, "{what}: {spread}");
}

#[test]
fn quick_run_measures_every_group_and_writes_the_json_file() {
    let dir = TempDir::new("bench");
    let json = dir.0.join("bench.json");
    let text = stdout(&ddirac(&["bench", "--quick", "--json", json.to_str().unwrap()], &dir.0));
    for group in GROUPS {
        assert!(text.contains(&format!("== {group}:")), "no `{group}` table:\n{text}");
    }
    // The race of the compositions (and DOP853 in a build with the `dop853` feature), with its figure.
    assert!(text.contains("== work-precision: compositions against DOP853"), "{text}");
    for system in ["double spherical pendulum", "Kepler", "charged particle (§7.1)", "heavy top on SO(3)"] {
        assert!(text.contains(&format!("  {system}")), "no race on {system}:\n{text}");
    }
    for figure in ["work-precision.png", "work-precision.svg"] {
        let path = dir.0.join("out/bench").join(figure);
        assert!(std::fs::metadata(&path).map(|m| m.len() > 1000).unwrap_or(false), "{path:?}");
    }

    // The two dimensions give the same trajectory, bit for bit.
    let same: Vec<&str> = text.lines().filter(|l| l.contains("fixed and dynamic, max |q_N difference|")).collect();
    assert!(same.len() >= 4, "{text}");
    assert!(same.iter().all(|l| l.ends_with(": 0.00e0")), "{same:?}");

    // Every printed ratio: median, quartiles and extremes (and a target), all finite and positive.
    let ratios = printed_ratios(&text);
    assert!(ratios.len() >= 15, "only {} ratio lines:\n{text}", ratios.len());
    for (name, values) in &ratios {
        assert!(values.len() >= 5, "ratio `{name}`: {values:?}");
        assert!(values.iter().all(|v| v.is_finite() && *v > 0.0), "ratio `{name}`: {values:?}");
    }

    let document: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(!dir.0.join(".bench.json.partial").exists());
    assert_eq!(document["quick"], true);
    let rounds = document["rounds"].as_u64().unwrap() as usize;
    assert_eq!(rounds, 3);
    for group in GROUPS {
        assert!(document["groups"][group].is_object(), "no group `{group}` in the JSON file");
    }

    // Each ratio is formed round by round from the times of its two contenders.
    let mut found = vec![];
    comparisons(&document["groups"], "groups".into(), &mut found);
    assert!(found.len() >= 10, "only {} comparisons", found.len());
    let mut json_ratios = 0;
    for (path, comparison) in &found {
        for timing in comparison["timings"].as_array().unwrap() {
            let what = format!("{path}: {}", timing["name"]);
            spread_is_ordered(&timing["ns_per_step"], &what);
            assert_eq!(numbers(&timing["rounds"]).len(), rounds, "{what}");
            assert!(timing["reps"].as_u64().unwrap() >= 1);
        }
        let timing = |name: &Value| {
            comparison["timings"].as_array().unwrap().iter().find(|t| &t["name"] == name).map(|t| numbers(&t["rounds"]))
        };
        for ratio in comparison["ratios"].as_array().unwrap() {
            let what = format!("{path}: {}", ratio["name"]);
            spread_is_ordered(&ratio["spread"], &what);
            let per_round = numbers(&ratio["rounds"]);
            let (a, b) = (timing(&ratio["numerator"]).unwrap(), timing(&ratio["denominator"]).unwrap());
            assert_eq!(per_round.len(), rounds, "{what}");
            for r in 0..rounds {
                assert!((per_round[r] - a[r] / b[r]).abs() <= 1e-12 * per_round[r], "{what}, round {r}");
            }
            json_ratios += 1;
        }
    }
    assert!(json_ratios >= 10);

    // Reduced and unreduced equations are different schemes with the same trajectory.
    // (+) and (−), each at the default Newton tolerance and at 1e-13.
    let agreement = document["groups"]["reduction"]["agreement"].as_array().unwrap();
    assert_eq!(agreement.len(), 4);
    let tolerances: Vec<f64> = agreement.iter().map(|a| a["tolerance"].as_f64().unwrap()).collect();
    assert_eq!(tolerances, [1e-12, 1e-12, 1e-13, 1e-13]);
    for a in agreement {
        let difference = a["max_abs_difference"].as_f64().unwrap();
        assert!(difference.is_finite() && difference <= 1e-8, "{a}");
        assert_eq!(a["target_met"], true);
        assert!(a["rows"].as_u64().unwrap() >= 10, "{a}");
    }
    assert!(text.contains("reduced (+) vs unreduced (+): "), "{text}");

    work_precision(&document["groups"]["work-precision"]);
    heavy_top_race(&document["groups"]["work-precision"]);

    // One scheme computed by the engine and by the hand-written step.
    let difference = document["groups"]["charged-particle"]["engine_vs_specialised"].as_f64().unwrap();
    assert!(difference < 1e-10, "{difference}");
    // The same Lagrangian written as text and in Rust.
    let difference = document["groups"]["expression"]["final_q_difference"].as_f64().unwrap();
    assert!(difference < 1e-9, "{difference}");
}

/// Errors decrease at order 2 for both schemes; the engine and the hand-written step agree (one
/// scheme) and reproduce the paper's Table 1.
fn work_precision(group: &Value) {
    let rows = group["rows"].as_array().unwrap();
    assert!(rows.len() >= 4, "{} rows", rows.len());
    let steps: Vec<f64> = rows.iter().map(|r| r["steps"].as_f64().unwrap()).collect();
    let errors = |name: &str| -> Vec<f64> { rows.iter().map(|r| r["errors"][name].as_f64().unwrap()).collect() };
    let (engine, specialised, boris) = (errors("engine"), errors("specialised"), errors("boris"));
    for (name, e) in [("engine", &engine), ("boris", &boris)] {
        for i in 1..rows.len() {
            let slope = (e[i - 1] / e[i]).ln() / (steps[i] / steps[i - 1]).ln();
            assert!(
                (1.9..=2.1).contains(&slope),
                "{name}: slope {slope} between N = {} and {}",
                steps[i - 1],
                steps[i]
            );
        }
    }
    for i in 0..rows.len() {
        assert!((engine[i] - specialised[i]).abs() <= 1e-10 * engine[i], "N = {}", steps[i]);
    }
    // Paper, Table 1: ‖q(T) − q_N‖ = 0.06626 for N = 100.
    let n100 = steps.iter().position(|&n| n == 100.0).expect("a row for N = 100");
    assert_eq!(format!("{:.5}", engine[n100]), "0.06626");
    // At equal error the three have ratios with a spread, and Boris needs about as many steps.
    let equal = group["equal_error"].as_array().unwrap();
    assert!(!equal.is_empty());
    for level in equal {
        let n = |name: &str| level["steps"][name].as_f64().unwrap();
        assert!((n("engine") / n("specialised") - 1.0).abs() < 1e-9, "{level}");
        assert!((0.9..1.0).contains(&(n("boris") / n("engine"))), "{level}");
        assert_eq!(level["ratios"].as_array().unwrap().len(), 3);
    }
}

/// The heavy top's race: the composition of order 2 observes its order on R(T), and each higher order
/// is more accurate at its coarsest N than order 2 at its finest.
fn heavy_top_race(group: &Value) {
    let races = group["race"].as_array().unwrap();
    let top = races.iter().find(|r| r["system"].as_str().unwrap().contains("SO(3)")).expect("the heavy top's race");
    let points = |method: &str| -> Vec<(f64, f64)> {
        let points = top["methods"][method].as_array().unwrap_or_else(|| panic!("no `{method}`: {top}"));
        points.iter().map(|p| (p["parameter"].as_f64().unwrap(), p["error"].as_f64().unwrap())).collect()
    };
    let second = points("order 2");
    for pair in second.windows(2) {
        let slope = (pair[0].1 / pair[1].1).ln() / (pair[1].0 / pair[0].0).ln();
        assert!((1.8..2.3).contains(&slope), "order 2 on the heavy top: slope {slope} ({second:?})");
    }
    let finest_second = second.last().unwrap().1;
    for order in ["order 4", "order 6", "order 8"] {
        let coarsest = points(order)[0].1;
        assert!(coarsest < finest_second, "{order}: {coarsest:e} against order 2's {finest_second:e}");
    }
}

#[test]
fn only_runs_the_groups_named() {
    let dir = TempDir::new("bench-only");
    let text = stdout(&ddirac(&["bench", "--quick", "--only", "expression"], &dir.0));
    assert!(text.contains("== expression:"), "{text}");
    for group in GROUPS.iter().filter(|g| **g != "expression") {
        assert!(!text.contains(&format!("== {group}:")), "`{group}` ran:\n{text}");
    }
    // The double spherical pendulum and the chain of 50, text against Rust; the padded chain of 13
    // against those of 13 and 16.
    let ratios = printed_ratios(&text);
    let names: Vec<&str> = ratios.iter().map(|r| r.0.as_str()).collect();
    assert_eq!(names, ["text / Rust", "text / Rust", "13 in 16 / 13", "13 in 16 / 16"], "{text}");

    let text = stdout(&ddirac(&["bench", "--quick", "--rounds", "2", "--only", "linearity,charged-particle"], &dir.0));
    assert!(text.contains("== linearity:") && text.contains("== charged-particle:"), "{text}");
    assert!(!text.contains("== reduction:"), "{text}");
    assert!(text.contains("2 rounds per comparison"), "{text}");
}

#[test]
fn unknown_group_and_bad_options_are_refused() {
    let dir = TempDir::new("bench-refused");
    let output = ddirac(&["bench", "--quick", "--only", "reduction,speed"], &dir.0);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("invalid value 'speed' for '--only"), "{stderr}");
    assert!(stderr.contains("work-precision"), "the message lists the groups: {stderr}");
    assert!(output.stdout.is_empty(), "something ran: {}", String::from_utf8_lossy(&output.stdout));

    let output = ddirac(&["bench", "--quick", "--rounds", "0"], &dir.0);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("--rounds"));
}

#[test]
fn json_file_is_written_whole_or_not_at_all() {
    let dir = TempDir::new("bench-json");
    // A missing directory is reported before measuring.
    let missing = dir.0.join("missing/bench.json");
    let output = ddirac(&["bench", "--quick", "--json", missing.to_str().unwrap()], &dir.0);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("is not a directory"), "{stderr}");
    assert!(output.stdout.is_empty());

    // A directory in the way of the file: the rename fails after measuring, and no temporary file
    // stays behind.
    let taken = dir.0.join("taken");
    std::fs::create_dir(&taken).unwrap();
    let output = ddirac(&["bench", "--quick", "--only", "expression", "--json", taken.to_str().unwrap()], &dir.0);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("cannot write"), "{stderr}");
    let left: Vec<_> = std::fs::read_dir(&dir.0).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left, ["taken"], "{left:?}");
    assert_eq!(std::fs::read_dir(&taken).unwrap().count(), 0);
}
