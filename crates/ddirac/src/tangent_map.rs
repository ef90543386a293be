//! The tangent map of the discrete flow: d(q_k, p_k)/d(q_0, p_0), propagated through every step by
//! the implicit function theorem on the step's own equations ([`crate::scheme`]).
//!
//! A (sub-)step from (q, m) (m: the scheme momenta) solves r(z) = ∂f/∂a(base, 0, z) + s ∘ m = 0 for
//! z and sets q' = q + I z (I: [`Scheme::increment`], linear) and m'_i = ∂f/∂b_i(base, 0, z) where
//! m_i advances (m'_i = m_i elsewhere). The generating function depends on the base through
//! base + a and base + b alone (L_d(base + a, base + b), and the reduced l̂ in the shape), so with
//! B = ∂base/∂q (a mask) and the Hessian blocks f_aa, f_ab, f_bb at (0, z):
//!
//! ```text
//! dz  = −f_ab⁻¹ ((f_aa + f_ab) B dq + s ∘ dm)
//! dq' = dq + I dz
//! dm' = (f_ba + f_bb) B dq + f_bb dz      (advancing rows; dm elsewhere)
//! ```
//!
//! and d(q, p) ↔ d(q, m) by the scheme's linear maps p ↔ m. f_ab is the Newton Jacobian of the
//! step; the Hessian of f in (a, b) comes from one pass of dual numbers. The map of a composition
//! is the product of its sub-steps' maps, and a chart switch multiplies by the Jacobian of the
//! cotangent lift ([`switch`]). The product is symplectic, as the flow is: ΦᵀJΦ = J.

use std::cell::RefCell;

use nalgebra::DMatrix;

use crate::compiled::{pair_programs_with_runtime_inputs, CompiledPair, Traced};
use crate::dim::{self, Dim, Dynamic, FirstDerivatives, PairFunction};
use crate::mechanics::lagrangian::SystemIn;
use crate::scheme::Scheme;
use crate::Scalar;

/// `$body(k)` for the size `$k`, a constant for the sizes of up to 8 coordinates (so that `$body`,
/// inlined, is compiled for each with its loops unrolled: the 4 × 4 solves and 8 × 8 products of a
/// step with runtime sizes cost twice as much), a runtime number above.
macro_rules! sized {
    ($k:expr, $body:expr, [$($size:literal),*]) => {{
        #[allow(unused_mut)]
        let mut body = $body;
        match $k {
            $($size => body($size),)*
            k => body(k),
        }
    }};
}

/// How a run takes the Hessian of its steps' generating function in (a, b): a compiled program of
/// f(base, a, b) seen as a pair function of 2n arguments (what the run's compiled derivatives are for
/// its Newton iterates), or dual numbers.
pub(crate) enum Hessian {
    /// f(base₂, A, B) = f(base, A_a + B_a, z + A_b + B_b) with base₂ = (base, z): its mixed block at
    /// A = B = 0 is the Hessian at (0, z).
    Compiled(Box<CompiledPair<Dynamic>>),
    Dual,
}

impl Hessian {
    /// The compiled Hessian of `scheme`'s generating function, traced at (`base`, `z`) and checked
    /// there against dual numbers; dual numbers if the trace or the check fails.
    pub(crate) fn compiled<Sc: Scheme<Dm>, Dm: Dim>(scheme: &Sc, base: &Dm::Array<f64>, z: &Dm::Array<f64>) -> Self {
        let dim = Dm::of(base);
        let n = dim.n();
        let doubled = |base: &Vec<Traced>, a: &Vec<Traced>, b: &Vec<Traced>| {
            let inner = dim.array(|i| base[i]);
            let a_in = dim.array(|i| a[i] + b[i]);
            let b_in = dim.array(|i| base[n + i] + a[n + i] + b[n + i]);
            scheme.generating::<Traced, Traced>(&inner, &a_in, &b_in)
        };
        let base2: Vec<f64> = base.as_ref().iter().chain(z.as_ref()).copied().collect();
        let zeros = vec![0.0; 2 * n];
        let compiled = pair_programs_with_runtime_inputs(Dynamic(2 * n), doubled, &base2, &zeros)
            .map_err(|e| e.to_string())
            .and_then(|programs| CompiledPair::from_programs(Dynamic(2 * n), &programs).map_err(|e| e.to_string()))
            .and_then(|pair| {
                let dual = dual_hessian(scheme, base, z);
                let first = FirstDerivatives { value: dual.value, da: dual.da, db: dual.db };
                pair.check_against(&base2, &zeros, (first, dual.dadb), 1e-9).map(|()| pair).map_err(|e| e.to_string())
            });
        match compiled {
            Ok(pair) => Self::Compiled(Box::new(pair)),
            Err(_) => Self::Dual,
        }
    }

