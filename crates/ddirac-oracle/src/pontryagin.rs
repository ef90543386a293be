//! Discrete Lagrange–Pontryagin actions, generalized energies and their reduced forms (paper §2.3.3
//! and §5), with gradients by automatic differentiation to check that a trajectory is stationary.
//!
//! ```text
//! S⁺[(q_k, q_k^+, p_{k+1})] = Σ_{k<N} E_{d+}(q_k, q_k^+, q_{k+1}, p_{k+1})    eq:lagrangepontryaginaction
//! E_{d+}(q0, q0^+, q1, p1)  = L_d(q0, q0^+) + ⟨p1, q1 − q0^+⟩                  eq:Ed
//! S⁻[(q_{k+1}^−, p_k, q_{k+1})] = Σ_{k<N} E_{d−}(q_{k+1}^−, q_{k+1}, p_k, q_k)  eq:lagrangepontryaginactionminus
//! E_{d−}(q1^−, q1, p0, q0)  = L_d(q1^−, q1) + ⟨p0, q0 − q1^−⟩                  eq:Edminus
//! e_{d+}(x0, x0^+, g0^+, q1, w1, μ1) = l₊(x0, x0^+, g0^+) + ⟨w1 − h*_{d,Σ}(μ1), x1 − x0^+⟩
//!                                     + ⟨μ1, g1 − g0^+ − h_d((x0, 0), x0^+)⟩   lemma:reducedactionlocal
//! e_{d−}(x1^−, g1^−, x1, w0, μ0, q0) = l₋(x1^−, g1^−, x1) + ⟨w0 − h*_{d,Σ}(μ0), x0 − x1^−⟩
//!                                     + ⟨μ0, g0 − g1^− − h_d((x1, 0), x1^−)⟩   lemma:reducedactionlocalminus
//! ```
//!
//! In e_{d+} the point q1 is taken relative to g0 (quotient eq:localquotientQQQQ*), in e_{d−} the
//! point q0 relative to g1. The reduced actions are Σ e_{d±} along the trivialized curve
//! Λ_{d±}(…) (eq:Lambdadlocal, eq:Lambdadlocalminus); by the reduced variational principle they equal
//! S^± ([`PlusCurve::trivialize`], [`MinusCurve::trivialize`]).
//!
//! *Erratum.* Stationarity of S⁻ as printed gives p_k = D1 L_d(q_{k+1}^−, q_{k+1}) and
//! p_{k+1} = −D2 L_d(q_{k+1}^−, q_{k+1}): the (−) Lagrange–Dirac equations of paper §2.3.2 with the
//! momenta reversed (the same slip as in eq:geometricequationsminus, see
//! [`crate::dirac_structure`]). With ⟨p0, q1^− − q0⟩ instead, stationarity is exactly
//! p_k = −D1 L_d, p_{k+1} = D2 L_d. [`Signs`] selects the printed or the corrected pairing sign in
//! E_{d−}, e_{d−} and S⁻.
//!
//! Gradients are assembled term by term: each term's gradient with respect to its four blocks of N
//! local arguments comes from forward-mode automatic differentiation (the engine's
//! [`ddirac::ad::Gradient`], one pass per block), and is added into the entries of the variables the
//! block stands for. Only the free
//! variables are reported: the interior q_k (q_0 and q_N are fixed), every q_k^+ (or q_{k+1}^−) and
//! every p_{k+1} (or p_k).

use ddirac::reduction::reduced_lagrangian::ReducedLagrangian;
use ddirac::Scalar;
use ddirac::{Connection, DiscreteLagrangian, Error, Input, Split, System};

use crate::dirac_structure::Signs;
use crate::gradient::{block_gradient, Dual};
use crate::reduced_lagrangian::{l_minus, l_plus, pack};
use crate::trivialization::{lambda_d, lambda_hat, lambda_tilde, SplitVector};

