//! A planar chain of N pendula under gravity, in absolute angles q = (θ1, …, θN): the scaling example,
//! with as many coordinates as links.
//!
//! Link i has length l and a bob of mass m at its end; θ_i is its angle from the downward vertical.
//! The bobs sit at x_i = l Σ_{j≤i} sin θ_j, y_i = −l Σ_{j≤i} cos θ_j, and
//!
//! ```text
//! L = ½ m Σ_i (ẋ_i² + ẏ_i²) − g m Σ_i y_i
//!   = ½ m l² Σ_i [(Σ_{j≤i} θ̇_j cos θ_j)² + (Σ_{j≤i} θ̇_j sin θ_j)²] + g m l Σ_i Σ_{j≤i} cos θ_j.
//! ```
//!
//! [`System::lagrangian`] accumulates the inner sums link by link, so one evaluation costs O(N)
//! operations (one sin/cos pair per link). With μ_i = m (N − i + 1), the mass below and at link i,
//! the kinetic energy is ½ θ̇ᵀ M(θ) θ̇ with M_ij = l² μ_max(i,j) cos(θ_i − θ_j), and the equations of
//! motion are
//!
//! ```text
//! Σ_j M_ij θ̈_j = −Σ_j l² μ_max(i,j) sin(θ_i − θ_j) θ̇_j² − g l μ_i sin θ_i.
//! ```
//!
//! Small oscillations about the hanging rest have ω² the generalised eigenvalues of
//! K = diag(g l μ_i) and M(0): ω² = (2 ∓ √2) g/l for two links, and for three links ω² l/g the roots
//! 0.41577…, 2.29428…, 6.28995… of λ³ − 9λ² + 18λ − 6.
//!
//! No rotation or translation leaves L invariant (gravity fixes the vertical, the pivot fixes the
//! origin), so every θ_i is a shape coordinate and a reduced run is refused with
//! [`Error::NoSymmetry`]. The built-in `pendulum_chain` takes the number of links as the parameter
//! `links`, any positive integer: [`PendulumChain<N>`] for the counts of [`super::CHAIN_LINKS`] (arrays on
//! the stack), [`DynamicPendulumChain`] for the others (a dimension chosen at run time, [`Dynamic`]);
//! `built_in_chain.rs` builds it.

use num_dual::DualNum;

use crate::dim::Dynamic;
use crate::mechanics::lagrangian::{Lagrangian, SystemIn};
use crate::{Coordinate, DynSystem, ErasedDynamic, Error, InitialMomentum, Input, Problem, Scalar, System};

/// A planar chain of `N` identical pendula (uniform mass and length) hanging from a fixed pivot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PendulumChain<const N: usize> {
    /// Mass of each bob.
    pub m: f64,
    /// Length of each link.
    pub l: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl<const N: usize> Default for PendulumChain<N> {
    fn default() -> Self {
        Self::default_parameters()
    }
}

impl<const N: usize> PendulumChain<N> {
    /// m = 1, l = 1, g = 9.8.
    pub fn default_parameters() -> Self {
        Self { m: 1.0, l: 1.0, g: 9.8 }
    }

    /// The chain released from rest (p0 = 0), bent into one arch θ_i(0) = ½ sin(π i/(N + 1)), with
    /// `steps` steps of size `step`.
    ///
    /// ```
    /// use ddirac::systems::PendulumChain;
    /// let problem = PendulumChain::<3>::problem(100, 0.01);
    /// assert!((problem.q0[1] - 0.5).abs() < 1e-15);
    /// assert!((problem.duration() - 1.0).abs() < 1e-12);
    /// ```
    pub fn problem(steps: usize, step: f64) -> Problem {
        let arch = |i: usize| 0.5 * (std::f64::consts::PI * i as f64 / (N + 1) as f64).sin();
        Problem::new(step, steps, (1..=N).map(arch).collect(), InitialMomentum::Momentum(vec![0.0; N]))
    }

    /// Positions (x_i, y_i) of the bobs relative to the pivot, y pointing up.
    ///
    /// ```
    /// use ddirac::systems::PendulumChain;
    /// let bobs = PendulumChain::<2>::default().bobs(&[0.0, std::f64::consts::FRAC_PI_2]);
    /// assert!((bobs[1][0] - 1.0).abs() < 1e-15 && (bobs[1][1] + 1.0).abs() < 1e-15);
    /// ```
    pub fn bobs(&self, q: &[f64; N]) -> [[f64; 2]; N] {
        let mut at = [0.0; 2];
        q.map(|theta| {
            at = [at[0] + self.l * theta.sin(), at[1] - self.l * theta.cos()];
            at
        })
    }
}

