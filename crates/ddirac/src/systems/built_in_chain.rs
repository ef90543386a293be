//! The built-in `pendulum_chain`: the chain of pendula with its number of links chosen when a run is
//! set up, erased as the command line and the bindings run it.

use super::pendulum_chain::{DynamicPendulumChain, PendulumChain};
use crate::runtime_sized::RuntimeSized;
use crate::{DynSystem, Erased, ErasedDynamic, Error, Input};

/// The most links the built-in `pendulum_chain` takes.
pub const MAX_LINKS: usize = 4096;

/// Links of the default built-in `pendulum_chain`.
const DEFAULT_LINKS: usize = 4;

/// Instantiates the chain for each number of links of [`crate::SIZES`]: [`CHAIN_LINKS`] and the
/// dispatch on it (other counts run as a [`DynamicPendulumChain`]).
macro_rules! fixed_links {
    ($($n:literal)*) => {
        /// The numbers of links the built-in `pendulum_chain` runs with arrays on the stack (each is a
        /// separate instance of the engine, [`PendulumChain<N>`] for that N); any other positive number
        /// of links runs as a [`DynamicPendulumChain`].
        ///
        /// ```
        /// let chain = ddirac::systems::find("pendulum_chain").unwrap();
        /// let system = (chain.build)(&[("links".to_string(), 12.0)]).unwrap();
        /// assert_eq!(system.coordinates()[11].name, "theta12");
        /// let system = (chain.build)(&[("links".to_string(), 57.0)]).unwrap();
        /// assert_eq!(system.coordinates()[56].name, "theta57");
        /// let error = (chain.build)(&[("links".to_string(), 2.5)]).err().unwrap();
        /// assert!(error.to_string().contains("a positive whole number"), "{error}");
        /// ```
        pub const CHAIN_LINKS: &[usize] = &[$($n),*];

        fn build_links(links: usize, overrides: &[(String, f64)]) -> Result<Box<dyn DynSystem>, Error> {
            match links {
                $($n => {
                    let chain = super::with_overrides(PendulumChain::<$n>::default(), overrides)?;
                    Ok(Box::new(Erased(RuntimeSized::Chain(chain))))
                })*
                _ => {
                    let chain = super::with_overrides(DynamicPendulumChain::new(links), overrides)?;
                    Ok(Box::new(ErasedDynamic(chain)))
                }
            }
        }
    };
}

crate::sizes::with_sizes!(fixed_links);

fn unsupported_links(value: f64) -> Error {
    Error::Invalid { what: Input::Parameter("links".into()), why: crate::Reason::NotANumberOfLinks { value } }
}

/// The default parameters of the built-in `pendulum_chain`, `links` first.
pub(super) fn defaults() -> Vec<(&'static str, f64)> {
    super::Parameters::parameters(&PendulumChain::<DEFAULT_LINKS>::default())
}

/// Builds the built-in `pendulum_chain` with `links` (default 4) links and the other overrides.
pub(super) fn build(overrides: &[(String, f64)]) -> Result<Box<dyn DynSystem>, Error> {
    let links = match overrides.iter().rev().find(|(name, _)| name == "links") {
        Some((name, value)) => super::finite(name, *value)?,
        None => DEFAULT_LINKS as f64,
    };
    if links.fract() != 0.0 || links < 1.0 {
        return Err(unsupported_links(links));
    }
    if links > MAX_LINKS as f64 {
        return Err(Error::Invalid {
            what: Input::Parameter("links".into()),
            why: crate::Reason::TooManyLinks { links, max: MAX_LINKS },
        });
    }
    build_links(links as usize, overrides)
}
