//! Unreduced (+) and (−) discrete Lagrange–Dirac equations (paper §2.3.2).
//!
//! In the unconstrained case both read, in position–momentum form,
//!
//! ```text
//! (+):  q_k^+ = q_{k+1},  p_k = −D1 L_d(q_k, q_k^+),  p_{k+1} = D2 L_d(q_k, q_k^+)
//! (−):  q_{k+1}^- = q_k,  p_k = −D1 L_d(q_{k+1}^-, q_{k+1}),  p_{k+1} = D2 L_d(q_{k+1}^-, q_{k+1})
//! ```
//!
//! which is the same map (the discrete Euler–Lagrange equations): given (q_k, p_k), solve the first
//! momentum equation for q_{k+1} by Newton's method (Jacobian D1 D2 L_d), then evaluate p_{k+1}.
//! Degenerate Lagrangians are allowed as long as D1 D2 L_d is invertible.
//!
//! The unknowns are the chart increments z = q_{k+1} − q_k.

use crate::dim::{Dim, Entry};
use crate::mechanics::lagrangian::Lagrangian;
use crate::scheme::{Scheme, StepEquations};
use crate::{DiscreteLagrangian, Scalar};

/// The position–momentum discrete Euler–Lagrange map, shared by the (+) and (−) variants.
pub(crate) struct LagrangeDirac<S, Dm> {
    pub ld: DiscreteLagrangian<S>,
    /// The number of coordinates.
    pub dim: Dm,
}

impl<S: Lagrangian<Dm> + Clone, Dm: Dim> Scheme<Dm> for LagrangeDirac<S, Dm> {
    fn base(&self, q: &Dm::Array<f64>) -> Dm::Array<f64> {
        q.clone()
    }

    fn resized(&self, step: f64) -> Self {
        Self { ld: DiscreteLagrangian::new(self.ld.system.clone(), self.ld.rule, step), dim: self.dim }
    }

    fn generating<D, B>(&self, base: &Dm::Array<B>, a: &Dm::Array<D>, b: &Dm::Array<D>) -> D
    where
        D: Scalar + std::ops::Add<B, Output = D>,
        B: Entry + Copy,
    {
        self.ld.eval_in::<Dm, D, B>(base, a, b)
    }

    /// p_k + D1 L_d = 0, p_{k+1} = D2 L_d.
    fn equations(&self) -> StepEquations<Dm> {
        let dim = self.dim;
        StepEquations { sign: dim.array(|_| 1.0), advances: dim.array(|_| true), eliminable: dim.array(|_| false) }
    }

    fn increment(&self, z: &Dm::Vector) -> Dm::Array<f64> {
        self.dim.array(|i| z[i])
    }

    fn unknowns(&self, dq: &Dm::Array<f64>) -> Dm::Vector {
        self.dim.vector(|i| dq[i])
    }

    fn momenta_from_p(&self, p: &Dm::Array<f64>) -> Dm::Array<f64> {
        p.clone()
    }

