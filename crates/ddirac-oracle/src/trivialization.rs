//! Trivializations of Q × Q and of T*Q by a discrete connection, in a trivialization Q = Σ × G
//! (paper §3.1–3.2), for a linear connection K = h_{d,Σ} (see [`Connection`]).
//!
//! ```text
//! λ_d(q0, q1)            = (q0, x1, g1 − h_d(q0, x1))                                  eq:lambdadlocal
//! λ_d⁻¹(q0, x1, g1)      = (q0, (x1, g1 + h_d(q0, x1)))                                eq:invlambdadlocal
//! λ_d*(p0, w1, r1)       = (p0 − ⟨r1, h_d(·, 0)⟩, (w1 − ⟨r1, h_d(0, ·)⟩, r1))        eq:adjointlambdadlocal
//! (λ_d*)⁻¹(p0, p1)       = (p0 + ⟨r1, h_d(·, 0)⟩, w1 + ⟨r1, h_d(0, ·)⟩, r1)          eq:invadjointlambdadlocal
//! λ̃_d(q0, q1)            = ([q0], ω_d(q1, q0), q1) = (x0, g0 − h_d(q1, x0), q1)       remark:lambdaminus
//! λ̂_d(q0, p0)            = (q0, w0 + h*_{d,Σ}(r0), r0)                                 eq:hatlambdadlocal
//! λ̂_d⁻¹(q0, w0, μ0)      = (q0, (w0 − h*_{d,Σ}(μ0), μ0))                               eq:invhatlambdadlocal
//! λ̂_d*(p1, x1, ξ1)       = (p1, (x1, h_{d,Σ}(x1) + ξ1))                                eq:adjointhatlambdadlocal
//! (λ̂_d*)⁻¹(p1, q1)       = (p1, x1, g1 − h_{d,Σ}(x1))                                  eq:invadjointhatlambdadlocal
//! λ̌_d(p0, q0)            = (π2 ∘ h̄_d*(p0), J(q0, p0), q0) = (w0 + h*_{d,Σ}(r0), r0, q0) remark:hatlambdaminus
//! ```
//!
//! Points q = (x, g) ∈ Q and covectors p = (w, r) ∈ Q* = Σ* × G* are [`SplitVector`]s. With a linear
//! connection, h_d(q0, x1) = g0 + K(x1 − x0), so that λ̂_d(q, p) = (q, w = p_x + Kᵀ p_g, μ = p_g), the
//! reduced momenta of the integrators (the engine's closed form is in `ddirac::reduction::trivialization`,
//! with Kᵀμ = [`Connection::transpose_apply`]). Here the pairings ⟨r, h_d(·, 0)⟩, ⟨r, h_d(0, ·)⟩ and
//! h*_{d,Σ}(r) are formed as printed instead, by evaluating the linear maps h_d, h_{d,Σ} of the
//! [`Connection`] on basis vectors.
//!
//! The G-action induced on Q × (Σ × G) is g·(q0, x1, g1) = (g + q0, x1, g1) and λ_d is equivariant
//! ([`TrivializedPair::act`]); likewise g·(q0, w0, μ0) = (g + q0, w0, μ0) for λ̂_d.
//!
//! Every map checks the sizes of its arguments against the connection (n_x = dim Σ, n_g = dim G) and
//! returns [`Error::Size`] on a mismatch.

use ddirac::{Connection, Error, Input, Split};

/// A vector of Q = Σ × G, or a covector of Q* = Σ* × G*, as its shape part `x` and group part `g`.
///
/// ```
/// use ddirac_oracle::trivialization::SplitVector;
/// let q = SplitVector::new(vec![1.0, 2.0], vec![3.0]);
/// let p = SplitVector::new(vec![0.5, 0.0], vec![-1.0]);
/// assert_eq!(q.dot(&p), -2.5);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SplitVector {
    /// The Σ (or Σ*) component.
    pub x: Vec<f64>,
    /// The G (or G*) component.
    pub g: Vec<f64>,
}

impl SplitVector {
    /// A vector from its parts.
    pub fn new(x: Vec<f64>, g: Vec<f64>) -> Self {
        Self { x, g }
    }

    /// The zero vector of Σ × G.
    pub fn zeros(n_x: usize, n_g: usize) -> Self {
        Self { x: vec![0.0; n_x], g: vec![0.0; n_g] }
    }

