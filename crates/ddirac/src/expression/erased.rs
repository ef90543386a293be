//! A text system erased for the command line and the bindings ([`ExpressionSpec::into_dyn`]): in the
//! engine of its number of coordinates up to the largest of [`crate::SIZES`], in a dimension chosen
//! at run time above.

use super::compiled_spec::compile;
use super::{ExpressionError, ExpressionLagrangian, ExpressionSpec, ExpressionSystem};
use crate::runtime_sized::RuntimeSized;
use crate::{DynSystem, Erased, ErasedDynamic};

impl ExpressionSpec {
    /// Checks and compiles the spec into a type-erased system with as many coordinates as it declares.
    /// Up to the largest of [`crate::SIZES`] (16) it runs in an engine whose arrays are sized when it
    /// is compiled, on the stack; above, in a dimension chosen at run time ([`crate::dim::Dynamic`],
    /// [`ExpressionLagrangian`]).
    ///
    /// ```
    /// use ddirac::expression::{ExpressionError, ExpressionSpec};
    /// use ddirac::Coordinate;
    /// let chain = |n: usize| ExpressionSpec {
    ///     coordinates: (0..n).map(|i| Coordinate::shape(&format!("x{i}"))).collect(),
    ///     lagrangian: (0..n).map(|i| format!("0.5*x{i}_dot^2")).collect::<Vec<_>>().join(" + "),
    ///     ..ExpressionSpec::default()
    /// };
    /// assert_eq!(chain(24).into_dyn().unwrap().coordinates().len(), 24);
    /// assert_eq!(chain(17).into_dyn().unwrap().coordinates().len(), 17);
    /// assert_eq!(chain(150).into_dyn().unwrap().coordinates().len(), 150);
    /// ```
    pub fn into_dyn(self) -> Result<Box<dyn DynSystem>, ExpressionError> {
        match crate::sizes::engine_size(self.coordinates.len()) {
            Some(size) => self.into_dyn_in(size),
            None => Ok(Box::new(ErasedDynamic(ExpressionLagrangian::from_compiled(compile(&self)?)))),
        }
    }

    /// [`ExpressionSpec::into_dyn`] in the engine of `size` coordinates, one of [`crate::SIZES`] and
    /// at least the spec's count; the coordinates beyond the spec's are padding
    /// (the module `padding`). For comparing a padded run with an unpadded one, and for measuring what
    /// a larger engine costs.
    ///
    /// ```
    /// use ddirac::expression::{ExpressionError, ExpressionSpec};
    /// use ddirac::Coordinate;
    /// let spec = ExpressionSpec {
    ///     coordinates: vec![Coordinate::shape("x")],
    ///     lagrangian: "0.5*x_dot^2 - 0.5*x^2".into(),
    ///     ..ExpressionSpec::default()
    /// };
    /// assert_eq!(spec.clone().into_dyn_in(4).unwrap().coordinates().len(), 1);
    /// assert!(matches!(spec.into_dyn_in(17), Err(ExpressionError::EngineSize { size: 17, found: 1 })));
    /// ```
    pub fn into_dyn_in(self, size: usize) -> Result<Box<dyn DynSystem>, ExpressionError> {
        let compiled = compile(&self)?;
        let own = compiled.coordinates.clone();
        if own.len() > size {
            return Err(ExpressionError::EngineSize { size, found: own.len() });
        }
        macro_rules! dispatch {
            ($($n:literal)*) => {
                match size {
                    $($n => Box::new(Erased::<_, $n>(RuntimeSized::Text(ExpressionSystem::<$n>::padded(compiled))))
                        as Box<dyn DynSystem>,)*
                    _ => return Err(ExpressionError::EngineSize { size, found: own.len() }),
                }
            };
        }
        let inner = crate::sizes::with_sizes!(dispatch);
        Ok(if own.len() == size { inner } else { Box::new(crate::padding::Padded { inner, own, size }) })
    }
}
