//! Built-in example systems, each with its default parameters, its Lagrangian in the module doc and
//! the published numbers it must reproduce. Tests, benchmarks and the command line use the same
//! modules; [`BUILT_IN`] lists them by name for type-erased use.

mod built_in_chain;
mod charged_particle;
mod double_spherical_pendulum;
mod heavy_top;
mod kepler;
mod pendulum_chain;
mod rigid_body;
mod spherical_pendulum;
mod two_body;

pub use built_in_chain::CHAIN_LINKS;
pub use charged_particle::{ChargedParticle, TABLE_1};
pub use double_spherical_pendulum::DoubleSphericalPendulum;
pub use heavy_top::HeavyTop;
pub use kepler::Kepler;
pub use pendulum_chain::{DynamicPendulumChain, PendulumChain};
pub use rigid_body::RigidBody;
pub use spherical_pendulum::SphericalPendulum;
pub use two_body::TwoBody;

use crate::{DynSystem, Erased, Error, Input};

/// Named, real-valued parameters of a built-in system.
pub trait Parameters {
    /// Names and current values, in a fixed order.
    fn parameters(&self) -> Vec<(&'static str, f64)>;

    /// Sets one parameter by name; rejects unknown names and invalid values.
    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), Error>;
}

fn finite(name: &str, value: f64) -> Result<f64, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite { what: Input::Parameter(name.into()), entry: None, value })
    }
}

fn positive(name: &str, value: f64) -> Result<f64, Error> {
    if finite(name, value)? > 0.0 {
        Ok(value)
    } else {
        Err(Error::Invalid { what: Input::Parameter(name.into()), why: crate::Reason::NotPositive { value } })
    }
}

fn unknown_parameter(name: &str, system: &impl Parameters) -> Error {
    let known = system.parameters().into_iter().map(|(n, _)| n.to_string()).collect();
    Error::Invalid { what: Input::Parameter(name.into()), why: crate::Reason::UnknownParameter { known } }
}

/// Builds a built-in system from parameter overrides `(name, value)`.
pub type Builder = fn(&[(String, f64)]) -> Result<Box<dyn DynSystem>, Error>;

/// A built-in system: its name, a one-line description, and a constructor from parameter overrides.
#[derive(Debug, Clone, Copy)]
pub struct BuiltIn {
    /// Name used in specs (`system = "..."`).
    pub name: &'static str,
    /// One line on what it is.
    pub description: &'static str,
    /// Default parameters, by name.
    pub defaults: fn() -> Vec<(&'static str, f64)>,
    /// Builds the system with some parameters overridden.
    pub build: Builder,
}

fn build<S, const N: usize>(system: S, overrides: &[(String, f64)]) -> Result<Box<dyn DynSystem>, Error>
where
    S: crate::System<N> + Parameters + Send + Sync + 'static,
{
    Ok(Box::new(Erased(with_overrides(system, overrides)?)))
}

/// `system` with the parameter values `overrides`, in order.
fn with_overrides<S: Parameters>(mut system: S, overrides: &[(String, f64)]) -> Result<S, Error> {
    for (name, value) in overrides {
        system.set_parameter(name, *value)?;
    }
    Ok(system)
}

/// The built-in systems.
///
/// A `static`, not a `const`: a constant is copied into every crate that names it, and with it the
/// closures that build each system, each of which instantiates the whole engine for its system type;
/// the command line, the Python module and the tests each compiled six copies of the engine of their
/// own that way. A static is one value, and its builders are compiled once, here.
pub static BUILT_IN: &[BuiltIn] = &[
    BuiltIn {
        name: "charged_particle",
        description: "charged particle in a constant magnetic field, Kaluza–Klein form (paper §7.1)",
        defaults: || ChargedParticle::default().parameters(),
        build: |o| build(ChargedParticle::default(), o),
    },
    BuiltIn {
        name: "double_spherical_pendulum",
        description: "double spherical pendulum in coordinates (ϑ1, φ1, ϑ2, φ2) (paper §7.2)",
        defaults: || DoubleSphericalPendulum::default().parameters(),
        build: |o| build(DoubleSphericalPendulum::default(), o),
    },
    BuiltIn {
        name: "two_body",
        description: "two bodies in the plane, g = r1, x = r2 − r1 (centre-of-mass connection K ≠ 0)",
        defaults: || TwoBody::default().parameters(),
        build: |o| build(TwoBody::default(), o),
    },
    BuiltIn {
        name: "kepler",
        description: "Kepler problem in polar coordinates (r, φ), φ cyclic; exact solution for bound orbits",
        defaults: || Kepler::default().parameters(),
        build: |o| build(Kepler::default(), o),
    },
    BuiltIn {
        name: "heavy_top",
        description: "heavy symmetric top in Euler angles (φ, θ, ψ), G = T² (φ, ψ)",
        defaults: || HeavyTop::default().parameters(),
        build: |o| build(HeavyTop::default(), o),
    },
    BuiltIn {
        name: "pendulum_chain",
        description: "planar chain of `links` pendula under gravity, angles θ_i from the vertical; no symmetry",
        defaults: built_in_chain::defaults,
        build: built_in_chain::build,
    },
    BuiltIn {
        name: "spherical_pendulum",
        description:
            "spherical pendulum in (θ, φ), θ the azimuth (group), φ from the upward vertical; atlas with two polar caps",
        defaults: || SphericalPendulum::default().parameters(),
        build: |o| build(SphericalPendulum::default(), o),
    },
];

/// The built-in system called `name`.
///
/// ```
/// let cp = ddirac::systems::find("charged_particle").unwrap();
/// let system = (cp.build)(&[("B0".to_string(), 2.0)]).unwrap();
/// assert_eq!(system.coordinates().len(), 4);
/// assert!(ddirac::systems::find("pendulum_on_a_cart").is_none());
/// ```
pub fn find(name: &str) -> Option<&'static BuiltIn> {
    BUILT_IN.iter().find(|b| b.name == name)
}
