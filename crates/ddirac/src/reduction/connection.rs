//! Linear discrete principal connections (paper Definition 2.1 and §2.2.1).
//!
//! With h_d(q0, x1) linear, the axiom h_d(q0, x0) = g0 and equivariance force
//!
//! ```text
//! h_d(q0, x1) = g0 + K (x1 − x0),            K = h_{d,Σ} ∈ ℝ^{n_g × n_x}
//! ω_d(q0, q1) = g1 − h_d(q0, x1) = g1 − g0 − K (x1 − x0)
//! h_{d,Q}(x0, g0) = h_d(q0, 0) = g0 − K x0,   h_{d,Σ}(x1) = h_d(0, x1) = K x1
//! h_d^0(x0, x1) = h_d((x0, 0), x1) = K (x1 − x0)
//! ```
//!
//! so a linear connection is one matrix K. Both examples of the paper use K = 0; the centre-of-mass
//! connection of two bodies (x = r2 − r1, g = r1) has K = −m2/(m1 + m2) · I.

use nalgebra::DMatrix;

use crate::{Error, Input, Reason};

/// A linear discrete principal connection, given by K = h_{d,Σ}.
///
/// ```
/// use ddirac::Connection;
/// let k = Connection::new(&[vec![-0.5]]).unwrap();
/// // ω_d((x0, g0), (x1, g1)) = g1 − g0 − K (x1 − x0)
/// assert_eq!(k.omega_d((&[0.0], &[0.0]), (&[2.0], &[1.0])), vec![2.0]);
/// assert!(k.check_axioms().is_ok());
/// assert!(Connection::new(&[vec![0.0, 1.0], vec![0.0]]).is_err());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Connection {
    k: DMatrix<f64>,
}

impl Connection {
    /// The trivial connection K = 0: ω_d(q0, q1) = g1 − g0.
    pub fn zero(n_x: usize, n_g: usize) -> Self {
        Self { k: DMatrix::zeros(n_g, n_x) }
    }

    /// K from its rows, one per group coordinate with one entry per shape coordinate: the rows must
    /// have equal lengths and finite entries. Whether the sizes fit a system is checked when a run is
    /// set up ([`Connection::fitted`]).
    pub fn new(rows: &[Vec<f64>]) -> Result<Self, Error> {
        let invalid = |why: Reason| Error::Invalid { what: Input::Connection, why };
        let n_x = rows.first().map_or(0, Vec::len);
        for (j, row) in rows.iter().enumerate() {
            if row.len() != n_x {
                return Err(invalid(Reason::UnequalRows { row: j + 1, found: row.len(), first: n_x }));
            }
            if let Some(&value) = row.iter().find(|v| !v.is_finite()) {
                return Err(invalid(Reason::NonFiniteEntry { row: j + 1, value }));
            }
        }
        Ok(Self { k: DMatrix::from_fn(rows.len(), n_x, |j, i| rows[j][i]) })
    }

    /// This K for a system with `n_x` shape and `n_g` group coordinates: an error unless K has
    /// `n_g` rows of `n_x` entries. K without rows fits a system without group coordinates.
    ///
    /// ```
    /// use ddirac::Connection;
    /// let k = Connection::new(&[vec![0.0, 0.0]]).unwrap();
    /// assert!(k.fitted(2, 1).is_ok());
    /// assert_eq!(
    ///     k.fitted(3, 1).unwrap_err().to_string(),
    ///     "invalid connection: row 1 of K has 2 entries, expected one per shape coordinate (3)"
    /// );
    /// assert_eq!(Connection::new(&[]).unwrap().fitted(3, 0).unwrap(), Connection::zero(3, 0));
    /// ```
    pub fn fitted(&self, n_x: usize, n_g: usize) -> Result<Self, Error> {
        let invalid = |why: Reason| Error::Invalid { what: Input::Connection, why };
        if self.n_g() != n_g {
            return Err(invalid(Reason::Rows { expected: n_g, found: self.n_g() }));
        }
        if n_g == 0 {
            return Ok(Self::zero(n_x, 0));
        }
        if self.n_x() != n_x {
            return Err(invalid(Reason::Columns { expected: n_x, found: self.n_x() }));
        }
        Ok(self.clone())
    }