    /// The same for the scheme with step size `step` (a composition's other sub-steps): the compiled
    /// program with h set to `step` where h is a runtime input of it, else dual numbers.
    pub(crate) fn for_step(&self, step: f64) -> Self {
        match self {
            Self::Compiled(pair) if pair.is_unguarded() => {
                pair.with_step(step).map_or(Self::Dual, |pair| Self::Compiled(Box::new(pair)))
            }
            _ => Self::Dual,
        }
    }

    /// Writes the Hessian of `scheme`'s generating function in (a, b) at (`base`, 0, `z`) into
    /// `out` (2n × 2n); `base2` is room for (base, z), `zeros` holds 2n zeros.
    fn write<Sc: Scheme<Dm>, Dm: Dim>(
        &self,
        scheme: &Sc,
        (base, z): (&Dm::Array<f64>, &Dm::Vector),
        base2: &mut Vec<f64>,
        zeros: &[f64],
        out: &mut DMatrix<f64>,
    ) {
        let n = Dm::of(base).n();
        let compiled = match self {
            Self::Compiled(pair) => {
                base2.clear();
                base2.extend(base.as_ref().iter().copied().chain((0..n).map(|i| z[i])));
                pair.mixed_with(base2, zeros, |i, j, x| out[(i, j)] = x)
            }
            Self::Dual => false,
        };
        // Where a guard of the trace fails (another branch of a comparison), dual numbers answer.
        if !compiled {
            let hessian = dual_hessian(scheme, base, &Dm::of(base).array(|i| z[i])).dadb;
            out.iter_mut().enumerate().for_each(|(k, x)| *x = hessian[(k % (2 * n), k / (2 * n))]);
        }
    }
}

/// The Hessian of `scheme`'s generating function in (a, b) at (`base`, 0, `z`) by dual numbers.
fn dual_hessian<Sc: Scheme<Dm>, Dm: Dim>(
    scheme: &Sc,
    base: &Dm::Array<f64>,
    z: &Dm::Array<f64>,
) -> dim::MixedDerivatives<Dynamic> {
    let dim = Dm::of(base);
    let n = dim.n();
    let f = Generating { scheme, base, dim };
    let y: Vec<f64> = (0..2 * n).map(|i| if i < n { 0.0 } else { z[i - n] }).collect();
    dim::mixed(Dynamic(2 * n), &f, &vec![0.0; 2 * n], &y)
}

/// f(base, x_a + y_a, x_b + y_b): its mixed block in (x, y) is the Hessian of f in (a, b).
struct Generating<'a, Sc, Dm: Dim> {
    scheme: &'a Sc,
    base: &'a Dm::Array<f64>,
    dim: Dm,
}

impl<Sc: Scheme<Dm>, Dm: Dim> PairFunction<Dynamic> for Generating<'_, Sc, Dm> {
    fn eval<D: Scalar>(&self, x: &Vec<D>, y: &Vec<D>) -> D {
        let n = self.dim.n();
        let a = self.dim.array(|i| x[i] + y[i]);
        let b = self.dim.array(|i| x[n + i] + y[n + i]);
        self.scheme.generating::<D, f64>(self.base, &a, &b)
    }
}

/// The matrix of a linear map of n numbers, column by column.
fn linear<Dm: Dim>(dim: Dm, map: impl Fn(&Dm::Array<f64>) -> Dm::Array<f64>) -> DMatrix<f64> {
    let n = dim.n();
    let zero = map(&dim.array(|_| 0.0));
    DMatrix::from_fn(n, n, |i, j| map(&dim.array(|k| if k == j { 1.0 } else { 0.0 }))[i] - zero[i])
}

/// What the tangent map of a scheme's (sub-)steps needs besides the point: how the Hessian is taken,
/// the scheme's linear maps (the same at every step) and room for the step's matrices.
pub(crate) struct StepTangent {
    hessian: Hessian,
    /// Whether the base depends on coordinate j (B = diag(mask)).
    mask: Vec<bool>,
    /// I: z ↦ q_{k+1} − q_k.
    increment: DMatrix<f64>,
    /// T: p ↦ m and P: m ↦ p, `None` where they are the identity.
    to_momenta: Option<DMatrix<f64>>,
    to_p: Option<DMatrix<f64>>,
    sign: Vec<f64>,
    advances: Vec<bool>,
    work: RefCell<Work>,
}

