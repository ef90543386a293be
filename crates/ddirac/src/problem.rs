//! Problems (step size, number of steps, initial data) and methods (rule, variant, reduction,
//! connection, Newton options): the two things that, joined with a [`System`](crate::System), make
//! an integration.

use crate::{Composition, Connection, EnergyJump, Error, Input, NewtonOptions, Rule};

/// How the initial momentum is given.
#[derive(Debug, Clone, PartialEq)]
pub enum InitialMomentum {
    /// Canonical momenta p0.
    Momentum(Vec<f64>),
    /// Velocities v0, mapped to p0 = ∂L/∂v(q0, v0) by the Legendre transform.
    Velocity(Vec<f64>),
}

/// Step size, number of steps and initial data.
///
/// ```
/// use ddirac::{InitialMomentum, Problem};
/// let problem = Problem::new(0.2, 100, vec![0.0; 4], InitialMomentum::Momentum(vec![1.0, 0.0, 1.0, 1.0]));
/// assert!((problem.duration() - 20.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    /// Step size h.
    pub step: f64,
    /// Number of steps N.
    pub steps: usize,
    /// Initial configuration q0 (angles may be unwrapped).
    pub q0: Vec<f64>,
    /// Initial momentum or velocity.
    pub initial: InitialMomentum,
}

impl Problem {
    /// A problem from its parts.
    pub fn new(step: f64, steps: usize, q0: Vec<f64>, initial: InitialMomentum) -> Self {
        Self { step, steps, q0, initial }
    }

    /// Final time N·h.
    pub fn duration(&self) -> f64 {
        self.step * self.steps as f64
    }

    /// A problem for a system with `N` coordinates from arrays, so that the compiler checks the sizes:
    /// initial configuration `q0` and canonical momenta `p0`.
    ///
    /// ```
    /// use ddirac::{InitialMomentum, Problem};
    /// let problem = Problem::with_momentum(0.2, 100, [0.0; 4], [1.0, 0.0, 1.0, 1.0]);
    /// assert_eq!(problem, Problem::new(0.2, 100, vec![0.0; 4], InitialMomentum::Momentum(vec![1.0, 0.0, 1.0, 1.0])));
    /// assert_eq!(problem.initial_data::<4>().unwrap().0, [0.0; 4]);
    /// assert!(problem.initial_data::<3>().is_err());
    /// ```
    pub fn with_momentum<const N: usize>(step: f64, steps: usize, q0: [f64; N], p0: [f64; N]) -> Self {
        Self::new(step, steps, q0.to_vec(), InitialMomentum::Momentum(p0.to_vec()))
    }

    /// A problem for a system with `N` coordinates from arrays: initial configuration `q0` and
    /// velocities `v0` (mapped to momenta by the Legendre transform).
    ///
    /// ```
    /// let problem = ddirac::Problem::with_velocity(0.01, 10, [1.0, 0.0], [0.0, 1.2]);
    /// assert_eq!(problem.initial_data::<2>().unwrap().1, ddirac::InitialData::Velocity([0.0, 1.2]));
    /// ```
    pub fn with_velocity<const N: usize>(step: f64, steps: usize, q0: [f64; N], v0: [f64; N]) -> Self {
        Self::new(step, steps, q0.to_vec(), InitialMomentum::Velocity(v0.to_vec()))
    }

    /// The initial data as arrays for a system with `N` coordinates, checked as a run checks them
    /// (sizes and finite values; step and number of steps too).
    pub fn initial_data<const N: usize>(&self) -> Result<([f64; N], InitialData<N>), Error> {
        self.validate(N)?;
        let sized = |v: &[f64]| -> [f64; N] { v.try_into().expect("validated size") };
        let initial = match &self.initial {
            InitialMomentum::Momentum(p) => InitialData::Momentum(sized(p)),
            InitialMomentum::Velocity(v) => InitialData::Velocity(sized(v)),
        };
        Ok((sized(&self.q0), initial))
    }

    /// Checks sizes and values against a system with `n` coordinates.
    pub(crate) fn validate(&self, n: usize) -> Result<(), Error> {
        if !(self.step.is_finite() && self.step > 0.0) {
            return Err(Error::Invalid {
                what: Input::Step,
                why: crate::Reason::NotPositiveFinite { value: self.step },
            });
        }
        if self.steps == 0 {
            return Err(Error::Invalid { what: Input::Steps, why: crate::Reason::Zero });
        }
        let (what, v) = match &self.initial {
            InitialMomentum::Momentum(p) => (Input::InitialMomentum, p),
            InitialMomentum::Velocity(v) => (Input::InitialVelocity, v),
        };
        for (what, values) in [(Input::InitialConfiguration, &self.q0), (what, v)] {
            if values.len() != n {
                return Err(Error::Size { what, expected: n, found: values.len() });
            }
            if let Some((i, &value)) = values.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(Error::NonFinite { what, entry: Some(i), value });
            }
        }
        Ok(())
    }
}