    fn p_from_momenta(&self, momenta: &Dm::Array<f64>) -> Dm::Array<f64> {
        momenta.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dim::{Dynamic, Fixed};
    use crate::newton::{self, NewtonOptions};
    use crate::scheme::StepDerivatives;
    use crate::systems::PendulumChain;
    use crate::{Differentiation, Rule, System};

    /// A system of a fixed dimension seen as one of a dimension chosen at run time.
    #[derive(Clone)]
    struct AsDynamic<S, const N: usize>(S);

    impl<S: System<N>, const N: usize> Lagrangian<Dynamic> for AsDynamic<S, N> {
        fn lagrangian<D: Scalar>(&self, q: &Vec<D>, v: &Vec<D>) -> D {
            let array = |x: &Vec<D>| -> [D; N] { x.as_slice().try_into().expect("n coordinates") };
            self.0.lagrangian(&array(q), &array(v))
        }
    }

    /// `steps` steps of the scheme from (q, p), each solved by classical Newton from z = 0: the
    /// configurations and momenta after each.
    fn run<Dm: Dim, S: Lagrangian<Dm> + Clone>(
        scheme: &LagrangeDirac<S, Dm>,
        choice: Differentiation,
        q: Dm::Array<f64>,
        p: Dm::Array<f64>,
        steps: usize,
    ) -> Vec<(Vec<f64>, Vec<f64>)>
    where
        Dm::Vector: crate::dim::Column<Dim = Dm>,
    {
        let (dim, equations) = (scheme.dim, scheme.equations());
        let (mut q, mut momenta) = (q, scheme.momenta_from_p(&p));
        let zero = dim.array(|_| 0.0);
        let (derivatives, _) = StepDerivatives::new(scheme, choice, steps, &q, &zero, &momenta).unwrap();
        let mut out = Vec::new();
        for _ in 0..steps {
            let base = scheme.base(&q);
            let mut z = scheme.unknowns(&zero);
            newton::solve(&mut z, 1.0, &NewtonOptions::default(), |z| {
                let (first, mixed) = derivatives.first_or_mixed(scheme, &base, z, true);
                (equations.evaluate(&momenta, &first).residual, mixed.unwrap())
            })
            .unwrap();
            let (first, _) = derivatives.first_or_mixed(scheme, &base, &z, false);
            momenta = equations.evaluate(&momenta, &first).momenta_next;
            let dq = scheme.increment(&z);
            q = dim.array(|i| q[i] + dq[i]);
            out.push((q.as_ref().to_vec(), scheme.p_from_momenta(&momenta).as_ref().to_vec()));
        }
        out
    }

    #[test]
    fn unreduced_steps_are_alike_in_a_fixed_and_a_dynamic_dimension() {
        const N: usize = 5;
        let chain = PendulumChain::<N>::default();
        let q: [f64; N] = std::array::from_fn(|i| 0.4 * (i as f64 + 1.0).sin());
        let p: [f64; N] = std::array::from_fn(|i| 0.1 * i as f64);
        for choice in [Differentiation::Dual, Differentiation::Compiled] {
            for rule in [Rule::Midpoint, Rule::Trapezoid] {
                let fixed = LagrangeDirac { ld: DiscreteLagrangian::new(chain.clone(), rule, 0.01), dim: Fixed::<N> };
                let dynamic = LagrangeDirac {
                    ld: DiscreteLagrangian::new(AsDynamic::<_, N>(chain.clone()), rule, 0.01),
                    dim: Dynamic(N),
                };
                let a = run(&fixed, choice, q, p, 30);
                let b = run(&dynamic, choice, q.to_vec(), p.to_vec(), 30);
                let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                for (k, ((qa, pa), (qb, pb))) in a.iter().zip(&b).enumerate() {
                    assert_eq!(bits(qa), bits(qb), "{choice:?} {rule:?}: q after step {}", k + 1);
                    assert_eq!(bits(pa), bits(pb), "{choice:?} {rule:?}: p after step {}", k + 1);
                }
                // And the steps are the library's: against a run of the chain (its own predictor
                // and Newton iterates, so within the Newton tolerance).
                let problem = crate::Problem::with_momentum(0.01, 30, q, p);
                let method = crate::Method { rule, differentiation: choice, ..crate::Method::default() };
                let solution = crate::solve(&chain, &problem, &method, &crate::OutputOptions::default()).unwrap();
                let (last_q, last_p) = (solution.q.last().unwrap(), solution.p.last().unwrap());
                let (qb, pb) = b.last().unwrap();
                for i in 0..N {
                    assert!(
                        (last_q[i] - qb[i]).abs() < 1e-11,
                        "{choice:?} {rule:?}: q[{i}] {} against {}",
                        last_q[i],
                        qb[i]
                    );
                    assert!(
                        (last_p[i] - pb[i]).abs() < 1e-11,
                        "{choice:?} {rule:?}: p[{i}] {} against {}",
                        last_p[i],
                        pb[i]
                    );
                }
            }
        }
    }
}