/// The matrices of a sub-step's tangent map, kept from step to step so that a step allocates
/// nothing but the map it returns (heap-allocated 8 × 8 matrices were a fifth of the cost).
struct Work {
    /// (base, z) and 2n zeros: the compiled Hessian's inputs.
    base2: Vec<f64>,
    zeros: Vec<f64>,
    /// The Hessian of the generating function in (a, b), 2n × 2n.
    hessian: DMatrix<f64>,
    /// f_ab, factorized in place (LU with partial pivoting), and its row exchanges.
    lu: DMatrix<f64>,
    pivots: Vec<usize>,
    /// dz = Z (dq, dm), n × 2n.
    z_map: DMatrix<f64>,
    /// The sub-step's map and a product, 2n × 2n.
    map: DMatrix<f64>,
    product: DMatrix<f64>,
}

impl Work {
    fn new(n: usize) -> Self {
        Self {
            base2: Vec::with_capacity(2 * n),
            zeros: vec![0.0; 2 * n],
            hessian: DMatrix::zeros(2 * n, 2 * n),
            lu: DMatrix::zeros(n, n),
            pivots: vec![0; n],
            z_map: DMatrix::zeros(n, 2 * n),
            map: DMatrix::zeros(2 * n, 2 * n),
            product: DMatrix::zeros(2 * n, 2 * n),
        }
    }
}

impl StepTangent {
    /// The tangent map of `scheme`'s steps with the Hessian taken as `hessian` says.
    pub(crate) fn new<Sc: Scheme<Dm>, Dm: Dim>(scheme: &Sc, dim: Dm, hessian: Hessian) -> Self {
        let n = dim.n();
        let mask_matrix = linear(dim, |q| scheme.base(q));
        let identity = |m: DMatrix<f64>| (m != DMatrix::identity(n, n)).then_some(m);
        let equations = scheme.equations();
        Self {
            hessian,
            mask: (0..n).map(|j| mask_matrix[(j, j)] != 0.0).collect(),
            increment: linear(dim, |v| scheme.increment(&dim.vector(|i| v[i]))),
            to_momenta: identity(linear(dim, |p| scheme.momenta_from_p(p))),
            to_p: identity(linear(dim, |m| scheme.p_from_momenta(m))),
            sign: equations.sign.as_ref().to_vec(),
            advances: equations.advances.as_ref().to_vec(),
            work: RefCell::new(Work::new(n)),
        }
    }

    /// The same for the scheme with step size `step` ([`Hessian::for_step`]).
    pub(crate) fn for_step(&self, step: f64) -> Self {
        Self {
            hessian: self.hessian.for_step(step),
            mask: self.mask.clone(),
            increment: self.increment.clone(),
            to_momenta: self.to_momenta.clone(),
            to_p: self.to_p.clone(),
            sign: self.sign.clone(),
            advances: self.advances.clone(),
            work: RefCell::new(Work::new(self.sign.len())),
        }
    }

    /// d(q', p')/d(q, p) of one (sub-)step of `scheme` from a configuration whose chart base is `q`,
    /// solved by the unknowns `z`, times `before` (the map of the step's earlier sub-steps, whose
    /// storage the product takes): a 2n × 2n matrix, q then p. NaN when the step's Jacobian f_ab is
    /// singular there (the step then has no tangent map) or the map is not finite.
    pub(crate) fn step<Sc: Scheme<Dm>, Dm: Dim>(
        &self,
        scheme: &Sc,
        q: &Dm::Array<f64>,
        z: &Dm::Vector,
        before: Option<DMatrix<f64>>,
    ) -> DMatrix<f64> {
        let n = Dm::of(q).n();
        let n2 = 2 * n;
        let mut work = self.work.borrow_mut();
        let Work { base2, zeros, hessian, lu, pivots, z_map, map, product } = &mut *work;
        self.hessian.write(scheme, (&scheme.base(q), z), base2, zeros, hessian);
        let regular = sized!(
            n,
            |n| self.linearized(
                hessian.as_slice(),
                lu.as_mut_slice(),
                pivots,
                z_map.as_mut_slice(),
                map.as_mut_slice(),
                n
            ),
            [1, 2, 3, 4, 5, 6, 7, 8]
        );
        // In (q, p): dm = T dp, dp' = P dm'.
        if let Some(t) = &self.to_momenta {
            product.view_mut((0, 0), (n2, n)).gemm(1.0, &map.columns(n, n), t, 0.0);
            map.columns_mut(n, n).copy_from(&product.view((0, 0), (n2, n)));
        }
        if let Some(p) = &self.to_p {
            product.view_mut((0, 0), (n, n2)).gemm(1.0, p, &map.rows(n, n), 0.0);
            map.rows_mut(n, n).copy_from(&product.view((0, 0), (n, n2)));
        }
        if !regular || !map.iter().fold(true, |all, x| all & x.is_finite()) {
            map.fill(f64::NAN);
        }
        match before {
            Some(mut before) => {
                multiply(product.as_mut_slice(), map.as_slice(), before.as_slice(), n2);
                std::mem::swap(product, &mut before);
                before
            }
            None => map.clone(),
        }
    }

