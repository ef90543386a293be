//! A text system with n coordinates run by the engine built for a larger size M ∈ [`crate::SIZES`],
//! on request ([`crate::expression::ExpressionSpec::into_dyn_in`]): for measuring what a larger
//! engine costs and holding the runs of two engines against each other.
//!
//! The system is embedded in the larger engine: it gets M − n
//! *padding coordinates*, shape coordinates on ℝ with the Lagrangian ½ c v² each, added to L. They
//! are decoupled from the system's own coordinates and start at q = p = 0, so every discrete scheme
//! keeps them at exactly 0: their step equations are c (q₁ − q₀)/h = p = 0 whatever the other
//! coordinates do, every derivative of L that mixes them with another coordinate is exactly 0, and
//! an elimination that meets their rows or columns subtracts exact zeros from the others. The
//! system's own coordinates therefore follow the same arithmetic as in an engine of exactly n
//! coordinates (the tests hold a padded run against an unpadded one, bit for bit).
//!
//! What the padding can change is the scale the engine compares pivots with (a pivot below 10⁻¹⁰ of
//! the largest entry counts as zero): c is the largest entry of ∂²L/∂v² (or, for a Lagrangian
//! linear in v, of ∂²L/∂q∂v) at a reference point, so that it is of the system's own scale, not of
//! an arbitrary unit (a system in SI units with an electron's mass has entries of 10⁻³⁰).
//!
//! `Padded` hides the padding: the problem, the connection and cold states are extended by zeros
//! (after their sizes are checked against n, so errors name the system's own sizes), and rows,
//! states, summaries and the check's report are cut back to n.

use crate::diagnostics::OutputError;
use crate::diagnostics::{Row, Summary};
use crate::dim::Fixed;
use crate::dim::{self, PairFunction};
use crate::mechanics::legendre;
use crate::{
    CheckReport, Connection, Coordinate, DynRow, DynState, DynStepper, DynSystem, Error, InitialMomentum, Input,
    Method, OutputOptions, Problem, Role, Scalar, StepReport, System,
};

/// The padding coordinates `used .. N` after the system's own: shape coordinates on ℝ, named so
/// that no spec can declare the name.
pub(crate) fn coordinates<const N: usize>(own: &[Coordinate]) -> [Coordinate; N] {
    std::array::from_fn(|i| match own.get(i) {
        Some(c) => c.clone(),
        None => Coordinate::shape(&format!("(padding {})", i - own.len() + 1)),
    })
}

/// ½ c Σ v_i² over the padding coordinates `used .. N`.
#[inline(always)]
pub(crate) fn lagrangian<D: Scalar, const N: usize>(v: &[D; N], used: usize, mass: f64) -> D {
    v[used..].iter().fold(D::from(0.0), |sum, &vi| sum + vi * vi * (0.5 * mass))
}

/// The mass c of the padding coordinates of `system` (whose padding has mass 0 while this is
/// measured): the largest entry of ∂²L/∂v² at a reference point, or of ∂²L/∂q∂v where L is linear
/// in v; 1 where neither is finite and nonzero at any reference point.
pub(crate) fn mass<S: System<N>, const N: usize>(system: &S) -> f64 {
    // Its dual numbers need the stack a step needs (`crate::stack`).
    crate::stack::enough(crate::dim::Fixed::<N>, || reference_scale(system))
}

// Not inlined into `mass`: its dual numbers' arrays would be part of the frame that decides on the stack.
#[inline(never)]
fn reference_scale<S: System<N>, const N: usize>(system: &S) -> f64 {
    struct Lagrangian<'a, S>(&'a S);
    impl<S: System<N>, const N: usize> PairFunction<Fixed<N>> for Lagrangian<'_, S> {
        fn eval<D: Scalar>(&self, q: &[D; N], v: &[D; N]) -> D {
            self.0.lagrangian(q, v)
        }
    }
    let usable = |scale: f64| scale.is_finite() && scale > 0.0;
    for q in [0.0, 0.5, 1.0] {
        let (q, v) = ([q; N], [0.0; N]);
        let velocities = legendre::velocity_hessian(system, &q, &v).2.amax();
        if usable(velocities) {
            return velocities;
        }
        let mixed = dim::mixed(Fixed, &Lagrangian(system), &q, &v).dadb.amax();
        if usable(mixed) {
            return mixed;
        }
    }
    1.0
}

