//! The trivializations of paper §3 (eqs. lambdadlocal … invadjointhatlambdadlocal, remarks
//! lambdaminus and hatlambdaminus): inverses, adjoint identities, equivariance, the closed forms
//! for a linear connection, and the trivialized initial data of paper §7.1.

use ddirac::mechanics::legendre;
use ddirac::systems::{ChargedParticle, TwoBody};
use ddirac::{Connection, Error, Split, System};
use ddirac_oracle::trivialization::*;
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

const N_X: usize = 3;
const N_G: usize = 2;

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(u, v)| (u - v).abs() <= tol * (1.0 + u.abs().max(v.abs())))
}

fn close_sv(a: &SplitVector, b: &SplitVector) -> bool {
    close(&a.x, &b.x, 1e-13) && close(&a.g, &b.g, 1e-13)
}

fn sv(v: &[f64]) -> SplitVector {
    SplitVector::new(v[..N_X].to_vec(), v[N_X..].to_vec())
}

/// Random inputs: K (n_g × n_x) and four vectors of Q = ℝ³ × ℝ², and one of G.
fn inputs() -> impl Strategy<Value = (Vec<f64>, Vec<Vec<f64>>, Vec<f64>)> {
    let n = N_X + N_G;
    (
        prop::collection::vec(-2.0..2.0f64, N_X * N_G),
        prop::collection::vec(prop::collection::vec(-10.0..10.0f64, n), 4),
        prop::collection::vec(-10.0..10.0f64, N_G),
    )
}

fn connection(k: &[f64]) -> Connection {
    let rows: Vec<Vec<f64>> = k.chunks(N_X).map(<[f64]>::to_vec).collect();
    Connection::new(&rows).unwrap()
}