    /// The sub-step's map M in (q, m) (column-major, 2n × 2n) from the Hessian h of the generating
    /// function; `l`, `pivots` and `zs` are room for the factorized f_ab and Z. `false` when f_ab is
    /// singular.
    #[inline(always)]
    fn linearized(
        &self,
        h: &[f64],
        l: &mut [f64],
        pivots: &mut [usize],
        zs: &mut [f64],
        m: &mut [f64],
        n: usize,
    ) -> bool {
        // Column-major slices: h(i, j) = h[j·2n + i], Z(i, j) = z[j·n + i], M(i, j) = m[j·2n + i].
        let n2 = 2 * n;
        // dz = Z (dq, dm): Z = −f_ab⁻¹ [(f_aa + f_ab) B | S].
        for j in 0..n {
            l[j * n..(j + 1) * n].copy_from_slice(&h[(n + j) * n2..(n + j) * n2 + n]);
        }
        for j in 0..n2 {
            let column = &mut zs[j * n..(j + 1) * n];
            match j < n {
                true if self.mask[j] => {
                    let (aa, ab) = (&h[j * n2..j * n2 + n], &h[(n + j) * n2..(n + j) * n2 + n]);
                    column.iter_mut().zip(aa.iter().zip(ab)).for_each(|(z, (aa, ab))| *z = -(aa + ab));
                }
                true => column.fill(0.0),
                false => {
                    column.fill(0.0);
                    column[j - n] = -self.sign[j - n];
                }
            }
        }
        let regular = factorize(l, pivots, n);
        if regular {
            solve_in_place(l, pivots, zs, n);
        }
        // dq' = dq + I dz: the top n rows of M.
        let increment = self.increment.as_slice();
        for j in 0..n2 {
            let (column, z) = (&mut m[j * n2..j * n2 + n], &zs[j * n..(j + 1) * n]);
            column.fill(0.0);
            for (k, zk) in z.iter().enumerate() {
                column.iter_mut().zip(&increment[k * n..(k + 1) * n]).for_each(|(c, i)| *c += i * zk);
            }
            if j < n {
                column[j] += 1.0;
            }
        }
        // dm' = (f_ba + f_bb) B dq + f_bb dz where m advances, dm elsewhere: the bottom n rows.
        for j in 0..n2 {
            let (column, z) = (&mut m[j * n2 + n..(j + 1) * n2], &zs[j * n..(j + 1) * n]);
            column.fill(0.0);
            for (k, zk) in z.iter().enumerate() {
                column.iter_mut().zip(&h[(n + k) * n2 + n..(n + k + 1) * n2]).for_each(|(c, bb)| *c += bb * zk);
            }
            if j < n && self.mask[j] {
                let (ba, bb) = (&h[j * n2 + n..(j + 1) * n2], &h[(n + j) * n2 + n..(n + j + 1) * n2]);
                column.iter_mut().zip(ba.iter().zip(bb)).for_each(|(c, (ba, bb))| *c += ba + bb);
            }
            for (i, c) in column.iter_mut().enumerate() {
                if !self.advances[i] {
                    *c = f64::from(u8::from(j == n + i));
                }
            }
        }
        regular
    }
}

/// c = a b for square k × k matrices in column-major slices.
pub(crate) fn multiply(c: &mut [f64], a: &[f64], b: &[f64], k: usize) {
    sized!(k, |k| multiply_body(c, a, b, k), [2, 4, 6, 8, 10, 12, 14, 16])
}

