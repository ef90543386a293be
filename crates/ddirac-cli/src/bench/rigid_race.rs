//! `work-precision`, rigid part: the heavy top on SO(3) of `examples/heavy_top_upright.toml` (I = (1,
//! 1.3, 0.4), m g c = (0, 0, 4.9), released 0.01 rad from the upright attitude spinning at Ω3 = 2, so
//! that it falls through the attitudes where Euler angles are singular) up to T = 10: the
//! compositions of orders 2, 4, 6 and 8 of the rigid engine (midpoint rule at the group midpoint,
//! unreduced; the body declares its principal axes, so its steps have closed-form derivatives)
//! against DOP853 on Euler's equations in (R, Π) ([`super::dop853::integrate_rigid`]).
//!
//! The error is the Frobenius distance of R(T) from the reference: DOP853 at tolerance 1e-14, checked
//! against the order-8 composition at twice its finest N. The rest is the race of [`super::race`]:
//! every run timed side by side, the time of the fastest composition against DOP853's at each decade
//! of error, and the energy error of both over ten times the duration at equal cost.

use std::collections::BTreeMap;
use std::hint::black_box;

use ddirac::rigid::{integrate_rigid, RigidInitial, RigidProblem};
use ddirac::systems::RigidBody;
use ddirac::{Composition, Method, Rule};

use super::dop853;
use super::harness::Contender;
use super::race::{equal_error, long_run_steps, timed_points, LongRun, Point, Race};
use super::{failed, Settings};

type M3 = [[f64; 3]; 3];

const NAME: &str = "heavy top on SO(3), from near upright, T = 10";
const DURATION: f64 = 10.0;
const INERTIA: [f64; 3] = [1.0, 1.3, 0.4];
const WEIGHT: [f64; 3] = [0.0, 0.0, 0.5 * 9.8];
const TOLERANCES: [f64; 8] = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13];
const QUICK_TOLERANCES: [f64; 3] = [1e-6, 1e-8, 1e-10];

/// The top of the example: tilted by 0.01 rad about the first axis, Π0 = I Ω0 with Ω0 = (0, 0, 2).
fn initial() -> (M3, [f64; 3]) {
    let (c, s) = (0.01f64.cos(), 0.01f64.sin());
    ([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]], [0.0, 0.0, INERTIA[2] * 2.0])
}

fn body() -> RigidBody {
    RigidBody { inertia: INERTIA, m: 1.0, g: 9.8, c: [0.0, 0.0, 0.5] }
}

fn composed(order: u8) -> Method {
    let composition = Composition::for_order(order).expect("an order of the table");
    Method { rule: Rule::Midpoint, composition, ..Method::default() }
}

fn problem(duration: f64, n: usize) -> RigidProblem {
    let (r0, pi) = initial();
    RigidProblem::new(duration / n as f64, n, r0, RigidInitial::Momentum { pi, p: vec![] })
}

/// ‖R − R_ref‖ (Frobenius).
fn distance(r: &M3, reference: &M3) -> f64 {
    (0..9).map(|k| (r[k / 3][k % 3] - reference[k / 3][k % 3]).powi(2)).sum::<f64>().sqrt()
}

/// R(T) of the composition of `order` with `n` steps over `duration`.
fn run_composition(order: u8, n: usize, duration: f64) -> Result<M3, miette::Report> {
    let what = format!("the heavy top, order {order}, N = {n}");
    integrate_rigid(&body(), problem(duration, n), &composed(order), usize::MAX, |_| {})
        .map(|summary| summary.final_r)
        .map_err(|e| failed(&what, e))
}

