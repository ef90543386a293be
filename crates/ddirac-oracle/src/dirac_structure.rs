//! Reduced discrete Dirac structures and reduced discrete Dirac differentials in a trivialization
//! Q = Σ × G (paper §3.4 and §4.1–4.4), for a linear connection K = h_{d,Σ}.
//!
//! **Reduced Dirac structures** (lemmas before `prop:reduceddiractructurelocal` and
//! `prop:reduceddiractructurelocalminus`), with q1 taken relative to g0 in (+) and q0 relative to g1
//! in (−):
//!
//! ```text
//! [Ω̂♭_{d+}](x0, w0, μ0, q1, w1, μ1) = (x0, w1, μ1, (w0 − h*_{d,Σ}(μ0), μ0), x1, g1 − h_{d,Σ}(x1))
//! [Ω̂♭_{d−}](q0, w0, μ0, x1, w1, μ1) = (w0, μ0, x1, −x0, −g0 + h_{d,Σ}(x0), (−w1 + h*_{d,Σ}(μ1), −μ1))
//! ```
//!
//! **Reduced Dirac differentials** (`prop:reduceddiracdifferentiallocal`, `…minus`):
//!
//! ```text
//! [D̂⁺L_d](x0, x1, g1) = (x0, ∂L_d/∂x1 + h*_{d,Σ}(∂L_d/∂g1), ∂L_d/∂g1, −∂L_d/∂q0, x1, g1 + h_{d,Q}(x0, 0))
//!                       at (x0, 0, x1, g1 + h_d^0(x0, x1))
//! [D̂⁻L_d](x0, g0, x1) = (−∂L_d/∂x0 − h*_{d,Σ}(∂L_d/∂g0), −∂L_d/∂g0, x1, −x0, −g0 − h_{d,Q}(x1, 0), −∂L_d/∂q1)
//!                       at (x0, g0 + h_d^0(x1, x0), x1, 0)
//! ```
//!
//! A reduced step X satisfies the reduced Lagrange–Poincaré–Dirac equations when
//! \[Ω̂♭_{d±}\](X) = \[D̂^±L_d\](…) ([`dirac_residual_plus`], `…_minus`).
//!
//! Lemmas `lemma:partialderivativesld` / `…minus` express D1 L_d, D2 L_d through the partials of the
//! reduced Lagrangians l± ([`ReducedLagrangian::lagrangian_plus`], `…_minus`), differentiated in
//! [`crate::reduced_lagrangian`].
//!
//! **General form** of the reduced equations, with the maps h_d^0, h_{d,Q}, h_{d,Σ}, h*_{d,Σ} exactly
//! as printed: eq:geometricequations ([`general_form_plus`]) and
//! eq:geometricequationsminus ([`general_form_minus`]).
//!
//! *Erratum.* Derived from [Ω̂♭_{d−}] and [D̂⁻L_d] above with `lemma:partialderivativesldminus`, the
//! (−) equations read
//!
//! ```text
//! w_k = −∂l₋/∂x0,  μ_k = −∂l₋/∂γ,  w_{k+1} = ∂l₋/∂x1,  μ_{k+1} = μ_k,  g_{k+1} = g_k − γ_k + K(x_{k+1} − x_k)
//! ```
//!
//! whereas the printed eq:geometricequationsminus carries the opposite sign on every momentum term
//! w_k, μ_k, w_{k+1}, μ_{k+1}: it describes the motion with reversed momenta. [`Signs`] selects the
//! printed or the corrected display; trajectories of the integrators satisfy the corrected one.

use ddirac::reduction::reduced_lagrangian::ReducedLagrangian;
use ddirac::{Connection, Error, System};

use crate::reduced_lagrangian::{ld_partials, partials_minus, partials_plus};
use crate::trivialization::{add, expect_len, h_sigma_star, pullback, sub, SplitVector};

/// Which signs to use for the (−) equations and actions: the paper's as printed, or corrected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Signs {
    /// The signs printed in the paper (eq:geometricequationsminus, eq:lagrangepontryaginactionminus).
    AsPrinted,
    /// Every momentum term with its sign flipped, consistent with the (−) Dirac structure.
    Corrected,
}

