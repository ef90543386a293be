//! Problems (step size, number of steps, initial data) and methods (rule, variant, reduction,
//! connection, Newton options): the two things that, joined with a [`System`](crate::System), make
//! an integration.

use crate::{EnergyJump, Error, NewtonOptions, Rule};

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

    /// Checks sizes and values against a system with `n` coordinates.
    pub(crate) fn validate(&self, n: usize) -> Result<(), Error> {
        if !(self.step.is_finite() && self.step > 0.0) {
            return Err(Error::Invalid {
                what: "step".into(),
                why: format!("must be positive and finite, got {}", self.step),
            });
        }
        if self.steps == 0 {
            return Err(Error::Invalid { what: "steps".into(), why: "must be at least 1".into() });
        }
        let (what, v) = match &self.initial {
            InitialMomentum::Momentum(p) => ("initial momentum p", p),
            InitialMomentum::Velocity(v) => ("initial velocity v", v),
        };
        for (name, values) in [("initial configuration q", &self.q0), (what, v)] {
            if values.len() != n {
                return Err(Error::Size { what: name.into(), expected: n, found: values.len() });
            }
            if let Some((i, &x)) = values.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(Error::NonFinite { what: format!("entry {} of the {name}", i + 1), value: x });
            }
        }
        Ok(())
    }
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
/// use ddirac::{Method, Rule, Variant};
/// let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
/// assert_eq!(method.variant, Variant::Plus);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Method {
    /// Quadrature rule of L_d.
    pub rule: Rule,
    /// (+) or (−).
    pub variant: Variant,
    /// Integrate the reduced equations on (x, w, μ) and reconstruct g, or the unreduced ones.
    pub reduced: bool,
    /// K = h_{d,Σ}, n_g rows of n_x entries; `None` means K = 0.
    pub connection: Option<Vec<Vec<f64>>>,
    /// Newton tolerance and iteration limit.
    pub newton: NewtonOptions,
    /// Check the invariance of L_d before a reduced run.
    pub check_invariance: bool,
    /// Compiled derivatives or dual numbers.
    pub differentiation: Differentiation,
    /// The watch on jumps of the energy between steps ([`EnergyJump`]).
    pub energy_jump: EnergyJump,
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