#[inline(always)]
fn multiply_body(c: &mut [f64], a: &[f64], b: &[f64], k: usize) {
    let (c, a, b) = (&mut c[..k * k], &a[..k * k], &b[..k * k]);
    for (column, b) in c.chunks_exact_mut(k).zip(b.chunks_exact(k)) {
        column.fill(0.0);
        for (a, blj) in a.chunks_exact(k).zip(b) {
            column.iter_mut().zip(a).for_each(|(c, a)| *c += a * blj);
        }
    }
}

/// Factorizes the n × n matrix `a` (column-major) in place as P a = L U with partial pivoting (L unit
/// lower, below the diagonal; U on and above it), row k exchanged with `pivots[k]`; `false` when a
/// pivot is zero or not finite (a singular or not finite matrix).
#[inline(always)]
fn factorize(a: &mut [f64], pivots: &mut [usize], n: usize) -> bool {
    let (a, pivots) = (&mut a[..n * n], &mut pivots[..n]);
    for k in 0..n {
        let column = &a[k * n..(k + 1) * n];
        let (p, largest) = (k..n).fold((k, -1.0), |m, i| if column[i].abs() > m.1 { (i, column[i].abs()) } else { m });
        if !(largest > 0.0 && largest.is_finite()) {
            return false;
        }
        pivots[k] = p;
        if p != k {
            (0..n).for_each(|j| a.swap(j * n + k, j * n + p));
        }
        let reciprocal = 1.0 / a[k * n + k];
        a[k * n + k + 1..(k + 1) * n].iter_mut().for_each(|x| *x *= reciprocal);
        let (left, right) = a.split_at_mut((k + 1) * n);
        let l = &left[k * n + k + 1..(k + 1) * n];
        for column in right.chunks_exact_mut(n) {
            let akj = column[k];
            column[k + 1..].iter_mut().zip(l).for_each(|(x, l)| *x -= l * akj);
        }
    }
    true
}

/// Overwrites the columns of `b` (column-major, n rows) with a⁻¹ b for `a` factorized by [`factorize`].
#[inline(always)]
fn solve_in_place(lu: &[f64], pivots: &[usize], b: &mut [f64], n: usize) {
    let (lu, pivots) = (&lu[..n * n], &pivots[..n]);
    // One division per row, not per row and column (a division's latency is that of a dozen products).
    let mut reciprocals = [0.0; 8];
    let reciprocals: &mut [f64] = match n <= 8 {
        true => &mut reciprocals[..n],
        false => &mut vec![0.0; n],
    };
    reciprocals.iter_mut().enumerate().for_each(|(k, r)| *r = 1.0 / lu[k * n + k]);
    for column in b.chunks_exact_mut(n) {
        for (k, &p) in pivots.iter().enumerate() {
            column.swap(k, p);
        }
        for k in 0..n {
            let x = column[k];
            column[k + 1..].iter_mut().zip(&lu[k * n + k + 1..(k + 1) * n]).for_each(|(c, l)| *c -= l * x);
        }
        for k in (0..n).rev() {
            let x = column[k] * reciprocals[k];
            column[k] = x;
            column[..k].iter_mut().zip(&lu[k * n..k * n + k]).for_each(|(c, u)| *c -= u * x);
        }
    }
}

/// ⟨w, τ(q + x + y)⟩ for the map τ from chart `from` to chart `to`: its mixed block in (x, y) is
/// the Hessian of ⟨w, τ⟩.
struct Paired<'a, S, Dm: Dim> {
    system: &'a S,
    from: usize,
    to: usize,
    q: &'a Dm::Array<f64>,
    w: &'a Dm::Array<f64>,
    dim: Dm,
}

impl<S: SystemIn<Dm>, Dm: Dim> PairFunction<Dynamic> for Paired<'_, S, Dm> {
    fn eval<D: Scalar>(&self, x: &Vec<D>, y: &Vec<D>) -> D {
        let q = self.dim.array(|i| x[i] + y[i] + self.q[i]);
        let moved = crate::atlas::map(self.system, self.from, self.to, &q);
        (0..self.dim.n()).fold(D::from(0.0), |sum, j| sum + moved[j] * self.w[j])
    }
}

/// Σ_j y_j τ_j(q + x) for the map τ from chart `from` to chart `to`: its mixed block in (x, y) is
/// Dτᵀ, entry (i, j) = ∂τ_j/∂q_i.
struct Weighted<'a, S, Dm: Dim> {
    system: &'a S,
    from: usize,
    to: usize,
    q: &'a Dm::Array<f64>,
    dim: Dm,
}

