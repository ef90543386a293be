//! A rigid body in principal axes with a potential linear in the attitude,
//!
//! ```text
//! ℓ(R, Ω) = ½ ⟨Ω, 𝕀 Ω⟩ − ⟨e3, R w⟩,      𝕀 = diag(I1, I2, I3),  w = m g c
//! ```
//!
//! (the built-in `rigid_body`; a [`RigidSystem`] says it has this form through
//! [`RigidSystem::principal_axes`]), whose steps are solved with the derivatives of the discrete
//! Lagrangian in closed form, in f64 and on the stack, instead of dual numbers of the general
//! Lagrangian ([`super::discrete_lagrangian`]). The equations are the same ([`super::step`]); only how
//! their derivatives are obtained differs, and a test holds both to round-off.
//!
//! With γ = R_kᵀ e3 (e3 for a reduced step, which evaluates ℓ at R = I) and the rule's attitudes
//! R_k (I + η̂) M_j(ζ) with weights c_j (left: M = I; right: M = cay(ζ); midpoint: M = cay(half(ζ));
//! trapezoid: ½ I and ½ cay(ζ)), the discrete Lagrangian is
//!
//! ```text
//! L_d = ζᵀ𝕀ζ / (2h) − h Σ_j c_j ⟨γ, (I + η̂) w_j(ζ)⟩,        w_j(ζ) = M_j(ζ) w
//! ∂L_d/∂ζ   = 𝕀ζ/h − h Σ_j c_j W_jᵀ γ                      W_j = ∂w_j/∂ζ
//! ∂L_d/∂η   = −h Σ_j c_j w_j × γ                           (0 for a reduced step)
//! ∂²L_d/∂ζ² = 𝕀/h − h Σ_j c_j Σ_i γ_i ∇²(w_j)_i
//! ∂²L_d/∂η∂ζ = h Σ_j c_j γ̂ W_j
//! ```
//!
//! The derivatives of w_j(ζ) are those of the Cayley map applied to w ([`moved`]), in closed form; a
//! free body (w = 0) needs none. The Legendre transform is Ω = 𝕀⁻¹Π and the energy
//! ½⟨Π, 𝕀⁻¹Π⟩ + ⟨e3, R w⟩.

use nalgebra::{SMatrix, SVector};

use super::so3::{self, Matrix3};
use super::step::{orthonormalized, Point, Trivialized};
use super::system::{PrincipalAxes, RigidSystem};
use crate::dim::Fixed;
use crate::newton::{self, KeptJacobian, NewtonFailure, NewtonOptions, NewtonStats};
use crate::{Error, Input, Reason, Rule, Scalar};

/// Three unknowns on the stack.
pub(crate) type Vector3 = SVector<f64, 3>;
type Jacobian3 = SMatrix<f64, 3, 3>;

/// Which attitude of the step a potential term is evaluated at.
#[derive(Debug, Clone, Copy)]
enum At {
    Start,
    End,
    Middle,
}

/// The potential terms (weight c_j, attitude M_j) of a rule.
fn terms(rule: Rule) -> &'static [(f64, At)] {
    match rule {
        Rule::Left => &[(1.0, At::Start)],
        Rule::Right => &[(1.0, At::End)],
        Rule::Midpoint => &[(1.0, At::Middle)],
        Rule::Trapezoid => &[(0.5, At::Start), (0.5, At::End)],
    }
}

