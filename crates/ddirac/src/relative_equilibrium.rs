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
//! group coordinate, through its folds by pseudo-arclength continuation (Keller), each fold located
//! where the family's tangent has no momentum component ([`Fold`]).

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
    let far = 1e3 * amax(&x).max(1.0);
    loop {
        if iterations >= options.max_iterations {
            let (k, value) =
                x.iter().enumerate().fold((0usize, 0.0f64), |m, (k, v)| if v.abs() > m.1.abs() { (k, *v) } else { m });
            let cause = match value.abs() > far {
                true => {
                    let name = &map.coordinates[map.shape[k % n]].name;
                    let name = if k < n { name.clone() } else { format!("p_{name}") };
                    SearchFailure::RanOff { name, value }
                }
                false => SearchFailure::NoConvergence,
            };
            return Err(failed(iterations, amax(&g), cause));
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
    /// The folds passed, in the order of the family: at each the momentum turns back, and the family
    /// continues over the values already visited on another branch.
    pub folds: Vec<Fold>,
    /// Where the family ended before the last value, and why: the value whose search failed and its
    /// error.
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
/// starts from the two points of the family before it, extrapolated linearly). The first value's search
/// starts from `problem`'s shape; when it fails, so does the family.
///
/// Where a later search fails, the family is continued from its last two points by pseudo-arclength
/// (Keller: predictor along the tangent, corrector on the hyperplane normal to it, with DΦ_h and ∂Φ_h/∂μ
/// by extrapolated central differences). If the momentum reaches the value, its member is found from
/// there; if the momentum turns back first, the family has a fold: it is located where the tangent's
/// momentum component vanishes ([`Fold`]), and the family continues on the other branch over the values
/// already visited, in reverse order. A failure of both ends the family there ([`Family::ended`]).
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
    let point = |m: &RelativeEquilibrium, value: f64| [m.shape.clone(), m.shape_momentum.clone(), vec![value]].concat();
    let (mut members, mut folds) = (Vec::<RelativeEquilibrium>::new(), Vec::<Fold>::new());
    let mut ended = None;
    // The last two points of the family, (s, p_s, μ), the newest last.
    let mut trail: Vec<Point> = vec![];
    let (mut k, mut forward) = (0usize, true);
    loop {
        let value = values[k];
        map.p0[index] = value;
        let guess = match trail.as_slice() {
            [] => map.start(),
            [only] => only[..only.len() - 1].to_vec(),
            [.., a, b] => extrapolate(a, b, value),
        };
        match solve(&mut map, guess, options) {
            Ok(found) => {
                trail.push(point(&found, value));
                members.push(found);
            }
            Err(error @ Error::Interrupted { .. }) => return Err(error),
            Err(error) if members.is_empty() => return Err(error),
            Err(error) => {
                let behind = neighbour(k, !forward, values.len()).map(|j| values[j]);
                let passage = match trail.as_slice() {
                    [.., a, b] => Some(pass(&mut map, index, (a, b), value, behind, options)),
                    _ => None,
                };
                let passage = match passage {
                    Some(Ok(passage)) => passage,
                    Some(Err(interrupted @ Error::Interrupted { .. })) => return Err(interrupted),
                    _ => {
                        ended = Some((value, error));
                        break;
                    }
                };
                for y in &passage.folds {
                    let n = map.shape.len();
                    folds.push(Fold {
                        momentum: y[2 * n],
                        shape: y[..n].to_vec(),
                        shape_momentum: y[n..2 * n].to_vec(),
                        next_member: members.len(),
                    });
                    forward = !forward;
                }
                let Some((target, guess, before)) = passage.reached else { break };
                if passage.folds.len() % 2 == 1 {
                    k = neighbour(k, forward, values.len()).expect("a value lies behind a fold the family reached");
                }
                map.p0[index] = target;
                match solve(&mut map, guess, options) {
                    Ok(found) => {
                        trail = vec![before, point(&found, target)];
                        members.push(found);
                    }
                    Err(error @ Error::Interrupted { .. }) => return Err(error),
                    Err(error) => {
                        ended = Some((target, error));
                        break;
                    }
                }
            }
        }
        if trail.len() > 2 {
            trail.remove(0);
        }
        match neighbour(k, forward, values.len()) {
            Some(next) if folds.len() <= MAX_FOLDS => k = next,
            _ => break,
        }
    }
    Ok(Family { along: along.to_owned(), members, folds, ended })
}

/// The index after `k` among `len` values, going forward or backward.
fn neighbour(k: usize, forward: bool, len: usize) -> Option<usize> {
    match forward {
        true => (k + 1 < len).then_some(k + 1),
        false => k.checked_sub(1),
    }
}

/// (s, p_s) at the momentum `value` on the line through the points `a` and `b` of the family.
fn extrapolate(a: &[f64], b: &[f64], value: f64) -> Vec<f64> {
    let m = a.len() - 1;
    let t = if b[m] != a[m] { (value - b[m]) / (b[m] - a[m]) } else { 0.0 };
    b[..m].iter().zip(&a[..m]).map(|(b, a)| b + t * (b - a)).collect()
}

/// A fold of a family: where its momentum turns back, and the family with it onto another branch.
#[derive(Debug, Clone, PartialEq)]
pub struct Fold {
    /// The momentum of the family's group coordinate at the fold.
    pub momentum: f64,
    /// s* at the fold.
    pub shape: Vec<f64>,
    /// p_s* at the fold.
    pub shape_momentum: Vec<f64>,
    /// The index of the first member past the fold: the members before it lie on the branch that
    /// reaches the fold, those from it on the branch that leaves it.
    pub next_member: usize,
}

/// The most arclength steps of one passage between two values of the momentum.
const MAX_ARCLENGTH_STEPS: usize = 400;

/// The most folds a family passes (each turns the family back over the values already visited).
const MAX_FOLDS: usize = 8;

/// A point of a family in y = (s, p_s, μ): the momentum last.
type Point = Vec<f64>;

/// Where an arclength passage ended: at a value of the momentum (a guess there, interpolated between the
/// points that straddle it, and the point before), with the folds passed on the way; or at a fold past
/// which no value lies.
struct Passage {
    folds: Vec<Point>,
    reached: Option<(f64, Point, Point)>,
}

impl ReducedMap<'_> {
    /// Φ_h(x) − x on the level μ, for y = (x, μ), with the momentum of coordinate `index`.
    fn gap(&mut self, index: usize, y: &[f64]) -> Result<Vec<f64>, Error> {
        let m = y.len() - 1;
        self.p0[index] = y[m];
        let (image, _) = self.apply(&y[..m])?;
        Ok(image.iter().zip(y).map(|(a, b)| a - b).collect())
    }

    /// The Jacobian of y ↦ Φ_h(x) − x on the level μ: [DΦ_h − I | ∂Φ_h/∂μ], m × (m + 1), by the
    /// extrapolated central differences of [`ReducedMap::jacobian`].
    fn extended_jacobian(&mut self, index: usize, y: &[f64]) -> Result<DMatrix<f64>, Error> {
        let m = y.len() - 1;
        self.p0[index] = y[m];
        let (jacobian, _) = self.jacobian(&y[..m])?;
        let delta = 1e-3 * y[m].abs().max(1.0);
        let mut at = |factor: f64| -> Result<Vec<f64>, Error> {
            self.p0[index] = y[m] + factor * delta;
            Ok(self.apply(&y[..m])?.0)
        };
        let (p1, m1, p2, m2) = (at(1.0)?, at(-1.0)?, at(2.0)?, at(-2.0)?);
        self.p0[index] = y[m];
        let mut extended = DMatrix::zeros(m, m + 1);
        extended.view_mut((0, 0), (m, m)).copy_from(&(jacobian - DMatrix::identity(m, m)));
        for i in 0..m {
            let (d1, d2) = ((p1[i] - m1[i]) / (2.0 * delta), (p2[i] - m2[i]) / (4.0 * delta));
            extended[(i, m)] = (4.0 * d1 - d2) / 3.0;
        }
        Ok(extended)
    }
}