/// A type-erased system of `used` coordinates run by an engine with padding coordinates after them.
pub(crate) struct Padded {
    /// The engine's system, padding included.
    pub(crate) inner: Box<dyn DynSystem>,
    /// The system's own coordinates.
    pub(crate) own: Vec<Coordinate>,
    /// The engine's number of coordinates.
    pub(crate) size: usize,
}

impl Padded {
    fn problem(&self, problem: &Problem) -> Result<Problem, Error> {
        extended(problem, self.own.len(), self.size)
    }

    /// `method` with its connection checked against the system's own shape and group coordinates,
    /// then given a zero column per padding coordinate.
    fn method(&self, method: &Method) -> Result<Method, Error> {
        let Some(connection) = &method.connection else { return Ok(method.clone()) };
        let (n_x, n_g) = roles(&self.own);
        let fitted = connection.fitted(n_x, n_g)?;
        let extra = self.size - self.own.len();
        let rows: Vec<Vec<f64>> = fitted.rows().iter().map(|row| zeros_after(row, n_x + extra)).collect();
        let connection = if rows.is_empty() { Connection::zero(n_x + extra, 0) } else { Connection::new(&rows)? };
        Ok(Method { connection: Some(connection), ..method.clone() })
    }

    fn both(&self, problem: &Problem, method: &Method) -> Result<(Problem, Method), Error> {
        Ok((self.problem(problem)?, self.method(method)?))
    }
}

/// `problem` checked against `own` coordinates, then extended by zeros to `size`.
fn extended(problem: &Problem, own: usize, size: usize) -> Result<Problem, Error> {
    problem.validate(own)?;
    let extend = |v: &[f64]| zeros_after(v, size);
    let initial = match &problem.initial {
        InitialMomentum::Momentum(p) => InitialMomentum::Momentum(extend(p)),
        InitialMomentum::Velocity(v) => InitialMomentum::Velocity(extend(v)),
    };
    Ok(Problem { q0: extend(&problem.q0), initial, ..problem.clone() })
}

/// `v` followed by zeros up to `size` entries.
fn zeros_after(v: &[f64], size: usize) -> Vec<f64> {
    let mut out = v.to_vec();
    out.resize(size.max(v.len()), 0.0);
    out
}

/// The numbers of shape and group coordinates.
fn roles(coordinates: &[Coordinate]) -> (usize, usize) {
    let group = coordinates.iter().filter(|c| c.role == Role::Group).count();
    (coordinates.len() - group, group)
}

/// `row` with its configuration and momenta cut to the first `n` entries.
fn cut<'a>(row: &Row<'a>, n: usize) -> Row<'a> {
    Row { q: &row.q[..n], p: &row.p[..n], ..*row }
}

fn cut_summary(mut summary: Summary, n: usize) -> Summary {
    summary.coordinates.truncate(n);
    summary.final_q.truncate(n);
    summary.final_p.truncate(n);
    summary
}

impl DynSystem for Padded {
    fn coordinates(&self) -> Vec<Coordinate> {
        self.own.clone()
    }

    fn charts(&self) -> Vec<String> {
        self.inner.charts()
    }

    fn integrate(
        &self,
        problem: &Problem,
        method: &Method,
        output: &OutputOptions,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
    ) -> Result<Summary, Error> {
        self.integrate_watched(problem, method, output, observer, &mut |_| Ok(()))
    }