/// The weight's position M(ζ) w of a rule's term with its derivatives: u = M(ζ) w (M = I at the start
/// of the step, cay(ζ) at its end, cay(half(ζ)) at its middle), the Jacobian ∂u/∂ζ (rows:
/// components) and, when asked, the Hessian of ⟨γ, u⟩ in ζ.
///
/// [`so3::cayley`] is cay(ζ) = C(ζ/2) for C(x) = I + c (x̂ + x̂²), c = 2/(1 + |x|²), so u = C(x) w with
/// x = ζ/2 at the end and x = σ ζ / 2, σ = 1/(1 + r), r = √(1 + |ζ|²/4) ([`so3::half`]) at the middle.
/// With a = x × w and b = x × a = x ⟨x, w⟩ − w |x|², u = w + c (a + b) and
///
/// ```text
/// ∂u/∂x = −c² (a + b) xᵀ + c (−ŵ + ⟨x, w⟩ I + x wᵀ − 2 w xᵀ)
/// ⟨γ, u⟩ = ⟨γ, w⟩ + c g,   g = ⟨x, w × γ⟩ + ⟨x, γ⟩⟨x, w⟩ − ⟨γ, w⟩ |x|²
/// ∇²ₓ⟨γ, u⟩ = g ∇²c + ∇c ∇gᵀ + ∇g ∇cᵀ + c ∇²g,   ∇c = −c² x,  ∇²c = 2c³ x xᵀ − c² I,
/// ∇g = w × γ + γ ⟨x, w⟩ + w ⟨x, γ⟩ − 2 ⟨γ, w⟩ x,   ∇²g = γ wᵀ + w γᵀ − 2 ⟨γ, w⟩ I
/// ```
///
/// and in ζ by the chain rule, ∂x/∂ζ = (σ I + 2σ' ζ ζᵀ)/2 and, with p = (∂u/∂x)ᵀ γ, the curvature of
/// x(ζ) adding σ' (p ζᵀ + ζ pᵀ + ⟨p, ζ⟩ I) + 2σ'' ⟨p, ζ⟩ ζ ζᵀ (σ', σ'' in q = |ζ|²; σ = 1, σ' = 0 at
/// the end).
fn moved(at: At, zeta: &[f64; 3], w: &[f64; 3], gamma: &[f64; 3], second: bool) -> Moved {
    let (sigma, d1, d2) = match at {
        At::Start => return Moved { u: *w, jacobian: [[0.0; 3]; 3], hessian: second.then_some([[0.0; 3]; 3]) },
        At::End => (1.0, 0.0, 0.0),
        At::Middle => {
            let r = (1.0 + 0.25 * so3::dot(zeta, zeta)).sqrt();
            let (sigma, dr) = (1.0 / (1.0 + r), 1.0 / (8.0 * r));
            let d1 = -sigma * sigma * dr;
            let d2 = (2.0 * sigma * sigma * sigma * dr + sigma * sigma / (8.0 * r * r)) * dr;
            (sigma, d1, d2)
        }
    };
    let x = zeta.map(|z| 0.5 * sigma * z);
    // ∂x/∂ζ.
    let jx = so3::matrix(|m, k| 0.5 * (if m == k { sigma } else { 0.0 } + 2.0 * d1 * zeta[m] * zeta[k]));
    let xx = so3::dot(&x, &x);
    let c = 2.0 / (1.0 + xx);
    let a = so3::cross(&x, w);
    let xw = so3::dot(&x, w);
    let ab = so3::vector(|i| a[i] + x[i] * xw - w[i] * xx);
    let u = so3::vector(|i| w[i] + c * ab[i]);
    let w_hat = so3::hat(w);
    let ux = so3::matrix(|i, k| {
        let delta = if i == k { xw } else { 0.0 };
        -c * c * ab[i] * x[k] + c * (-w_hat[i][k] + delta + x[i] * w[k] - 2.0 * w[i] * x[k])
    });
    let jacobian = so3::mul(&ux, &jx);
    let hessian = second.then(|| {
        let gw = so3::dot(gamma, w);
        let xg = so3::dot(&x, gamma);
        let w_cross_gamma = so3::cross(w, gamma);
        let g = so3::dot(&x, &w_cross_gamma) + xg * xw - gw * xx;
        let grad_c = x.map(|xi| -c * c * xi);
        let grad_g = so3::vector(|i| w_cross_gamma[i] + gamma[i] * xw + w[i] * xg - 2.0 * gw * x[i]);
        let hx = so3::matrix(|i, k| {
            let delta = if i == k { 1.0 } else { 0.0 };
            let hc = 2.0 * c * c * c * x[i] * x[k] - c * c * delta;
            let hg = gamma[i] * w[k] + w[i] * gamma[k] - 2.0 * gw * delta;
            g * hc + grad_c[i] * grad_g[k] + grad_g[i] * grad_c[k] + c * hg
        });
        let p = so3::apply_transpose(&ux, gamma);
        let pz = so3::dot(&p, zeta);
        // (∂x/∂ζ)ᵀ ∇²ₓ (∂x/∂ζ) and the curvature of x(ζ).
        let pulled = so3::mul(&so3::transpose(&jx), &so3::mul(&hx, &jx));
        so3::matrix(|i, k| {
            let delta = if i == k { pz } else { 0.0 };
            pulled[i][k] + d1 * (p[i] * zeta[k] + zeta[i] * p[k] + delta) + 2.0 * d2 * pz * zeta[i] * zeta[k]
        })
    });
    Moved { u, jacobian, hessian }
}