    /// The shape and group entries of a vector in the system's coordinate order.
    ///
    /// ```
    /// use ddirac::{systems::ChargedParticle, Split, System};
    /// use ddirac_oracle::trivialization::SplitVector;
    /// let split = Split::new(&ChargedParticle::default().coordinates());
    /// let q = SplitVector::from_full(&split, &[1.0, 2.0, 3.0, 4.0]).unwrap();
    /// assert_eq!((q.x, q.g), (vec![1.0, 2.0, 3.0], vec![4.0]));
    /// ```
    pub fn from_full(split: &Split, full: &[f64]) -> Result<Self, Error> {
        expect_len("vector", full, split.n_x() + split.n_g())?;
        Ok(Self { x: split.x(full), g: split.g(full) })
    }

    /// The vector in the system's coordinate order.
    pub fn to_full(&self, split: &Split) -> Result<Vec<f64>, Error> {
        expect_len("shape part", &self.x, split.n_x())?;
        expect_len("group part", &self.g, split.n_g())?;
        Ok(split.join(&self.x, &self.g))
    }

    /// The pairing ⟨self, other⟩ = Σ x_i x'_i + Σ g_j g'_j.
    pub fn dot(&self, other: &SplitVector) -> f64 {
        dot(&self.x, &other.x) + dot(&self.g, &other.g)
    }

    /// The translate a·q = (x, g + a) by a ∈ G.
    pub fn translate(&self, a: &[f64]) -> Self {
        Self { x: self.x.clone(), g: add(&self.g, a) }
    }

    fn check(&self, connection: &Connection, what: &str) -> Result<(), Error> {
        expect_len(&format!("shape part of {what}"), &self.x, connection.n_x())?;
        expect_len(&format!("group part of {what}"), &self.g, connection.n_g())
    }
}

/// An element (q0, x1, g1) of Q × (Σ × G), the image of λ_d.
#[derive(Debug, Clone, PartialEq)]
pub struct TrivializedPair {
    /// The base point q0 ∈ Q.
    pub q0: SplitVector,
    /// x1 = \[q1\] ∈ Σ.
    pub x1: Vec<f64>,
    /// The connection part g1 = ω_d(q0, q1) ∈ G.
    pub g1: Vec<f64>,
}

impl TrivializedPair {
    /// The induced action a·(q0, x1, g1) = (a + q0, x1, g1) of a ∈ G (paper §3.1).
    pub fn act(&self, a: &[f64]) -> Self {
        Self { q0: self.q0.translate(a), x1: self.x1.clone(), g1: self.g1.clone() }
    }
}

/// An element (p0, w1, r1) of Q* × (Σ* × G*), a covector on Q × (Σ × G).
#[derive(Debug, Clone, PartialEq)]
pub struct TrivializedPairDual {
    /// The Q* component.
    pub p0: SplitVector,
    /// The Σ* component.
    pub w1: Vec<f64>,
    /// The G* component.
    pub r1: Vec<f64>,
}

/// An element (x0, g0, q1) of (Σ × G) × Q, the image of λ̃_d.
#[derive(Debug, Clone, PartialEq)]
pub struct TrivializedPairMinus {
    /// x0 = \[q0\] ∈ Σ.
    pub x0: Vec<f64>,
    /// The connection part g0 = ω_d(q1, q0) ∈ G.
    pub g0: Vec<f64>,
    /// The base point q1 ∈ Q.
    pub q1: SplitVector,
}

/// An element (q, w, μ) of Q × (Σ* × 𝔤*), the image of λ̂_d.
#[derive(Debug, Clone, PartialEq)]
pub struct TrivializedCovector {
    /// The base point q ∈ Q.
    pub q: SplitVector,
    /// w = π2 ∘ h̄_d*(p) ∈ Σ*.
    pub w: Vec<f64>,
    /// μ = J(q, p) ∈ 𝔤*.
    pub mu: Vec<f64>,
}

/// An element (p, x, ξ) of Q* × (Σ × 𝔤), a covector on Q × (Σ* × 𝔤*).
#[derive(Debug, Clone, PartialEq)]
pub struct TrivializedCovectorDual {
    /// The Q* component.
    pub p: SplitVector,
    /// The Σ component.
    pub x: Vec<f64>,
    /// The 𝔤 component.
    pub xi: Vec<f64>,
}

