//! `reduction`: the reduced equations (paper eqs. `geometricequations` (+) and
//! `geometricequationsminus` (−)) against the unreduced ones on the double spherical pendulum of
//! §7.2 (midpoint rule, h = 0.01, 10⁴ steps), where the paper reports the reduced scheme about 75 %
//! faster than the discrete Euler–Lagrange equations, and the agreement of the two trajectories;
//! then reduced against unreduced for the other engine runs of `benches/steps.rs` (1000 steps): the
//! charged particle (left and midpoint rules, (+) and (−)), Kepler and the heavy top ((+)).

use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum};
use ddirac::{DynSystem, InitialMomentum, Method, NewtonOptions, OutputOptions, Problem, Rule, Variant};
use serde::Serialize;
use serde_json::Value;

use super::harness::{compare, Comparison, Pair, Target};
use super::{built_in, engine, max_difference, method, method_name, print, to_json, Settings};

/// The paper's target: reduced at least 1.75 times as fast as unreduced.
const SPEED_UP: Target = Target::AtLeast(1.75);
/// The paper's target: the trajectories agree to 10⁻⁸.
const AGREEMENT: f64 = 1e-8;
/// The tighter Newton tolerance the agreement is also measured at (10⁻¹⁴ is below the round-off
/// floor of this problem's residual).
const TIGHT: f64 = 1e-13;
/// Rows compared for the agreement: every this many steps.
const EVERY: usize = 100;

/// The largest difference between a reduced and the unreduced trajectory.
#[derive(Serialize)]
struct Agreement {
    /// The Newton tolerance of both runs.
    tolerance: f64,
    reduced: String,
    unreduced: String,
    /// Rows every this many steps (and the last).
    every: usize,
    rows: usize,
    /// max over rows and coordinates of |q_reduced − q_unreduced|.
    max_abs_difference: f64,
    /// The time of the row where it is largest.
    at_time: f64,
    /// The largest difference in the last row.
    final_abs_difference: f64,
    /// The first time the difference exceeds the target, if it does.
    first_above_target: Option<f64>,
    /// max over rows of |x_reduced − x_unreduced| / (l1 + l2) for the position x of the second bob,
    /// which does not depend on the chart (the azimuths are ill-conditioned near the vertical).
    max_relative_position_difference: f64,
    target: f64,
    target_met: bool,
}

#[derive(Serialize)]
struct Report {
    double_spherical_pendulum: Comparison,
    agreement: Vec<Agreement>,
    /// Charged particle (left and midpoint), Kepler, heavy top.
    others: Vec<Comparison>,
}