/// A curve on the (+) discrete Pontryagin bundle: q_0 … q_N, q_0^+ … q_{N−1}^+, p_1 … p_N.
///
/// After [`PlusCurve::trivialize`], `q_plus[k]` holds (x_k^+, g_k^+) and `p_next[k]` holds
/// (w_{k+1}, μ_{k+1}) at the positions of the shape and group coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct PlusCurve<const N: usize> {
    /// q_k, k = 0 … N.
    pub q: Vec<[f64; N]>,
    /// q_k^+, k = 0 … N − 1.
    pub q_plus: Vec<[f64; N]>,
    /// p_{k+1}, k = 0 … N − 1.
    pub p_next: Vec<[f64; N]>,
}

/// A curve on the (−) discrete Pontryagin bundle: q_0 … q_N, q_1^− … q_N^−, p_0 … p_{N−1}.
///
/// After [`MinusCurve::trivialize`], `q_minus[k]` holds (x_{k+1}^−, g_{k+1}^−) and `p[k]` holds
/// (w_k, μ_k) at the positions of the shape and group coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct MinusCurve<const N: usize> {
    /// q_k, k = 0 … N.
    pub q: Vec<[f64; N]>,
    /// q_{k+1}^−, k = 0 … N − 1.
    pub q_minus: Vec<[f64; N]>,
    /// p_k, k = 0 … N − 1.
    pub p: Vec<[f64; N]>,
}

/// The gradient of an action with respect to its free variables.
#[derive(Debug, Clone, PartialEq)]
pub struct ActionGradient<const N: usize> {
    /// ∂S/∂q_k for the interior k = 1 … N − 1 (entry j is k = j + 1).
    pub q: Vec<[f64; N]>,
    /// ∂S/∂q_k^+ (or ∂S/∂q_{k+1}^−, or with respect to the trivialized (x, g)^±), k = 0 … N − 1.
    pub aux: Vec<[f64; N]>,
    /// ∂S/∂p_{k+1} (or ∂S/∂p_k, or with respect to the trivialized (w, μ)), k = 0 … N − 1.
    pub momenta: Vec<[f64; N]>,
    /// The largest entry of any single term's gradient: the size of what cancels in the sums.
    pub scale: f64,
}

impl<const N: usize> ActionGradient<N> {
    /// The largest entry of the gradient.
    pub fn max_abs(&self) -> f64 {
        self.q.iter().chain(&self.aux).chain(&self.momenta).flatten().fold(0.0f64, |m, v| m.max(v.abs()))
    }
}

impl<const N: usize> PlusCurve<N> {
    /// The curve of a trajectory (q_k, p_k), k = 0 … N: q_k^+ = q_{k+1}, p_{k+1} as given.
    ///
    /// ```
    /// let q = vec![vec![0.0], vec![1.0], vec![3.0]];
    /// let p = vec![vec![1.0], vec![2.0], vec![2.0]];
    /// let curve = ddirac_oracle::pontryagin::PlusCurve::<1>::from_trajectory(&q, &p).unwrap();
    /// assert_eq!((curve.q_plus, curve.p_next), (vec![[1.0], [3.0]], vec![[2.0], [2.0]]));
    /// ```
    pub fn from_trajectory(q: &[Vec<f64>], p: &[Vec<f64>]) -> Result<Self, Error> {
        let (q, p) = trajectory_arrays(q, p)?;
        Ok(Self { q_plus: q[1..].to_vec(), p_next: p[1..].to_vec(), q })
    }

