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

use nalgebra::DMatrix;

use crate::compiled::{pair_programs_with_runtime_inputs, CompiledPair, Traced};
use crate::dim::{self, Dim, Dynamic, FirstDerivatives, PairFunction};
use crate::mechanics::lagrangian::SystemIn;
use crate::scheme::Scheme;
use crate::Scalar;

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

    /// The Hessian of `scheme`'s generating function in (a, b) at (`base`, 0, `z`), 2n × 2n.
    fn at<Sc: Scheme<Dm>, Dm: Dim>(&self, scheme: &Sc, base: &Dm::Array<f64>, z: &Dm::Array<f64>) -> DMatrix<f64> {
        let n = Dm::of(base).n();
        let compiled = match self {
            Self::Compiled(pair) => {
                let base2: Vec<f64> = base.as_ref().iter().chain(z.as_ref()).copied().collect();
                pair.first_or_mixed(&base2, &vec![0.0; 2 * n], true).and_then(|(_, mixed)| mixed)
            }
            Self::Dual => None,
        };
        // Where a guard of the trace fails (another branch of a comparison), dual numbers answer.
        let hessian = compiled.unwrap_or_else(|| dual_hessian(scheme, base, z).dadb);
        DMatrix::from_fn(2 * n, 2 * n, |i, j| hessian[(i, j)])
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
/// and the scheme's linear maps (the same at every step).
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
        }
    }

    /// d(q', p')/d(q, p) of one (sub-)step of `scheme` from a configuration whose chart base is `q`,
    /// solved by the unknowns `z`: a 2n × 2n matrix, q then p. `None` when the step's Jacobian f_ab
    /// is singular there (the step then has no tangent map).
    pub(crate) fn step<Sc: Scheme<Dm>, Dm: Dim>(
        &self,
        scheme: &Sc,
        q: &Dm::Array<f64>,
        z: &Dm::Vector,
    ) -> Option<DMatrix<f64>> {
        let dim = Dm::of(q);
        let n = dim.n();
        let base = scheme.base(q);
        let h = self.hessian.at(scheme, &base, &dim.array(|i| z[i]));
        // dz = Z (dq, dm): Z = −f_ab⁻¹ [(f_aa + f_ab) B | S].
        let rhs = DMatrix::from_fn(n, 2 * n, |i, j| match j < n {
            true if self.mask[j] => h[(i, j)] + h[(i, n + j)],
            true => 0.0,
            false if i == j - n => self.sign[i],
            false => 0.0,
        });
        let lu = h.view((0, n), (n, n)).into_owned().lu();
        let mut z_map = lu.solve(&rhs)?;
        z_map.neg_mut();
        let mut map = DMatrix::zeros(2 * n, 2 * n);
        // dq' = dq + I dz.
        map.view_mut((0, 0), (n, 2 * n)).copy_from(&(&self.increment * &z_map));
        for i in 0..n {
            map[(i, i)] += 1.0;
        }
        // dm' = (f_ba + f_bb) B dq + f_bb dz where m advances, dm elsewhere.
        let m_rows = h.view((n, n), (n, n)) * &z_map;
        for i in 0..n {
            for j in 0..2 * n {
                map[(n + i, j)] = match self.advances[i] {
                    true if j < n && self.mask[j] => m_rows[(i, j)] + h[(n + i, j)] + h[(n + i, n + j)],
                    true => m_rows[(i, j)],
                    false => f64::from(u8::from(j == n + i)),
                };
            }
        }
        // In (q, p): dm = T dp, dp' = P dm'.
        if let Some(t) = &self.to_momenta {
            let columns = map.columns(n, n) * t;
            map.columns_mut(n, n).copy_from(&columns);
        }
        if let Some(p) = &self.to_p {
            let rows = p * map.rows(n, n);
            map.rows_mut(n, n).copy_from(&rows);
        }
        map.iter().all(|x| x.is_finite()).then_some(map)
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