/// Runs the group.
pub fn run(settings: &Settings) -> Result<Value, miette::Report> {
    let steps = if settings.quick { 1000 } else { 10_000 };
    print::heading("reduction", "reduced against unreduced equations");

    let geometry = DoubleSphericalPendulum::default();
    let system = built_in("double_spherical_pendulum")?;
    let system = system.as_ref();
    let problem = Problem { steps, ..DoubleSphericalPendulum::paper_problem(10_000) };
    let plus = method(Rule::Midpoint, true, Variant::Plus);
    let minus = method(Rule::Midpoint, true, Variant::Minus);
    let unreduced = method(Rule::Midpoint, false, Variant::Plus);
    let what = |m: &Method| format!("double spherical pendulum, midpoint, {}", method_name(m));
    let contenders = vec![
        engine("reduced (+)", &what(&plus), system, &problem, plus.clone())?,
        engine("reduced (−)", &what(&minus), system, &problem, minus.clone())?,
        engine("unreduced (+)", &what(&unreduced), system, &problem, unreduced.clone())?,
    ];
    let title = format!("double spherical pendulum (paper §7.2), midpoint, h = 0.01, {steps} steps");
    let pendulum = compare(
        title,
        settings.schedule,
        contenders,
        &[
            Pair::new("unreduced (+)", "reduced (+)").target(SPEED_UP),
            Pair::new("unreduced (+)", "reduced (−)").target(SPEED_UP),
        ],
    )?;
    print::comparison(&pendulum);

    let rows = |m: &Method| -> Result<(Vec<f64>, Vec<Vec<f64>>), miette::Report> {
        let output = OutputOptions { every: EVERY, wrap_angles: false };
        let (mut t, mut q) = (vec![], vec![]);
        let mut keep = |row: &ddirac::Row<'_>| {
            t.push(row.t);
            q.push(row.q.to_vec());
            Ok(())
        };
        system.integrate(&problem, m, &output, &mut keep).map_err(|e| super::failed(&what(m), e))?;
        Ok((t, q))
    };
    let mut agreement = vec![];
    println!("    agreement, max over rows every {EVERY} steps and coordinates of |q_reduced − q_unreduced|:");
    // The default Newton tolerance, and a tighter one: the near-pole passage amplifies the
    // per-step differences left by the Newton solves about 10⁵ times.
    for tolerance in [unreduced.newton.tolerance, TIGHT] {
        let tight = |m: &Method| Method { newton: NewtonOptions { tolerance, ..m.newton }, ..m.clone() };
        let unreduced = tight(&unreduced);
        println!("      Newton tolerance {tolerance:e}:");
        let (times, reference) = rows(&unreduced)?;
        for m in [&tight(&plus), &tight(&minus)] {
            let (_, q) = rows(m)?;
            let difference = max_difference(&q, &reference);
            let per_row: Vec<f64> = q
                .iter()
                .zip(&reference)
                .map(|(a, b)| max_difference(std::slice::from_ref(a), std::slice::from_ref(b)))
                .collect();
            let largest = per_row.iter().position(|&d| d == difference || d.is_nan()).unwrap_or(0);
            let at_time = times.get(largest).copied().unwrap_or(f64::NAN);
            let first_above_target =
                per_row.iter().position(|&d| d > AGREEMENT || d.is_nan()).and_then(|i| times.get(i).copied());
            let final_abs_difference = per_row.last().copied().unwrap_or(f64::NAN);
            let bobs = |rows: &[Vec<f64>]| -> Vec<[f64; 3]> {
                rows.iter()
                    .filter_map(|q| <[f64; 4]>::try_from(q.as_slice()).ok())
                    .map(|q| geometry.second_bob(&q))
                    .collect()
            };
            let position = max_difference(&bobs(&q), &bobs(&reference)) / (geometry.l1 + geometry.l2);
            let met = difference <= AGREEMENT;
            let above = first_above_target.map_or(String::new(), |t| format!(", above {AGREEMENT:e} from t = {t}"));
            println!(
                "        {} vs {}: {difference:.3e} at t = {at_time} (last row {final_abs_difference:.3e}{above})  \
             target ≤ {AGREEMENT:e}: {}",
                method_name(m),
                method_name(&unreduced),
                if met { "met" } else { "NOT met" }
            );
            println!("          second bob's position, max |Δx| / (l1 + l2): {position:.3e}");
            agreement.push(Agreement {
                tolerance,
                reduced: method_name(m),
                unreduced: method_name(&unreduced),
                every: EVERY,
                rows: reference.len(),
                max_abs_difference: difference,
                at_time,
                final_abs_difference,
                first_above_target,
                max_relative_position_difference: position,
                target: AGREEMENT,
                target_met: met,
            });
        }
    }

    // The engine runs of benches/steps.rs, 1000 steps each.
    let steps = if settings.quick { 200 } else { 1000 };
    let particle = built_in("charged_particle")?;
    // The paper's problem with h = 0.02.
    let particle_problem = Problem { steps, ..ChargedParticle::paper_problem(1000) };
    let others = vec![
        against_unreduced(
            settings,
            "charged particle, left, h = 0.02",
            particle.as_ref(),
            &particle_problem,
            Rule::Left,
            true,
        )?,
        against_unreduced(
            settings,
            "charged particle, midpoint, h = 0.02",
            particle.as_ref(),
            &particle_problem,
            Rule::Midpoint,
            true,
        )?,
        // An eccentric bound orbit (e ≈ 0.45).
        against_unreduced(
            settings,
            "Kepler, eccentric orbit, midpoint, h = 0.01",
            built_in("kepler")?.as_ref(),
            &Problem::new(0.01, steps, vec![1.0, 0.3], InitialMomentum::Momentum(vec![0.2, 1.2])),
            Rule::Midpoint,
            false,
        )?,
        // Fast spin ψ̇ ≈ 30.
        against_unreduced(
            settings,
            "heavy top, fast spin, midpoint, h = 0.001",
            built_in("heavy_top")?.as_ref(),
            &Problem::new(1e-3, steps, vec![0.0, 0.6, 0.0], InitialMomentum::Velocity(vec![0.4, 0.0, 30.0])),
            Rule::Midpoint,
            false,
        )?,
    ];
    to_json(&Report { double_spherical_pendulum: pendulum, agreement, others })
}

/// Reduced (+), with `minus` also reduced (−), against unreduced (+).
fn against_unreduced(
    settings: &Settings,
    name: &str,
    system: &dyn DynSystem,
    problem: &Problem,
    rule: Rule,
    minus: bool,
) -> Result<Comparison, miette::Report> {
    let mut methods = vec![method(rule, true, Variant::Plus)];
    if minus {
        methods.push(method(rule, true, Variant::Minus));
    }
    methods.push(method(rule, false, Variant::Plus));
    let names: Vec<String> = methods.iter().map(method_name).collect();
    let mut contenders = vec![];
    for (m, label) in methods.into_iter().zip(&names) {
        contenders.push(engine(label, &format!("{name}, {label}"), system, problem, m)?);
    }
    let (unreduced, reduced) = names.split_last().ok_or_else(|| miette::miette!("no methods to compare"))?;
    let pairs: Vec<Pair<'_>> = reduced.iter().map(|r| Pair::new(unreduced, r)).collect();
    let title = format!("{name}, {} steps", problem.steps);
    let comparison = compare(title, settings.schedule, contenders, &pairs)?;
    print::comparison(&comparison);
    Ok(comparison)
}