    /// Λ_{d+}(q_k, q_k^+, q_{k+1}, p_{k+1}) = (q_k, x_k^+, g_k^+ − h_d(q_k, x_k^+), q_{k+1},
    /// w_{k+1} + h*_{d,Σ}(r_{k+1}), r_{k+1}) for every k (eq:Lambdadlocal).
    pub fn trivialize(&self, connection: &Connection, split: &Split) -> Result<Self, Error> {
        let steps = self.steps()?;
        let mut out = self.clone();
        for k in 0..steps {
            let qk = SplitVector::from_full(split, &self.q[k])?;
            let pair = lambda_d(connection, &qk, &SplitVector::from_full(split, &self.q_plus[k])?)?;
            let next = SplitVector::from_full(split, &self.q[k + 1])?;
            let covector = lambda_hat(connection, &next, &SplitVector::from_full(split, &self.p_next[k])?)?;
            out.q_plus[k] = array(&split.join(&pair.x1, &pair.g1))?;
            out.p_next[k] = array(&split.join(&covector.w, &covector.mu))?;
        }
        Ok(out)
    }

    fn steps(&self) -> Result<usize, Error> {
        check_curve(self.q.len(), self.q_plus.len(), self.p_next.len())
    }
}

impl<const N: usize> MinusCurve<N> {
    /// The curve of a trajectory (q_k, p_k), k = 0 … N: q_{k+1}^− = q_k, p_k as given (k < N).
    pub fn from_trajectory(q: &[Vec<f64>], p: &[Vec<f64>]) -> Result<Self, Error> {
        let (q, p) = trajectory_arrays(q, p)?;
        let steps = q.len() - 1;
        Ok(Self { q_minus: q[..steps].to_vec(), p: p[..steps].to_vec(), q })
    }

    /// Λ_{d−}(q_{k+1}^−, q_{k+1}, p_k, q_k) = (x_{k+1}^−, g_{k+1}^− − h_d(q_{k+1}, x_{k+1}^−), q_{k+1},
    /// w_k + h*_{d,Σ}(r_k), r_k, q_k) for every k (eq:Lambdadlocalminus).
    pub fn trivialize(&self, connection: &Connection, split: &Split) -> Result<Self, Error> {
        let steps = self.steps()?;
        let mut out = self.clone();
        for k in 0..steps {
            let next = SplitVector::from_full(split, &self.q[k + 1])?;
            let pair = lambda_tilde(connection, &SplitVector::from_full(split, &self.q_minus[k])?, &next)?;
            let qk = SplitVector::from_full(split, &self.q[k])?;
            let covector = lambda_hat(connection, &qk, &SplitVector::from_full(split, &self.p[k])?)?;
            out.q_minus[k] = array(&split.join(&pair.x0, &pair.g0))?;
            out.p[k] = array(&split.join(&covector.w, &covector.mu))?;
        }
        Ok(out)
    }

    fn steps(&self) -> Result<usize, Error> {
        check_curve(self.q.len(), self.q_minus.len(), self.p.len())
    }
}

/// E_{d+}(q0, q0^+, q1, p1) = L_d(q0, q0^+) + ⟨p1, q1 − q0^+⟩ (eq:Ed), generic over the scalar.
///
/// ```
/// use ddirac::{systems::ChargedParticle, DiscreteLagrangian, Rule};
/// use ddirac_oracle::pontryagin::energy_plus;
/// let system = ChargedParticle::default();
/// let ld = DiscreteLagrangian::new(&system, Rule::Left, 0.1);
/// let (q0, q1) = ([0.0; 4], [0.0, 0.0, 0.1, 0.0]);
/// let e: f64 = energy_plus(&ld, &q0, &q1, &[0.0, 0.0, 0.2, 0.0], &[0.0, 0.0, 1.0, 0.0]);
/// assert!((e - (0.05 + 0.1)).abs() < 1e-15);
/// ```
pub fn energy_plus<S, D, const N: usize>(
    ld: &DiscreteLagrangian<S>,
    q0: &[D; N],
    q0_plus: &[D; N],
    q1: &[D; N],
    p1: &[D; N],
) -> D
where
    S: System<N>,
    D: Scalar,
{
    ld.eval(q0, q0_plus) + pairing(p1, q1, q0_plus)
}