/// An element (w, μ, q) of (Σ* × 𝔤*) × Q, the image of λ̌_d.
#[derive(Debug, Clone, PartialEq)]
pub struct TrivializedCovectorMinus {
    /// w ∈ Σ*.
    pub w: Vec<f64>,
    /// μ ∈ 𝔤*.
    pub mu: Vec<f64>,
    /// The base point q ∈ Q.
    pub q: SplitVector,
}

/// An element (x, ξ, p) of (Σ × 𝔤) × Q*, a covector on (Σ* × 𝔤*) × Q.
#[derive(Debug, Clone, PartialEq)]
pub struct TrivializedCovectorMinusDual {
    /// The Σ component.
    pub x: Vec<f64>,
    /// The 𝔤 component.
    pub xi: Vec<f64>,
    /// The Q* component.
    pub p: SplitVector,
}

/// λ_d(q0, q1) = (q0, x1, g1 − h_d(q0, x1)) (eq:lambdadlocal).
///
/// ```
/// use ddirac::Connection;
/// use ddirac_oracle::trivialization::{lambda_d, SplitVector};
/// let k = Connection::new(&[vec![-0.5]]).unwrap();
/// let t = lambda_d(&k, &SplitVector::new(vec![0.0], vec![0.0]), &SplitVector::new(vec![2.0], vec![1.0])).unwrap();
/// assert_eq!(t.g1, vec![2.0]); // 1 − (0 − 0.5 · 2)
/// ```
pub fn lambda_d(connection: &Connection, q0: &SplitVector, q1: &SplitVector) -> Result<TrivializedPair, Error> {
    q0.check(connection, "q0")?;
    q1.check(connection, "q1")?;
    let h = connection.h_d((&q0.x, &q0.g), &q1.x);
    Ok(TrivializedPair { q0: q0.clone(), x1: q1.x.clone(), g1: sub(&q1.g, &h) })
}

/// λ_d⁻¹(q0, x1, g1) = (q0, (x1, g1 + h_d(q0, x1))) (eq:invlambdadlocal).
pub fn lambda_d_inv(connection: &Connection, t: &TrivializedPair) -> Result<(SplitVector, SplitVector), Error> {
    t.q0.check(connection, "q0")?;
    expect_len("x1", &t.x1, connection.n_x())?;
    expect_len("g1", &t.g1, connection.n_g())?;
    let h = connection.h_d((&t.q0.x, &t.q0.g), &t.x1);
    Ok((t.q0.clone(), SplitVector::new(t.x1.clone(), add(&t.g1, &h))))
}

/// λ_d*(p0, w1, r1) = (p0 − ⟨r1, h_d(·, 0)⟩, (w1 − ⟨r1, h_d(0, ·)⟩, r1)) (eq:adjointlambdadlocal).
pub fn lambda_d_adjoint(connection: &Connection, a: &TrivializedPairDual) -> Result<(SplitVector, SplitVector), Error> {
    a.p0.check(connection, "p0")?;
    expect_len("w1", &a.w1, connection.n_x())?;
    expect_len("r1", &a.r1, connection.n_g())?;
    let (on_q, on_sigma) = (pairing_h_d_q(connection, &a.r1), pairing_h_d_sigma(connection, &a.r1));
    let p0 = SplitVector::new(sub(&a.p0.x, &on_q.x), sub(&a.p0.g, &on_q.g));
    Ok((p0, SplitVector::new(sub(&a.w1, &on_sigma), a.r1.clone())))
}

/// (λ_d*)⁻¹(p0, p1) = (p0 + ⟨r1, h_d(·, 0)⟩, w1 + ⟨r1, h_d(0, ·)⟩, r1) with p1 = (w1, r1)
/// (eq:invadjointlambdadlocal).
pub fn lambda_d_adjoint_inv(
    connection: &Connection,
    p0: &SplitVector,
    p1: &SplitVector,
) -> Result<TrivializedPairDual, Error> {
    p0.check(connection, "p0")?;
    p1.check(connection, "p1")?;
    let (on_q, on_sigma) = (pairing_h_d_q(connection, &p1.g), pairing_h_d_sigma(connection, &p1.g));
    Ok(TrivializedPairDual {
        p0: SplitVector::new(add(&p0.x, &on_q.x), add(&p0.g, &on_q.g)),
        w1: add(&p1.x, &on_sigma),
        r1: p1.g.clone(),
    })
}