/// K as an nalgebra matrix, for closed forms computed independently of the library.
fn matrix(k: &[f64]) -> DMatrix<f64> {
    DMatrix::from_row_slice(N_G, N_X, k)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn inverses_undo_the_maps((k, v, _) in inputs()) {
        let c = connection(&k);
        let (a, b) = (sv(&v[0]), sv(&v[1]));

        let (q0, q1) = lambda_d_inv(&c, &lambda_d(&c, &a, &b).unwrap()).unwrap();
        prop_assert!(close_sv(&q0, &a) && close_sv(&q1, &b));
        let t = TrivializedPair { q0: a.clone(), x1: b.x.clone(), g1: b.g.clone() };
        let back = lambda_d(&c, &lambda_d_inv(&c, &t).unwrap().0, &lambda_d_inv(&c, &t).unwrap().1).unwrap();
        prop_assert!(close(&back.g1, &t.g1, 1e-13));

        let (q0, q1) = lambda_tilde_inv(&c, &lambda_tilde(&c, &a, &b).unwrap()).unwrap();
        prop_assert!(close_sv(&q0, &a) && close_sv(&q1, &b));

        let (q, p) = lambda_hat_inv(&c, &lambda_hat(&c, &a, &b).unwrap()).unwrap();
        prop_assert!(close_sv(&q, &a) && close_sv(&p, &b));

        let (p, q) = lambda_check_inv(&c, &lambda_check(&c, &b, &a).unwrap()).unwrap();
        prop_assert!(close_sv(&q, &a) && close_sv(&p, &b));

        let (p0, p1) = lambda_d_adjoint(&c, &lambda_d_adjoint_inv(&c, &a, &b).unwrap()).unwrap();
        prop_assert!(close_sv(&p0, &a) && close_sv(&p1, &b));

        let (p, q) = lambda_hat_adjoint(&c, &lambda_hat_adjoint_inv(&c, &a, &b).unwrap()).unwrap();
        prop_assert!(close_sv(&p, &a) && close_sv(&q, &b));

        let (q, p) = lambda_check_adjoint(&c, &lambda_check_adjoint_inv(&c, &a, &b).unwrap()).unwrap();
        prop_assert!(close_sv(&q, &a) && close_sv(&p, &b));
    }

    /// ⟨λ*(α), v⟩ = ⟨α, λ(v)⟩ for λ_d, λ̂_d and λ̌_d.
    #[test]
    fn adjoints_satisfy_the_pairing_identity((k, v, _) in inputs()) {
        let c = connection(&k);
        let (q0, q1) = (sv(&v[0]), sv(&v[1]));
        let (a, b) = (sv(&v[2]), sv(&v[3]));
        let tol = 1e-11 * (1.0 + v.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()))).powi(2);

        let alpha = TrivializedPairDual { p0: a.clone(), w1: b.x.clone(), r1: b.g.clone() };
        let (s0, s1) = lambda_d_adjoint(&c, &alpha).unwrap();
        let t = lambda_d(&c, &q0, &q1).unwrap();
        let rhs = alpha.p0.dot(&t.q0) + dot(&alpha.w1, &t.x1) + dot(&alpha.r1, &t.g1);
        prop_assert!((s0.dot(&q0) + s1.dot(&q1) - rhs).abs() <= tol);

        let beta = TrivializedCovectorDual { p: a.clone(), x: b.x.clone(), xi: b.g.clone() };
        let (s_p, s_q) = lambda_hat_adjoint(&c, &beta).unwrap();
        let t = lambda_hat(&c, &q0, &q1).unwrap();
        let rhs = beta.p.dot(&t.q) + dot(&beta.x, &t.w) + dot(&beta.xi, &t.mu);
        prop_assert!((s_p.dot(&q0) + s_q.dot(&q1) - rhs).abs() <= tol);

        let gamma = TrivializedCovectorMinusDual { x: b.x.clone(), xi: b.g.clone(), p: a.clone() };
        let (s_q, s_p) = lambda_check_adjoint(&c, &gamma).unwrap();
        let t = lambda_check(&c, &q1, &q0).unwrap();
        let rhs = dot(&gamma.x, &t.w) + dot(&gamma.xi, &t.mu) + gamma.p.dot(&t.q);
        prop_assert!((s_q.dot(&q1) + s_p.dot(&q0) - rhs).abs() <= tol);
    }

    /// λ_d(a·q0, a·q1) = a·λ_d(q0, q1) with a·(q0, x1, g1) = (a + q0, x1, g1); likewise λ̂_d and λ̃_d.
    #[test]
    fn trivializations_are_equivariant((k, v, a) in inputs()) {
        let c = connection(&k);
        let (q0, q1, p) = (sv(&v[0]), sv(&v[1]), sv(&v[2]));
        let moved = lambda_d(&c, &q0.translate(&a), &q1.translate(&a)).unwrap();
        let expected = lambda_d(&c, &q0, &q1).unwrap().act(&a);
        prop_assert!(close_sv(&moved.q0, &expected.q0) && close(&moved.g1, &expected.g1, 1e-13));
        prop_assert_eq!(&moved.x1, &expected.x1);

        let moved = lambda_hat(&c, &q0.translate(&a), &p).unwrap();
        let fixed = lambda_hat(&c, &q0, &p).unwrap();
        prop_assert!(close_sv(&moved.q, &q0.translate(&a)) && moved.w == fixed.w && moved.mu == fixed.mu);

        let moved = lambda_tilde(&c, &q0.translate(&a), &q1.translate(&a)).unwrap();
        let fixed = lambda_tilde(&c, &q0, &q1).unwrap();
        prop_assert!(close(&moved.g0, &fixed.g0, 1e-13) && close_sv(&moved.q1, &q1.translate(&a)));
    }

    /// The closed forms of note 2: ω_d = g1 − g0 − K(x1 − x0), w = p_x + Kᵀp_g, μ = p_g,
    /// λ_d* (p0, w1, r1) = ((p0x + Kᵀr1, p0g − r1), (w1 − Kᵀr1, r1)), λ̂_d*(p, x, ξ) = (p, (x, Kx + ξ)).
    #[test]
    fn closed_forms_with_a_matrix((k, v, _) in inputs()) {
        let (c, km) = (connection(&k), matrix(&k));
        let col = |s: &[f64]| DVector::from_column_slice(s);
        let (q0, q1, r) = (sv(&v[0]), sv(&v[1]), sv(&v[2]));
        let omega = col(&q1.g) - col(&q0.g) - &km * (col(&q1.x) - col(&q0.x));
        prop_assert!(close(&lambda_d(&c, &q0, &q1).unwrap().g1, omega.as_slice(), 1e-13));
        let omega_minus = col(&q0.g) - col(&q1.g) - &km * (col(&q0.x) - col(&q1.x));
        prop_assert!(close(&lambda_tilde(&c, &q0, &q1).unwrap().g0, omega_minus.as_slice(), 1e-13));

        let t = lambda_hat(&c, &q0, &r).unwrap();
        let w = col(&r.x) + km.transpose() * col(&r.g);
        prop_assert!(close(&t.w, w.as_slice(), 1e-13) && t.mu == r.g);

        let alpha = TrivializedPairDual { p0: q0.clone(), w1: q1.x.clone(), r1: r.g.clone() };
        let (s0, s1) = lambda_d_adjoint(&c, &alpha).unwrap();
        let ktr = km.transpose() * col(&r.g);
        prop_assert!(close(&s0.x, (col(&q0.x) + &ktr).as_slice(), 1e-13));
        prop_assert!(close(&s0.g, (col(&q0.g) - col(&r.g)).as_slice(), 1e-13));
        prop_assert!(close(&s1.x, (col(&q1.x) - &ktr).as_slice(), 1e-13) && s1.g == r.g);

        let beta = TrivializedCovectorDual { p: q0.clone(), x: q1.x.clone(), xi: r.g.clone() };
        let (_, s_q) = lambda_hat_adjoint(&c, &beta).unwrap();
        prop_assert!(close(&s_q.g, (&km * col(&q1.x) + col(&r.g)).as_slice(), 1e-13));
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(u, v)| u * v).sum()
}