impl Signs {
    /// +1 as printed, −1 corrected: the factor of the momentum terms.
    pub fn factor(self) -> f64 {
        match self {
            Signs::AsPrinted => 1.0,
            Signs::Corrected => -1.0,
        }
    }
}

/// A reduced (+) step [X̂_{d+}^k] = (x_k, w_k, μ_k, q_{k+1}, w_{k+1}, μ_{k+1}) with q_{k+1} relative to
/// g_k, i.e. (x_{k+1}, g_{k+1} − g_k): an element of Σ × (Σ* × 𝔤*) × Q × (Σ* × 𝔤*).
#[derive(Debug, Clone, PartialEq)]
pub struct ReducedStepPlus {
    /// x_k.
    pub x0: Vec<f64>,
    /// w_k.
    pub w0: Vec<f64>,
    /// μ_k.
    pub mu0: Vec<f64>,
    /// q_{k+1} relative to g_k.
    pub q1: SplitVector,
    /// w_{k+1}.
    pub w1: Vec<f64>,
    /// μ_{k+1}.
    pub mu1: Vec<f64>,
}

/// An element (x0, w1, μ1, p, x1, ξ) of Σ × (Σ* × 𝔤*) × Q* × (Σ × 𝔤), the target of [Ω̂♭_{d+}] and
/// [D̂⁺L_d].
#[derive(Debug, Clone, PartialEq)]
pub struct ReducedCovectorPlus {
    /// Base point in Σ.
    pub x0: Vec<f64>,
    /// Σ* component of the base point.
    pub w1: Vec<f64>,
    /// 𝔤* component of the base point.
    pub mu1: Vec<f64>,
    /// Q* component of the covector.
    pub p: SplitVector,
    /// Σ component of the covector.
    pub x1: Vec<f64>,
    /// 𝔤 component of the covector.
    pub xi: Vec<f64>,
}

/// A reduced (−) step [X̂_{d−}^k] = (q_k, w_k, μ_k, x_{k+1}, w_{k+1}, μ_{k+1}) with q_k relative to
/// g_{k+1}, i.e. (x_k, g_k − g_{k+1}): an element of Q × (Σ* × 𝔤*) × Σ × (Σ* × 𝔤*).
#[derive(Debug, Clone, PartialEq)]
pub struct ReducedStepMinus {
    /// q_k relative to g_{k+1}.
    pub q0: SplitVector,
    /// w_k.
    pub w0: Vec<f64>,
    /// μ_k.
    pub mu0: Vec<f64>,
    /// x_{k+1}.
    pub x1: Vec<f64>,
    /// w_{k+1}.
    pub w1: Vec<f64>,
    /// μ_{k+1}.
    pub mu1: Vec<f64>,
}

/// An element (w0, μ0, x1, x, ξ, p) of (Σ* × 𝔤*) × Σ × (Σ × 𝔤) × Q*, the target of [Ω̂♭_{d−}] and
/// [D̂⁻L_d].
#[derive(Debug, Clone, PartialEq)]
pub struct ReducedCovectorMinus {
    /// Σ* component of the base point.
    pub w0: Vec<f64>,
    /// 𝔤* component of the base point.
    pub mu0: Vec<f64>,
    /// Base point in Σ.
    pub x1: Vec<f64>,
    /// Σ component of the covector (−x0 in the paper's formulas).
    pub x: Vec<f64>,
    /// 𝔤 component of the covector.
    pub xi: Vec<f64>,
    /// Q* component of the covector.
    pub p: SplitVector,
}

impl ReducedCovectorPlus {
    /// All entries, in the order (x0, w1, μ1, p_x, p_g, x1, ξ).
    pub fn components(&self) -> Vec<f64> {
        [&self.x0, &self.w1, &self.mu1, &self.p.x, &self.p.g, &self.x1, &self.xi]
            .into_iter()
            .flatten()
            .copied()
            .collect()
    }
}

