//! `work-precision`, second part: the compositions of orders 2, 4, 6 and 8 (midpoint rule,
//! [`ddirac::composition`]) against DOP853 (Hairer's explicit Runge–Kutta method of order 8 with
//! step-size control, from the `ode_solvers` crate, with the `dop853` feature) on the double spherical
//! pendulum (paper §7.2), Kepler's eccentric orbit and the charged particle (§7.1), and on the heavy
//! top on SO(3) ([`super::rigid_race`]).
//!
//! DOP853 integrates the Euler–Lagrange equations of the same Lagrangian
//! ([`ddirac::mechanics::euler_lagrange`]) with the same derivative machinery: compiled where the
//! engine compiles. Every run of a system is timed side by side with the others ([`compare`]); its
//! error is ‖q(T) − q_ref‖ against the exact motion, or, for the pendulum, against DOP853 at
//! tolerance 1e-14 (checked against the order-8 composition at its finest step). Then, at each decade
//! of error that both reach, the time of the fastest composition against DOP853's (log–log
//! interpolation along each method's points), and the energy error of both over a ten times longer
//! run at equal cost.

use std::collections::BTreeMap;
use std::hint::black_box;
use std::path::Path;

use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, Kepler};
use ddirac::{Composition, Differentiation, DynSystem, InitialMomentum, Method, Problem, Rule, System};
use serde::Serialize;

use super::harness::{compare, Contender};
use super::interpolation::{between, bracket};
use super::{built_in, dop853, failed, print, Settings, LAST_ROW_ONLY};
use crate::plot::{self, Figure, Panel, Scale, Series};

/// One point of a method's curve: its parameter (N, or DOP853's tolerance), error and time per run.
#[derive(Debug, Clone, Serialize)]
pub struct Point {
    pub parameter: f64,
    pub error: f64,
    pub seconds: f64,
}

/// The race on one system.
#[derive(Debug, Serialize)]
pub struct Race {
    pub system: &'static str,
    pub duration: f64,
    pub reference: String,
    /// Per method (`order 2` … `order 8`, `DOP853`): its points, by decreasing error.
    pub methods: BTreeMap<String, Vec<Point>>,
    /// At each decade of error: seconds per method and the fastest composition ÷ DOP853.
    pub equal_error: Vec<EqualError>,
    /// Over ten times the duration at about equal cost: max |H − H₀|/|H₀| of each.
    pub long_run: Option<LongRun>,
}

#[derive(Debug, Serialize)]
pub struct EqualError {
    pub error: f64,
    pub seconds: BTreeMap<String, f64>,
    pub best_composition: String,
    pub composition_over_dop853: Option<f64>,
}

#[derive(Debug, Serialize)]
pub struct LongRun {
    pub duration: f64,
    pub composition: String,
    pub composition_seconds: f64,
    pub composition_energy_error: f64,
    pub dop853_tolerance: f64,
    pub dop853_seconds: f64,
    pub dop853_energy_error: f64,
}

/// A system with its initial data, duration and the step counts of each order.
struct Case<'a, S, const N: usize> {
    name: &'static str,
    /// The system as DOP853's field evaluates it.
    system: &'a S,
    /// The same system as the engine runs it (type-erased by the library, as a spec runs it).
    erased: Box<dyn DynSystem>,
    q0: [f64; N],
    p0: [f64; N],
    duration: f64,
    steps: [&'a [usize]; 4],
}

const TOLERANCES: [f64; 9] = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13];
const QUICK_TOLERANCES: [f64; 3] = [1e-6, 1e-8, 1e-10];

