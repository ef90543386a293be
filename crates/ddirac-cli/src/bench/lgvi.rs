//! A hand-written Lie group variational integrator of the free rigid body (Lee, Leok & McClamroch):
//! the baseline of the `rigid` group. With J_d = ½ tr(J) I − J, a step solves
//!
//! ```text
//! h Π_k^ = F_k J_d − J_d F_kᵀ        for F_k = (I + f̂)(I − f̂)⁻¹ (Cayley, f ∈ ℝ³):
//! G(f) = h Π_k + h Π_k × f + h (Π_k · f) f − 2 J f = 0
//! ```
//!
//! by Newton's method on f (Jacobian h Π̂_k + h (f Π_kᵀ + (Π_k · f) I) − 2 J, from the previous step's
//! f), then Π_{k+1} = F_kᵀ Π_k and R_{k+1} = R_k F_k. Plain f64, fixed size, no allocation: what a user
//! would write by hand for this one system.

type M3 = [[f64; 3]; 3];

/// The state (R, Π) of the free body.
#[derive(Debug, Clone, Copy)]
pub struct State {
    /// Attitude, body to space.
    pub r: M3,
    /// Body angular momentum.
    pub pi: [f64; 3],
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The solution x of the 3 × 3 system a x = b (Cramer's rule).
fn solve(a: &M3, b: [f64; 3]) -> [f64; 3] {
    let det = dot(a[0], cross(a[1], a[2]));
    let column = |k: usize| [a[0][k], a[1][k], a[2][k]];
    let (c0, c1, c2) = (column(0), column(1), column(2));
    [dot(b, cross(c1, c2)) / det, dot(c0, cross(b, c2)) / det, dot(c0, cross(c1, b)) / det]
}

/// (I + f̂)(I − f̂)⁻¹ = I + 2/(1 + |f|²) (f̂ + f̂²).
fn cayley(f: [f64; 3]) -> M3 {
    let c = 2.0 / (1.0 + dot(f, f));
    let k = [[0.0, -f[2], f[1]], [f[2], 0.0, -f[0]], [-f[1], f[0], 0.0]];
    let mut out = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let k2: f64 = (0..3).map(|l| k[i][l] * k[l][j]).sum();
            out[i][j] = f64::from(u8::from(i == j)) + c * (k[i][j] + k2);
        }
    }
    out
}

/// `steps` steps of h from `state` for the principal moments `inertia`; Newton to `tolerance`.
pub fn integrate(inertia: [f64; 3], state: State, h: f64, steps: usize, tolerance: f64) -> State {
    let State { mut r, mut pi } = state;
    let mut f = [0.0; 3];
    for _ in 0..steps {
        for _ in 0..50 {
            let pf = dot(pi, f);
            let pxf = cross(pi, f);
            let g = [0, 1, 2].map(|i| h * pi[i] + h * pxf[i] + h * pf * f[i] - 2.0 * inertia[i] * f[i]);
            let mut jac = [[0.0; 3]; 3];
            for i in 0..3 {
                for j in 0..3 {
                    let hat = match (i, j) {
                        (0, 1) => -pi[2],
                        (0, 2) => pi[1],
                        (1, 0) => pi[2],
                        (1, 2) => -pi[0],
                        (2, 0) => -pi[1],
                        (2, 1) => pi[0],
                        _ => 0.0,
                    };
                    let diagonal = if i == j { h * pf - 2.0 * inertia[i] } else { 0.0 };
                    jac[i][j] = h * hat + h * f[i] * pi[j] + diagonal;
                }
            }
            let d = solve(&jac, g);
            f = [0, 1, 2].map(|i| f[i] - d[i]);
            if d.iter().fold(0.0f64, |m, x| m.max(x.abs()))
                <= tolerance * (1.0 + f.iter().fold(0.0f64, |m, x| m.max(x.abs())))
            {
                break;
            }
        }
        let big_f = cayley(f);
        pi = [0, 1, 2].map(|j| (0..3).map(|i| big_f[i][j] * pi[i]).sum());
        let mut next = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                next[i][j] = (0..3).map(|l| r[i][l] * big_f[l][j]).sum();
            }
        }
        r = next;
    }
    State { r, pi }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Euler's equations by RK4, for the test of the baseline.
    fn reference(inertia: [f64; 3], pi0: [f64; 3], t: f64, n: usize) -> [f64; 3] {
        let field = |p: [f64; 3]| cross(p, [0, 1, 2].map(|i| p[i] / inertia[i]));
        let h = t / n as f64;
        let mut p = pi0;
        for _ in 0..n {
            let k1 = field(p);
            let k2 = field([0, 1, 2].map(|i| p[i] + h / 2.0 * k1[i]));
            let k3 = field([0, 1, 2].map(|i| p[i] + h / 2.0 * k2[i]));
            let k4 = field([0, 1, 2].map(|i| p[i] + h * k3[i]));
            p = [0, 1, 2].map(|i| p[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
        }
        p
    }

    #[test]
    fn the_baseline_converges_at_order_2_and_keeps_r_orthogonal() {
        let inertia = [1.0, 2.0, 3.0];
        let pi0 = [0.3, 2.0, 0.5];
        let exact = reference(inertia, pi0, 5.0, 50_000);
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let error = |h: f64| {
            let end = integrate(inertia, State { r: identity, pi: pi0 }, h, (5.0 / h).round() as usize, 1e-14);
            (0..3).map(|i| (end.pi[i] - exact[i]).abs()).fold(0.0, f64::max)
        };
        let (coarse, fine) = (error(0.02), error(0.01));
        let order = (coarse / fine).log2();
        assert!((order - 2.0).abs() < 0.1, "order {order}: errors {coarse:e}, {fine:e}");
        let end = integrate(inertia, State { r: identity, pi: pi0 }, 0.01, 10_000, 1e-14);
        for i in 0..3 {
            for j in 0..3 {
                let rtr: f64 = (0..3).map(|l| end.r[l][i] * end.r[l][j]).sum();
                let off = (rtr - f64::from(u8::from(i == j))).abs();
                assert!(off < 1e-12, "RᵀR − I has an entry {off:e} after 10⁴ steps");
            }
        }
    }
}
