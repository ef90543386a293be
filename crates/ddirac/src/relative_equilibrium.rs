//! Relative equilibria of the discrete flow on a momentum level (discrete Routh reduction,
//! Jalnapurkar, Leok, Marsden & West).
//!
//! With an abelian symmetry the momenta μ of the group coordinates g are conserved by every step, and
//! a step does not depend on g: on the level J = μ it is a map of the shape coordinates and their
//! momenta, x = (s, p_s),
//!
//! ```text
//! Φ_h(x) = (s_{k+1}, p_{s,k+1})   for the step from (s_k, g_k, p_{s,k}, μ) with any g_k,
//! ```
//!
//! the reduced discrete map of the method (its rule, composition, reduction and atlas, with the step h
//! of the spec). A relative equilibrium is a fixed point Φ_h(x*) = x*: the shape and its momenta stay
//! and the group coordinates advance by the same increment Δg at every step, the group velocity Δg/h.
//! Its stability on the level is read from the linearized map DΦ_h(x*): a symplectic map's
//! multipliers (eigenvalues) come in pairs λ, 1/λ̄; the relative equilibrium is (spectrally) stable
//! when all of them lie on the unit circle, unstable when one lies outside.
//!
//! [`find`] solves Φ_h(x) − x = 0 by Newton's method from the spec's initial shape and shape momenta
//! on the level of its initial group momenta. DΦ_h is taken from the method's own steps by central
//! differences extrapolated to fourth order (Richardson: steps ±δ and ±2δ, δ = 10⁻³ max(1, |x_i|)),
//! with an estimate of its error from the same extrapolation at 2δ; the multipliers' moduli are
//! judged against that estimate. [`family`] continues a relative equilibrium along the momentum of one
//! group coordinate.

use nalgebra::DMatrix;

use crate::coordinate::{Coordinate, CoordinateKind, Role};
pub use crate::error::SearchFailure;
use crate::{DynState, DynStepper, DynSystem, Error, Input, Method, Problem, Reason};

/// Tolerances of the search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchOptions {
    /// The search stops when a Newton correction is below `tolerance · max(1, ‖x‖∞)`.
    pub tolerance: f64,
    /// The largest number of Newton corrections.
    pub max_iterations: usize,
}

impl Default for SearchOptions {
    fn default() -> Self {
        Self { tolerance: 1e-12, max_iterations: 50 }
    }
}

/// A relative equilibrium of the reduced discrete map.
#[derive(Debug, Clone, PartialEq)]
pub struct RelativeEquilibrium {
    /// The shape coordinates' names, in the system's order.
    pub shape_names: Vec<String>,
    /// s*.
    pub shape: Vec<f64>,
    /// p_s*.
    pub shape_momentum: Vec<f64>,
    /// The group coordinates' names.
    pub group_names: Vec<String>,
    /// The momentum level μ (the group coordinates' momenta).
    pub momentum: Vec<f64>,
    /// Δg / h: the group coordinates' increment per unit time.
    pub group_velocity: Vec<f64>,
    /// The step h of the map.
    pub step: f64,
    /// The eigenvalues of DΦ_h(x*) as (re, im), by increasing angle.
    pub multipliers: Vec<(f64, f64)>,
    /// The uncertainty of the multipliers' moduli from that of DΦ_h: a modulus within this of 1 counts
    /// as on the unit circle.
    pub modulus_tolerance: f64,
    /// Whether every multiplier lies on the unit circle (within `modulus_tolerance`).
    pub stable: bool,
    /// det DΦ_h(x*): 1 for a symplectic map.
    pub determinant: f64,
    /// ‖Φ_h(x*) − x*‖∞.
    pub residual: f64,
    /// Newton corrections taken.
    pub iterations: usize,
    /// The angles among the group coordinates that turn by more than π/2 in a step: their increment,
    /// read from angles, is known only modulo 2π, and their group velocity modulo 2π/h.
    pub ambiguous: Vec<String>,
}

impl RelativeEquilibrium {
    /// The largest ||λ| − 1| over the multipliers.
    pub fn off_circle(&self) -> f64 {
        self.multipliers.iter().map(|(re, im)| (re.hypot(*im) - 1.0).abs()).fold(0.0, f64::max)
    }
}

