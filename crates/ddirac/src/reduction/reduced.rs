//! Reduced (+) and (−) discrete Lagrange–Poincaré–Dirac equations (paper §4.3–4.4), for a linear
//! connection K (see [`crate::Connection`]).
//!
//! **(+)**, paper eq. `geometricequations`, with l₊(x0, x1, γ) = L_d((x0, 0), (x1, γ + K(x1 − x0)))
//! (eq. `reducedlagrangianlocal`):
//!
//! ```text
//! w_k = −∂l₊/∂x0,   μ_k = ∂l₊/∂γ,   w_{k+1} = ∂l₊/∂x1,   μ_{k+1} = μ_k,
//! g_{k+1} = g_k + γ_k + K (x_{k+1} − x_k)
//! ```
//!
//! **(−)**, with l₋(x0, γ, x1) = L_d((x0, γ + K(x0 − x1)), (x1, 0)) (eq. `reducedlagrangianlocalminus`):
//!
//! ```text
//! w_k = −∂l₋/∂x0,   μ_k = −∂l₋/∂γ,   w_{k+1} = ∂l₋/∂x1,   μ_{k+1} = μ_k,
//! g_{k+1} = g_k − γ_k + K (x_{k+1} − x_k)
//! ```
//!
//! *Erratum.* The paper's display `geometricequationsminus` prints the opposite sign on every
//! momentum term. The signs above follow from the reduced (−) Dirac structure and Dirac differential
//! (`prop:reduceddiractructurelocalminus`, `prop:reduceddiracdifferentiallocalminus`) with Lemma
//! `lemma:partialderivativesldminus`; with the printed signs the charged particle of §7 runs
//! backwards in time (θ̇ = −1, z(20) = −20). The `ddirac-oracle` crate transcribes the reduced Dirac
//! structures and differentials and both forms of the display independently, and its tests hold the
//! runs of this scheme against them.
//!
//! The momenta (w, μ) = λ̂_d(q, p) are [`crate::reduction::trivialization`]'s.
//!
//! Unknowns z (stored at the coordinates' own positions): Δx = x_{k+1} − x_k at the shape
//! positions and γ_k at the group positions. A step solves the first two equations by Newton's
//! method. Derivatives come from one pass of automatic differentiation of
//! l̂(a, b) = l(x_k + a_x, x_k + b_x, b_γ + a_γ) at a = 0: ∂l̂/∂a gives (∂l/∂x0, ∂l/∂γ), and the
//! mixed block ∂²l̂/∂a∂b is the Jacobian with respect to z = b.

use crate::dim::{Dim, Entry};
use crate::mechanics::lagrangian::Lagrangian;
use crate::Scalar;

use crate::reduction::reduced_lagrangian::ReducedLagrangian;
use crate::reduction::trivialization::{lambda_hat, lambda_hat_inv};
use crate::scheme::{Scheme, StepEquations};
use crate::{DiscreteLagrangian, Variant};

/// The reduced scheme of one variant, on the reduced Lagrangians l± of [`ReducedLagrangian`].
pub(crate) struct LagrangePoincareDirac<S, Dm> {
    /// The number of coordinates.
    dim: Dm,
    reduction: ReducedLagrangian<S>,
    variant: Variant,
    /// Whether the connection K is zero (then K(x1 − x0) and Kᵀμ vanish, and λ̂_d is the identity).
    flat: bool,
}

impl<S, Dm: Dim> LagrangePoincareDirac<S, Dm> {
    /// The scheme of `variant` on the reduced Lagrangians of `reduction`, for `dim` coordinates.
    pub(crate) fn new(dim: Dm, reduction: ReducedLagrangian<S>, variant: Variant) -> Self {
        let flat = reduction.connection.is_zero();
        Self { dim, reduction, variant, flat }
    }

    /// l̂(a, b): the reduced Lagrangian l± with x0 = x_k + a_x, x1 = x_k + b_x, γ = b_γ + a_γ.
    pub(crate) fn lhat<D, B>(&self, base: &Dm::Array<B>, a: &Dm::Array<D>, b: &Dm::Array<D>) -> D
    where
        S: Lagrangian<Dm>,
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy,
    {
        let mut shifted = a.clone();
        for &gj in &self.reduction.split.group {
            shifted[gj] = a[gj] + b[gj];
        }
        match self.variant {
            Variant::Plus => self.reduction.l_plus_in_place::<Dm, D, B>(base, shifted, b.clone()),
            Variant::Minus => self.reduction.l_minus_in_place::<Dm, D, B>(base, shifted, b.clone()),
        }
    }

    /// Row j of K (x1 − x0) from a full increment (its shape entries).
    fn k_dx(&self, j: usize, dx_full: &[f64]) -> f64 {
        if self.flat {
            return 0.0;
        }
        let shape = &self.reduction.split.shape;
        self.reduction.connection.row_apply(j, |i| dx_full[shape[i]]).unwrap_or(0.0)
    }
}