/// [`moved`]'s answer.
struct Moved {
    /// M(ζ) w.
    u: [f64; 3],
    /// ∂u/∂ζ, rows: components.
    jacobian: Matrix3<f64>,
    /// ∇²⟨γ, u⟩ in ζ, when asked.
    hessian: Option<Matrix3<f64>>,
}

/// The derivatives of a step's discrete Lagrangian at ζ.
struct Derivatives {
    /// ∂L_d/∂ζ.
    zeta: [f64; 3],
    /// ∂L_d/∂η.
    eta: [f64; 3],
    /// (∂²L_d/∂ζ², ∂²L_d/∂η∂ζ) when asked.
    second: Option<(Matrix3<f64>, Matrix3<f64>)>,
}

impl PrincipalAxes {
    /// Whether the body has weight: w ≠ 0.
    fn heavy(&self) -> bool {
        self.weight.iter().any(|&x| x != 0.0)
    }

    /// Ω = 𝕀⁻¹Π.
    pub(crate) fn velocity(&self, pi: &[f64; 3]) -> [f64; 3] {
        so3::vector(|i| pi[i] / self.moments[i])
    }

    /// ½⟨Π, 𝕀⁻¹Π⟩ + ⟨e3, R w⟩.
    pub(crate) fn energy(&self, r: &Matrix3<f64>, pi: &[f64; 3]) -> f64 {
        0.5 * so3::dot(pi, &self.velocity(pi)) + so3::dot(&r[2], &self.weight)
    }

    /// ℓ(R, Ω) over any scalar, as [`RigidSystem::lagrangian`] must give it.
    pub(crate) fn lagrangian<D: Scalar>(&self, r: &Matrix3<D>, omega: &[D; 3]) -> D {
        let kinetic = (0..3).fold(D::zero(), |t, i| t + omega[i] * omega[i] * self.moments[i]) * 0.5;
        kinetic - (0..3).fold(D::zero(), |v, i| v + r[2][i] * self.weight[i])
    }

    fn derivatives(&self, step: &PrincipalStep<'_>, zeta: &[f64; 3], with_jacobian: bool) -> Derivatives {
        let h = step.h;
        let gamma = step.gamma;
        let mut zeta_gradient = so3::vector(|i| self.moments[i] * zeta[i] / h);
        let mut eta = [0.0; 3];
        let mut second = with_jacobian.then(|| {
            let mut hzz = [[0.0; 3]; 3];
            for (i, row) in hzz.iter_mut().enumerate() {
                row[i] = self.moments[i] / h;
            }
            (hzz, [[0.0; 3]; 3])
        });
        if !self.heavy() {
            return Derivatives { zeta: zeta_gradient, eta, second };
        }
        let gamma_hat = so3::hat(&gamma);
        for &(c, at) in terms(step.rule) {
            let ch = c * h;
            let Moved { u: w, jacobian: jac, hessian } = moved(at, zeta, &self.weight, &gamma, with_jacobian);
            for k in 0..3 {
                zeta_gradient[k] -= ch * (0..3).map(|i| jac[i][k] * gamma[i]).sum::<f64>();
            }
            if !step.reduced {
                let torque = so3::cross(&w, &gamma);
                for k in 0..3 {
                    eta[k] -= ch * torque[k];
                }
            }
            if let (Some((hzz, hez)), Some(curvature)) = (&mut second, hessian) {
                for i in 0..3 {
                    for k in 0..3 {
                        hzz[i][k] -= ch * curvature[i][k];
                        if !step.reduced {
                            hez[i][k] += ch * (0..3).map(|l| gamma_hat[i][l] * jac[l][k]).sum::<f64>();
                        }
                    }
                }
            }
        }
        Derivatives { zeta: zeta_gradient, eta, second }
    }
}