/// The reduced map of one step on a momentum level.
struct ReducedMap<'a> {
    stepper: Box<dyn DynStepper + 'a>,
    q0: Vec<f64>,
    p0: Vec<f64>,
    shape: Vec<usize>,
    group: Vec<usize>,
    coordinates: Vec<Coordinate>,
    step: f64,
}

impl ReducedMap<'_> {
    /// Φ_h(x) and the group coordinates' increment.
    fn apply(&mut self, x: &[f64]) -> Result<(Vec<f64>, Vec<f64>), Error> {
        let n = self.shape.len();
        let (mut q, mut p) = (self.q0.clone(), self.p0.clone());
        for (k, &i) in self.shape.iter().enumerate() {
            q[i] = x[k];
            p[i] = x[n + k];
        }
        self.stepper.restart(&DynState::new(0, q.clone(), p))?;
        self.stepper.step()?;
        let row = self.stepper.row();
        let mut next: Vec<f64> = self.shape.iter().map(|&i| row.q[i]).collect();
        next.extend(self.shape.iter().map(|&i| row.p[i]));
        let increment = self.group.iter().map(|&i| row.q[i] - q[i]).collect();
        Ok((next, increment))
    }

    /// DΦ_h(x) by central differences extrapolated to fourth order, and an estimate of its error (the
    /// largest entry of the difference from the same extrapolation at twice the steps).
    fn jacobian(&mut self, x: &[f64]) -> Result<(DMatrix<f64>, f64), Error> {
        let m = x.len();
        let mut jacobian = DMatrix::zeros(m, m);
        let mut error: f64 = 0.0;
        for j in 0..m {
            let delta = 1e-3 * x[j].abs().max(1.0);
            let mut at = |factor: f64| -> Result<Vec<f64>, Error> {
                let mut y = x.to_vec();
                y[j] += factor * delta;
                Ok(self.apply(&y)?.0)
            };
            let (p1, m1, p2, m2, p4, m4) = (at(1.0)?, at(-1.0)?, at(2.0)?, at(-2.0)?, at(4.0)?, at(-4.0)?);
            for i in 0..m {
                let d1 = (p1[i] - m1[i]) / (2.0 * delta);
                let d2 = (p2[i] - m2[i]) / (4.0 * delta);
                let d4 = (p4[i] - m4[i]) / (8.0 * delta);
                let fine = (4.0 * d1 - d2) / 3.0;
                let coarse = (4.0 * d2 - d4) / 3.0;
                jacobian[(i, j)] = fine;
                error = error.max((fine - coarse).abs() / 16.0);
            }
        }
        Ok((jacobian, error))
    }
}

