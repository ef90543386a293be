//! The trivialization of covectors λ̂_d (paper §3.2) as the reduced integrators use it, for a linear
//! connection K = h_{d,Σ}:
//!
//! ```text
//! λ̂_d(q, p)       = (q, w, μ),  w = p_x + h*_{d,Σ}(p_g) = p_x + Kᵀ p_g,  μ = p_g = J(q, p)   eq:hatlambdadlocal
//! λ̂_d⁻¹(q, w, μ)  = (q, (w − Kᵀ μ, μ))                                                     eq:invhatlambdadlocal
//! ```
//!
//! The reduced schemes keep (w, μ) at the positions of the shape and group coordinates, so both maps
//! act on one array of N entries and leave q alone. Kᵀμ is [`Connection::transpose_apply`].
//!
//! Every trivialization of paper §3 (λ_d, λ̃_d, λ̂_d, λ̌_d, their inverses and adjoints) is transcribed
//! independently, as printed, in the `ddirac-oracle` crate, against which the tests hold this one.

use crate::dim::Dim;
use crate::{Connection, Split};

/// (w, μ) = λ̂_d(q, p) for p in the system's coordinate order: w at the shape positions, μ at the group
/// positions (eq:hatlambdadlocal).
pub(crate) fn lambda_hat<Dm: Dim>(connection: &Connection, split: &Split, p: &Dm::Array<f64>) -> Dm::Array<f64> {
    let kt_mu = kt_mu::<Dm>(connection, split, p);
    let mut wm = p.clone();
    for (i, &si) in split.shape.iter().enumerate() {
        wm[si] = p[si] + kt_mu[i];
    }
    wm
}

/// p = λ̂_d⁻¹(q, w, μ), the inverse of [`lambda_hat`] (eq:invhatlambdadlocal).
pub(crate) fn lambda_hat_inv<Dm: Dim>(connection: &Connection, split: &Split, wm: &Dm::Array<f64>) -> Dm::Array<f64> {
    let kt_mu = kt_mu::<Dm>(connection, split, wm);
    let mut p = wm.clone();
    for (i, &si) in split.shape.iter().enumerate() {
        p[si] = wm[si] - kt_mu[i];
    }
    p
}

/// Kᵀμ (first n_x entries) for μ at the group positions of `packed`.
fn kt_mu<Dm: Dim>(connection: &Connection, split: &Split, packed: &Dm::Array<f64>) -> Dm::Array<f64> {
    let dim = Dm::of(packed);
    let mut mu = dim.array(|_| 0.0);
    for (j, &gj) in split.group.iter().enumerate() {
        mu[j] = packed[gj];
    }
    let mut out = dim.array(|_| 0.0);
    connection.transpose_apply(&mu.as_ref()[..split.n_g()], &mut out.as_mut()[..split.n_x()]);
    out
}