/// The race on the heavy top.
pub fn race(settings: &Settings) -> Result<Race, miette::Report> {
    let quick = settings.quick;
    let steps = |full: &'static [usize], short: &'static [usize]| if quick { short } else { full };
    let orders: [(u8, &[usize]); 4] = [
        (2, steps(&[1_000, 2_000, 4_000, 8_000, 16_000, 32_000], &[1_000, 2_000])),
        (4, steps(&[250, 500, 1_000, 2_000, 4_000, 8_000], &[500, 1_000])),
        (6, steps(&[125, 250, 500, 1_000, 2_000], &[250, 500])),
        (8, steps(&[100, 140, 200, 280, 400, 560, 800], &[200, 280])),
    ];
    let (r0, pi0) = initial();
    let finest = 2 * orders[3].1.iter().max().copied().unwrap_or(1000);
    let composed_reference = run_composition(8, finest, DURATION)?;
    let (reference, r_ref) = match dop853::integrate_rigid(INERTIA, WEIGHT, r0, pi0, DURATION, 1e-14, false) {
        Some(end) => {
            let end = end?;
            let agree = distance(&end.r, &composed_reference);
            let name =
                format!("DOP853 at tolerance 1e-14 (the order-8 composition with N = {finest} differs by {agree:.1e})");
            (name, end.r)
        }
        None => (format!("the order-8 composition with N = {finest}"), composed_reference),
    };
    println!("  {NAME}: errors ‖R(T) − R_ref‖ against {reference}");
    let mut contenders: Vec<Contender<'_>> = vec![];
    let mut labels: Vec<(String, f64, f64)> = vec![];
    for (order, ns) in orders {
        for &n in ns {
            let error = distance(&run_composition(order, n, DURATION)?, &r_ref);
            labels.push((format!("order {order}"), n as f64, error));
            let run = move || black_box(run_composition(order, black_box(n), DURATION)).map(|_| ());
            contenders.push(Contender::new(format!("order {order}, N = {n}"), 1, run));
        }
    }
    let tolerances: &[f64] = if quick { &QUICK_TOLERANCES } else { &TOLERANCES };
    for &tolerance in tolerances {
        let Some(end) = dop853::integrate_rigid(INERTIA, WEIGHT, r0, pi0, DURATION, tolerance, false) else { break };
        labels.push(("DOP853".to_owned(), tolerance, distance(&end?.r, &r_ref)));
        let run = move || match dop853::integrate_rigid(INERTIA, WEIGHT, r0, pi0, DURATION, tolerance, false) {
            Some(end) => black_box(end).map(|_| ()),
            None => Err(miette::miette!("DOP853 is not in this build")),
        };
        contenders.push(Contender::new(format!("DOP853, tolerance {tolerance:e}"), 1, run));
    }
    let methods = timed_points(NAME, settings, contenders, labels)?;
    let equal_error = equal_error(&methods);
    let long_run = long_run(&methods)?;
    Ok(Race { system: NAME, duration: DURATION, reference, methods, equal_error, long_run })
}

/// Over ten times the duration: DOP853 at 1e-8 and the composition of order 8 with the step count of
/// equal cost (from the timed runs), each with its largest relative energy error.
fn long_run(methods: &BTreeMap<String, Vec<Point>>) -> Result<Option<LongRun>, miette::Report> {
    let (tolerance, long) = (1e-8, 10.0 * DURATION);
    let (r0, pi0) = initial();
    let started = std::time::Instant::now();
    let Some(end) = dop853::integrate_rigid(INERTIA, WEIGHT, r0, pi0, long, tolerance, true) else { return Ok(None) };
    let dop853_energy_error = end?.energy_error;
    let dop853_seconds = started.elapsed().as_secs_f64();
    let Some(points) = methods.get("order 8") else { return Ok(None) };
    let n = long_run_steps(points, dop853_seconds);
    let mut h0 = f64::NAN;
    let mut largest: f64 = 0.0;
    let started = std::time::Instant::now();
    integrate_rigid(&body(), problem(long, n), &composed(8), 1, |row| {
        if row.k == 0 {
            h0 = row.energy;
        }
        largest = largest.max(((row.energy - h0) / h0).abs());
    })
    .map_err(|e| failed("the heavy top's long run of order 8", e))?;
    let composition_seconds = started.elapsed().as_secs_f64();
    println!(
        "    T = {long}: DOP853 (tolerance {tolerance:e}) {dop853_seconds:.3} s, max |ΔH/H₀| {dop853_energy_error:.2e}; \
         order 8 with N = {n}: {composition_seconds:.3} s, max |ΔH/H₀| {largest:.2e}"
    );
    Ok(Some(LongRun {
        duration: long,
        composition: format!("order 8, N = {n}"),
        composition_seconds,
        composition_energy_error: largest,
        dop853_tolerance: tolerance,
        dop853_seconds,
        dop853_energy_error,
    }))
}