/// Runs the race on the three systems.
pub fn run(settings: &Settings) -> Result<Vec<Race>, miette::Report> {
    print::heading(
        "work-precision: compositions against DOP853",
        "error ‖q(T) − q_ref‖ against time per run, side by side",
    );
    if !dop853::AVAILABLE {
        println!("  DOP853 is not in this build (`cargo build --release -p ddirac-cli --features dop853`): compositions only");
    }
    let quick = settings.quick;
    let pendulum = DoubleSphericalPendulum::default();
    let kepler = Kepler::default();
    let particle = ChargedParticle::default();
    let steps = |full: &'static [usize], short: &'static [usize]| if quick { short } else { full };
    let races = vec![
        race(
            settings,
            Case {
                name: "double spherical pendulum (§7.2), T = 100",
                system: &pendulum,
                erased: built_in("double_spherical_pendulum")?,
                q0: [0.0, 2.25, 2.0, 3.0],
                p0: [0.0, 0.0, 1.0, 1.0],
                duration: 100.0,
                steps: [
                    steps(&[1_000, 2_000, 4_000, 8_000, 16_000, 32_000], &[1_000, 2_000]),
                    steps(&[100, 200, 400, 800, 1_600, 3_200], &[200, 400]),
                    steps(&[50, 100, 200, 400, 800], &[100, 200]),
                    steps(&[50, 70, 100, 140, 200, 280], &[70, 100]),
                ],
            },
        )?,
        race(
            settings,
            Case {
                name: "Kepler, eccentricity 0.51, T = 20",
                system: &kepler,
                erased: built_in("kepler")?,
                q0: [1.0, 0.0],
                p0: [0.0, 0.7],
                duration: 20.0,
                steps: [
                    steps(&[400, 800, 1600, 3200, 6400, 12_800, 25_600], &[400, 800]),
                    steps(&[200, 400, 800, 1600, 3200, 6400], &[400, 800]),
                    steps(&[200, 400, 800, 1600, 3200], &[400, 800]),
                    steps(&[200, 400, 800, 1600], &[400, 800]),
                ],
            },
        )?,
        race(
            settings,
            Case {
                name: "charged particle (§7.1), T = 20",
                system: &particle,
                erased: built_in("charged_particle")?,
                q0: [0.0; 4],
                p0: [1.0, 0.0, 1.0, 1.0],
                duration: 20.0,
                steps: [
                    steps(&[100, 200, 400, 800, 1600, 3200, 6400, 12_800], &[200, 400]),
                    steps(&[50, 100, 200, 400, 800, 1600], &[100, 200]),
                    steps(&[25, 50, 100, 200, 400], &[50, 100]),
                    steps(&[20, 28, 40, 56, 80], &[28, 40]),
                ],
            },
        )?,
    ];
    Ok(races)
}