impl ReducedCovectorMinus {
    /// All entries, in the order (w0, μ0, x1, x, ξ, p_x, p_g).
    pub fn components(&self) -> Vec<f64> {
        [&self.w0, &self.mu0, &self.x1, &self.x, &self.xi, &self.p.x, &self.p.g]
            .into_iter()
            .flatten()
            .copied()
            .collect()
    }
}

/// [Ω̂♭_{d+}](x0, w0, μ0, q1, w1, μ1) = (x0, w1, μ1, (w0 − h*_{d,Σ}(μ0), μ0), x1, g1 − h_{d,Σ}(x1)).
///
/// ```
/// use ddirac_oracle::{dirac_structure::{omega_flat_plus, ReducedStepPlus}, trivialization::SplitVector};
/// let k = ddirac::Connection::new(&[vec![2.0]]).unwrap();
/// let step = ReducedStepPlus { x0: vec![1.0], w0: vec![5.0], mu0: vec![1.0],
///     q1: SplitVector::new(vec![3.0], vec![7.0]), w1: vec![0.0], mu1: vec![1.0] };
/// let image = omega_flat_plus(&k, &step).unwrap();
/// assert_eq!((image.p.x, image.xi), (vec![3.0], vec![1.0])); // 5 − 2·1, 7 − 2·3
/// ```
pub fn omega_flat_plus(connection: &Connection, step: &ReducedStepPlus) -> Result<ReducedCovectorPlus, Error> {
    check_step_plus(connection, step)?;
    Ok(ReducedCovectorPlus {
        x0: step.x0.clone(),
        w1: step.w1.clone(),
        mu1: step.mu1.clone(),
        p: SplitVector::new(sub(&step.w0, &h_sigma_star(connection, &step.mu0)), step.mu0.clone()),
        x1: step.q1.x.clone(),
        xi: sub(&step.q1.g, &connection.h_dsigma(&step.q1.x)),
    })
}

/// [Ω̂♭_{d−}](q0, w0, μ0, x1, w1, μ1) = (w0, μ0, x1, −x0, −g0 + h_{d,Σ}(x0), (−w1 + h*_{d,Σ}(μ1), −μ1)).
pub fn omega_flat_minus(connection: &Connection, step: &ReducedStepMinus) -> Result<ReducedCovectorMinus, Error> {
    check_step_minus(connection, step)?;
    Ok(ReducedCovectorMinus {
        w0: step.w0.clone(),
        mu0: step.mu0.clone(),
        x1: step.x1.clone(),
        x: neg(&step.q0.x),
        xi: sub(&connection.h_dsigma(&step.q0.x), &step.q0.g),
        p: SplitVector::new(sub(&h_sigma_star(connection, &step.mu1), &step.w1), neg(&step.mu1)),
    })
}

/// The residuals (left side − right side) of the six lines of eq:geometricequations or
/// eq:geometricequationsminus, in the paper's order.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneralForm {
    /// Line i of the display holds in `lines[i]`.
    pub lines: [Vec<f64>; 6],
}

impl GeneralForm {
    /// The largest residual over all lines.
    pub fn max_abs(&self) -> f64 {
        self.lines.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()))
    }
}

/// (D1 L_d, D2 L_d) at (x0, 0, x1, g1 + h_d^0(x0, x1)) from the partials of l₊ at (x0, x1, g1), as
/// printed in `lemma:partialderivativesld`.
pub fn ld_partials_from_plus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    x0: &[f64],
    x1: &[f64],
    g1: &[f64],
) -> Result<(SplitVector, SplitVector), Error> {
    let l = partials_plus(reduction, x0, x1, g1)?;
    let d1 = SplitVector::new(sub(&l.x0, &pair_h0_first(reduction, &l.gamma)), neg(&pair_h_group(reduction, &l.gamma)));
    let d2 = SplitVector::new(sub(&l.x1, &pair_h0_second(reduction, &l.gamma)), l.gamma.clone());
    Ok((d1, d2))
}