/// E_{d−}(q1^−, q1, p0, q0) = L_d(q1^−, q1) + s ⟨p0, q0 − q1^−⟩ (eq:Edminus), s = +1 as printed,
/// −1 corrected; generic over the scalar.
pub fn energy_minus<S, D, const N: usize>(
    ld: &DiscreteLagrangian<S>,
    q1_minus: &[D; N],
    q1: &[D; N],
    p0: &[D; N],
    q0: &[D; N],
    signs: Signs,
) -> D
where
    S: System<N>,
    D: Scalar,
{
    ld.eval(q1_minus, q1) + pairing(p0, q0, q1_minus) * signs.factor()
}

/// e_{d+}(x0, x0^+, g0^+, q1, w1, μ1) (lemma:reducedactionlocal), with `plus` = (x0^+, g0^+) and
/// q1 = (x1, g1) relative to g0; generic over the scalar.
pub fn reduced_energy_plus<S, D, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    x0: &[D],
    plus: (&[D], &[D]),
    q1: (&[D], &[D]),
    w1: &[D],
    mu1: &[D],
) -> Result<D, Error>
where
    S: System<N>,
    D: Scalar,
{
    let (n_x, n_g) = (reduction.split.n_x(), reduction.split.n_g());
    check_lengths(&[(x0.len(), n_x), (plus.0.len(), n_x), (plus.1.len(), n_g), (q1.0.len(), n_x)])?;
    check_lengths(&[(q1.1.len(), n_g), (w1.len(), n_x), (mu1.len(), n_g)])?;
    let zero = D::from(0.0);
    let pack = |x: &[D], g: &[D]| pack::<S, D, N>(reduction, x, g, zero);
    e_plus(reduction, &pack(x0, &[]), &pack(plus.0, plus.1), &pack(q1.0, q1.1), &pack(w1, mu1))
}

/// e_{d−}(x1^−, g1^−, x1, w0, μ0, q0) (lemma:reducedactionlocalminus) with the pairing terms
/// multiplied by s = +1 as printed, −1 corrected, `minus` = (x1^−, g1^−) and q0 = (x0, g0) relative
/// to g1; generic over the scalar.
#[allow(clippy::too_many_arguments)]
pub fn reduced_energy_minus<S, D, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    minus: (&[D], &[D]),
    x1: &[D],
    w0: &[D],
    mu0: &[D],
    q0: (&[D], &[D]),
    signs: Signs,
) -> Result<D, Error>
where
    S: System<N>,
    D: Scalar,
{
    let (n_x, n_g) = (reduction.split.n_x(), reduction.split.n_g());
    check_lengths(&[(minus.0.len(), n_x), (minus.1.len(), n_g), (x1.len(), n_x), (w0.len(), n_x)])?;
    check_lengths(&[(mu0.len(), n_g), (q0.0.len(), n_x), (q0.1.len(), n_g)])?;
    let zero = D::from(0.0);
    let pack = |x: &[D], g: &[D]| pack::<S, D, N>(reduction, x, g, zero);
    e_minus(reduction, &pack(minus.0, minus.1), &pack(x1, &[]), &pack(w0, mu0), &pack(q0.0, q0.1), signs)
}

/// S⁺ along a curve (eq:lagrangepontryaginaction).
pub fn action_plus<S: System<N>, const N: usize>(
    ld: &DiscreteLagrangian<S>,
    curve: &PlusCurve<N>,
) -> Result<f64, Error> {
    let steps = curve.steps()?;
    Ok((0..steps).map(|k| energy_plus(ld, &curve.q[k], &curve.q_plus[k], &curve.q[k + 1], &curve.p_next[k])).sum())
}

/// S⁻ along a curve (eq:lagrangepontryaginactionminus), with the pairing sign chosen by `signs`.
pub fn action_minus<S: System<N>, const N: usize>(
    ld: &DiscreteLagrangian<S>,
    curve: &MinusCurve<N>,
    signs: Signs,
) -> Result<f64, Error> {
    let steps = curve.steps()?;
    Ok((0..steps).map(|k| energy_minus(ld, &curve.q_minus[k], &curve.q[k + 1], &curve.p[k], &curve.q[k], signs)).sum())
}

