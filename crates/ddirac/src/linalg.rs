//! Dense linear solves by Gaussian elimination with full pivoting; the factorization can be kept and
//! reused for several right-hand sides.
//!
//! Written over a [`Dim`] (nalgebra's factorizations need type-level dimension bounds that const
//! generics cannot name): allocation-free for [`crate::dim::Fixed`], the same arithmetic on the heap
//! for [`crate::dim::Dynamic`].

use crate::dim::Dim;

/// Solves `a x = b`. Pivots smaller than `rel_tol · max|a|` count as zero: the corresponding
/// unknowns are set to 0 and the returned rank is below N (for a consistent singular system this is
/// one of its solutions). Returns `None` if `a` is zero or non-finite.
pub(crate) fn solve<Dm: Dim>(dim: Dm, a: &Dm::Matrix, b: &Dm::Vector, rel_tol: f64) -> Option<(Dm::Vector, usize)> {
    let lu = Factorization::new(dim, a, rel_tol)?;
    Some((lu.solve(b), lu.rank))
}

/// P A Q = L U with full pivoting, kept to solve several right-hand sides.
#[derive(Debug, Clone)]
pub(crate) struct Factorization<Dm: Dim> {
    dim: Dm,
    /// Row-major: U on and above the diagonal, the multipliers of L below it (first `rank` columns).
    lu: Dm::Array<Dm::Array<f64>>,
    /// Row k of the factorization is row `row_of[k]` of A.
    row_of: Dm::Array<usize>,
    /// Column k of the factorization is column `col_of[k]` of A.
    col_of: Dm::Array<usize>,
    /// Number of pivots above the threshold.
    pub rank: usize,
}

impl<Dm: Dim> Factorization<Dm> {
    /// Factorizes `a`; pivots below `rel_tol · max|a|` end the elimination (rank < n). `None` if `a`
    /// is zero or non-finite.
    pub(crate) fn new(dim: Dm, a: &Dm::Matrix, rel_tol: f64) -> Option<Self> {
        let mut lu = Self {
            dim,
            lu: dim.array(|_| dim.array(|_| 0.0)),
            row_of: dim.array(|i| i),
            col_of: dim.array(|i| i),
            rank: 0,
        };
        lu.refactor(a, rel_tol).then_some(lu)
    }

    /// Factorizes `a` in place of the factorization held (the storage of a dimension chosen at run
    /// time is kept, not allocated again); pivots below `rel_tol · max|a|` end the elimination. False,
    /// and the factorization unusable, if `a` is zero or non-finite.
    pub(crate) fn refactor(&mut self, a: &Dm::Matrix, rel_tol: f64) -> bool {
        let n = self.dim.n();
        // `f64::max` passes over NaN: it is looked for apart.
        let (scale, nan) = Dm::matrix_entries(a)
            .iter()
            .fold((0.0, false), |(m, nan): (f64, bool), x| (x.abs().max(m), nan | x.is_nan()));
        if nan || !(scale.is_finite() && scale > 0.0) {
            self.rank = 0;
            return false;
        }
        let threshold = rel_tol * scale;
        for (r, row) in self.lu.as_mut().iter_mut().enumerate() {
            for (c, x) in row.as_mut().iter_mut().enumerate() {
                *x = a[(r, c)];
            }
        }
        for (i, (row, col)) in self.row_of.as_mut().iter_mut().zip(self.col_of.as_mut()).enumerate() {
            (*row, *col) = (i, i);
        }
        let Self { lu, row_of, col_of, rank, .. } = self;
        *rank = 0;
        // Index loops over constant bounds: about half the instructions of the iterator chains they
        // replaced (callgrind, 4 × 4), with the same arithmetic in the same order.
        #[allow(clippy::needless_range_loop)]
        for k in 0..n {
            let (mut pr, mut pc, mut best) = (k, k, 0.0);
            for r in k..n {
                for c in k..n {
                    let x = lu[r][c].abs();
                    if x > best {
                        (pr, pc, best) = (r, c, x);
                    }
                }
            }
            if best <= threshold {
                break;
            }
            if pr != k {
                lu.as_mut().swap(k, pr);
                row_of.as_mut().swap(k, pr);
            }
            if pc != k {
                for row in lu.as_mut() {
                    row.as_mut().swap(k, pc);
                }
                col_of.as_mut().swap(k, pc);
            }
            // Rows by slices: no copy of the pivot row and no bounds checks in a dynamic dimension.
            let (above, below) = lu.as_mut().split_at_mut(k + 1);
            let pivot_row = above[k].as_ref();
            for row in below {
                let row = row.as_mut();
                let f = row[k] / pivot_row[k];
                row[k] = f;
                for (x, p) in row[k + 1..n].iter_mut().zip(&pivot_row[k + 1..n]) {
                    *x -= f * p;
                }
            }
            *rank += 1;
        }
        true
    }