/// λ̃_d(q0, q1) = (\[q0\], ω_d(q1, q0), q1) = (x0, g0 − h_d(q1, x0), q1) (remark:lambdaminus).
pub fn lambda_tilde(
    connection: &Connection,
    q0: &SplitVector,
    q1: &SplitVector,
) -> Result<TrivializedPairMinus, Error> {
    q0.check(connection, "q0")?;
    q1.check(connection, "q1")?;
    let h = connection.h_d((&q1.x, &q1.g), &q0.x);
    Ok(TrivializedPairMinus { x0: q0.x.clone(), g0: sub(&q0.g, &h), q1: q1.clone() })
}

/// λ̃_d⁻¹(x0, g0, q1) = ((x0, g0 + h_d(q1, x0)), q1), the inverse of [`lambda_tilde`].
pub fn lambda_tilde_inv(
    connection: &Connection,
    t: &TrivializedPairMinus,
) -> Result<(SplitVector, SplitVector), Error> {
    t.q1.check(connection, "q1")?;
    expect_len("x0", &t.x0, connection.n_x())?;
    expect_len("g0", &t.g0, connection.n_g())?;
    let h = connection.h_d((&t.q1.x, &t.q1.g), &t.x0);
    Ok((SplitVector::new(t.x0.clone(), add(&t.g0, &h)), t.q1.clone()))
}

/// λ̂_d(q, p) = (q, w + h*_{d,Σ}(r), r) for p = (w, r) (eq:hatlambdadlocal).
///
/// Paper §7.1: the charged particle's initial data q0 = 0, p0 = (1, 0, 1, 1) with K = 0 trivialize
/// to ((0, 0), (1, 0, 1), 1).
///
/// ```
/// use ddirac::Connection;
/// use ddirac_oracle::trivialization::{lambda_hat, SplitVector};
/// let k = Connection::zero(3, 1);
/// let t = lambda_hat(&k, &SplitVector::zeros(3, 1), &SplitVector::new(vec![1.0, 0.0, 1.0], vec![1.0])).unwrap();
/// assert_eq!((t.w, t.mu), (vec![1.0, 0.0, 1.0], vec![1.0]));
/// ```
pub fn lambda_hat(connection: &Connection, q: &SplitVector, p: &SplitVector) -> Result<TrivializedCovector, Error> {
    q.check(connection, "q")?;
    p.check(connection, "p")?;
    Ok(TrivializedCovector { q: q.clone(), w: add(&p.x, &h_sigma_star(connection, &p.g)), mu: p.g.clone() })
}

/// λ̂_d⁻¹(q, w, μ) = (q, (w − h*_{d,Σ}(μ), μ)) (eq:invhatlambdadlocal).
pub fn lambda_hat_inv(connection: &Connection, t: &TrivializedCovector) -> Result<(SplitVector, SplitVector), Error> {
    t.q.check(connection, "q")?;
    expect_len("w", &t.w, connection.n_x())?;
    expect_len("mu", &t.mu, connection.n_g())?;
    Ok((t.q.clone(), SplitVector::new(sub(&t.w, &h_sigma_star(connection, &t.mu)), t.mu.clone())))
}

/// λ̂_d*(p, x, ξ) = (p, (x, h_{d,Σ}(x) + ξ)) ∈ Q* × Q (eq:adjointhatlambdadlocal).
pub fn lambda_hat_adjoint(
    connection: &Connection,
    a: &TrivializedCovectorDual,
) -> Result<(SplitVector, SplitVector), Error> {
    a.p.check(connection, "p")?;
    expect_len("x", &a.x, connection.n_x())?;
    expect_len("xi", &a.xi, connection.n_g())?;
    Ok((a.p.clone(), SplitVector::new(a.x.clone(), add(&connection.h_dsigma(&a.x), &a.xi))))
}

/// (λ̂_d*)⁻¹(p, q) = (p, x, g − h_{d,Σ}(x)) (eq:invadjointhatlambdadlocal).
pub fn lambda_hat_adjoint_inv(
    connection: &Connection,
    p: &SplitVector,
    q: &SplitVector,
) -> Result<TrivializedCovectorDual, Error> {
    p.check(connection, "p")?;
    q.check(connection, "q")?;
    Ok(TrivializedCovectorDual { p: p.clone(), x: q.x.clone(), xi: sub(&q.g, &connection.h_dsigma(&q.x)) })
}