    fn integrate_watched(
        &self,
        problem: &Problem,
        method: &Method,
        output: &OutputOptions,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
        watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
    ) -> Result<Summary, Error> {
        let (problem, method) = self.both(problem, method)?;
        let n = self.own.len();
        let summary =
            self.inner.integrate_watched(&problem, &method, output, &mut |row| observer(&cut(row, n)), watch)?;
        Ok(cut_summary(summary, n))
    }

    /// The padding coordinates are regular: the report's rank and count are of the system's own.
    fn check(&self, problem: &Problem, method: &Method) -> Result<CheckReport, Error> {
        let (problem, method) = self.both(problem, method)?;
        let extra = self.size - self.own.len();
        let report = self.inner.check(&problem, &method)?;
        Ok(CheckReport {
            legendre_rank: report.legendre_rank.saturating_sub(extra),
            coordinates: self.own.len(),
            ..report
        })
    }

    fn stepper<'a>(&'a self, problem: &Problem, method: &Method) -> Result<Box<dyn DynStepper + 'a>, Error> {
        let (problem, method) = self.both(problem, method)?;
        let inner = self.inner.stepper(&problem, &method)?;
        Ok(Box::new(PaddedStepper { inner, own: self.own.len(), size: self.size }))
    }

    fn exact_solution(&self, q0: &[f64], p0: &[f64], t: f64) -> Option<Vec<Option<f64>>> {
        let n = self.own.len();
        if q0.len() != n || p0.len() != n {
            return None;
        }
        let mut exact = self.inner.exact_solution(&zeros_after(q0, self.size), &zeros_after(p0, self.size), t)?;
        exact.truncate(n);
        Some(exact)
    }
}

/// The stepper of a [`Padded`] system.
struct PaddedStepper<'a> {
    inner: Box<dyn DynStepper + 'a>,
    /// The system's own coordinates.
    own: usize,
    /// The engine's.
    size: usize,
}

impl DynStepper for PaddedStepper<'_> {
    fn k(&self) -> usize {
        self.inner.k()
    }

    fn t(&self) -> f64 {
        self.inner.t()
    }

    fn steps(&self) -> usize {
        self.inner.steps()
    }

    fn is_finished(&self) -> bool {
        self.inner.is_finished()
    }

    fn set_wrap_angles(&mut self, wrap: bool) {
        self.inner.set_wrap_angles(wrap);
    }

    fn step(&mut self) -> Result<StepReport, Error> {
        self.inner.step()
    }

    fn run_to_end(
        &mut self,
        every: usize,
        observer: &mut dyn FnMut(&Row<'_>) -> Result<(), OutputError>,
        watch: &mut dyn FnMut(usize) -> Result<(), OutputError>,
    ) -> Result<(), Error> {
        let n = self.own;
        self.inner.run_to_end(every, &mut |row| observer(&cut(row, n)), watch)
    }

    fn row(&mut self) -> DynRow {
        let mut row = self.inner.row();
        row.q.truncate(self.own);
        row.p.truncate(self.own);
        row
    }

    fn state(&self) -> DynState {
        self.inner.state().resized(self.own)
    }

    /// A state of the system's own size, extended by the padding's zeros (a state taken from this
    /// stepper keeps the engine's memory, padding included).
    fn restart(&mut self, state: &DynState) -> Result<(), Error> {
        for v in [state.q(), state.p()] {
            if v.len() != self.own {
                return Err(Error::Size { what: Input::State, expected: self.own, found: v.len() });
            }
        }
        self.inner.restart(&state.clone().resized(self.size))
    }

    fn finish(self: Box<Self>) -> Result<Summary, Error> {
        let own = self.own;
        Ok(cut_summary(self.inner.finish()?, own))
    }

    fn summary(&mut self) -> Result<Summary, Error> {
        Ok(cut_summary(self.inner.summary()?, self.own))
    }

    fn renew(&mut self, problem: &Problem) -> Result<bool, Error> {
        self.inner.renew(&extended(problem, self.own, self.size)?)
    }
}