/// (D1 L_d, D2 L_d) at (x0, g0 + h_d^0(x1, x0), x1, 0) from the partials of l₋ at (x0, g0, x1), as
/// printed in `lemma:partialderivativesldminus`.
pub fn ld_partials_from_minus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    x0: &[f64],
    g0: &[f64],
    x1: &[f64],
) -> Result<(SplitVector, SplitVector), Error> {
    let l = partials_minus(reduction, x0, g0, x1)?;
    let d1 = SplitVector::new(sub(&l.x0, &pair_h0_second(reduction, &l.gamma)), l.gamma.clone());
    let d2 = SplitVector::new(sub(&l.x1, &pair_h0_first(reduction, &l.gamma)), neg(&pair_h_group(reduction, &l.gamma)));
    Ok((d1, d2))
}

/// [D̂⁺L_d](x0, x1, g1) (`prop:reduceddiracdifferentiallocal`).
pub fn dirac_differential_plus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    x0: &[f64],
    x1: &[f64],
    g1: &[f64],
) -> Result<ReducedCovectorPlus, Error> {
    let k = &reduction.connection;
    check_sizes(k, &[("x0", x0, true), ("x1", x1, true), ("g1", g1, false)])?;
    let zero_g = vec![0.0; k.n_g()];
    let q0 = SplitVector::new(x0.to_vec(), zero_g.clone());
    let q1 = SplitVector::new(x1.to_vec(), add(g1, &k.h_d0(x0, x1)));
    let (d1, d2) = ld_partials(reduction, &q0, &q1)?;
    Ok(ReducedCovectorPlus {
        x0: x0.to_vec(),
        w1: add(&d2.x, &h_sigma_star(k, &d2.g)),
        mu1: d2.g,
        p: SplitVector::new(neg(&d1.x), neg(&d1.g)),
        x1: x1.to_vec(),
        xi: add(g1, &k.h_dq((x0, &zero_g))),
    })
}

/// [D̂⁻L_d](x0, g0, x1) (`prop:reduceddiracdifferentiallocalminus`).
pub fn dirac_differential_minus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    x0: &[f64],
    g0: &[f64],
    x1: &[f64],
) -> Result<ReducedCovectorMinus, Error> {
    let k = &reduction.connection;
    check_sizes(k, &[("x0", x0, true), ("x1", x1, true), ("g0", g0, false)])?;
    let zero_g = vec![0.0; k.n_g()];
    let q0 = SplitVector::new(x0.to_vec(), add(g0, &k.h_d0(x1, x0)));
    let q1 = SplitVector::new(x1.to_vec(), zero_g.clone());
    let (d1, d2) = ld_partials(reduction, &q0, &q1)?;
    Ok(ReducedCovectorMinus {
        w0: neg(&add(&d1.x, &h_sigma_star(k, &d1.g))),
        mu0: neg(&d1.g),
        x1: x1.to_vec(),
        x: neg(x0),
        xi: neg(&add(g0, &k.h_dq((x1, &zero_g)))),
        p: SplitVector::new(neg(&d2.x), neg(&d2.g)),
    })
}

/// max |\[Ω̂♭_{d+}\](X) − \[D̂⁺L_d\](x_k, x_k^+, g_k^+)| over all components: zero when
/// (X, [D̂⁺L_d](x_k, x_k^+, g_k^+)) ∈ [D̂^{d+}].
pub fn dirac_residual_plus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    step: &ReducedStepPlus,
    x_plus: &[f64],
    g_plus: &[f64],
) -> Result<f64, Error> {
    let lhs = omega_flat_plus(&reduction.connection, step)?.components();
    let rhs = dirac_differential_plus(reduction, &step.x0, x_plus, g_plus)?.components();
    Ok(lhs.iter().zip(&rhs).fold(0.0f64, |m, (a, b)| m.max((a - b).abs())))
}