/// One step's equations for a body in principal axes from a [`Point`] with step h.
pub(crate) struct PrincipalStep<'s> {
    pub form: &'s PrincipalAxes,
    pub from: &'s Point,
    pub h: f64,
    pub rule: Rule,
    /// Evaluate ℓ at R = I with no variation η (a reduced step).
    pub reduced: bool,
    /// γ = R_kᵀ e3 (e3 for a reduced step).
    gamma: [f64; 3],
}

impl<'s> PrincipalStep<'s> {
    pub fn new(form: &'s PrincipalAxes, from: &'s Point, h: f64, rule: Rule, reduced: bool) -> Self {
        let gamma = if reduced { [0.0, 0.0, 1.0] } else { [from.r[2][0], from.r[2][1], from.r[2][2]] };
        Self { form, from, h, rule, reduced, gamma }
    }

    /// The residual r_g of [`super::step`] at ζ, with its Jacobian when asked, and ∂L_d/∂η.
    fn evaluate(&self, x: &Vector3, with_jacobian: bool) -> (Vector3, Option<Jacobian3>, [f64; 3]) {
        let zeta = [x[0], x[1], x[2]];
        let d = self.form.derivatives(self, &zeta, with_jacobian);
        let t = Trivialized::new(zeta, d.zeta);
        let mu = t.momentum();
        let r = Vector3::from_fn(|i, _| mu[i] - d.eta[i] - self.from.pi[i]);
        let jacobian = d.second.map(|(hzz, hez)| {
            Jacobian3::from_fn(|i, j| t.transported(i, |l| hzz[l][j]) - hez[i][j] + t.correction(i, j))
        });
        (r, jacobian, d.eta)
    }

    /// Solves the step from the predicted ζ in `x`, which holds the solution on success, and returns
    /// the next point: Π_{k+1} = cay(ζ)ᵀ (Π_k + ∂L_d/∂η), R_{k+1} = R_k cay(ζ).
    pub fn solve(
        &self,
        x: &mut Vector3,
        options: &NewtonOptions,
        kept: &mut KeptJacobian<Fixed<3>>,
    ) -> Result<(Point, NewtonStats), NewtonFailure> {
        let scale = self.from.pi.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut eta = [0.0; 3];
        let stats = newton::solve_with(x, scale, options, kept, |x, with_jacobian| {
            let (r, j, e) = self.evaluate(x, with_jacobian);
            eta = e;
            (r, j)
        })?;
        let zeta = [x[0], x[1], x[2]];
        let f = so3::cayley(&zeta);
        let mu = so3::vector(|i| self.from.pi[i] + eta[i]);
        let pi = so3::apply_transpose(&f, &mu);
        let r = orthonormalized(&so3::mul(&self.from.r, &f));
        Ok((Point { r, pi, s: Vec::new(), p: Vec::new() }, stats))
    }
}