/// The unit tangent of the family at `y` oriented along `along`: the kernel of the extended Jacobian `a`.
fn tangent(a: &DMatrix<f64>, along: &[f64]) -> Option<Point> {
    let m = a.nrows();
    let mut bordered = DMatrix::zeros(m + 1, m + 1);
    bordered.view_mut((0, 0), (m, m + 1)).copy_from(a);
    bordered.row_mut(m).iter_mut().zip(along).for_each(|(b, t)| *b = *t);
    let mut rhs = nalgebra::DVector::zeros(m + 1);
    rhs[m] = 1.0;
    let t = bordered.full_piv_lu().solve(&rhs)?;
    let norm = t.norm();
    (norm.is_finite() && norm > 0.0).then(|| t.iter().map(|x| x / norm).collect())
}

/// The point of the family on the hyperplane through `predicted` normal to `t` (pseudo-arclength),
/// by Newton's method from `predicted`, with the family's tangent there.
fn correct(
    map: &mut ReducedMap<'_>,
    index: usize,
    predicted: &[f64],
    t: &[f64],
    options: &SearchOptions,
) -> Result<(Point, Point), Error> {
    let m = predicted.len() - 1;
    let mut y = predicted.to_vec();
    for _ in 0..options.max_iterations {
        let gap = map.gap(index, &y)?;
        let a = map.extended_jacobian(index, &y)?;
        let mut bordered = DMatrix::zeros(m + 1, m + 1);
        bordered.view_mut((0, 0), (m, m + 1)).copy_from(&a);
        bordered.row_mut(m).iter_mut().zip(t).for_each(|(b, t)| *b = *t);
        let plane: f64 = y.iter().zip(predicted).zip(t).map(|((y, p), t)| (y - p) * t).sum();
        let rhs = nalgebra::DVector::from_iterator(m + 1, gap.iter().chain([&plane]).map(|v| -v));
        let step = bordered.full_piv_lu().solve(&rhs).ok_or(Error::RelativeEquilibrium {
            iterations: 0,
            residual: amax(&gap),
            cause: SearchFailure::Singular,
        })?;
        y.iter_mut().zip(step.iter()).for_each(|(y, d)| *y += d);
        if !y.iter().all(|v| v.is_finite()) {
            break;
        }
        if amax(step.as_slice()) <= options.tolerance * amax(&y).max(1.0) {
            let a = map.extended_jacobian(index, &y)?;
            if let Some(tangent) = tangent(&a, t) {
                return Ok((y, tangent));
            }
            break;
        }
    }
    Err(Error::RelativeEquilibrium {
        iterations: options.max_iterations,
        residual: f64::NAN,
        cause: SearchFailure::NoConvergence,
    })
}