/// Paper §7.1: ((q0, θ0), w0, μ0) = λ̂_d((q0, θ0), (p0, (p_θ)0)) = ((0, 0), (1, 0, 1), 1) with K = 0.
#[test]
fn charged_particle_initial_data_of_section_7_1() {
    let split = Split::new(&ChargedParticle::default().coordinates());
    let q0 = SplitVector::from_full(&split, &[0.0; 4]).unwrap();
    let p0 = SplitVector::from_full(&split, &[1.0, 0.0, 1.0, 1.0]).unwrap();
    let t = lambda_hat(&Connection::zero(3, 1), &q0, &p0).unwrap();
    assert_eq!((t.q.x, t.q.g, t.w, t.mu), (vec![0.0; 3], vec![0.0], vec![1.0, 0.0, 1.0], vec![1.0]));
}

/// Two bodies with the centre-of-mass connection K = −m2/M · I: w = p_r − (m2/M) p_{r1} is the
/// relative momentum m1 m2/M · ṙ, and μ = p_{r1} the total momentum m1 ṙ1 + m2 ṙ2.
#[test]
fn two_body_momenta_trivialize_to_relative_and_total_momentum() {
    let system = TwoBody::default();
    let split = Split::new(&system.coordinates());
    let c = system.centre_of_mass_connection().unwrap();
    let (q, v) = ([0.3, -0.2, 1.0, 0.5], [0.25, -0.5, 0.7, 1.1]);
    let p = legendre::momentum(&system, &q, &v);
    let t = lambda_hat(&c, &SplitVector::from_full(&split, &q).unwrap(), &SplitVector::from_full(&split, &p).unwrap())
        .unwrap();
    let (m1, m2) = (system.m1, system.m2);
    let reduced_mass = m1 * m2 / (m1 + m2);
    let total = [m1 * v[0] + m2 * (v[0] + v[2]), m1 * v[1] + m2 * (v[1] + v[3])];
    assert!(close(&t.w, &[reduced_mass * v[2], reduced_mass * v[3]], 1e-15), "w = {:?}", t.w);
    assert!(close(&t.mu, &total, 1e-15), "mu = {:?}", t.mu);
    // and by hand for p = (1, 2, 3, 4): w = (3, 4) + Kᵀ(1, 2) = (3 − 1/3, 4 − 2/3)
    let t = lambda_hat(&c, &SplitVector::zeros(2, 2), &SplitVector::from_full(&split, &[1.0, 2.0, 3.0, 4.0]).unwrap())
        .unwrap();
    assert!(close(&t.w, &[8.0 / 3.0, 10.0 / 3.0], 1e-15) && t.mu == vec![1.0, 2.0]);
}

#[test]
fn wrong_sizes_are_reported() {
    let c = Connection::zero(N_X, N_G);
    let good = SplitVector::zeros(N_X, N_G);
    let bad = SplitVector::zeros(N_X + 1, N_G);
    assert!(matches!(lambda_d(&c, &good, &bad), Err(Error::Size { expected: 3, found: 4, .. })));
    assert!(matches!(lambda_hat(&c, &bad, &good), Err(Error::Size { .. })));
    let t = TrivializedCovector { q: good.clone(), w: vec![0.0; N_X], mu: vec![0.0] };
    assert!(matches!(lambda_hat_inv(&c, &t), Err(Error::Size { expected: 2, found: 1, .. })));
    let split = Split::new(&ChargedParticle::default().coordinates());
    assert!(matches!(SplitVector::from_full(&split, &[0.0; 3]), Err(Error::Size { .. })));
}
