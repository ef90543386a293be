//! `Method::sensitivities`: the tangent map d(q_N, p_N)/d(q_0, p_0) propagated by the implicit
//! function theorem through every step, held against central finite differences of whole runs and
//! tested for symplecticity (ΦᵀJΦ = J), unreduced and reduced (with a connection), for compositions,
//! the closed-form step, and across the chart switches of an atlas.

use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, SphericalPendulum};
use ddirac::{
    solve, Composition, Connection, Differentiation, InitialMomentum, Method, OutputOptions, Problem, Rule, System,
    Variant,
};
use nalgebra::DMatrix;

/// The final state (q_N, p_N) of a run from (q0, p0), with its summary's sensitivity.
fn run<S: System<N>, const N: usize>(
    system: &S,
    method: &Method,
    (h, steps): (f64, usize),
    q0: &[f64],
    p0: &[f64],
) -> (Vec<f64>, Option<Vec<Vec<f64>>>, usize) {
    let problem = Problem::new(h, steps, q0.to_vec(), InitialMomentum::Momentum(p0.to_vec()));
    let every = OutputOptions { every: steps, ..OutputOptions::default() };
    let solution = solve(system, &problem, method, &every).expect("the run completes");
    let s = solution.summary;
    let state = s.final_q.iter().chain(&s.final_p).copied().collect();
    (state, s.sensitivity, s.chart_switches)
}

/// The tangent map by central differences of whole runs, column by column.
fn finite_differences<S: System<N>, const N: usize>(
    system: &S,
    method: &Method,
    grid: (f64, usize),
    q0: &[f64],
    p0: &[f64],
) -> DMatrix<f64> {
    let plain = Method { sensitivities: false, ..method.clone() };
    let x0: Vec<f64> = q0.iter().chain(p0).copied().collect();
    let m = x0.len();
    let mut fd = DMatrix::zeros(m, m);
    for j in 0..m {
        let delta = 1e-6 * (1.0 + x0[j].abs());
        let at = |sign: f64| {
            let mut x = x0.clone();
            x[j] += sign * delta;
            run(system, &plain, grid, &x[..m / 2], &x[m / 2..]).0
        };
        let (plus, minus) = (at(1.0), at(-1.0));
        for i in 0..m {
            fd[(i, j)] = (plus[i] - minus[i]) / (2.0 * delta);
        }
    }
    fd
}

fn matrix(rows: &[Vec<f64>]) -> DMatrix<f64> {
    DMatrix::from_fn(rows.len(), rows.len(), |i, j| rows[i][j])
}

/// max |ΦᵀJΦ − J| / max(1, max|Φ|²).
fn symplectic_defect(phi: &DMatrix<f64>) -> f64 {
    let (m, n) = (phi.nrows(), phi.nrows() / 2);
    let j = DMatrix::from_fn(m, m, |r, c| match () {
        _ if r < n && c == r + n => 1.0,
        _ if r >= n && c + n == r => -1.0,
        _ => 0.0,
    });
    (phi.transpose() * &j * phi - &j).amax() / phi.amax().powi(2).max(1.0)
}

/// The run's tangent map is symplectic to round-off and equals the finite differences to `agree`
/// relative to its largest entry; returns the number of chart switches.
fn holds<S: System<N>, const N: usize>(
    system: &S,
    method: &Method,
    grid: (f64, usize),
    q0: &[f64],
    p0: &[f64],
    agree: f64,
) -> usize {
    let method = Method { sensitivities: true, ..method.clone() };
    let (_, sensitivity, switches) = run(system, &method, grid, q0, p0);
    let phi = matrix(&sensitivity.expect("the summary has the tangent map"));
    assert_eq!(phi.nrows(), 2 * N);
    let defect = symplectic_defect(&phi);
    assert!(defect < 1e-9, "not symplectic: defect {defect:.2e}\n{phi:.4}");
    let fd = finite_differences(system, &method, grid, q0, p0);
    let apart = (&phi - &fd).amax() / phi.amax();
    assert!(apart < agree, "IFT and finite differences {apart:.2e} apart\nIFT {phi:.6}\nFD {fd:.6}");
    eprintln!("defect {defect:.1e}, IFT − FD {apart:.1e} of max |Φ| = {:.3}, {switches} switches", phi.amax());
    switches
}

const DSP_Q: [f64; 4] = [0.0, 0.6, 0.2, 0.9];
const DSP_P: [f64; 4] = [0.3, 0.1, -0.2, 0.05];

#[test]
fn double_spherical_pendulum_unreduced() {
    let method = Method { atlas: false, ..Method::default() };
    holds(&DoubleSphericalPendulum::default(), &method, (0.01, 40), &DSP_Q, &DSP_P, 1e-5);
}

#[test]
fn double_spherical_pendulum_reduced_with_a_connection_and_either_variant() {
    let connection = Connection::new(&[vec![0.3, -0.2, 0.1]]).unwrap();
    for variant in [Variant::Plus, Variant::Minus] {
        let method =
            Method { reduced: true, variant, connection: Some(connection.clone()), atlas: false, ..Method::default() };
        holds(&DoubleSphericalPendulum::default(), &method, (0.01, 40), &DSP_Q, &DSP_P, 1e-5);
    }
}

#[test]
fn compositions_and_compiled_derivatives() {
    let method = Method {
        reduced: true,
        composition: Composition::Suzuki5,
        differentiation: Differentiation::Compiled,
        atlas: false,
        ..Method::default()
    };
    holds(&DoubleSphericalPendulum::default(), &method, (0.02, 60), &DSP_Q, &DSP_P, 1e-5);
    let order6 = Method { composition: Composition::TripleJump { order: 6 }, rule: Rule::Trapezoid, ..method };
    holds(&DoubleSphericalPendulum::default(), &order6, (0.02, 30), &DSP_Q, &DSP_P, 1e-5);
}

/// The charged particle's step equations are linear: a compiled run takes its steps in closed form.
#[test]
fn the_closed_form_step() {
    let system = ChargedParticle::default();
    let problem = ChargedParticle::paper_problem(200);
    let method = Method { reduced: true, differentiation: Differentiation::Compiled, ..Method::default() };
    let q0: [f64; 4] = problem.q0.clone().try_into().unwrap();
    let p0 = match &problem.initial {
        InitialMomentum::Momentum(p) => p.clone(),
        InitialMomentum::Velocity(v) => {
            ddirac::mechanics::legendre::momentum(&system, &q0, &v.clone().try_into().unwrap()).to_vec()
        }
    };
    holds(&system, &method, (problem.step, 200), &q0, &p0, 1e-5);
}

/// The spherical pendulum over the top, through the caps of its atlas: each switch multiplies the
/// tangent map by the Jacobian of the cotangent lift, and the map comes back to the main chart.
#[test]
fn across_chart_switches() {
    let method = Method { reduced: true, ..Method::default() };
    let (q0, p0) = ([0.0, std::f64::consts::PI - 1.0], [1.4, -6.3]);
    let switches = holds(&SphericalPendulum::default(), &method, (0.01, 120), &q0, &p0, 1e-5);
    assert!(switches >= 2, "{switches} switches");
}

#[test]
fn off_by_default() {
    let (_, sensitivity, _) =
        run(&SphericalPendulum::default(), &Method::default(), (0.01, 10), &[0.0, 2.0], &[0.5, 0.1]);
    assert!(sensitivity.is_none());
}