    /// The largest entry of the factorized matrix, |a| at the first pivot of full pivoting.
    pub(crate) fn scale(&self) -> f64 {
        if self.dim.n() == 0 {
            return 0.0;
        }
        self.lu[0][0].abs()
    }

    /// How near to singular the factorized matrix is: its smallest pivot over its largest (0 when the
    /// rank is below n), and the column of `a` whose pivot that is. Full pivoting orders the pivots by
    /// size, so the ratio estimates the reciprocal condition number within a factor of a few.
    pub(crate) fn smallest_pivot(&self) -> (f64, usize) {
        let n = self.dim.n();
        if n == 0 {
            return (1.0, 0);
        }
        if self.rank < n {
            return (0.0, self.col_of[self.rank]);
        }
        let (first, last) = (self.lu[0][0].abs(), self.lu[n - 1][n - 1].abs());
        (last / first, self.col_of[n - 1])
    }

    /// Whether every pivot is above the threshold: the factorized matrix is regular.
    pub(crate) fn is_regular(&self) -> bool {
        self.rank == self.dim.n()
    }

    /// A solution of `a x = b` (unknowns beyond the rank set to 0).
    pub(crate) fn solve(&self, b: &Dm::Vector) -> Dm::Vector {
        let (mut y, mut x) = (self.dim.array(|_| 0.0), self.dim.zeros());
        self.solve_into(b, &mut y, &mut x);
        x
    }

