//! The text tables of `ddirac bench`.
//!
//! Every ratio is printed on one line `ratio NAME: MEDIAN [IQR Q1 – Q3, range MIN – MAX]`, followed
//! by its target when it has one, so that the lines can be read back by scripts.

use super::harness::{Comparison, Ratio, Spread, Target};

/// A group's heading.
pub fn heading(group: &str, what: &str) {
    println!("== {group}: {what}");
}

/// Nanoseconds with about four significant digits.
pub fn ns(x: f64) -> String {
    if x >= 1000.0 {
        format!("{x:.0}")
    } else if x >= 10.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2}")
    }
}

/// A ratio with three or four significant digits.
pub fn number(x: f64) -> String {
    if x >= 100.0 {
        format!("{x:.1}")
    } else if x >= 10.0 {
        format!("{x:.2}")
    } else {
        format!("{x:.3}")
    }
}

/// `[IQR q1 – q3, range min – max]` with `format` applied to each number.
pub fn spread(s: &Spread, format: fn(f64) -> String) -> String {
    format!("[IQR {} – {}, range {} – {}]", format(s.q1), format(s.q3), format(s.min), format(s.max))
}

/// `target ≥ 1.75: met`.
pub fn target(target: Target, met: bool) -> String {
    format!("target {}: {}", target.text(), if met { "met" } else { "NOT met" })
}

/// The timings and ratios of a comparison under its title.
pub fn comparison(c: &Comparison) {
    println!("  {}", c.title);
    let name = c.timings.iter().map(|t| t.name.chars().count()).max().unwrap_or(0).max("contender".len());
    let median: Vec<String> = c.timings.iter().map(|t| ns(t.ns_per_step.median)).collect();
    let spreads: Vec<String> = c.timings.iter().map(|t| spread(&t.ns_per_step, ns)).collect();
    let width = median.iter().map(String::len).max().unwrap_or(0).max("ns/step".len());
    let spread_width = spreads.iter().map(|s| s.chars().count()).max().unwrap_or(0);
    let newton = if c.timings.iter().any(|t| t.newton.is_some()) { "  Newton it./step  Jacobians/step" } else { "" };
    let header = format!("    {:<name$}  {:>width$}  {:<spread_width$}{newton}", "contender", "ns/step", "");
    println!("{}", header.trim_end());
    for ((t, median), spread) in c.timings.iter().zip(&median).zip(&spreads) {
        let newton = t.newton.map_or(String::new(), |n| format!("  {:>15.2}  {:>14.2}", n.iterations, n.jacobians));
        let line = format!("    {:<name$}  {median:>width$}  {spread:<spread_width$}{newton}", t.name);
        println!("{}", line.trim_end());
    }
    for r in &c.ratios {
        ratio(r);
    }
}

/// One ratio line.
pub fn ratio(r: &Ratio) {
    let goal = match (r.target, r.target_met) {
        (Some(t), Some(met)) => format!("  {}", target(t, met)),
        _ => String::new(),
    };
    println!("    ratio {}: {} {}{goal}", r.name, number(r.spread.median), spread(&r.spread, number));
}