/// The fold between the points `a` and `b` of the family, whose tangents `ta` and `tb` point to
/// opposite sides in the momentum: the point where the tangent's momentum component vanishes, found by
/// regula falsi (Illinois) on the arclength from `a` along `ta`.
fn locate_fold(
    map: &mut ReducedMap<'_>,
    index: usize,
    (a, ta): (&Point, &Point),
    (b, tb): (&Point, &Point),
    options: &SearchOptions,
) -> Result<Point, Error> {
    let m = a.len() - 1;
    let mut low = (0.0, ta[m], a.clone());
    let mut high = (b.iter().zip(a).zip(ta.iter()).map(|((b, a), t)| (b - a) * t).sum::<f64>(), tb[m], b.clone());
    let mut side = 0i8;
    for _ in 0..40 {
        let (f0, f1) = (low.1, high.1);
        let sigma = low.0 - f0 * (high.0 - low.0) / (f1 - f0);
        if !(sigma > low.0.min(high.0) && sigma < low.0.max(high.0)) {
            break;
        }
        let predicted: Point = a.iter().zip(ta.iter()).map(|(a, t)| a + sigma * t).collect();
        let (y, t) = correct(map, index, &predicted, ta, options)?;
        let f = t[m];
        if f.abs() <= 1e-10 || (high.0 - low.0).abs() <= 1e-12 * amax(&y).max(1.0) {
            return Ok(y);
        }
        // Illinois: halve the value kept at the end that stays twice in a row.
        if (f > 0.0) == (f0 > 0.0) {
            low = (sigma, f, y);
            if side == -1 {
                high.1 *= 0.5;
            }
            side = -1;
        } else {
            high = (sigma, f, y);
            if side == 1 {
                low.1 *= 0.5;
            }
            side = 1;
        }
    }
    Ok(if low.1.abs() < high.1.abs() { low.2 } else { high.2 })
}