/// Σ_k e_{d+} along a trivialized curve (eq:reducedlagrangepontryaginprinciple).
pub fn reduced_action_plus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    curve: &PlusCurve<N>,
) -> Result<f64, Error> {
    let steps = curve.steps()?;
    (0..steps).map(|k| e_plus(reduction, &curve.q[k], &curve.q_plus[k], &curve.q[k + 1], &curve.p_next[k])).sum()
}

/// Σ_k e_{d−} along a trivialized curve (eq:reducedlagrangepontryaginprincipleminus).
pub fn reduced_action_minus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    curve: &MinusCurve<N>,
    signs: Signs,
) -> Result<f64, Error> {
    let steps = curve.steps()?;
    (0..steps).map(|k| e_minus(reduction, &curve.q_minus[k], &curve.q[k + 1], &curve.p[k], &curve.q[k], signs)).sum()
}

/// The gradient of S⁺ with respect to the interior q_k, every q_k^+ and every p_{k+1}.
pub fn action_plus_gradient<S: System<N>, const N: usize>(
    ld: &DiscreteLagrangian<S>,
    curve: &PlusCurve<N>,
) -> Result<ActionGradient<N>, Error> {
    let steps = curve.steps()?;
    let slots = |k| [Slot::Q(k), Slot::Aux(k), Slot::Q(k + 1), Slot::Momenta(k)];
    assemble(steps, (&curve.q, &curve.q_plus, &curve.p_next), slots, |[a, b, c, d]| Ok(energy_plus(ld, a, b, c, d)))
}

/// The gradient of S⁻ with respect to the interior q_k, every q_{k+1}^− and every p_k.
pub fn action_minus_gradient<S: System<N>, const N: usize>(
    ld: &DiscreteLagrangian<S>,
    curve: &MinusCurve<N>,
    signs: Signs,
) -> Result<ActionGradient<N>, Error> {
    let steps = curve.steps()?;
    let slots = |k| [Slot::Aux(k), Slot::Q(k + 1), Slot::Momenta(k), Slot::Q(k)];
    assemble(steps, (&curve.q, &curve.q_minus, &curve.p), slots, |[a, b, c, d]| Ok(energy_minus(ld, a, b, c, d, signs)))
}

/// The gradient of Σ e_{d+} along a trivialized curve with respect to the interior q̂_k = (x_k, g_k),
/// every (x_k^+, g_k^+) and every (w_{k+1}, μ_{k+1}).
pub fn reduced_action_plus_gradient<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    curve: &PlusCurve<N>,
) -> Result<ActionGradient<N>, Error> {
    let steps = curve.steps()?;
    let slots = |k| [Slot::Q(k), Slot::Aux(k), Slot::Q(k + 1), Slot::Momenta(k)];
    assemble(steps, (&curve.q, &curve.q_plus, &curve.p_next), slots, |[a, b, c, d]| e_plus(reduction, a, b, c, d))
}

/// The gradient of Σ e_{d−} along a trivialized curve with respect to the interior q̂_k, every
/// (x_{k+1}^−, g_{k+1}^−) and every (w_k, μ_k).
pub fn reduced_action_minus_gradient<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    curve: &MinusCurve<N>,
    signs: Signs,
) -> Result<ActionGradient<N>, Error> {
    let steps = curve.steps()?;
    let slots = |k| [Slot::Aux(k), Slot::Q(k + 1), Slot::Momenta(k), Slot::Q(k)];
    assemble(steps, (&curve.q, &curve.q_minus, &curve.p), slots, |[a, b, c, d]| e_minus(reduction, a, b, c, d, signs))
}

