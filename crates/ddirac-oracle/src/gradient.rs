//! Gradients of a scalar function of B blocks of N arguments, by the engine's forward-mode dual
//! numbers ([`ddirac::ad::Gradient`]): one pass per block, the other blocks held constant.

use ddirac::ad::Gradient;
use ddirac::Error;

/// A dual number carrying the derivatives along the N arguments of one block.
pub(crate) type Dual<const N: usize> = Gradient<N, 0>;

/// The value of `f` and its gradient with respect to each of its B blocks of N arguments.
pub(crate) fn block_gradient<const N: usize, const B: usize>(
    blocks: &[[f64; N]; B],
    f: impl Fn(&[[Dual<N>; N]; B]) -> Result<Dual<N>, Error>,
) -> Result<(f64, [[f64; N]; B]), Error> {
    let mut value = 0.0;
    let mut gradient = [[0.0; N]; B];
    for (seeded, out) in gradient.iter_mut().enumerate() {
        let args: [[Dual<N>; N]; B] = std::array::from_fn(|c| {
            if c == seeded {
                Dual::<N>::seed(&blocks[c], &[]).0
            } else {
                blocks[c].map(Dual::<N>::constant)
            }
        });
        let result = f(&args)?;
        value = result.re;
        *out = result.a;
    }
    Ok((value, gradient))
}