impl<S: Lagrangian<Dm> + Clone, Dm: Dim> Scheme<Dm> for LagrangePoincareDirac<S, Dm> {
    fn resized(&self, step: f64) -> Self {
        let ld = DiscreteLagrangian::new(self.reduction.ld.system.clone(), self.reduction.ld.rule, step);
        let reduction = ReducedLagrangian {
            ld,
            split: self.reduction.split.clone(),
            connection: self.reduction.connection.clone(),
        };
        Self { dim: self.dim, reduction, variant: self.variant, flat: self.flat }
    }

    #[inline(always)]
    fn base(&self, q: &Dm::Array<f64>) -> Dm::Array<f64> {
        let mut base = q.clone();
        for &gj in &self.reduction.split.group {
            base[gj] = 0.0;
        }
        base
    }

    fn generating<D, B>(&self, base: &Dm::Array<B>, a: &Dm::Array<D>, b: &Dm::Array<D>) -> D
    where
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy,
    {
        self.lhat::<D, B>(base, a, b)
    }

    /// (+): w_k + ∂l₊/∂x0 = 0 and ∂l₊/∂γ − μ_k = 0; (−): w_k + ∂l₋/∂x0 = 0 and μ_k + ∂l₋/∂γ = 0.
    /// w advances to ∂l±/∂x1, μ is conserved.
    fn equations(&self) -> StepEquations<Dm> {
        let group = |i: usize| self.reduction.split.group.contains(&i);
        let sign = self.dim.array(|i| if group(i) && self.variant == Variant::Plus { -1.0 } else { 1.0 });
        StepEquations { sign, advances: self.dim.array(|i| !group(i)), eliminable: self.dim.array(group) }
    }

    #[inline(always)]
    fn increment(&self, z: &Dm::Vector) -> Dm::Array<f64> {
        let mut dq = self.dim.array(|i| z[i]);
        for (j, &gj) in self.reduction.split.group.iter().enumerate() {
            let gamma = match self.variant {
                Variant::Plus => z[gj],
                Variant::Minus => -z[gj],
            };
            dq[gj] = gamma + self.k_dx(j, Dm::entries(z));
        }
        dq
    }

    fn unknowns(&self, dq: &Dm::Array<f64>) -> Dm::Vector {
        let mut z = self.dim.vector(|i| dq[i]);
        for (j, &gj) in self.reduction.split.group.iter().enumerate() {
            let gamma = dq[gj] - self.k_dx(j, dq.as_ref());
            z[gj] = match self.variant {
                Variant::Plus => gamma,
                Variant::Minus => -gamma,
            };
        }
        z
    }

    /// (w, μ) = λ̂_d(q, p).
    fn momenta_from_p(&self, p: &Dm::Array<f64>) -> Dm::Array<f64> {
        if self.flat {
            return p.clone();
        }
        lambda_hat::<Dm>(&self.reduction.connection, &self.reduction.split, p)
    }

    /// p = λ̂_d⁻¹(q, w, μ).
    #[inline(always)]
    fn p_from_momenta(&self, wm: &Dm::Array<f64>) -> Dm::Array<f64> {
        if self.flat {
            return wm.clone();
        }
        lambda_hat_inv::<Dm>(&self.reduction.connection, &self.reduction.split, wm)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dim::{Dynamic, Fixed};
    use crate::scheme::testing::{assert_alike, AsDynamic};
    use crate::systems::DoubleSphericalPendulum;
    use crate::{Connection, Differentiation, Method, Rule};

    #[test]
    fn reduced_steps_are_alike_in_a_fixed_and_a_dynamic_dimension() {
        const N: usize = 4;
        let system = DoubleSphericalPendulum::default();
        let (q, p) = ([0.0, 0.6, 0.2, 0.9], [0.3, 0.1, -0.2, 0.05]);
        // The flat connection, and one that couples the group angle to all three shape angles.
        for connection in [Connection::zero(3, 1), Connection::new(&[vec![0.3, -0.2, 0.1]]).unwrap()] {
            for variant in [Variant::Plus, Variant::Minus] {
                for choice in [Differentiation::Dual, Differentiation::Compiled] {
                    let reduction = ReducedLagrangian::new(system, Rule::Midpoint, 0.01, connection.clone()).unwrap();
                    let dynamic = ReducedLagrangian {
                        ld: DiscreteLagrangian::new(AsDynamic::<_, N>(system), Rule::Midpoint, 0.01),
                        split: reduction.split.clone(),
                        connection: reduction.connection.clone(),
                    };
                    let fixed = LagrangePoincareDirac::new(Fixed::<N>, reduction, variant);
                    let dynamic = LagrangePoincareDirac::new(Dynamic(N), dynamic, variant);
                    let method = Method {
                        rule: Rule::Midpoint,
                        reduced: true,
                        variant,
                        connection: Some(connection.clone()),
                        differentiation: choice,
                        // The steps of the main chart (the library would move to another near a pole).
                        atlas: false,
                        ..Method::default()
                    };
                    assert_alike(&system, &fixed, &dynamic, &method, q, p, 30);
                }
            }
        }
    }
}