/// The three families of variables of a curve: q_k, the auxiliary points and the momenta.
type Families<'a, const N: usize> = (&'a [[f64; N]], &'a [[f64; N]], &'a [[f64; N]]);

/// Which variable a block of a term stands for.
#[derive(Clone, Copy)]
enum Slot {
    Q(usize),
    Aux(usize),
    Momenta(usize),
}

fn assemble<const N: usize>(
    steps: usize,
    (q, aux, momenta): Families<'_, N>,
    slots: impl Fn(usize) -> [Slot; 4],
    term: impl Fn(&[[Dual<N>; N]; 4]) -> Result<Dual<N>, Error>,
) -> Result<ActionGradient<N>, Error> {
    let mut grad_q = vec![[0.0; N]; steps + 1];
    let mut grad_aux = vec![[0.0; N]; steps];
    let mut grad_momenta = vec![[0.0; N]; steps];
    let mut scale = 0.0f64;
    for k in 0..steps {
        let slots = slots(k);
        let blocks = slots.map(|slot| match slot {
            Slot::Q(i) => q[i],
            Slot::Aux(i) => aux[i],
            Slot::Momenta(i) => momenta[i],
        });
        let (_, gradient) = block_gradient(&blocks, &term)?;
        for (slot, g) in slots.iter().zip(&gradient) {
            let target = match *slot {
                Slot::Q(i) => &mut grad_q[i],
                Slot::Aux(i) => &mut grad_aux[i],
                Slot::Momenta(i) => &mut grad_momenta[i],
            };
            for (t, v) in target.iter_mut().zip(g) {
                *t += v;
                scale = scale.max(v.abs());
            }
        }
    }
    let interior = if steps >= 1 { grad_q[1..steps].to_vec() } else { Vec::new() };
    Ok(ActionGradient { q: interior, aux: grad_aux, momenta: grad_momenta, scale })
}

/// e_{d+} on packed blocks: q0 = (x0, g0), plus = (x0^+, g0^+), q1 = (x1, g1) (absolute; made relative
/// to g0 here) and wm1 = (w1, μ1).
fn e_plus<S, D, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    q0: &[D; N],
    plus: &[D; N],
    q1: &[D; N],
    wm1: &[D; N],
) -> Result<D, Error>
where
    S: System<N>,
    D: Scalar,
{
    let x0 = shape_only(reduction, q0);
    let mut total = l_plus(reduction, &x0_gamma(reduction, &x0, plus), plus)?;
    for (i, &si) in reduction.split.shape.iter().enumerate() {
        let kt_mu = kt_times(reduction, i, wm1);
        total += (wm1[si] - kt_mu) * (q1[si] - plus[si]);
    }
    for (j, &gj) in reduction.split.group.iter().enumerate() {
        let h = k_times(reduction, j, plus, &x0);
        total += wm1[gj] * (q1[gj] - q0[gj] - plus[gj] - h);
    }
    Ok(total)
}

/// e_{d−} on packed blocks: minus = (x1^−, g1^−), q1 = (x1, g1), wm0 = (w0, μ0) and q0 = (x0, g0)
/// (absolute; made relative to g1 here).
fn e_minus<S, D, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    minus: &[D; N],
    q1: &[D; N],
    wm0: &[D; N],
    q0: &[D; N],
    signs: Signs,
) -> Result<D, Error>
where
    S: System<N>,
    D: Scalar,
{
    let x1 = shape_only(reduction, q1);
    let l = l_minus(reduction, minus, &x1)?;
    let mut pairings = D::from(0.0);
    for (i, &si) in reduction.split.shape.iter().enumerate() {
        let kt_mu = kt_times(reduction, i, wm0);
        pairings += (wm0[si] - kt_mu) * (q0[si] - minus[si]);
    }
    for (j, &gj) in reduction.split.group.iter().enumerate() {
        let h = k_times(reduction, j, minus, &x1);
        pairings += wm0[gj] * (q0[gj] - q1[gj] - minus[gj] - h);
    }
    Ok(l + pairings * signs.factor())
}