/// max |\[Ω̂♭_{d−}\](X) − \[D̂⁻L_d\](x_{k+1}^−, g_{k+1}^−, x_{k+1})| over all components: zero when
/// (X, [D̂⁻L_d](x_{k+1}^−, g_{k+1}^−, x_{k+1})) ∈ [D̂^{d−}].
pub fn dirac_residual_minus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    step: &ReducedStepMinus,
    x_minus: &[f64],
    g_minus: &[f64],
) -> Result<f64, Error> {
    let lhs = omega_flat_minus(&reduction.connection, step)?.components();
    let rhs = dirac_differential_minus(reduction, x_minus, g_minus, &step.x1)?.components();
    Ok(lhs.iter().zip(&rhs).fold(0.0f64, |m, (a, b)| m.max((a - b).abs())))
}

/// The residuals of eq:geometricequations for the step X = (x_k, w_k, μ_k, q_{k+1}, w_{k+1}, μ_{k+1})
/// and the Dirac-differential arguments (x_k^+, g_k^+), partials of l₊ at (x_k, x_k^+, g_k^+):
///
/// ```text
/// ∂l₊/∂x1 − ⟨∂l₊/∂g1, h_d^0(0, ·)⟩ + h*_{d,Σ}(∂l₊/∂g1) = w_{k+1}
/// ∂l₊/∂g1 = μ_{k+1}
/// −∂l₊/∂x0 + ⟨∂l₊/∂g1, h_d^0(·, 0)⟩ = w_k − h*_{d,Σ}(μ_k)
/// ⟨∂l₊/∂g1, h_d((0, ·), 0)⟩ = μ_k
/// x_k^+ = x_{k+1}
/// g_k^+ + h_{d,Q}(x_k, 0) = g_{k+1} − h_{d,Σ}(x_{k+1})
/// ```
pub fn general_form_plus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    step: &ReducedStepPlus,
    x_plus: &[f64],
    g_plus: &[f64],
) -> Result<GeneralForm, Error> {
    check_step_plus(&reduction.connection, step)?;
    let k = &reduction.connection;
    let l = partials_plus(reduction, &step.x0, x_plus, g_plus)?;
    let dg = &l.gamma;
    let line1 = add(&sub(&l.x1, &pair_h0_second(reduction, dg)), &h_sigma_star(k, dg));
    let line3 = add(&neg(&l.x0), &pair_h0_first(reduction, dg));
    let rhs6 = sub(&step.q1.g, &k.h_dsigma(&step.q1.x));
    Ok(GeneralForm {
        lines: [
            sub(&line1, &step.w1),
            sub(dg, &step.mu1),
            sub(&line3, &sub(&step.w0, &h_sigma_star(k, &step.mu0))),
            sub(&pair_h_group(reduction, dg), &step.mu0),
            sub(x_plus, &step.q1.x),
            sub(&add(g_plus, &k.h_dq((&step.x0, &vec![0.0; k.n_g()]))), &rhs6),
        ],
    })
}

/// The residuals of eq:geometricequationsminus for X = (q_k, w_k, μ_k, x_{k+1}, w_{k+1}, μ_{k+1})
/// and the Dirac-differential arguments (x_{k+1}^−, g_{k+1}^−), partials of l₋ at
/// (x_{k+1}^−, g_{k+1}^−, x_{k+1}); s = +1 [`Signs::AsPrinted`], −1 [`Signs::Corrected`]:
///
/// ```text
/// ∂l₋/∂x0 − ⟨∂l₋/∂g0, h_d^0(0, ·)⟩ + h*_{d,Σ}(∂l₋/∂g0) = s w_k
/// ∂l₋/∂g0 = s μ_k
/// −∂l₋/∂x1 + ⟨∂l₋/∂g0, h_d^0(·, 0)⟩ = s (w_{k+1} − h*_{d,Σ}(μ_{k+1}))
/// ⟨∂l₋/∂g0, h_d((0, ·), 0)⟩ = s μ_{k+1}
/// x_{k+1}^− = x_k
/// g_{k+1}^− + h_{d,Q}(x_{k+1}, 0) = g_k − h_{d,Σ}(x_k)
/// ```
pub fn general_form_minus<S: System<N>, const N: usize>(
    reduction: &ReducedLagrangian<S>,
    step: &ReducedStepMinus,
    x_minus: &[f64],
    g_minus: &[f64],
    signs: Signs,
) -> Result<GeneralForm, Error> {
    check_step_minus(&reduction.connection, step)?;
    let (k, s) = (&reduction.connection, signs.factor());
    let scaled = |v: &[f64]| v.iter().map(|a| s * a).collect::<Vec<f64>>();
    let l = partials_minus(reduction, x_minus, g_minus, &step.x1)?;
    let dg = &l.gamma;
    let line1 = add(&sub(&l.x0, &pair_h0_second(reduction, dg)), &h_sigma_star(k, dg));
    let line3 = add(&neg(&l.x1), &pair_h0_first(reduction, dg));
    let rhs6 = sub(&step.q0.g, &k.h_dsigma(&step.q0.x));
    Ok(GeneralForm {
        lines: [
            sub(&line1, &scaled(&step.w0)),
            sub(dg, &scaled(&step.mu0)),
            sub(&line3, &scaled(&sub(&step.w1, &h_sigma_star(k, &step.mu1)))),
            sub(&pair_h_group(reduction, dg), &scaled(&step.mu1)),
            sub(x_minus, &step.q0.x),
            sub(&add(g_minus, &k.h_dq((&step.x1, &vec![0.0; k.n_g()]))), &rhs6),
        ],
    })
}

