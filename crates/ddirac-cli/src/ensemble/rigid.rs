//! The members of an ensemble of a rigid body: each is run exactly as `ddirac run SPEC --set
//! KEY=VALUE ...` runs it ([`RigidStepper`], one step after another), so its results equal that run's
//! bit for bit, and a member that fails is recorded while the others go on.

use std::time::Instant;

use ddirac::rigid::{RigidInitial, RigidProblem, RigidRow, RigidStepper, RigidSystem};
use ddirac::{Error, Method};

use super::{Ended, MemberRows};
use crate::rigid::plan::RigidModel;

/// A member's state as [`super::Layout`] orders it: R (rows), Π, then s and p when the body has
/// shape coordinates.
fn state(row: &RigidRow) -> Vec<f64> {
    let mut values: Vec<f64> = row.r.iter().flatten().copied().collect();
    values.extend_from_slice(&row.pi);
    values.extend_from_slice(&row.s);
    values.extend_from_slice(&row.p);
    values
}

/// The state of a member refused before its first step: R0, Π0 (NaN when the spec gives Ω0), s0 and
/// p0 (NaN when it gives velocities).
fn initial_state(problem: &RigidProblem) -> Vec<f64> {
    let (pi, p) = match &problem.initial {
        RigidInitial::Momentum { pi, p } => (*pi, p.clone()),
        RigidInitial::Velocity { v, .. } => ([f64::NAN; 3], vec![f64::NAN; v.len()]),
    };
    let mut values: Vec<f64> = problem.r0.iter().flatten().copied().collect();
    values.extend_from_slice(&pi);
    values.extend_from_slice(&problem.s0);
    values.extend_from_slice(&p);
    values
}

/// What a member gives the ensemble: its final state, how it ended, its rows (when kept) and its wall
/// time in seconds.
pub(super) struct RigidOutcome {
    pub state: Vec<f64>,
    pub ended: Ended,
    pub rows: Option<MemberRows>,
    pub seconds: f64,
}

/// Runs one member, reporting every `every`-th row (and the last) when `keep_rows`. Only a stop
/// request is an error; every other failure is the member's.
pub(super) fn run_member(
    body: &RigidModel,
    problem: RigidProblem,
    method: &Method,
    every: usize,
    keep_rows: bool,
) -> Result<RigidOutcome, Error> {
    let started = Instant::now();
    let shape = body.shape().len();
    let mut stepper = match RigidStepper::new(body, problem.clone(), method) {
        Ok(stepper) => stepper,
        Err(error) => {
            let ended = Ended::Failed { step: 0, t: 0.0, error: error.to_string() };
            return Ok(RigidOutcome { state: initial_state(&problem), ended, rows: None, seconds: 0.0 });
        }
    };
    let mut rows = keep_rows.then(|| MemberRows::new(if shape > 0 { 4 } else { 2 }));
    let mut keep = |row: &RigidRow| {
        if let Some(rows) = &mut rows {
            rows.t.push(row.t);
            rows.state[0].extend(row.r.iter().flatten());
            rows.state[1].extend_from_slice(&row.pi);
            if shape > 0 {
                rows.state[2].extend_from_slice(&row.s);
                rows.state[3].extend_from_slice(&row.p);
            }
            rows.energy.push(row.energy);
        }
    };
    keep(&stepper.row());
    let every = every.max(1);
    while !stepper.is_finished() {
        if ddirac::interrupt::requested() {
            return Err(Error::Interrupted { step: stepper.k(), t: stepper.row().t });
        }
        if let Err(error) = stepper.step() {
            let row = stepper.row();
            let ended = Ended::Failed { step: row.k, t: row.t, error: error.to_string() };
            return Ok(RigidOutcome { state: state(&row), ended, rows, seconds: 0.0 });
        }
        if stepper.k() % every == 0 || stepper.is_finished() {
            keep(&stepper.row());
        }
    }
    let summary = stepper.summary();
    let derivatives = if body.principal_axes().is_some() { "closed form" } else { "dual" };
    let ended = Ended::finished(
        summary.steps,
        &summary.energy,
        summary.momentum_map.max_drift,
        &summary.newton,
        None,
        derivatives.to_owned(),
        &summary.warnings,
    );
    let state = state(&stepper.row());
    Ok(RigidOutcome { state, ended, rows, seconds: started.elapsed().as_secs_f64() })
}
