//! Bodies in principal axes (`RigidSystem::principal_axes`): their steps solved with closed-form
//! derivatives against the same bodies differentiated by dual numbers (a wrapper that does not
//! declare the form), for every rule, composition and both reductions; and the declarations that
//! are refused (a form that is not the Lagrangian's, shape coordinates, a moment that is not positive).

use ddirac::rigid::so3::{self, Matrix3};
use ddirac::rigid::{solve_rigid, PrincipalAxes, RigidInitial, RigidProblem, RigidSummary, RigidSystem, Symmetry};
use ddirac::systems::RigidBody;
use ddirac::{Composition, Coordinate, Error, Input, Method, Rule, Scalar};

/// The body with the same Lagrangian and symmetry and no declared form: differentiated by dual numbers.
struct Undeclared(RigidBody);

impl RigidSystem for Undeclared {
    fn lagrangian<D: Scalar>(&self, r: &Matrix3<D>, omega: &[D; 3], s: &[D], v: &[D]) -> D {
        self.0.lagrangian(r, omega, s, v)
    }

    fn symmetry(&self) -> Symmetry {
        self.0.symmetry()
    }
}

/// A body that declares a form of its own, over a Lagrangian and shape of another body.
struct Declaring {
    body: RigidBody,
    form: PrincipalAxes,
    shape: bool,
}

impl RigidSystem for Declaring {
    fn shape(&self) -> Vec<Coordinate> {
        if self.shape {
            vec![Coordinate::shape("s")]
        } else {
            Vec::new()
        }
    }

    fn lagrangian<D: Scalar>(&self, r: &Matrix3<D>, omega: &[D; 3], s: &[D], v: &[D]) -> D {
        let rotor = if self.shape { v[0] * v[0] * 0.5 + s[0] * 0.0 } else { D::zero() };
        self.body.lagrangian(r, omega, &[], &[]) + rotor
    }

    fn symmetry(&self) -> Symmetry {
        self.body.symmetry()
    }

    fn principal_axes(&self) -> Option<PrincipalAxes> {
        Some(self.form)
    }
}

fn run<S: RigidSystem>(system: &S, r0: Matrix3<f64>, pi0: [f64; 3], method: &Method) -> RigidSummary {
    let problem = RigidProblem::new(0.02, 300, r0, RigidInitial::Momentum { pi: pi0, p: vec![] });
    solve_rigid(system, problem, method, 300).unwrap().summary
}

fn gap(a: &RigidSummary, b: &RigidSummary) -> f64 {
    let r = (0..3).flat_map(|i| (0..3).map(move |j| (i, j))).map(|(i, j)| (a.final_r[i][j] - b.final_r[i][j]).abs());
    let pi = (0..3).map(|i| (a.final_pi[i] - b.final_pi[i]).abs());
    r.chain(pi).fold(0.0, f64::max)
}

#[test]
fn closed_form_steps_are_the_dual_number_steps_to_round_off() {
    let heavy = RigidBody { inertia: [1.0, 1.5, 0.8], m: 1.2, g: 9.81, c: [0.05, -0.03, 0.2] };
    let free = RigidBody::free(1.0, 2.0, 3.0);
    let r0 = so3::cayley(&[0.9, -0.4, 0.3]);
    for (body, pi0) in [(heavy, [0.5, -0.3, 2.0]), (free, [0.05, 2.0, 0.05])] {
        for rule in [Rule::Left, Rule::Right, Rule::Midpoint, Rule::Trapezoid] {
            let symmetric = matches!(rule, Rule::Midpoint | Rule::Trapezoid);
            let compositions: &[Composition] = if symmetric {
                &[Composition::Basic, Composition::TripleJump { order: 4 }]
            } else {
                &[Composition::Basic]
            };
            for &composition in compositions {
                for reduced in [false, true].into_iter().filter(|&r| !r || !body.is_heavy()) {
                    let method = Method { rule, composition, reduced, ..Method::default() };
                    let (closed, dual) = (run(&body, r0, pi0, &method), run(&Undeclared(body), r0, pi0, &method));
                    let gap = gap(&closed, &dual);
                    assert!(
                        gap < 1e-11,
                        "{rule:?} {composition:?} reduced {reduced}, heavy {}: {gap:e}",
                        body.is_heavy()
                    );
                    let energy =
                        (closed.energy.max - dual.energy.max).abs() + (closed.energy.mean - dual.energy.mean).abs();
                    assert!(energy < 1e-11 * closed.energy.initial.abs().max(1.0), "{rule:?}: energy {energy:e}");
                    assert_eq!(closed.momentum_map.initial, dual.momentum_map.initial);
                }
            }
        }
    }
}

fn refused(system: &Declaring) -> String {
    let problem = RigidProblem::new(
        0.01,
        10,
        so3::identity(),
        RigidInitial::Momentum { pi: [0.1, 0.2, 0.3], p: vec![0.0; usize::from(system.shape)] },
    );
    match solve_rigid(system, problem, &Method::default(), 1) {
        Err(e @ Error::Invalid { what: Input::Argument(_), .. }) => e.to_string(),
        other => panic!("not refused: {other:?}"),
    }
}

#[test]
fn a_declared_form_that_is_not_the_lagrangian_is_refused() {
    let body = RigidBody { inertia: [1.0, 1.5, 0.8], m: 1.0, g: 9.81, c: [0.0, 0.0, 0.2] };
    let right = PrincipalAxes { moments: body.inertia, weight: [0.0, 0.0, 9.81 * 0.2] };
    // The right form runs, and as the dual numbers do.
    let ok = Declaring { body, form: right, shape: false };
    let r0 = so3::cayley(&[0.2, 0.1, 0.0]);
    let gap = gap(
        &run(&ok, r0, [0.3, 0.1, 1.0], &Method::default()),
        &run(&Undeclared(body), r0, [0.3, 0.1, 1.0], &Method::default()),
    );
    assert!(gap < 1e-11, "{gap:e}");
    // A moment off by 1e-6 relative, a weight at the wrong place, a weight of the wrong sign.
    let wrong_moment = PrincipalAxes { moments: [1.0, 1.5, 0.8 * (1.0 + 1e-6)], ..right };
    let wrong_place = PrincipalAxes { weight: [9.81 * 0.2, 0.0, 0.0], ..right };
    let wrong_sign = PrincipalAxes { weight: [0.0, 0.0, -9.81 * 0.2], ..right };
    for form in [wrong_moment, wrong_place, wrong_sign] {
        let text = refused(&Declaring { body, form, shape: false });
        assert!(text.contains("principal_axes") && text.contains("where the Lagrangian gives"), "{text}");
    }
}

#[test]
fn a_declared_form_with_shape_or_a_moment_not_positive_is_refused() {
    let body = RigidBody::free(1.0, 2.0, 3.0);
    let right = body.principal_axes().unwrap();
    let text = refused(&Declaring { body, form: right, shape: true });
    assert!(text.contains("no shape coordinates"), "{text}");
    for moment in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let form = PrincipalAxes { moments: [1.0, moment, 3.0], ..right };
        let text = refused(&Declaring { body, form, shape: false });
        assert!(text.contains("positive and finite"), "{moment}: {text}");
    }
    let form = PrincipalAxes { weight: [0.0, f64::NAN, 0.0], ..right };
    assert!(refused(&Declaring { body, form, shape: false }).contains("finite"));
}