/// Draws the races' figure into `figures`.
pub fn figure(races: &[Race], figures: &Path) -> Result<(), miette::Report> {
    let panels = races.iter().map(panel).collect();
    let figure = Figure::new("work-precision", "Work–precision: compositions against DOP853", panels)
        .subtitle("error of q(T) (of R(T) for the heavy top) against time per run (log–log); one line per method");
    std::fs::create_dir_all(figures)
        .map_err(|e| miette::miette!("cannot create the figures' directory `{}`: {e}", figures.display()))?;
    let written = plot::save(&figure, figures).map_err(|e| miette::miette!("{e}"))?;
    println!("  figure       {}", written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "));
    Ok(())
}

/// The composition of `order` on the midpoint rule, with compiled derivatives (as DOP853's field):
/// one derivative path at every step count. A system's atlas is used (the default): the double
/// spherical pendulum's steps near a pole are taken in a chart regular there, while DOP853 integrates
/// the main chart's equations, as a user of it would.
fn composed(order: u8) -> Method {
    let composition = Composition::for_order(order).expect("an order of the table");
    Method { rule: Rule::Midpoint, composition, differentiation: Differentiation::Compiled, ..Method::default() }
}

/// The euclidean distance of a configuration from a reference, on the coordinates the reference gives.
fn distance(a: &[f64], reference: &[Option<f64>]) -> f64 {
    a.iter().zip(reference).filter_map(|(x, y)| y.map(|y| (x - y).powi(2))).sum::<f64>().sqrt()
}

fn race<S: System<N>, const N: usize>(settings: &Settings, case: Case<'_, S, N>) -> Result<Race, miette::Report> {
    let Case { name, system, erased, q0, p0, duration, steps } = case;
    let erased = erased.as_ref();
    let problem = |n: usize| Problem::new(duration / n as f64, n, q0.to_vec(), InitialMomentum::Momentum(p0.to_vec()));
    let (reference, q_ref): (String, Vec<Option<f64>>) = match erased.exact_solution(&q0, &p0, duration) {
        Some(exact) => ("the exact motion (on the coordinates it gives)".to_owned(), exact),
        None => {
            let (name, q) = reference_run(system, erased, &q0, &p0, duration, steps[3], &problem)?;
            (name, q.into_iter().map(Some).collect())
        }
    };
    println!("  {name}: errors against {reference}");
    let problems: Vec<(u8, Problem)> = [2u8, 4, 6, 8]
        .iter()
        .zip(steps)
        .flat_map(|(&order, ns)| ns.iter().map(move |&n| (order, n)))
        .map(|(order, n)| (order, problem(n)))
        .collect();
    let mut contenders: Vec<Contender<'_>> = vec![];
    let mut labels: Vec<(String, f64, f64)> = vec![];
    for (order, problem) in &problems {
        let method = composed(*order);
        let what = format!("{name}, order {order}, N = {}", problem.steps);
        let summary =
            erased.integrate(problem, &method, &LAST_ROW_ONLY, &mut |_| Ok(())).map_err(|e| failed(&what, e))?;
        let error = distance(&summary.final_q, &q_ref);
        labels.push((format!("order {order}"), problem.steps as f64, error));
        let run = move || {
            black_box(black_box(erased).integrate(black_box(problem), &method, &LAST_ROW_ONLY, &mut |_| Ok(())))
                .map(|_| ())
                .map_err(|e| failed(&what, e))
        };
        contenders.push(Contender::new(format!("order {order}, N = {}", problem.steps), 1, run));
    }
    let tolerances: &[f64] = if settings.quick { &QUICK_TOLERANCES } else { &TOLERANCES };
    for &tolerance in tolerances {
        let Some(first) = dop853::integrate(system, &q0, &p0, duration, tolerance, false) else { break };
        labels.push(("DOP853".to_owned(), tolerance, distance(&first?.0, &q_ref)));
        let run = move || match dop853::integrate(system, &q0, &p0, duration, tolerance, false) {
            Some(result) => black_box(result).map(|_| ()),
            None => Err(miette::miette!("DOP853 is not in this build")),
        };
        contenders.push(Contender::new(format!("DOP853, tolerance {tolerance:e}"), 1, run));
    }
    let methods = timed_points(name, settings, contenders, labels)?;
    let equal_error = equal_error(&methods);
    let long_run = long_run(system, erased, &q0, &p0, duration, &methods)?;
    Ok(Race { system: name, duration, reference, methods, equal_error, long_run })
}

/// Times `contenders` side by side and gives each method its points: the labels (method, N or
/// tolerance, error) of the contenders in order, with the median seconds per run; prints them.
pub(super) fn timed_points(
    name: &str,
    settings: &Settings,
    contenders: Vec<Contender<'_>>,
    labels: Vec<(String, f64, f64)>,
) -> Result<BTreeMap<String, Vec<Point>>, miette::Report> {
    let comparison = compare(name, settings.schedule, contenders, &[])?;
    let mut methods: BTreeMap<String, Vec<Point>> = BTreeMap::new();
    for ((method, parameter, error), timing) in labels.into_iter().zip(&comparison.timings) {
        let seconds = timing.ns_per_step.median * 1e-9;
        methods.entry(method).or_default().push(Point { parameter, error, seconds });
    }
    println!("    {:<10} {:>12} {:>12} {:>12}", "method", "N or tol.", "error", "s per run");
    for (method, points) in &methods {
        for p in points {
            println!("    {method:<10} {:>12.3e} {:>12.3e} {:>12.3e}", p.parameter, p.error, p.seconds);
        }
    }
    Ok(methods)
}

/// q(T) of the reference run: DOP853 at tolerance 1e-14 when the build has it, checked against the
/// order-8 composition at twice its finest N; that composition otherwise.
fn reference_run<S: System<N>, const N: usize>(
    system: &S,
    erased: &dyn DynSystem,
    q0: &[f64; N],
    p0: &[f64; N],
    duration: f64,
    order_8: &[usize],
    problem: &impl Fn(usize) -> Problem,
) -> Result<(String, Vec<f64>), miette::Report> {
    let n = 2 * order_8.iter().max().copied().unwrap_or(1000);
    let what = format!("the reference run of order 8 with N = {n}");
    let composed = erased
        .integrate(&problem(n), &composed(8), &LAST_ROW_ONLY, &mut |_| Ok(()))
        .map_err(|e| failed(&what, e))?
        .final_q;
    match dop853::integrate(system, q0, p0, duration, 1e-14, false) {
        Some(result) => {
            let (q, _) = result?;
            let agree = distance(&q, &composed.iter().copied().map(Some).collect::<Vec<_>>());
            let name =
                format!("DOP853 at tolerance 1e-14 (the order-8 composition with N = {n} differs by {agree:.1e})");
            Ok((name, q))
        }
        None => Ok((format!("the order-8 composition with N = {n}"), composed)),
    }
}

/// Seconds per run of each method at each decade of error all of them reach, and the fastest
/// composition against DOP853.
pub(super) fn equal_error(methods: &BTreeMap<String, Vec<Point>>) -> Vec<EqualError> {
    let at = |points: &[Point], target: f64| {
        let errors: Vec<f64> = points.iter().map(|p| p.error).collect();
        bracket(&errors, target).map(|(i, s)| between(points[i].seconds, points[i + 1].seconds, s))
    };
    let (low, high) =
        methods.values().flatten().fold((f64::INFINITY, 0.0f64), |(l, h), p| (l.min(p.error), h.max(p.error)));
    if !(low > 0.0 && high > low) {
        return vec![];
    }
    let mut result = vec![];
    for k in (low.log10().ceil() as i32..=high.log10().floor() as i32).rev() {
        let target = 10f64.powi(k);
        let seconds: BTreeMap<String, f64> =
            methods.iter().filter_map(|(m, points)| at(points, target).map(|s| (m.clone(), s))).collect();
        let best = seconds.iter().filter(|(m, _)| m.starts_with("order")).min_by(|a, b| a.1.total_cmp(b.1));
        let Some((best, best_seconds)) = best.map(|(m, s)| (m.clone(), *s)) else { continue };
        let ratio = seconds.get("DOP853").map(|d| best_seconds / d);
        let listed: Vec<String> = seconds.iter().map(|(m, s)| format!("{m} {s:.2e} s")).collect();
        let versus = ratio.map_or(String::new(), |r| format!("; {best} ÷ DOP853 = {r:.3}"));
        println!("    error 1e{k}: {}{versus}", listed.join(", "));
        result.push(EqualError { error: target, seconds, best_composition: best, composition_over_dop853: ratio });
    }
    result
}

/// The order-8 composition's step count over ten times the duration: that of DOP853's cost
/// `dop853_seconds` at the composition's cost per step in its fastest timed run (`points`), and at
/// least ten times the fewest timed steps, so that no step is longer than a timed run's (a longer step
/// may leave Newton's method without a solution); the line printed says when that raised the count.
pub(super) fn long_run_steps(points: &[Point], dop853_seconds: f64) -> usize {
    let per_step = points.iter().map(|p| p.seconds / p.parameter).fold(f64::INFINITY, f64::min);
    let equal_cost = (dop853_seconds / per_step) as usize;
    let fewest = points.iter().map(|p| p.parameter).fold(f64::INFINITY, f64::min);
    let shortest_timed = if fewest.is_finite() { 10 * fewest as usize } else { 10 };
    if equal_cost < shortest_timed {
        println!(
            "    the long run's order-8 composition at DOP853's cost would take {equal_cost} steps, longer than any \
             timed run's: it takes {shortest_timed} (not of equal cost)"
        );
    }
    equal_cost.max(shortest_timed)
}

/// Over ten times the duration: DOP853 at 1e-8 and the composition of order 8 with the step count
/// of equal cost (from the timed runs), each with its largest relative energy error; `None` without
/// the peer.
fn long_run<S: System<N>, const N: usize>(
    system: &S,
    erased: &dyn DynSystem,
    q0: &[f64; N],
    p0: &[f64; N],
    duration: f64,
    methods: &BTreeMap<String, Vec<Point>>,
) -> Result<Option<LongRun>, miette::Report> {
    let (tolerance, long) = (1e-8, 10.0 * duration);
    let started = std::time::Instant::now();
    let Some(result) = dop853::integrate(system, q0, p0, long, tolerance, true) else { return Ok(None) };
    let (_, dop853_energy_error) = result?;
    let dop853_seconds = started.elapsed().as_secs_f64();
    // The order-8 composition's cost per step, from its fastest timed run.
    let Some(points) = methods.get("order 8") else { return Ok(None) };
    let n = long_run_steps(points, dop853_seconds);
    let problem = Problem::new(long / n as f64, n, q0.to_vec(), InitialMomentum::Momentum(p0.to_vec()));
    // H(q0, p0): the energy of the first row.
    let mut h0 = f64::NAN;
    let mut largest: f64 = 0.0;
    let started = std::time::Instant::now();
    let every = ddirac::OutputOptions { every: 1, wrap_angles: false };
    erased
        .integrate(&problem, &composed(8), &every, &mut |row| {
            if row.k == 0 {
                h0 = row.energy;
            }
            largest = largest.max(((row.energy - h0) / h0).abs());
            Ok(())
        })
        .map_err(|e| failed("the long run of order 8", e))?;
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

/// The log–log panel of one race.
fn panel(race: &Race) -> Panel {
    let series = race
        .methods
        .iter()
        .map(|(method, points)| {
            let mut points: Vec<(f64, f64)> = points.iter().map(|p| (p.seconds, p.error)).collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            Series { markers: true, ..Series::named(method.clone(), points) }
        })
        .collect();
    let against = race.reference.split(" (").next().unwrap_or(&race.reference);
    let quantity = if race.system.contains("SO(3)") { "error of R(T)" } else { "error of q(T)" };
    Panel::new("seconds per run", quantity, series)
        .scale(Scale::LogLog)
        .caption(format!("{}; against {against}", race.system))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn timed(parameter: f64, seconds: f64) -> Point {
        Point { parameter, error: 1e-6, seconds }
    }

    #[test]
    fn the_long_run_takes_no_longer_steps_than_the_timed_runs() {
        // The double spherical pendulum's quick race once asked its long run for 59 steps over ten
        // times a duration whose timed runs took 70 and 100 (h = 16.9 against 1.43): Newton's method
        // found no step. The long run now takes at least ten times the fewest timed steps.
        let points = [timed(70.0, 0.057), timed(100.0, 0.073)];
        assert_eq!(long_run_steps(&points, 0.048), 700);
        // Where DOP853's cost buys more steps, the long run takes them: 0.073 s per 100 steps.
        assert_eq!(long_run_steps(&points, 1.5), 2054);
    }
}