/// λ̌_d(p, q) = (w + h*_{d,Σ}(r), r, q) for p = (w, r) (remark:hatlambdaminus).
pub fn lambda_check(
    connection: &Connection,
    p: &SplitVector,
    q: &SplitVector,
) -> Result<TrivializedCovectorMinus, Error> {
    let t = lambda_hat(connection, q, p)?;
    Ok(TrivializedCovectorMinus { w: t.w, mu: t.mu, q: t.q })
}

/// λ̌_d⁻¹(w, μ, q) = ((w − h*_{d,Σ}(μ), μ), q).
pub fn lambda_check_inv(
    connection: &Connection,
    t: &TrivializedCovectorMinus,
) -> Result<(SplitVector, SplitVector), Error> {
    let (q, p) = lambda_hat_inv(connection, &TrivializedCovector { q: t.q.clone(), w: t.w.clone(), mu: t.mu.clone() })?;
    Ok((p, q))
}

/// λ̌_d*(x, ξ, p) = ((x, h_{d,Σ}(x) + ξ), p) ∈ Q × Q*, the adjoint of [`lambda_check`] (the factors of
/// eq:adjointhatlambdadlocal exchanged).
pub fn lambda_check_adjoint(
    connection: &Connection,
    a: &TrivializedCovectorMinusDual,
) -> Result<(SplitVector, SplitVector), Error> {
    let (p, q) =
        lambda_hat_adjoint(connection, &TrivializedCovectorDual { p: a.p.clone(), x: a.x.clone(), xi: a.xi.clone() })?;
    Ok((q, p))
}

/// (λ̌_d*)⁻¹(q, p) = (x, g − h_{d,Σ}(x), p) (eq:invadjointhatlambdadlocal with the factors exchanged).
pub fn lambda_check_adjoint_inv(
    connection: &Connection,
    q: &SplitVector,
    p: &SplitVector,
) -> Result<TrivializedCovectorMinusDual, Error> {
    let t = lambda_hat_adjoint_inv(connection, p, q)?;
    Ok(TrivializedCovectorMinusDual { x: t.x, xi: t.xi, p: t.p })
}

/// h*_{d,Σ}(μ) = ⟨μ, h_{d,Σ}(·)⟩ ∈ Σ* (= Kᵀμ).
pub(crate) fn h_sigma_star(connection: &Connection, mu: &[f64]) -> Vec<f64> {
    pullback(mu, connection.n_x(), |x| connection.h_dsigma(x))
}

/// ⟨r, h_d(·, 0)⟩ ∈ Q*, the covector q ↦ ⟨r, h_d(q, 0)⟩ (= (−Kᵀr, r)).
fn pairing_h_d_q(connection: &Connection, r: &[f64]) -> SplitVector {
    let (n_x, n_g) = (connection.n_x(), connection.n_g());
    let zero_x = vec![0.0; n_x];
    let x = pullback(r, n_x, |x| connection.h_d((x, &vec![0.0; n_g]), &zero_x));
    let g = pullback(r, n_g, |g| connection.h_d((&zero_x, g), &zero_x));
    SplitVector::new(x, g)
}

/// ⟨r, h_d(0, ·)⟩ ∈ Σ*, the covector x ↦ ⟨r, h_d(0, x)⟩ (= Kᵀr).
fn pairing_h_d_sigma(connection: &Connection, r: &[f64]) -> Vec<f64> {
    let (zero_x, zero_g) = (vec![0.0; connection.n_x()], vec![0.0; connection.n_g()]);
    pullback(r, connection.n_x(), |x| connection.h_d((&zero_x, &zero_g), x))
}

/// The covector ⟨μ, f(·)⟩ on ℝⁿ of a linear map f: entry i is ⟨μ, f(e_i)⟩.
pub(crate) fn pullback(mu: &[f64], n: usize, f: impl Fn(&[f64]) -> Vec<f64>) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let mut e = vec![0.0; n];
            e[i] = 1.0;
            dot(mu, &f(&e))
        })
        .collect()
}

pub(crate) fn expect_len(what: &str, v: &[f64], expected: usize) -> Result<(), Error> {
    if v.len() == expected {
        Ok(())
    } else {
        Err(Error::Size { what: Input::Argument(what.to_owned()), expected, found: v.len() })
    }
}

pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(u, v)| u * v).sum()
}

pub(crate) fn add(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(u, v)| u + v).collect()
}

pub(crate) fn sub(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(u, v)| u - v).collect()
}