fn amax(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

impl<'a> ReducedMap<'a> {
    /// The map of one step of `method` with the step of `problem`, on the level of `problem`'s initial
    /// group momenta (the momenta of the Legendre transform when it gives velocities).
    fn new(system: &'a dyn DynSystem, problem: &Problem, method: &Method) -> Result<Self, Error> {
        let coordinates = system.coordinates();
        let shape = (0..coordinates.len()).filter(|&i| coordinates[i].role == Role::Shape).collect();
        let group = (0..coordinates.len()).filter(|&i| coordinates[i].role == Role::Group).collect();
        let one_step = Problem::new(problem.step, 1, problem.q0.clone(), problem.initial.clone());
        let mut stepper = system.stepper(&one_step, method)?;
        stepper.set_wrap_angles(false);
        let first = stepper.row();
        Ok(Self { stepper, q0: first.q, p0: first.p, shape, group, coordinates, step: problem.step })
    }

    /// The initial data's shape and shape momenta.
    fn start(&self) -> Vec<f64> {
        let mut x: Vec<f64> = self.shape.iter().map(|&i| self.q0[i]).collect();
        x.extend(self.shape.iter().map(|&i| self.p0[i]));
        x
    }
}

/// The relative equilibrium of the reduced discrete map of `method` with the step of `problem`, on
/// the momentum level of `problem`'s initial group momenta, nearest (by Newton's method) to its initial
/// shape and shape momenta. A system without group coordinates has equilibria: fixed points of the
/// step.
///
/// Errors: those of the stepper for the problem, and [`Error::RelativeEquilibrium`] when the search
/// fails.
pub fn find(
    system: &dyn DynSystem,
    problem: &Problem,
    method: &Method,
    options: &SearchOptions,
) -> Result<RelativeEquilibrium, Error> {
    let mut map = ReducedMap::new(system, problem, method)?;
    let start = map.start();
    solve(&mut map, start, options)
}

/// Newton's method on Φ_h(x) − x from `x`, and the relative equilibrium it finds.
fn solve(map: &mut ReducedMap<'_>, mut x: Vec<f64>, options: &SearchOptions) -> Result<RelativeEquilibrium, Error> {
    let n = map.shape.len();
    let failed = |iterations: usize, residual: f64, cause: SearchFailure| Error::RelativeEquilibrium {
        iterations,
        residual,
        cause,
    };
    let mut iterations = 0;
    let step_failed = |iterations, residual, e: Error| match e {
        interrupted @ Error::Interrupted { .. } => interrupted,
        other => failed(iterations, residual, SearchFailure::Step(Box::new(other))),
    };
    let (image, _) = map.apply(&x).map_err(|e| step_failed(0, f64::NAN, e))?;
    let mut g: Vec<f64> = image.iter().zip(&x).map(|(a, b)| a - b).collect();
    loop {
        if iterations >= options.max_iterations {
            return Err(failed(iterations, amax(&g), SearchFailure::NoConvergence));
        }
        let (jacobian, _) = map.jacobian(&x).map_err(|e| step_failed(iterations, amax(&g), e))?;
        let a = jacobian - DMatrix::identity(2 * n, 2 * n);
        let rhs = nalgebra::DVector::from_iterator(2 * n, g.iter().map(|v| -v));
        let Some(dx) = a.full_piv_lu().solve(&rhs) else {
            return Err(failed(iterations, amax(&g), SearchFailure::Singular));
        };
        iterations += 1;
        // Backtracking: halve the correction while it does not reduce the residual, unless the
        // residual is at the level of round-off in Φ_h, where it cannot decrease.
        let floor = 1e-15 * amax(&x).max(1.0);
        let mut scale = 1.0;
        let (candidate, candidate_g) = loop {
            let y: Vec<f64> = x.iter().zip(dx.iter()).map(|(a, d)| a + scale * d).collect();
            let attempt = map.apply(&y).map(|(f, _)| f.iter().zip(&y).map(|(a, b)| a - b).collect::<Vec<f64>>());
            match attempt {
                Ok(r) if amax(&r) < amax(&g) || amax(&r) <= floor || scale < 1.0 / 64.0 => break (y, r),
                Err(e) if scale < 1.0 / 64.0 => return Err(step_failed(iterations, amax(&g), e)),
                _ => scale *= 0.5,
            }
        };
        let correction = scale * amax(dx.as_slice());
        x = candidate;
        g = candidate_g;
        if !x.iter().chain(&g).all(|v| v.is_finite()) {
            return Err(failed(iterations, f64::NAN, SearchFailure::NoConvergence));
        }
        if scale == 1.0 && correction <= options.tolerance * amax(&x).max(1.0) {
            break;
        }
    }
    let (jacobian, error) = map.jacobian(&x).map_err(|e| step_failed(iterations, amax(&g), e))?;
    let (_, increment) = map.apply(&x).map_err(|e| step_failed(iterations, amax(&g), e))?;
    let determinant = jacobian.determinant();
    let mut multipliers: Vec<(f64, f64)> = jacobian.complex_eigenvalues().iter().map(|c| (c.re, c.im)).collect();
    multipliers.sort_by(|a, b| a.1.atan2(a.0).total_cmp(&b.1.atan2(b.0)));
    // An error E in DΦ moves its eigenvalues by about ‖E‖ (times their condition, near 1 for the
    // distinct multipliers of an elliptic fixed point).
    let modulus_tolerance = (100.0 * error * (2 * n) as f64).max(1e-9);
    let largest = multipliers.iter().map(|(re, im)| re.hypot(*im)).fold(0.0, f64::max);
    let stable = largest <= 1.0 + modulus_tolerance;
    let coordinates = &map.coordinates;
    let names = |indices: &[usize]| indices.iter().map(|&i| coordinates[i].name.clone()).collect::<Vec<_>>();
    let ambiguous = map
        .group
        .iter()
        .zip(&increment)
        .filter(|(&i, d)| coordinates[i].kind == CoordinateKind::Angle && d.abs() > std::f64::consts::FRAC_PI_2)
        .map(|(&i, _)| coordinates[i].name.clone())
        .collect();
    Ok(RelativeEquilibrium {
        shape_names: names(&map.shape),
        shape: x[..n].to_vec(),
        shape_momentum: x[n..].to_vec(),
        group_names: names(&map.group),
        momentum: map.group.iter().map(|&i| map.p0[i]).collect(),
        group_velocity: increment.iter().map(|d| d / map.step).collect(),
        step: map.step,
        multipliers,
        modulus_tolerance,
        stable,
        determinant,
        residual: amax(&g),
        iterations,
        ambiguous,
    })
}

/// A family of relative equilibria along the momentum of one group coordinate.
#[derive(Debug)]
pub struct Family {
    /// The group coordinate whose momentum varies.
    pub along: String,
    /// The relative equilibria found, one per value of its momentum, in the order of the values.
    pub members: Vec<RelativeEquilibrium>,
    /// Where the family ended before the last value, and why: the value whose search failed and its
    /// error (natural continuation ends at a fold, where the family turns back in the momentum).
    pub ended: Option<(f64, Error)>,
}

impl Family {
    /// The momentum of `along` of each member.
    pub fn values(&self) -> Vec<f64> {
        let k = self.members.first().map_or(0, |m| m.group_names.iter().position(|g| *g == self.along).unwrap_or(0));
        self.members.iter().map(|m| m.momentum[k]).collect()
    }

    /// The consecutive values between which the stability changes.
    pub fn stability_changes(&self) -> Vec<(f64, f64)> {
        let values = self.values();
        (1..self.members.len())
            .filter(|&k| self.members[k].stable != self.members[k - 1].stable)
            .map(|k| (values[k - 1], values[k]))
            .collect()
    }
}

/// The family of relative equilibria through the one [`find`] finds for `problem`, continued along the
/// momentum of the group coordinate `along` over `values` (natural continuation: each member's search
/// starts from the member before, extrapolated linearly from the two before). The first value's search
/// starts from `problem`'s shape; when it fails, so does the family. A later failure ends the family
/// there ([`Family::ended`]).
pub fn family(
    system: &dyn DynSystem,
    problem: &Problem,
    method: &Method,
    along: &str,
    values: &[f64],
    options: &SearchOptions,
) -> Result<Family, Error> {
    let mut map = ReducedMap::new(system, problem, method)?;
    let refuse = |why: String| Error::Invalid { what: Input::Argument("along".into()), why: Reason::Other(why) };
    let Some(&index) = map.group.iter().find(|&&i| map.coordinates[i].name == along) else {
        let group: Vec<&str> = map.group.iter().map(|&i| map.coordinates[i].name.as_str()).collect();
        return Err(refuse(match group.is_empty() {
            true => format!("`{along}` is not a group coordinate: this system has none, and no momentum to vary"),
            false => format!("`{along}` is not a group coordinate; the group coordinates are {}", group.join(", ")),
        }));
    };
    if values.is_empty() {
        return Err(refuse("the family has no values of the momentum".into()));
    }
    if let Some(v) = values.iter().find(|v| !v.is_finite()) {
        return Err(refuse(format!("the momentum {v} is not a finite number")));
    }
    let mut members: Vec<RelativeEquilibrium> = vec![];
    let mut ended = None;
    for (k, &value) in values.iter().enumerate() {
        map.p0[index] = value;
        let state = |m: &RelativeEquilibrium| [m.shape.clone(), m.shape_momentum.clone()].concat();
        let guess = match members.len() {
            0 => map.start(),
            1 => state(&members[0]),
            len => {
                let (a, b) = (state(&members[len - 2]), state(&members[len - 1]));
                let (va, vb) = (values[k - 2], values[k - 1]);
                let t = if vb != va { (value - vb) / (vb - va) } else { 0.0 };
                b.iter().zip(&a).map(|(b, a)| b + t * (b - a)).collect()
            }
        };
        match solve(&mut map, guess, options) {
            Ok(found) => members.push(found),
            Err(error @ Error::Interrupted { .. }) => return Err(error),
            Err(error) if k == 0 => return Err(error),
            Err(error) => {
                ended = Some((value, error));
                break;
            }
        }
    }
    Ok(Family { along: along.to_owned(), members, ended })
}