/// The initial momentum or velocity of a system with `N` coordinates ([`Problem::initial_data`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum InitialData<const N: usize> {
    /// Canonical momenta p0.
    Momentum([f64; N]),
    /// Velocities v0.
    Velocity([f64; N]),
}

/// Which discrete Dirac structure: (+) (type-2 generating function) or (−) (type-3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variant {
    /// The (+) equations.
    Plus,
    /// The (−) equations.
    Minus,
}

impl Variant {
    /// `plus` or `minus`.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Plus => "plus",
            Variant::Minus => "minus",
        }
    }
}

/// How a run evaluates the derivatives of its step equations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Differentiation {
    /// Compiled derivatives when the run has at least 5000 steps, the Lagrangian can be traced and
    /// compiling is estimated to pay ([`crate::compiled::CompileCost`]; without the `jit` feature, when
    /// the interpreted programs are estimated faster or the step has a closed form); dual numbers
    /// otherwise (the summary says which, and why).
    #[default]
    Auto,
    /// Compiled derivatives ([`crate::compiled`]); a run that cannot compile them fails.
    Compiled,
    /// Forward-mode dual numbers ([`crate::ad`]).
    Dual,
}

impl Differentiation {
    /// All choices, in spec order.
    pub const ALL: [Differentiation; 3] = [Differentiation::Auto, Differentiation::Compiled, Differentiation::Dual];

    /// The name in specs: `auto`, `compiled` or `dual`.
    pub fn name(self) -> &'static str {
        match self {
            Differentiation::Auto => "auto",
            Differentiation::Compiled => "compiled",
            Differentiation::Dual => "dual",
        }
    }

    /// Parses a name.
    ///
    /// ```
    /// use ddirac::Differentiation;
    /// assert_eq!(Differentiation::from_name("dual"), Some(Differentiation::Dual));
    /// assert_eq!(Differentiation::from_name("symbolic"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|d| d.name() == name)
    }
}

/// The discretization and the choice of equations.
///
/// ```
/// use ddirac::{Connection, Method, Rule, Variant};
/// let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
/// assert_eq!(method.variant, Variant::Plus);
/// // Two bodies (x = r2 − r1, g = r1) with equal masses, reduced with the centre-of-mass connection
/// // K = −m2/(m1 + m2) · I:
/// let k = Connection::new(&[vec![-0.5, 0.0], vec![0.0, -0.5]]).unwrap();
/// let centre_of_mass = Method { connection: Some(k), ..method };
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Method {
    /// Quadrature rule of L_d.
    pub rule: Rule,
    /// (+) or (−).
    pub variant: Variant,
    /// Integrate the reduced equations on (x, w, μ) and reconstruct g, or the unreduced ones.
    pub reduced: bool,
    /// K = h_{d,Σ}, n_g rows of n_x entries (checked against the system when a run is set up);
    /// `None` means K = 0.
    pub connection: Option<Connection>,
    /// Newton tolerance and iteration limit.
    pub newton: NewtonOptions,
    /// Check the invariance of L_d before a reduced run.
    pub check_invariance: bool,
    /// Compiled derivatives or dual numbers.
    pub differentiation: Differentiation,
    /// The watch on jumps of the energy between steps ([`EnergyJump`]).
    pub energy_jump: EnergyJump,
    /// How a step is composed of sub-steps of the basic method: [`Composition::Basic`] (order 2) or
    /// a symmetric composition of order 4, 6 or 8 (only for the symmetric rules, midpoint and
    /// trapezoid).
    pub composition: Composition,
    /// Switch between the charts of the system's atlas where the current one degrades (paper §6;
    /// [`crate::atlas`]); without an atlas, or with `false`, every step is taken in the main chart.
    pub atlas: bool,
    /// Propagate the tangent map d(q_k, p_k)/d(q_0, p_0) through every step
    /// ([`crate::Summary::sensitivity`]; [`crate::tangent_map`]).
    pub sensitivities: bool,
}

impl Default for Method {
    fn default() -> Self {
        Self {
            rule: Rule::Midpoint,
            variant: Variant::Plus,
            reduced: false,
            connection: None,
            newton: NewtonOptions::default(),
            check_invariance: true,
            differentiation: Differentiation::Auto,
            energy_jump: EnergyJump::default(),
            composition: Composition::Basic,
            atlas: true,
            sensitivities: false,
        }
    }
}

/// Which rows to report and how.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OutputOptions {
    /// Report every `every`-th step (and always the last).
    pub every: usize,
    /// Report angles wrapped to (−π, π] instead of continuous.
    pub wrap_angles: bool,
}

impl Default for OutputOptions {
    fn default() -> Self {
        Self { every: 1, wrap_angles: false }
    }
}