impl<S: SystemIn<Dm>, Dm: Dim> PairFunction<Dynamic> for Weighted<'_, S, Dm> {
    fn eval<D: Scalar>(&self, x: &Vec<D>, y: &Vec<D>) -> D {
        let q = self.dim.array(|i| x[i] + self.q[i]);
        let moved = crate::atlas::map(self.system, self.from, self.to, &q);
        (0..self.dim.n()).fold(D::from(0.0), |sum, j| sum + moved[j] * y[j])
    }
}

/// The Jacobian of the switch ([`crate::atlas::transition`]) from chart `from` to chart `to` of the
/// state (q, p) of chart `from`, which lands at q' = ψ(q) with p' = Dτ(q')ᵀ p (τ: chart `to` →
/// chart `from`): dq' = Dψ dq and dp' = Dτᵀ dp + ∇²⟨p, τ⟩(q') Dψ dq.
pub(crate) fn switch<S: SystemIn<Dm>, Dm: Dim>(
    system: &S,
    (from, to): (usize, usize),
    q: &Dm::Array<f64>,
    p: &Dm::Array<f64>,
    q_to: &Dm::Array<f64>,
) -> Option<DMatrix<f64>> {
    let dim = Dm::of(q);
    let n = dim.n();
    let zeros = vec![0.0; n];
    let square = |m: &<Dynamic as Dim>::Matrix| DMatrix::from_fn(n, n, |i, j| m[(i, j)]);
    let psi_t = square(&dim::mixed(Dynamic(n), &Weighted { system, from, to, q, dim }, &zeros, &zeros).dadb);
    let tau_t =
        square(&dim::mixed(Dynamic(n), &Weighted { system, from: to, to: from, q: q_to, dim }, &zeros, &zeros).dadb);
    let paired = Paired { system, from: to, to: from, q: q_to, w: p, dim };
    let curvature = square(&dim::mixed(Dynamic(n), &paired, &zeros, &zeros).dadb);
    let psi = psi_t.transpose();
    let mut map = DMatrix::zeros(2 * n, 2 * n);
    map.view_mut((n, 0), (n, n)).copy_from(&(curvature * &psi));
    map.view_mut((0, 0), (n, n)).copy_from(&psi);
    map.view_mut((n, n), (n, n)).copy_from(&tau_t);
    map.iter().all(|x| x.is_finite()).then_some(map)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The in-place LU solve agrees with nalgebra's, and the product with nalgebra's, for any
        /// well-conditioned matrix (diagonally weighted so that pivoting is still exercised).
        #[test]
        fn the_in_place_solve_and_product_agree_with_nalgebra(
            n in 1usize..7,
            entries in proptest::collection::vec(-1.0f64..1.0, 7 * 7 * 3),
        ) {
            let a = DMatrix::from_fn(n, n, |i, j| entries[i * n + j] + if (i + 1) % n == j { 3.0 } else { 0.0 });
            let b = DMatrix::from_fn(n, 2 * n, |i, j| entries[49 + i * 2 * n + j]);
            let expected = a.clone().lu().solve(&b).unwrap();
            let (mut lu, mut pivots, mut x) = (a.clone(), vec![0; n], b.clone());
            prop_assert!(factorize(lu.as_mut_slice(), &mut pivots, n));
            solve_in_place(lu.as_slice(), &pivots, x.as_mut_slice(), n);
            prop_assert!((&x - &expected).amax() < 1e-10 * (1.0 + expected.amax()));
            let c = DMatrix::from_fn(n, n, |i, j| entries[98 + i * n + j]);
            let mut product = DMatrix::zeros(n, n);
            multiply(product.as_mut_slice(), a.as_slice(), c.as_slice(), n);
            prop_assert!((&product - &a * &c).amax() < 1e-14);
        }
    }

    /// A singular matrix is refused, not divided by zero.
    #[test]
    fn a_singular_matrix_has_no_factorization() {
        let mut a = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0]);
        assert!(!factorize(a.as_mut_slice(), &mut [0, 0], 2));
        let mut nan = DMatrix::from_row_slice(2, 2, &[f64::NAN, 0.0, 0.0, 1.0]);
        assert!(!factorize(nan.as_mut_slice(), &mut [0, 0], 2));
    }
}