/// The form `system` declares, tested against its Lagrangian: `None` when it declares none, an error
/// when the form has no shape-free meaning (shape coordinates, a moment not positive and finite, a
/// weight not finite) or differs from ℓ at one of a few attitudes and velocities.
pub(crate) fn declared<S: RigidSystem>(system: &S) -> Result<Option<PrincipalAxes>, Error> {
    let Some(form) = system.principal_axes() else { return Ok(None) };
    let refuse =
        |why: String| Err(Error::Invalid { what: Input::Argument("principal_axes".into()), why: Reason::Other(why) });
    if !system.shape().is_empty() {
        return refuse("a body in principal axes has no shape coordinates, and this system has some".into());
    }
    if let Some(m) = form.moments.iter().find(|m| !(m.is_finite() && **m > 0.0)) {
        return refuse(format!("a principal moment must be positive and finite, not {m}"));
    }
    if let Some(w) = form.weight.iter().find(|w| !w.is_finite()) {
        return refuse(format!("the weight m g c must be finite, not {w}"));
    }
    let scale = form.moments.iter().chain(&form.weight).fold(0.0f64, |m, x| m.max(x.abs()));
    for (axis, omega) in
        [([0.3, -1.1, 0.7], [0.9, 0.2, -1.3]), ([-2.0, 0.5, 0.1], [-0.4, 1.7, 0.6]), ([0.0; 3], [1.0, 1.0, 1.0])]
    {
        let r = so3::cayley(&axis);
        let (expected, got) = (form.lagrangian(&r, &omega), system.lagrangian(&r, &omega, &[], &[]));
        // Written so that a NaN from the Lagrangian refuses as well.
        let agrees = (expected - got).abs() <= 1e-11 * scale;
        if !agrees {
            return refuse(format!(
                "the declared form ½⟨Ω, 𝕀Ω⟩ − ⟨e3, R w⟩ with 𝕀 = diag{:?}, w = {:?} gives {expected} at Ω = {omega:?}, R = \
                 cay({axis:?}), where the Lagrangian gives {got}",
                form.moments, form.weight
            ));
        }
    }
    Ok(Some(form))
}

#[cfg(test)]
mod tests {
    use nalgebra::{Const, U1};
    use num_dual::Dual2SVec64;

    use super::*;

    /// M(ζ) w over any scalar, as the rule's attitude gives it.
    fn moved_generic<D: Scalar>(at: At, zeta: &[D; 3], w: &[f64; 3]) -> [D; 3] {
        let w = w.map(D::from);
        match at {
            At::Start => w,
            At::End => so3::apply(&so3::cayley(zeta), &w),
            At::Middle => so3::apply(&so3::cayley(&so3::half(zeta)), &w),
        }
    }

    #[test]
    fn the_closed_form_derivatives_of_the_weight_s_position_are_those_of_dual_numbers() {
        let w = [0.3, -1.2, 4.9];
        let gamma = [0.2, -0.5, 0.84];
        for zeta in [[0.0; 3], [0.1, -0.3, 0.2], [1.5, 0.7, -2.0], [-40.0, 3.0, 12.0]] {
            for at in [At::Start, At::End, At::Middle] {
                let z = [0, 1, 2].map(|i| Dual2SVec64::<3>::from_re(zeta[i]).derivative(i));
                let m = moved_generic(at, &z, &w);
                let closed = moved(at, &zeta, &w, &gamma, true);
                let hessian = closed.hessian.unwrap();
                let mut curvature = SMatrix::<f64, 3, 3>::zeros();
                for i in 0..3 {
                    curvature += m[i].v2.unwrap_generic(Const::<3>, Const::<3>) * gamma[i];
                }
                let scale = 1.0 + w.iter().fold(0.0f64, |a, b| a.max(b.abs()));
                for i in 0..3 {
                    assert!((closed.u[i] - m[i].re).abs() < 1e-14 * scale, "{at:?} {zeta:?}: u");
                    let gradient = m[i].v1.unwrap_generic(U1, Const::<3>);
                    for k in 0..3 {
                        let (j, d) = (closed.jacobian[i][k], gradient[k]);
                        assert!((j - d).abs() < 1e-13 * scale, "{at:?} {zeta:?}: ∂u{i}/∂ζ{k} {j} against {d}");
                        let (h, d) = (hessian[i][k], curvature[(i, k)]);
                        assert!((h - d).abs() < 1e-12 * scale, "{at:?} {zeta:?}: Hessian {i}{k} {h} against {d}");
                    }
                }
            }
        }
    }
}