/// ⟨μ, h_d^0(·, 0)⟩ ∈ Σ*.
fn pair_h0_first<S>(reduction: &ReducedLagrangian<S>, mu: &[f64]) -> Vec<f64> {
    let zero = vec![0.0; reduction.split.n_x()];
    pullback(mu, reduction.split.n_x(), |x| reduction.connection.h_d0(x, &zero))
}

/// ⟨μ, h_d^0(0, ·)⟩ ∈ Σ*.
fn pair_h0_second<S>(reduction: &ReducedLagrangian<S>, mu: &[f64]) -> Vec<f64> {
    let zero = vec![0.0; reduction.split.n_x()];
    pullback(mu, reduction.split.n_x(), |x| reduction.connection.h_d0(&zero, x))
}

/// ⟨μ, h_d((0, ·), 0)⟩ ∈ 𝔤*.
fn pair_h_group<S>(reduction: &ReducedLagrangian<S>, mu: &[f64]) -> Vec<f64> {
    let zero = vec![0.0; reduction.split.n_x()];
    pullback(mu, reduction.split.n_g(), |g| reduction.connection.h_d((&zero, g), &zero))
}

fn check_step_plus(connection: &Connection, step: &ReducedStepPlus) -> Result<(), Error> {
    let (n_x, n_g) = (connection.n_x(), connection.n_g());
    for (what, v, n) in [
        ("x0", &step.x0, n_x),
        ("w0", &step.w0, n_x),
        ("mu0", &step.mu0, n_g),
        ("shape part of q1", &step.q1.x, n_x),
        ("group part of q1", &step.q1.g, n_g),
        ("w1", &step.w1, n_x),
        ("mu1", &step.mu1, n_g),
    ] {
        expect_len(what, v, n)?;
    }
    Ok(())
}

fn check_step_minus(connection: &Connection, step: &ReducedStepMinus) -> Result<(), Error> {
    let (n_x, n_g) = (connection.n_x(), connection.n_g());
    for (what, v, n) in [
        ("shape part of q0", &step.q0.x, n_x),
        ("group part of q0", &step.q0.g, n_g),
        ("w0", &step.w0, n_x),
        ("mu0", &step.mu0, n_g),
        ("x1", &step.x1, n_x),
        ("w1", &step.w1, n_x),
        ("mu1", &step.mu1, n_g),
    ] {
        expect_len(what, v, n)?;
    }
    Ok(())
}

/// Checks each vector's length: one entry per shape coordinate (`true`) or per group coordinate.
fn check_sizes(connection: &Connection, items: &[(&str, &[f64], bool)]) -> Result<(), Error> {
    for &(what, v, shape) in items {
        expect_len(what, v, if shape { connection.n_x() } else { connection.n_g() })?;
    }
    Ok(())
}

fn neg(v: &[f64]) -> Vec<f64> {
    v.iter().map(|a| -a).collect()
}