/// Continues the family by pseudo-arclength from its last two points `a` and `b` until the momentum
/// reaches `ahead`, or, past a fold (where it turns back), `behind` (past a second fold `ahead` again).
fn pass(
    map: &mut ReducedMap<'_>,
    index: usize,
    (a, b): (&Point, &Point),
    ahead: f64,
    behind: Option<f64>,
    options: &SearchOptions,
) -> Result<Passage, Error> {
    let m = b.len() - 1;
    let chord: Point = b.iter().zip(a).map(|(b, a)| b - a).collect();
    let longest = chord.iter().map(|c| c * c).sum::<f64>().sqrt();
    let no_passage = |cause| Error::RelativeEquilibrium { iterations: 0, residual: f64::NAN, cause };
    if !(longest > 0.0 && longest.is_finite()) {
        return Err(no_passage(SearchFailure::NoConvergence));
    }
    let chord: Point = chord.iter().map(|c| c / longest).collect();
    let mut t = tangent(&map.extended_jacobian(index, b)?, &chord).unwrap_or(chord);
    let (mut y, mut ds, mut direction) = (b.clone(), longest, t[m].signum());
    let mut folds: Vec<Point> = vec![];
    let mut target = Some(ahead);
    for _ in 0..MAX_ARCLENGTH_STEPS {
        let predicted: Point = y.iter().zip(&t).map(|(y, t)| y + ds * t).collect();
        let (next, t_next) = match correct(map, index, &predicted, &t, options) {
            Ok(corrected) => corrected,
            Err(interrupted @ Error::Interrupted { .. }) => return Err(interrupted),
            Err(error) => {
                ds *= 0.5;
                if ds < 1e-6 * longest {
                    return Err(error);
                }
                continue;
            }
        };
        // The momentum is compared from the fold on when the fold lies between y and next.
        let mut from = y.clone();
        if t_next[m] * direction < 0.0 {
            let fold = locate_fold(map, index, (&y, &t), (&next, &t_next), options)?;
            from = fold.clone();
            folds.push(fold);
            direction = -direction;
            target = if folds.len() % 2 == 1 { behind } else { Some(ahead) };
            let Some(_) = target else { return Ok(Passage { folds, reached: None }) };
            if folds.len() > MAX_FOLDS {
                return Err(no_passage(SearchFailure::NoConvergence));
            }
        }
        let value = target.expect("a passage has a target until a fold with none behind it");
        if (from[m] - value) * (next[m] - value) <= 0.0 && next[m] != from[m] {
            let w = (value - from[m]) / (next[m] - from[m]);
            let guess = from[..m].iter().zip(&next[..m]).map(|(f, n)| f + w * (n - f)).collect();
            return Ok(Passage { folds, reached: Some((value, guess, from)) });
        }
        y = next;
        t = t_next;
        ds = (1.5 * ds).min(longest);
    }
    Err(no_passage(SearchFailure::NoConvergence))
}
