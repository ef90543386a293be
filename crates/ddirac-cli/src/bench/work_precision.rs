//! `work-precision`: the charged particle of paper §7.1 up to T = 20 with N = 50 … 12800 steps by
//! the generic engine (reduced (+), left rule), the hand-written step of the same scheme and Boris:
//! the error ‖q(T) − q_N‖ against the exact motion q(t) = (sin t, cos t − 1, t) (the paper's
//! Table 1 for the first two) and the time of each, timed side by side for every N; then the time
//! ratios at equal error.
//!
//! At equal error e the steps N_c(e) of each integrator c come from linear interpolation of ln e
//! against ln N between the tabulated N, and its time per run from linear interpolation of ln t
//! against ln N at the same place, round by round, so that the ratios keep a spread over the rounds.

use std::collections::BTreeMap;

use ddirac::systems::ChargedParticle;
use serde::Serialize;
use serde_json::Value;

use super::charged_particle::{contenders, pairs, Contenders, BORIS, ENGINE, SPECIALISED};
use super::harness::{compare, ratio, Comparison, Pair, Ratio, Spread};
use super::interpolation::{between, bracket};
use super::{print, to_json, Settings};

/// Final time.
const T: f64 = 20.0;
const STEPS: [usize; 9] = [50, 100, 200, 400, 800, 1600, 3200, 6400, 12800];
const QUICK_STEPS: [usize; 5] = [50, 100, 200, 400, 800];
const NAMES: [&str; 3] = [ENGINE, SPECIALISED, BORIS];

/// ‖q − q(T)‖ for the exact motion q(t) = (sin t, cos t − 1, t).
fn error(q: &[f64; 3]) -> f64 {
    let exact = [T.sin(), T.cos() - 1.0, T];
    (0..3).map(|i| (q[i] - exact[i]).powi(2)).sum::<f64>().sqrt()
}

#[derive(Serialize)]
struct Row {
    steps: usize,
    step: f64,
    /// ‖q(T) − q_N‖ per integrator.
    errors: BTreeMap<&'static str, f64>,
    comparison: Comparison,
}

#[derive(Serialize)]
struct EqualError {
    error: f64,
    /// Interpolated N per integrator.
    steps: BTreeMap<&'static str, f64>,
    /// Interpolated seconds per run (median over rounds) per integrator.
    seconds: BTreeMap<&'static str, f64>,
    ratios: Vec<Ratio>,
}

#[derive(Serialize)]
struct Report {
    duration: f64,
    rows: Vec<Row>,
    equal_error: Vec<EqualError>,
    /// The compositions against DOP853 ([`super::race`]).
    race: Vec<super::race::Race>,
}

/// Runs the group.
pub fn run(settings: &Settings) -> Result<Value, miette::Report> {
    print::heading(
        "work-precision",
        "charged particle (paper §7.1), T = 20, error against time; the engine's compiled closed-form step at every N",
    );
    let steps: &[usize] = if settings.quick { &QUICK_STEPS } else { &STEPS };
    let system = super::built_in("charged_particle")?;
    println!(
        "  error ‖q(T) − q_N‖ against the exact motion and median time per step of each, timed side by side for each N; \
         Newton corrections (it.) and Jacobians (Jac.) per step of the engine"
    );
    println!(
        "    {:>6}  {:>10} {:>9} {:>5} {:>5}  {:>11} {:>9}  {:>10} {:>9}  {:>12}",
        "N", "engine", "ns/step", "it.", "Jac.", "specialised", "ns/step", "boris", "ns/step", "boris/engine"
    );
    let mut rows = vec![];
    for &n in steps {
        let problem = ChargedParticle::paper_problem(n);
        let Contenders { contenders, finals } = contenders(system.as_ref(), &problem)?;
        let title = format!("charged particle, T = 20, N = {n}");
        let comparison = compare(title, settings.schedule, contenders, &pairs())?;
        let errors: BTreeMap<&str, f64> = NAMES.iter().zip(&finals).map(|(&name, q)| (name, error(q))).collect();
        let ns = |name| comparison.timing(name).map_or(f64::NAN, |t| t.ns_per_step.median);
        let newton = comparison.timing(ENGINE).and_then(|t| t.newton);
        let (iterations, jacobians) = newton.map_or((f64::NAN, f64::NAN), |n| (n.iterations, n.jacobians));
        println!(
            "    {n:>6}  {:>10.3e} {:>9} {iterations:>5.2} {jacobians:>5.2}  {:>11.3e} {:>9}  {:>10.3e} {:>9}  {:>12.3}",
            errors[ENGINE],
            print::ns(ns(ENGINE)),
            errors[SPECIALISED],
            print::ns(ns(SPECIALISED)),
            errors[BORIS],
            print::ns(ns(BORIS)),
            errors[BORIS] / errors[ENGINE],
        );
        rows.push(Row { steps: n, step: problem.step, errors, comparison });
    }
    let equal_error = equal_error(&rows)?;
    let mut race = super::race::run(settings)?;
    race.push(super::rigid_race::race(settings)?);
    super::race::figure(&race, &settings.figures)?;
    to_json(&Report { duration: T, rows, equal_error, race })
}