    /// [`Factorization::solve`] into `x`, with `y` as the scratch of the substitutions: nothing
    /// allocated.
    #[allow(clippy::needless_range_loop)]
    pub(crate) fn solve_into(&self, b: &Dm::Vector, y: &mut Dm::Array<f64>, x: &mut Dm::Vector) {
        let n = self.dim.n();
        for (k, y) in y.as_mut().iter_mut().enumerate() {
            *y = b[self.row_of[k]];
        }
        let rank = self.rank.min(n);
        let (lu, y_all) = (self.lu.as_ref(), y.as_mut());
        // Forward substitution row by row (contiguous in `lu`): y_r −= L_rk y_k for k < min(r, rank)
        // in ascending k, the operations of the column-by-column order.
        for r in 1..n {
            let (done, rest) = y_all.split_at_mut(r);
            let k_end = r.min(rank);
            let mut s = rest[0];
            for (l, yk) in lu[r].as_ref()[..k_end].iter().zip(&done[..k_end]) {
                s -= l * yk;
            }
            rest[0] = s;
        }
        for k in (0..rank).rev() {
            let row = lu[k].as_ref();
            let mut s = y_all[k];
            for (a, yc) in row[k + 1..rank].iter().zip(&y_all[k + 1..rank]) {
                s -= a * yc;
            }
            y_all[k] = s / row[k];
        }
        for k in rank..n {
            x[self.col_of[k]] = 0.0;
        }
        for k in 0..rank {
            x[self.col_of[k]] = y_all[k];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dim::Fixed;
    use nalgebra::{SMatrix, SVector};

    #[test]
    fn solves_a_regular_system_like_lu() {
        let a = SMatrix::<f64, 3, 3>::new(2.0, 1.0, -1.0, -3.0, -1.0, 2.0, -2.0, 1.0, 2.0);
        let b = SVector::<f64, 3>::new(8.0, -11.0, -3.0);
        let (x, rank) = solve(Fixed, &a, &b, 1e-14).unwrap();
        assert_eq!(rank, 3);
        assert!((x - SVector::<f64, 3>::new(2.0, 3.0, -1.0)).amax() < 1e-14);
    }

    #[test]
    fn reports_rank_of_a_singular_system_and_solves_the_consistent_part() {
        let a = SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 4.0);
        let b = SVector::<f64, 2>::new(3.0, 6.0);
        let (x, rank) = solve(Fixed, &a, &b, 1e-12).unwrap();
        assert_eq!(rank, 1);
        assert!((a * x - b).amax() < 1e-14);
    }

    #[test]
    fn a_kept_factorization_solves_new_right_hand_sides() {
        let a =
            SMatrix::<f64, 4, 4>::from_fn(|i, j| 1.0 / (1.0 + i as f64 + j as f64) + if i == j { 0.5 } else { 0.0 });
        let lu = Factorization::new(Fixed, &a, 1e-14).unwrap();
        assert_eq!(lu.rank, 4);
        for k in 0..4 {
            let x = SVector::<f64, 4>::from_fn(|i, _| (i as f64 + 1.0) * (k as f64 - 1.5));
            assert!((lu.solve(&(a * x)) - x).amax() < 1e-13);
        }
    }

    /// A matrix that needs row and column exchanges, and a singular one.
    fn pivoting<Dm: Dim>(dim: Dm) -> (Dm::Matrix, Dm::Matrix) {
        let regular =
            dim.matrix(|i, j| if (i + 2 * j) % 3 == 0 { 0.0 } else { 1.0 / (1.0 + i as f64 + 2.0 * j as f64) });
        let singular = dim.matrix(|i, j| (i as f64 + 1.0) * (j as f64 - 0.5));
        (regular, singular)
    }

    #[test]
    fn a_refactored_factorization_is_a_new_one_bit_for_bit_in_both_dimensions() {
        use crate::dim::Dynamic;
        let (regular, singular) = pivoting(Fixed::<5>);
        let b = SVector::<f64, 5>::from_fn(|i, _| 0.3 * i as f64 - 1.0);
        let fresh = Factorization::new(Fixed, &regular, 1e-14).unwrap();
        // Storage that held another matrix (of lower rank) first.
        let mut reused = Factorization::new(Fixed, &singular, 1e-14).unwrap();
        assert!(reused.refactor(&regular, 1e-14));
        assert_eq!((reused.rank, reused.row_of, reused.col_of), (fresh.rank, fresh.row_of, fresh.col_of));
        assert_eq!(reused.solve(&b), fresh.solve(&b));

        let (dregular, dsingular) = pivoting(Dynamic(5));
        let db = nalgebra::DVector::from_column_slice(b.as_slice());
        let mut dynamic = Factorization::new(Dynamic(5), &dsingular, 1e-14).unwrap();
        assert_eq!(dynamic.rank, 1);
        assert!(dynamic.refactor(&dregular, 1e-14));
        let (mut y, mut x) = (vec![7.0; 5], nalgebra::DVector::from_element(5, f64::NAN));
        dynamic.solve_into(&db, &mut y, &mut x);
        assert_eq!(x.as_slice(), fresh.solve(&b).as_slice(), "solve_into in Dynamic(5) against Fixed<5>");
        assert!((regular * fresh.solve(&b) - b).amax() < 1e-13);

        // Back to the singular matrix: the entries beyond the rank are zeroed, not left from before.
        assert!(dynamic.refactor(&dsingular, 1e-12));
        dynamic.solve_into(&(&dsingular * nalgebra::DVector::from_element(5, 1.0)), &mut y, &mut x);
        assert_eq!(dynamic.rank, 1);
        assert_eq!(x.iter().filter(|v| **v == 0.0).count(), 4);
        assert!((&dsingular * &x - &dsingular * nalgebra::DVector::from_element(5, 1.0)).amax() < 1e-13);

        // A zero or non-finite matrix leaves the factorization unusable.
        assert!(!dynamic.refactor(&Dynamic(5).matrix(|_, _| 0.0), 1e-14));
        assert!(!dynamic.is_regular());
        assert!(!dynamic.refactor(&Dynamic(5).matrix(|i, _| if i == 2 { f64::NAN } else { 1.0 }), 1e-14));
        assert!(!dynamic.is_regular());
    }
}