    /// K by rows (n_g rows of n_x entries), as [`Connection::new`] takes it.
    ///
    /// ```
    /// let rows = vec![vec![-0.5, 0.0], vec![0.0, -0.5]];
    /// assert_eq!(ddirac::Connection::new(&rows).unwrap().rows(), rows);
    /// ```
    pub fn rows(&self) -> Vec<Vec<f64>> {
        self.k.row_iter().map(|row| row.iter().copied().collect()).collect()
    }

    /// K as a matrix.
    pub fn matrix(&self) -> &DMatrix<f64> {
        &self.k
    }

    /// dim Σ.
    pub fn n_x(&self) -> usize {
        self.k.ncols()
    }

    /// dim G.
    pub fn n_g(&self) -> usize {
        self.k.nrows()
    }

    /// Entry K[j, i] (group row j, shape column i).
    #[inline]
    pub fn entry(&self, j: usize, i: usize) -> f64 {
        self.k[(j, i)]
    }

    /// Whether K = 0.
    pub fn is_zero(&self) -> bool {
        self.k.iter().all(|&v| v == 0.0)
    }

    /// K x.
    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        (0..self.n_g()).map(|j| self.row_apply(j, |i| x[i]).unwrap_or(0.0)).collect()
    }

    /// Entry j of K x for a shape vector x given entry by entry (`x(i)` for shape coordinate i), on
    /// any scalar: the one place K acts on shape vectors (K x, h_d^0 = K (x1 − x0) in the reduced
    /// Lagrangians, the group increments of reconstruction). Zero entries of K are skipped, so a
    /// traced program has no terms for them; `None` when row j of K is zero.
    ///
    /// ```
    /// use ddirac::Connection;
    /// let k = Connection::new(&[vec![0.0, 2.0], vec![0.0, 0.0]]).unwrap();
    /// assert_eq!(k.row_apply(0, |i| [5.0, 3.0][i]), Some(6.0));
    /// assert_eq!(k.row_apply(1, |i| [5.0, 3.0][i]), None);
    /// ```
    #[inline]
    pub fn row_apply<D: crate::Scalar>(&self, j: usize, x: impl Fn(usize) -> D) -> Option<D> {
        let mut acc: Option<D> = None;
        for i in 0..self.n_x() {
            let kji = self.k[(j, i)];
            if kji != 0.0 {
                let term = x(i) * kji;
                acc = Some(acc.map_or(term, |s| s + term));
            }
        }
        acc
    }

    /// h*_{d,Σ}(μ) = Kᵀ μ ∈ Σ*, the pull-back of μ ∈ 𝔤* by h_{d,Σ}, written into `out`: μ has one entry
    /// per group coordinate, `out` one per shape coordinate. This is the only place Kᵀμ is formed; the
    /// reduced momenta w = p_x + Kᵀ p_g of λ̂_d use it.
    ///
    /// ```
    /// use ddirac::Connection;
    /// let k = Connection::new(&[vec![1.0, 2.0], vec![3.0, 4.0]]).unwrap();
    /// let mut w = [0.0; 2];
    /// k.transpose_apply(&[1.0, -1.0], &mut w);
    /// assert_eq!(w, [1.0 - 3.0, 2.0 - 4.0]);
    /// ```
    pub fn transpose_apply(&self, mu: &[f64], out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate().take(self.n_x()) {
            *o = (0..self.n_g()).map(|j| self.k[(j, i)] * mu[j]).sum();
        }
    }

    /// ω_d(q0, q1) = g1 − g0 − K (x1 − x0), with q = (x, g).
    pub fn omega_d(&self, (x0, g0): (&[f64], &[f64]), (x1, g1): (&[f64], &[f64])) -> Vec<f64> {
        let h = self.h_d((x0, g0), x1);
        g1.iter().zip(h).map(|(a, b)| a - b).collect()
    }

    /// The horizontal lift h_d(q0, x1) = g0 + K (x1 − x0).
    pub fn h_d(&self, (x0, g0): (&[f64], &[f64]), x1: &[f64]) -> Vec<f64> {
        let dx: Vec<f64> = x1.iter().zip(x0).map(|(a, b)| a - b).collect();
        g0.iter().zip(self.apply(&dx)).map(|(a, b)| a + b).collect()
    }

    /// h_{d,Q}(q0) = h_d(q0, 0) = g0 − K x0.
    pub fn h_dq(&self, (x0, g0): (&[f64], &[f64])) -> Vec<f64> {
        self.h_d((x0, g0), &vec![0.0; x0.len()])
    }

    /// h_{d,Σ}(x1) = h_d(0, x1) = K x1.
    pub fn h_dsigma(&self, x1: &[f64]) -> Vec<f64> {
        self.apply(x1)
    }

    /// h_d^0(x0, x1) = h_d((x0, 0), x1) = K (x1 − x0).
    pub fn h_d0(&self, x0: &[f64], x1: &[f64]) -> Vec<f64> {
        self.h_d((x0, &vec![0.0; self.n_g()]), x1)
    }

    /// Checks the axioms of Definition 2.1 and the decomposition (2.3) on a grid of sample points:
    /// (i) ω_d(q, q) = 0; (ii) ω_d(a·q0, b·q1) = b + ω_d(q0, q1) − a; h_d = h_{d,Q} + h_{d,Σ}.
    pub fn check_axioms(&self) -> Result<(), Error> {
        let (n_x, n_g) = (self.n_x(), self.n_g());
        let sample = |seed: usize, len: usize| -> Vec<f64> {
            (0..len).map(|i| ((seed * 7 + i * 13) % 11) as f64 * 0.37 - 1.7).collect()
        };
        let scale = 1.0 + self.k.amax();
        for s in 0..8 {
            let (x0, g0, x1, g1) = (sample(s, n_x), sample(s + 1, n_g), sample(s + 2, n_x), sample(s + 3, n_g));
            let (a, b) = (sample(s + 4, n_g), sample(s + 5, n_g));
            let fail = |axiom: &'static str, deviation: f64| Error::Invalid {
                what: Input::Connection,
                why: Reason::Axiom { axiom, deviation },
            };
            let dev0 = self.omega_d((&x0, &g0), (&x0, &g0)).iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if dev0 > 1e-12 * scale {
                return Err(fail("(i) ω_d(q, q) = e", dev0));
            }
            let shifted = |g: &[f64], by: &[f64]| -> Vec<f64> { g.iter().zip(by).map(|(u, v)| u + v).collect() };
            let lhs = self.omega_d((&x0, &shifted(&g0, &a)), (&x1, &shifted(&g1, &b)));
            let base = self.omega_d((&x0, &g0), (&x1, &g1));
            let dev1 = (0..n_g).fold(0.0f64, |m, j| m.max((lhs[j] - (b[j] + base[j] - a[j])).abs()));
            if dev1 > 1e-12 * scale * 10.0 {
                return Err(fail("(ii) equivariance", dev1));
            }
            let split = self.h_dq((&x0, &g0)).iter().zip(self.h_dsigma(&x1)).map(|(u, v)| u + v).collect::<Vec<_>>();
            let whole = self.h_d((&x0, &g0), &x1);
            let dev2 = (0..n_g).fold(0.0f64, |m, j| m.max((split[j] - whole[j]).abs()));
            if dev2 > 1e-12 * scale * 10.0 {
                return Err(fail("h_d = h_{d,Q} + h_{d,Σ}", dev2));
            }
        }
        Ok(())
    }
}