/// (K (u − v))_j with u, v at the shape positions of packed blocks: h_d((v, 0), u)_j.
fn k_times<S, D: Scalar, const N: usize>(reduction: &ReducedLagrangian<S>, j: usize, u: &[D; N], v: &[D; N]) -> D {
    reduction
        .split
        .shape
        .iter()
        .enumerate()
        .fold(D::from(0.0), |acc, (i, &si)| acc + (u[si] - v[si]) * reduction.connection.entry(j, i))
}

/// (Kᵀ μ)_i with μ at the group positions of a packed block.
fn kt_times<S, D: Scalar, const N: usize>(reduction: &ReducedLagrangian<S>, i: usize, packed: &[D; N]) -> D {
    reduction
        .split
        .group
        .iter()
        .enumerate()
        .fold(D::from(0.0), |acc, (j, &gj)| acc + packed[gj] * reduction.connection.entry(j, i))
}

/// The shape entries of a packed block, with zeros at the group positions.
fn shape_only<S, D: Scalar, const N: usize>(reduction: &ReducedLagrangian<S>, packed: &[D; N]) -> [D; N] {
    let mut out = [D::from(0.0); N];
    reduction.split.shape.iter().for_each(|&si| out[si] = packed[si]);
    out
}

/// (x0 at the shape positions, γ = g^+ at the group positions).
fn x0_gamma<S, D: Copy, const N: usize>(reduction: &ReducedLagrangian<S>, x0: &[D; N], plus: &[D; N]) -> [D; N] {
    let mut out = *x0;
    reduction.split.group.iter().for_each(|&gj| out[gj] = plus[gj]);
    out
}

/// ⟨p, a − b⟩.
fn pairing<D: Scalar, const N: usize>(p: &[D; N], a: &[D; N], b: &[D; N]) -> D {
    (0..N).fold(D::from(0.0), |acc, i| acc + p[i] * (a[i] - b[i]))
}

fn check_curve(q: usize, aux: usize, momenta: usize) -> Result<usize, Error> {
    if q < 2 {
        return Err(Error::Size {
            what: Input::Argument("curve configurations q_0 … q_N (N ≥ 1)".into()),
            expected: 2,
            found: q,
        });
    }
    for (what, found) in [("auxiliary points", aux), ("momenta", momenta)] {
        if found != q - 1 {
            return Err(Error::Size { what: Input::Argument(format!("curve {what}")), expected: q - 1, found });
        }
    }
    Ok(q - 1)
}

fn check_lengths(items: &[(usize, usize)]) -> Result<(), Error> {
    match items.iter().find(|(found, expected)| found != expected) {
        Some(&(found, expected)) => {
            Err(Error::Size { what: Input::Argument("argument of e_d".into()), expected, found })
        }
        None => Ok(()),
    }
}

fn array<const N: usize>(v: &[f64]) -> Result<[f64; N], Error> {
    v.try_into().map_err(|_| Error::Size { what: Input::Argument("vector".into()), expected: N, found: v.len() })
}

type Points<const N: usize> = Vec<[f64; N]>;

fn trajectory_arrays<const N: usize>(q: &[Vec<f64>], p: &[Vec<f64>]) -> Result<(Points<N>, Points<N>), Error> {
    if p.len() != q.len() {
        return Err(Error::Size {
            what: Input::Argument("momenta of the trajectory".into()),
            expected: q.len(),
            found: p.len(),
        });
    }
    check_curve(q.len(), q.len().saturating_sub(1), q.len().saturating_sub(1))?;
    let q = q.iter().map(|v| array(v)).collect::<Result<Vec<_>, _>>()?;
    let p = p.iter().map(|v| array(v)).collect::<Result<Vec<_>, _>>()?;
    Ok((q, p))
}