impl<const N: usize> super::Parameters for PendulumChain<N> {
    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![("links", N as f64), ("m", self.m), ("l", self.l), ("g", self.g)]
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), Error> {
        match name {
            "links" if value == N as f64 => {}
            "links" => {
                return Err(Error::Invalid {
                    what: Input::Parameter(name.into()),
                    why: crate::Reason::OtherLinks { links: N, value },
                })
            }
            "m" => self.m = super::positive(name, value)?,
            "l" => self.l = super::positive(name, value)?,
            "g" => self.g = super::finite(name, value)?,
            _ => return Err(super::unknown_parameter(name, self)),
        }
        Ok(())
    }
}

impl<const N: usize> System<N> for PendulumChain<N> {
    fn coordinates(&self) -> [Coordinate; N] {
        std::array::from_fn(|i| Coordinate::shape(&format!("theta{}", i + 1)).angle())
    }

    fn lagrangian<D: DualNum<Primitive = f64> + Copy>(&self, q: &[D; N], v: &[D; N]) -> D {
        let Self { m, l, g } = *self;
        chain_lagrangian((m, l, g), q, v)
    }
}

/// L of the chain of `q.len()` links with mass, length and gravity `(m, l, g)`, accumulating the
/// running sums over j ≤ i link by link.
#[inline(always)]
fn chain_lagrangian<D: DualNum<Primitive = f64> + Copy>((m, l, g): (f64, f64, f64), q: &[D], v: &[D]) -> D {
    let zero = D::from(0.0);
    // Running sums over j ≤ i: (ẋ_i, ẏ_i)/l and −y_i/l.
    let (mut vx, mut vy, mut depth) = (zero, zero, zero);
    let (mut speeds, mut depths) = (zero, zero);
    for (&theta, &omega) in q.iter().zip(v) {
        let (s, c) = theta.sin_cos();
        vx += omega * c;
        vy += omega * s;
        depth += c;
        speeds += vx * vx + vy * vy;
        depths += depth;
    }
    speeds * (0.5 * m * l * l) + depths * (g * m * l)
}

/// The chain of pendula with its number of links chosen at run time: [`PendulumChain`]'s Lagrangian
/// (the same operations, so the same numbers) in a dynamic dimension ([`Dynamic`]), one engine for
/// every number of links.
///
/// ```
/// use ddirac::systems::{DynamicPendulumChain, PendulumChain};
/// use ddirac::{solve, Method, OutputOptions};
/// let problem = PendulumChain::<3>::problem(50, 0.01);
/// let fixed = solve(&PendulumChain::<3>::default(), &problem, &Method::default(), &OutputOptions::default());
/// let dynamic = solve(&DynamicPendulumChain::new(3), &problem, &Method::default(), &OutputOptions::default());
/// assert_eq!(fixed.unwrap().q, dynamic.unwrap().q);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicPendulumChain {
    /// The number of links.
    pub links: usize,
    /// Mass of each bob.
    pub m: f64,
    /// Length of each link.
    pub l: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl DynamicPendulumChain {
    /// `links` links with m = 1, l = 1, g = 9.8.
    pub fn new(links: usize) -> Self {
        let PendulumChain::<0> { m, l, g } = PendulumChain::default_parameters();
        Self { links, m, l, g }
    }

    /// The chain as a type-erased system ([`ErasedDynamic`]), the engine the built-in
    /// `pendulum_chain` runs for a number of links outside [`CHAIN_LINKS`](super::CHAIN_LINKS): for comparing the two
    /// dimensions at the same number of links.
    pub fn erased(self) -> Box<dyn DynSystem> {
        Box::new(ErasedDynamic(self))
    }
}

impl super::Parameters for DynamicPendulumChain {
    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![("links", self.links as f64), ("m", self.m), ("l", self.l), ("g", self.g)]
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), Error> {
        match name {
            "links" if value == self.links as f64 => {}
            "links" => {
                return Err(Error::Invalid {
                    what: Input::Parameter(name.into()),
                    why: crate::Reason::OtherLinks { links: self.links, value },
                })
            }
            "m" => self.m = super::positive(name, value)?,
            "l" => self.l = super::positive(name, value)?,
            "g" => self.g = super::finite(name, value)?,
            _ => return Err(super::unknown_parameter(name, self)),
        }
        Ok(())
    }
}

impl Lagrangian<Dynamic> for DynamicPendulumChain {
    #[inline(always)]
    fn lagrangian<D: Scalar>(&self, q: &Vec<D>, v: &Vec<D>) -> D {
        chain_lagrangian((self.m, self.l, self.g), q, v)
    }
}

impl SystemIn<Dynamic> for DynamicPendulumChain {
    fn dim(&self) -> Dynamic {
        Dynamic(self.links)
    }

    fn coordinates(&self) -> Vec<Coordinate> {
        (0..self.links).map(|i| Coordinate::shape(&format!("theta{}", i + 1)).angle()).collect()
    }
}
