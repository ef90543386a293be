//! The number n of coordinates the engine works with: fixed when the engine is compiled
//! ([`Fixed<N>`]: arrays and matrices of the stack) or chosen when a run is set up ([`Dynamic`]: the
//! same values on the heap).
//!
//! The parts of the engine written over a [`Dim`] hold their dimension as a value (zero-sized for
//! [`Fixed`]) and make their arrays, vectors and matrices through it, so that one text serves both:
//! for `Fixed<N>` it compiles to the code of plain `[T; N]` and `SMatrix<f64, N, N>`, and the same
//! operations in the same order make both give the same numbers, bit for bit.

mod blocks;
mod derivatives;
mod widths;

pub use blocks::{first_blocks, mixed_blocks, BLOCK};
pub use derivatives::{
    first, first_or_mixed, first_single_pass, mixed, mixed_chunked, mixed_single_pass, FirstDerivatives,
    MixedDerivatives, PairFunction, CHUNK, CROSSOVER,
};
use nalgebra::{DMatrix, DVector, SMatrix, SVector};
use std::fmt::Debug;
use std::ops::{Index, IndexMut, SubAssign};
pub use widths::WIDEST;

/// What an entry of a [`Dim::Array`] must be.
pub trait Entry: Clone + Debug + PartialEq + Send + Sync + 'static {}
impl<T: Clone + Debug + PartialEq + Send + Sync + 'static> Entry for T {}

/// A number of coordinates, and the types that hold n values, a vector of n numbers and an n × n
/// matrix.
///
/// ```
/// use ddirac::dim::{Dim, Dynamic, Fixed};
/// let fixed: [f64; 3] = Fixed::<3>.array(|i| i as f64);
/// let dynamic: Vec<f64> = Dynamic(3).array(|i| i as f64);
/// assert_eq!(fixed.as_slice(), dynamic.as_slice());
/// assert_eq!(Dynamic(3).matrix(|i, j| (i * 3 + j) as f64)[(1, 2)], 5.0);
/// ```
pub trait Dim: Copy + Debug + PartialEq + Send + Sync + 'static {
    /// n values: `[T; N]` or `Vec<T>`.
    type Array<T: Entry>: Clone
        + 'static
        + Send
        + Sync
        + Debug
        + PartialEq
        + AsRef<[T]>
        + AsMut<[T]>
        + Index<usize, Output = T>
        + IndexMut<usize>;
    /// A column of n numbers: `SVector<f64, N>` or `DVector<f64>`.
    type Vector: Clone
        + Debug
        + PartialEq
        + Send
        + Sync
        + Index<usize, Output = f64>
        + IndexMut<usize>
        + for<'a> SubAssign<&'a Self::Vector>;
    /// An n × n matrix: `SMatrix<f64, N, N>` or `DMatrix<f64>`.
    type Matrix: Clone
        + Debug
        + PartialEq
        + Send
        + Sync
        + Index<(usize, usize), Output = f64>
        + IndexMut<(usize, usize)>;

    /// n.
    fn n(self) -> usize;

    /// Whether the arrays, vectors and matrices of this dimension live on the stack (what a step
    /// needs of the stack then grows with n², [`crate::stack`]).
    const ON_STACK: bool;

    /// The dimension of an array of it.
    fn of<T: Entry>(array: &Self::Array<T>) -> Self;

    /// The values f(0), …, f(n − 1).
    fn array<T: Entry>(self, f: impl FnMut(usize) -> T) -> Self::Array<T>;

    /// The vector with entries f(0), …, f(n − 1).
    fn vector(self, f: impl FnMut(usize) -> f64) -> Self::Vector;

    /// The matrix with entries f(i, j).
    fn matrix(self, f: impl FnMut(usize, usize) -> f64) -> Self::Matrix;

    /// The entries of a vector.
    fn entries(v: &Self::Vector) -> &[f64];

    /// The entries of a matrix, column by column.
    fn matrix_entries(m: &Self::Matrix) -> &[f64];

    /// Value, ∂f/∂a, ∂f/∂b and ∂²f/∂a∂b of f at (a, b) by dual numbers ([`mixed`]).
    fn mixed<F: PairFunction<Self>>(self, f: &F, a: &Self::Array<f64>, b: &Self::Array<f64>) -> MixedDerivatives<Self>;

    /// Value, ∂f/∂a and ∂f/∂b of f at (a, b) by dual numbers ([`first`]).
    fn first<F: PairFunction<Self>>(self, f: &F, a: &Self::Array<f64>, b: &Self::Array<f64>) -> FirstDerivatives<Self>;

    /// `f` of a buffer of at least 5n + 1 zeros: on the stack for a fixed dimension (where a compiled
    /// step program's inputs and outputs are kept, in a step that must not allocate).
    fn scratch<R>(self, f: impl FnOnce(&mut [f64]) -> R) -> R;

    /// The vector of zeros.
    fn zeros(self) -> Self::Vector {
        self.vector(|_| 0.0)
    }

    /// The largest absolute entry of a vector (0 for n = 0).
    fn amax(v: &Self::Vector) -> f64 {
        Self::entries(v).iter().fold(0.0, |m, x| x.abs().max(m))
    }
}

/// n = `N`, known when the engine is compiled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Fixed<const N: usize>;

impl<const N: usize> Dim for Fixed<N> {
    type Array<T: Entry> = [T; N];
    type Vector = SVector<f64, N>;
    type Matrix = SMatrix<f64, N, N>;
    const ON_STACK: bool = true;

    #[inline(always)]
    fn n(self) -> usize {
        N
    }

    #[inline(always)]
    fn of<T: Entry>(_: &[T; N]) -> Self {
        Fixed
    }

