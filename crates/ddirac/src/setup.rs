//! What a run needs before its first step, for the stepper and for the check of its hypotheses alike:
//! the problem and the method validated, the initial momenta (from velocities by the Legendre
//! transform), the split into shape and group coordinates, the connection fitted to it, and the first
//! step's predictor.

use crate::dim::Dim;
use crate::mechanics::lagrangian::SystemIn;
use crate::mechanics::legendre;
use crate::{Connection, Error, InitialMomentum, Input, Method, Problem, Rule, Split};

/// What a run needs before its first step: validated initial data, the split, the connection and a
/// first-step increment h · v0 for the predictor.
pub(crate) struct Setup<Dm: Dim> {
    pub split: Split,
    pub q0: Dm::Array<f64>,
    pub p0: Dm::Array<f64>,
    /// h · v0 with v0 from the inverse Legendre transform (0 where it is not finite).
    pub dq0: Dm::Array<f64>,
    pub connection: Connection,
}

impl<Dm: Dim> Setup<Dm> {
    pub(crate) fn new<S: SystemIn<Dm>>(system: &S, problem: &Problem, method: &Method) -> Result<Self, Error> {
        let dim = system.dim();
        problem.validate(dim.n())?;
        check_symmetric(method)?;
        let split = Split::new(system.coordinates().as_ref());
        let sized = |v: &[f64]| -> Dm::Array<f64> { dim.array(|i| v[i]) };
        let q0 = sized(&problem.q0);
        let p0 = match &problem.initial {
            InitialMomentum::Momentum(p) => sized(p),
            InitialMomentum::Velocity(v) => {
                let p0 = legendre::momentum_in(dim, system, &q0, &sized(v));
                if let Some((i, &value)) = p0.as_ref().iter().enumerate().find(|(_, x)| !x.is_finite()) {
                    return Err(Error::NonFinite { what: Input::MomentumFromVelocity, entry: Some(i), value });
                }
                p0
            }
        };
        let connection = match &method.connection {
            Some(k) => k.fitted(split.n_x(), split.n_g())?,
            None => Connection::zero(split.n_x(), split.n_g()),
        };
        connection.check_axioms()?;
        let (v0, _) = legendre::velocity_in(dim, system, &q0, &p0);
        let dq0 = first_increment::<Dm>(&v0, problem.step);
        Ok(Self { split, q0, p0, dq0, connection })
    }
}

/// h · v, 0 where v is not finite: the predictor of a first step, with v from the inverse Legendre
/// transform.
pub(crate) fn first_increment<Dm: Dim>(v: &Dm::Array<f64>, h: f64) -> Dm::Array<f64> {
    Dm::of(v).array(|i| if v[i].is_finite() { v[i] * h } else { 0.0 })
}

/// Refuses a composition of a basic method that is not symmetric: the left and right rules are each
/// other's adjoints, and a symmetric composition of either alone keeps order 1.
pub(crate) fn check_symmetric(method: &Method) -> Result<(), Error> {
    if method.composition.is_basic() || matches!(method.rule, Rule::Midpoint | Rule::Trapezoid) {
        return Ok(());
    }
    let why = crate::Reason::NotSymmetric { order: method.composition.order(), rule: method.rule.name() };
    Err(Error::Invalid { what: Input::Composition, why })
}