/// The decades 10^k inside the error range all integrators cover, largest first.
fn levels(rows: &[Row]) -> Vec<i32> {
    let (mut low, mut high) = (f64::NEG_INFINITY, f64::INFINITY);
    for name in NAMES {
        let errors = rows.iter().map(|r| r.errors[name]);
        low = low.max(errors.clone().fold(f64::INFINITY, f64::min));
        high = high.min(errors.fold(f64::NEG_INFINITY, f64::max));
    }
    if !(low > 0.0 && high >= low) {
        return vec![];
    }
    (low.log10().ceil() as i32..=high.log10().floor() as i32).rev().collect()
}

/// Steps and times of each integrator at each decade of error, and their ratios round by round.
fn equal_error(rows: &[Row]) -> Result<Vec<EqualError>, miette::Report> {
    println!("  at equal error: N by interpolation of ln error against ln N, time per run at that N, round by round");
    let mut result = vec![];
    for k in levels(rows) {
        let target = 10f64.powi(k);
        // Per integrator: N and the time per run in every round.
        let mut steps = BTreeMap::new();
        let mut seconds = BTreeMap::new();
        let mut per_round = BTreeMap::new();
        for name in NAMES {
            let errors: Vec<f64> = rows.iter().map(|r| r.errors[name]).collect();
            let Some((i, s)) = bracket(&errors, target) else { continue };
            let (a, b) = (&rows[i], &rows[i + 1]);
            let (Some(ta), Some(tb)) = (a.comparison.timing(name), b.comparison.timing(name)) else { continue };
            let times: Vec<f64> = ta
                .rounds
                .iter()
                .zip(&tb.rounds)
                .map(|(x, y)| between(x * 1e-9 * a.steps as f64, y * 1e-9 * b.steps as f64, s))
                .collect();
            steps.insert(name, between(a.steps as f64, b.steps as f64, s));
            seconds.insert(name, Spread::of(&times).map_or(f64::NAN, |s| s.median));
            per_round.insert(name, times);
        }
        if per_round.len() < NAMES.len() {
            continue;
        }
        println!(
            "    error 1e{k}: N = {:.0} (engine), {:.0} (specialised), {:.0} (boris); time per run {:.3e} s, {:.3e} s, \
             {:.3e} s",
            steps[ENGINE], steps[SPECIALISED], steps[BORIS], seconds[ENGINE], seconds[SPECIALISED], seconds[BORIS]
        );
        let mut ratios = vec![];
        for (numerator, denominator) in [(ENGINE, BORIS), (SPECIALISED, BORIS), (ENGINE, SPECIALISED)] {
            let rounds: Vec<f64> =
                per_round[numerator].iter().zip(&per_round[denominator]).map(|(x, y)| x / y).collect();
            let mut r = ratio(&Pair::new(numerator, denominator), rounds)?;
            r.name = format!("{} at error 1e{k}", r.name);
            print::ratio(&r);
            ratios.push(r);
        }
        result.push(EqualError { error: target, steps, seconds, ratios });
    }
    Ok(result)
}