    #[inline(always)]
    fn array<T: Entry>(self, f: impl FnMut(usize) -> T) -> [T; N] {
        std::array::from_fn(f)
    }

    #[inline(always)]
    fn vector(self, mut f: impl FnMut(usize) -> f64) -> SVector<f64, N> {
        SVector::from_fn(|i, _| f(i))
    }

    #[inline(always)]
    fn matrix(self, f: impl FnMut(usize, usize) -> f64) -> SMatrix<f64, N, N> {
        SMatrix::from_fn(f)
    }

    #[inline(always)]
    fn entries(v: &SVector<f64, N>) -> &[f64] {
        v.as_slice()
    }

    #[inline(always)]
    fn matrix_entries(m: &SMatrix<f64, N, N>) -> &[f64] {
        m.as_slice()
    }

    fn mixed<F: PairFunction<Self>>(self, f: &F, a: &[f64; N], b: &[f64; N]) -> MixedDerivatives<Self> {
        if N <= CROSSOVER {
            mixed_single_pass(f, a, b)
        } else {
            mixed_chunked(f, a, b)
        }
    }

    #[inline(always)]
    fn first<F: PairFunction<Self>>(self, f: &F, a: &[f64; N], b: &[f64; N]) -> FirstDerivatives<Self> {
        first_single_pass(f, a, b)
    }

    #[inline(always)]
    fn scratch<R>(self, f: impl FnOnce(&mut [f64]) -> R) -> R {
        if N == 0 {
            return f(&mut [0.0]);
        }
        // 6N ≥ 5N + 1.
        let mut buffer = [[0.0; N]; 6];
        f(buffer.as_flattened_mut())
    }

    #[inline(always)]
    fn zeros(self) -> SVector<f64, N> {
        SVector::zeros()
    }

    #[inline(always)]
    fn amax(v: &SVector<f64, N>) -> f64 {
        v.amax()
    }
}

/// n chosen when a run is set up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dynamic(pub usize);

impl Dim for Dynamic {
    type Array<T: Entry> = Vec<T>;
    type Vector = DVector<f64>;
    type Matrix = DMatrix<f64>;
    const ON_STACK: bool = false;

    fn n(self) -> usize {
        self.0
    }

    fn of<T: Entry>(array: &Vec<T>) -> Self {
        Dynamic(array.len())
    }

    #[inline(always)]
    fn array<T: Entry>(self, f: impl FnMut(usize) -> T) -> Vec<T> {
        filled(self.0, f)
    }

    #[inline(always)]
    fn vector(self, f: impl FnMut(usize) -> f64) -> DVector<f64> {
        DVector::from_vec(filled(self.0, f))
    }

    /// Column by column, as `DMatrix::from_fn`.
    #[inline(always)]
    fn matrix(self, mut f: impl FnMut(usize, usize) -> f64) -> DMatrix<f64> {
        let n = self.0;
        let mut entries = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                entries.push(f(i, j));
            }
        }
        DMatrix::from_vec(n, n, entries)
    }

    fn entries(v: &DVector<f64>) -> &[f64] {
        v.as_slice()
    }

    fn matrix_entries(m: &DMatrix<f64>) -> &[f64] {
        m.as_slice()
    }

    fn mixed<F: PairFunction<Self>>(self, f: &F, a: &Vec<f64>, b: &Vec<f64>) -> MixedDerivatives<Self> {
        let kernel = widths::by_width!(self.0, W => widths::mixed_width::<F, W>(f, a, b), _ => None);
        kernel.unwrap_or_else(|| mixed_blocks(self, f, a, b))
    }

    fn scratch<R>(self, f: impl FnOnce(&mut [f64]) -> R) -> R {
        f(&mut vec![0.0; 5 * self.0 + 1])
    }

    fn first<F: PairFunction<Self>>(self, f: &F, a: &Vec<f64>, b: &Vec<f64>) -> FirstDerivatives<Self> {
        let kernel = widths::by_width!(self.0, W => widths::first_width::<F, W>(f, a, b), _ => None);
        kernel.unwrap_or_else(|| first_blocks(self, f, a, b))
    }
}

/// f(0), …, f(n − 1) in a vector allocated once at its length. `collect` and nalgebra's `from_fn`
/// took most of the instructions of the dynamic dimension's arrays (callgrind, 4 coordinates: the
/// generic `from_iter` and `fold` not inlined, and `from_fn` growing its storage).
#[inline(always)]
fn filled<T>(n: usize, mut f: impl FnMut(usize) -> T) -> Vec<T> {
    let mut values = Vec::with_capacity(n);
    for i in 0..n {
        values.push(f(i));
    }
    values
}

/// A vector of a [`Dim`] that knows its dimension: what lets a function taking one infer the
/// dimension (`newton::solve` on an `SVector<f64, 2>` or a `DVector<f64>`).
pub trait Column: Clone + for<'a> SubAssign<&'a Self> {
    /// The dimension whose [`Dim::Vector`] this is.
    type Dim: Dim<Vector = Self>;

    /// The dimension of this vector.
    fn dim(&self) -> Self::Dim;
}

impl<const N: usize> Column for SVector<f64, N> {
    type Dim = Fixed<N>;

    #[inline(always)]
    fn dim(&self) -> Fixed<N> {
        Fixed
    }
}

impl Column for DVector<f64> {
    type Dim = Dynamic;

    fn dim(&self) -> Dynamic {
        Dynamic(self.len())
    }
}

/// The n × n matrix of a [`Column`]'s dimension.
pub type MatrixOf<V> = <<V as Column>::Dim as Dim>::Matrix;

#[cfg(test)]
mod tests;
