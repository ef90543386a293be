//! Dense linear solves on fixed-size matrices by Gaussian elimination with full pivoting.
//!
//! Written for `SMatrix<f64, N, N>` with a const `N` (nalgebra's factorizations need type-level
//! dimension bounds that const generics cannot name) and allocation-free.

use nalgebra::{SMatrix, SVector};

/// Solves `a x = b`. Pivots smaller than `rel_tol · max|a|` count as zero: the corresponding
/// unknowns are set to 0 and the returned rank is below N (for a consistent singular system this is
/// one of its solutions). Returns `None` if `a` is zero or non-finite.
pub(crate) fn solve<const N: usize>(
    mut a: SMatrix<f64, N, N>,
    mut b: SVector<f64, N>,
    rel_tol: f64,
) -> Option<(SVector<f64, N>, usize)> {
    let scale = a.amax();
    if !(scale.is_finite() && scale > 0.0) {
        return None;
    }
    let threshold = rel_tol * scale;
    let mut col_of = [0usize; N];
    for (i, c) in col_of.iter_mut().enumerate() {
        *c = i;
    }
    let mut rank = 0;
    for k in 0..N {
        let (mut pr, mut pc, mut best) = (k, k, 0.0);
        for r in k..N {
            for c in k..N {
                if a[(r, c)].abs() > best {
                    (pr, pc, best) = (r, c, a[(r, c)].abs());
                }
            }
        }
        if best <= threshold {
            break;
        }
        a.swap_rows(k, pr);
        b.swap_rows(k, pr);
        a.swap_columns(k, pc);
        col_of.swap(k, pc);
        for r in k + 1..N {
            let f = a[(r, k)] / a[(k, k)];
            if f != 0.0 {
                for c in k..N {
                    a[(r, c)] -= f * a[(k, c)];
                }
                b[r] -= f * b[k];
            }
        }
        rank += 1;
    }
    let mut y = SVector::<f64, N>::zeros();
    for k in (0..rank).rev() {
        let mut s = b[k];
        for c in k + 1..rank {
            s -= a[(k, c)] * y[c];
        }
        y[k] = s / a[(k, k)];
    }
    let mut x = SVector::<f64, N>::zeros();
    for k in 0..N {
        x[col_of[k]] = y[k];
    }
    Some((x, rank))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_regular_system_like_lu() {
        let a = SMatrix::<f64, 3, 3>::new(2.0, 1.0, -1.0, -3.0, -1.0, 2.0, -2.0, 1.0, 2.0);
        let b = SVector::<f64, 3>::new(8.0, -11.0, -3.0);
        let (x, rank) = solve(a, b, 1e-14).unwrap();
        assert_eq!(rank, 3);
        assert!((x - SVector::<f64, 3>::new(2.0, 3.0, -1.0)).amax() < 1e-14);
    }

    #[test]
    fn reports_rank_of_a_singular_system_and_solves_the_consistent_part() {
        let a = SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 4.0);
        let b = SVector::<f64, 2>::new(3.0, 6.0);
        let (x, rank) = solve(a, b, 1e-12).unwrap();
        assert_eq!(rank, 1);
        assert!((a * x - b).amax() < 1e-14);
    }
}
