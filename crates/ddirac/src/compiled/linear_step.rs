//! The closed-form step: step equations that are linear in their unknowns, solved by one compiled
//! elimination per step instead of Newton's method.
//!
//! A step solves r(z) = 0 with r_i = ∂f/∂a_i + s_i m_i, the derivatives of the generating function f
//! taken at (base, 0, z) and m the momenta of step k (see the schemes). For a reduced scheme the rows
//! of the group unknowns γ are momentum-map equations, and μ is known: it is conserved. When those
//! rows are affine in γ (the Lagrangian is quadratic in the group velocities, as a kinetic energy
//! is), they give γ in closed form,
//!
//! ```text
//! γ*(z_x) = −H⁻¹ r_γ(z_x, γ = 0),      H = ∂r_γ/∂γ (independent of γ),
//! ```
//!
//! and the shape rows become R(z_x) = r_x(z_x, γ*(z_x)): γ is eliminated, as paper §7 suggests. When R
//! is affine in z_x too (the charged particle: the magnetic term is linear in the velocity once μ is
//! known), its Jacobian J = ∂R/∂z_x does not depend on z_x and the step is
//!
//! ```text
//! z_x = −J⁻¹ R(0),      γ = γ*(z_x),
//! ```
//!
//! with no iteration. Unreduced schemes have no γ: their step is closed-form when r is affine in z.
//!
//! Both conditions are decided exactly, on the traced graph: a derivative that reads no unknown is
//! constant in them. The eliminations are done on the graph too (Gaussian elimination with the pivot
//! order that partial pivoting picks at the first step, kept from then on), where the structure of
//! H and J folds away: what remains is the arithmetic a hand-written step would do. One program
//! (native code with the `jit` feature) maps (base, m) to z, the value of f, the next momenta (∂f/∂b where they advance) and the residual r(z) of
//! the full equations, which the stepper checks against the Newton tolerance: a step whose fixed
//! pivot order has become poor fails that test and is finished by Newton's method.

use std::sync::{Mutex, PoisonError};

use super::derivative::{directional, pair_graph, PairGraph};
use super::executable::Executable;
use super::graph::{Graph, Node};
use super::{CompileError, Instruction, Program, Traced};
use crate::dim::{Dim, Fixed};
use rustc_hash::FxHashMap;

/// Derivatives that vary by less than this, relative, over unit moves of the unknowns count as
/// constant (see [`constant_in`]); the residual test of every step guards the rest.
const CONSTANT_TOLERANCE: f64 = 1e-11;

/// A pivot below this fraction of the largest entry of its matrix at the first step counts as zero.
const PIVOT_TOLERANCE: f64 = 1e-14;

/// The compiled closed-form step of linear step equations, for n coordinates.
pub struct LinearStep<Dm: Dim> {
    dim: Dm,
    program: std::sync::Arc<Executable>,
    /// Instructions of the step program.
    pub instructions: usize,
}

/// What [`LinearStep::solve`] returns: the unknowns and what the step needs at them.
#[derive(Debug, Clone)]
pub struct LinearSolution<Dm: Dim> {
    /// The unknowns z (shape increments and γ).
    pub z: Dm::Array<f64>,
    /// f at (base, 0, z): the discrete energy.
    pub value: f64,
    /// The residual r(z) of the full step equations.
    pub residual: Dm::Array<f64>,
    /// The momenta of the next step: ∂f/∂b at (base, 0, z) where they advance, m elsewhere.
    pub momenta_next: Dm::Array<f64>,
}

impl<const N: usize> Copy for LinearSolution<Fixed<N>> {}

impl<Dm: Dim> LinearSolution<Dm> {
    /// ‖r(z)‖∞ if everything is finite and it is at most `threshold` (Newton's residual test).
    #[inline]
    pub fn solves(&self, threshold: f64) -> Option<f64> {
        // Without a branch per entry: this runs every step.
        let finite = |values: &[f64]| values.iter().fold(true, |all, v| all & v.is_finite());
        let finite = finite(self.z.as_ref()) & finite(self.momenta_next.as_ref()) & self.value.is_finite();
        // The largest |r_i|, NaN entries skipped (as `f64::max` skips them), one comparison each.
        let residual = self.residual.as_ref().iter().fold(0.0f64, |m, r| if r.abs() > m { r.abs() } else { m });
        (finite & (residual <= threshold)).then_some(residual)
    }
}

impl<Dm: Dim> std::fmt::Debug for LinearStep<Dm> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LinearStep").field("instructions", &self.instructions).finish()
    }
}

impl<Dm: Dim> LinearStep<Dm> {
    /// Traces the generating function `f` at (`base`, 0, `z`) with momenta `momenta` and compiles its
    /// closed-form step, for residual signs `sign`, advancing momenta `advances` and group unknowns
    /// `eliminable` (see the module
    /// documentation). [`Refusal::NotAffine`] when the equations are not linear in the unknowns
    /// (after eliminating γ), [`Refusal::AtThisPoint`] when a pivot or an output is zero or not
    /// finite at this first step (or the trace has guards).
    #[allow(clippy::too_many_arguments)]
    pub fn new<F>(
        dim: Dm,
        f: F,
        base: &Dm::Array<f64>,
        z: &Dm::Array<f64>,
        momenta: &[f64],
        sign: &[f64],
        advances: &[bool],
        eliminable: &[bool],
    ) -> Result<Result<Self, Refusal>, CompileError>
    where
        F: Fn(&Dm::Array<Traced>, &Dm::Array<Traced>, &Dm::Array<Traced>) -> Traced,
    {
        let program = match step_program(pair_graph(dim, f, base, z, false)?, momenta, sign, advances, eliminable) {
            Ok(program) => program,
            Err(refusal) => return Ok(Err(refusal)),
        };
        let instructions = program.instructions.len();
        Ok(Ok(Self { dim, program: super::cache::shared(&program)?, instructions }))
    }

    /// The step from chart base `base` with momenta `momenta`. The momenta that do not advance are
    /// constants of the compiled step (a scheme conserves them): only their values given to
    /// [`LinearStep::new`] are used.
    #[inline(always)]
    pub fn solve(&self, base: &Dm::Array<f64>, momenta: &Dm::Array<f64>) -> LinearSolution<Dm> {
        let (dim, n) = (self.dim, self.dim.n());
        dim.scratch(
            #[inline(always)]
            |buffer| {
                let (inputs, outputs) = buffer.split_at_mut(2 * n);
                inputs[..n].copy_from_slice(base.as_ref());
                inputs[n..].copy_from_slice(momenta.as_ref());
                let outputs = &mut outputs[..1 + 3 * n];
                self.program.call(inputs, outputs);
                LinearSolution {
                    z: dim.array(|i| outputs[i]),
                    value: outputs[n],
                    residual: dim.array(|i| outputs[n + 1 + i]),
                    momenta_next: dim.array(|i| outputs[2 * n + 1 + i]),
                }
            },
        )
    }
}

/// Why a step has no closed form.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refusal {
    /// The step equations are not affine in the unknowns (after eliminating γ): a property of the
    /// function, wherever it is traced.
    NotAffine,
    /// A guard, a (nearly) zero pivot or a value that is not finite at the point of the trace.
    AtThisPoint,
}

/// The step equations found not affine ([`Refusal::NotAffine`]), by their compiled derivatives (the
/// programs with h and the parameters as runtime inputs), the values of those inputs, and the
/// conserved momenta, signs and roles the closed form was sought with: a run of the same equations
/// does not seek it again (it costs as much as tracing them, about a third of a run's set-up).
static NOT_AFFINE: Mutex<Option<FxHashMap<EquationsKey, ()>>> = Mutex::new(None);

/// Step equations as [`NOT_AFFINE`] knows them: their compiled derivatives and the bits of the
/// values they were sought with.
pub(crate) type EquationsKey = (Program, Vec<u64>);

/// How many verdicts [`NOT_AFFINE`] keeps before it starts anew.
const NOT_AFFINE_CAPACITY: usize = 64;

/// Whether the equations of `key` were found not affine.
pub(crate) fn known_not_affine(key: &EquationsKey) -> bool {
    let guard = NOT_AFFINE.lock().unwrap_or_else(PoisonError::into_inner);
    guard.as_ref().is_some_and(|found| found.contains_key(key))
}

/// Records that the equations of `key` are not affine.
pub(crate) fn remember_not_affine(key: EquationsKey) {
    let mut guard = NOT_AFFINE.lock().unwrap_or_else(PoisonError::into_inner);
    let found = guard.get_or_insert_with(FxHashMap::default);
    if found.len() >= NOT_AFFINE_CAPACITY {
        found.clear();
    }
    found.insert(key, ());
}

/// The program of the closed-form step: inputs (base, m), outputs (z, f, r, m').
fn step_program(
    pair: PairGraph,
    momenta: &[f64],
    sign: &[f64],
    advances: &[bool],
    eliminable: &[bool],
) -> Result<Program, Refusal> {
    let n = momenta.len();
    let PairGraph { mut graph, value, da, db, guards, .. } = pair;
    // A guarded trace holds on part of the space only; the closed form would have to check its guards.
    if !guards.is_empty() {
        return Err(Refusal::AtThisPoint);
    }
    let g = &mut graph;
    // Momenta that do not advance (μ) are conserved exactly: constants of the run.
    let m: Vec<Node> = (0..n)
        .map(|i| {
            let input = g.input(momenta[i]);
            if advances[i] {
                input
            } else {
                g.constant(momenta[i])
            }
        })
        .collect();
    let r: Vec<Node> = (0..n)
        .map(|i| {
            let s = g.constant(sign[i]);
            let term = g.mul(s, m[i]);
            g.add(da[i], term)
        })
        .collect();
    let (group, shape): (Vec<usize>, Vec<usize>) = (0..n).partition(|&i| eliminable[i]);
    let pick = |nodes: &[Node], at: &[usize]| -> Vec<Node> { at.iter().map(|&i| nodes[i]).collect() };
    let zero = g.constant(0.0);
    let inputs = 3 * n;

    // γ*(z_x) from the momentum-map rows, when they are affine in γ.
    let gamma = solve_affine(g, &pick(&r, &group), &group, n)?;

    // The shape rows with γ eliminated, when they are affine in z_x.
    let mut replace = vec![None; inputs];
    for (&e, &gamma_e) in group.iter().zip(&gamma) {
        replace[n + e] = Some(gamma_e);
    }
    let r_shape = g.replace_inputs(&pick(&r, &shape), &replace);
    let z_shape = solve_affine(g, &r_shape, &shape, n)?;

    // z, and f, r, ∂f/∂b there.
    let mut z = vec![zero; n];
    let mut replace = vec![None; inputs];
    for (&x, &z_x) in shape.iter().zip(&z_shape) {
        (z[x], replace[n + x]) = (z_x, Some(z_x));
    }
    for (&e, gamma_e) in group.iter().zip(g.replace_inputs(&gamma, &replace)) {
        z[e] = gamma_e;
    }
    let mut replace = vec![None; inputs];
    for (slot, &z_i) in replace[n..2 * n].iter_mut().zip(&z) {
        *slot = Some(z_i);
    }
    let at_z: Vec<Node> = std::iter::once(value).chain(r).chain(db).collect();
    let at_z = g.replace_inputs(&at_z, &replace);
    let momenta_next = (0..n).map(|i| if advances[i] { at_z[1 + n + i] } else { m[i] });
    let outputs: Vec<Node> = z.into_iter().chain(at_z[..=n].iter().copied()).chain(momenta_next).collect();
    if !outputs.iter().all(|&o| graph.value(o).is_finite()) {
        return Err(Refusal::AtThisPoint);
    }
    without_unknowns(graph.program(&outputs), n).ok_or(Refusal::AtThisPoint)
}

/// `program` with its inputs (base, b, m) renumbered to (base, m): the solution reads no b.
fn without_unknowns(mut program: Program, n: usize) -> Option<Program> {
    for instruction in &mut program.instructions {
        if let Instruction::Input(k) = instruction {
            match (*k as usize) / n {
                0 => {}
                1 => return None,
                _ => *k -= n as u32,
            }
        }
    }
    program.inputs -= n;
    Some(program)
}

/// The solution of `rows` = 0 for the unknowns b_i, i ∈ `unknowns` (inputs n + i of the graph), when
/// the rows are affine in them: −J⁻¹ rows(b_i = 0), with J = ∂rows/∂b_i constant in them. Other
/// unknowns the rows read stay variables of the result. `None` if the rows are not affine in the
/// unknowns or J is singular at the build point.
fn solve_affine(g: &mut Graph, rows: &[Node], unknowns: &[usize], n: usize) -> Result<Vec<Node>, Refusal> {
    let wrt: Vec<Node> =
        unknowns.iter().map(|&i| g.input_node(n + i)).collect::<Option<_>>().ok_or(Refusal::AtThisPoint)?;
    let j = jacobian(g, rows, &wrt);
    if !constant_in(g, &j.concat(), &wrt) {
        return Err(Refusal::NotAffine);
    }
    let zero = g.constant(0.0);
    let mut replace = vec![None; 3 * n];
    for &i in unknowns {
        replace[n + i] = Some(zero);
    }
    let at_zero = g.replace_inputs(rows, &replace);
    let rhs = negated(g, &at_zero);
    let j = at(g, j, &replace);
    eliminate(g, j, rhs).ok_or(Refusal::AtThisPoint)
}

/// Whether `nodes` are constant in the input nodes `wrt`: they do not read them, or (when rounding
/// hides an exact cancellation from the graph, as in A·v + γ*/h = μ) their values at the build point
/// and at three points moved along `wrt` agree to [`CONSTANT_TOLERANCE`] relative to the largest.
fn constant_in(g: &Graph, nodes: &[Node], wrt: &[Node]) -> bool {
    if !g.reads(nodes, wrt) {
        return true;
    }
    let program = g.program(nodes);
    let eval = |point: &[f64]| {
        let mut values = vec![0.0; nodes.len()];
        program.eval(point, &mut Vec::new(), &mut values);
        values
    };
    let at_build = eval(g.point());
    let scale = at_build.iter().fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
    [0.37, -0.61, 0.83].iter().all(|&step| {
        let mut point = g.point().to_vec();
        for (k, &w) in wrt.iter().enumerate() {
            let Instruction::Input(i) = g.instruction(w) else { continue };
            let x = &mut point[i as usize];
            *x += step * (1.0 + 0.1 * k as f64) * (1.0 + x.abs());
        }
        eval(&point).iter().zip(&at_build).all(|(v, v0)| (v - v0).abs() <= CONSTANT_TOLERANCE * scale)
    })
}

/// The Jacobian ∂rows/∂wrt (rows × wrt) by forward mode along each input node of `wrt`.
fn jacobian(g: &mut Graph, rows: &[Node], wrt: &[Node]) -> Vec<Vec<Node>> {
    let columns: Vec<Vec<Node>> = wrt.iter().map(|&w| directional(g, w, rows)).collect();
    (0..rows.len()).map(|i| columns.iter().map(|c| c[i]).collect()).collect()
}

/// The entries of `matrix` with the inputs replaced as in [`Graph::replace_inputs`]: a matrix constant
/// in some unknowns up to rounding, taken at zero there, so that it reads none of them. When it is
/// constant in the base too (a uniform field, a constant mass matrix), it is taken at the first
/// step's base and becomes a constant, and so does its elimination.
fn at(g: &mut Graph, matrix: Vec<Vec<Node>>, replace: &[Option<Node>]) -> Vec<Vec<Node>> {
    let n = replace.len() / 3;
    let base: Vec<Node> = (0..n).filter_map(|k| g.input_node(k)).collect();
    let mut frozen = replace.to_vec();
    if constant_in(g, &matrix.concat(), &base) {
        for (k, slot) in frozen.iter_mut().enumerate().take(n) {
            *slot = Some(g.constant(g.point()[k]));
        }
    }
    matrix.into_iter().map(|row| g.replace_inputs(&row, &frozen)).collect()
}

fn negated(g: &mut Graph, nodes: &[Node]) -> Vec<Node> {
    nodes.iter().map(|&n| g.neg(n)).collect()
}

/// x with A x = rhs, by Gaussian elimination on the graph. The pivot of each column is the entry of
/// largest magnitude at the graph's build point (partial pivoting there), and the order stays fixed.
/// Each pivot is inverted once and its row and the back substitution multiply by the inverse, which
/// keeps divisions, the slowest operations, off the chain that one step's solution feeds to the next.
/// Entries that are constant zeros cost nothing. `None` if a pivot is (nearly) zero or not finite
/// at the build point.
fn eliminate(g: &mut Graph, mut a: Vec<Vec<Node>>, mut rhs: Vec<Node>) -> Option<Vec<Node>> {
    let n = rhs.len();
    let scale = a.iter().flatten().fold(0.0f64, |s, &x| s.max(g.value(x).abs()));
    let one = g.constant(1.0);
    let mut inverse = Vec::with_capacity(n);
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| g.value(a[i][k]).abs().total_cmp(&g.value(a[j][k]).abs()))?;
        let pivot = g.value(a[p][k]).abs();
        if !(pivot.is_finite() && pivot > PIVOT_TOLERANCE * scale) {
            return None;
        }
        a.swap(k, p);
        rhs.swap(k, p);
        inverse.push(g.div(one, a[k][k]));
        let (pivot_row, pivot_rhs) = (a[k].clone(), rhs[k]);
        for (row, rhs_r) in a.iter_mut().zip(rhs.iter_mut()).skip(k + 1) {
            let f = g.mul(row[k], inverse[k]);
            for (entry, &above) in row.iter_mut().zip(&pivot_row).skip(k + 1) {
                let t = g.mul(f, above);
                *entry = g.sub(*entry, t);
            }
            let t = g.mul(f, pivot_rhs);
            *rhs_r = g.sub(*rhs_r, t);
        }
    }
    let mut x = vec![0; n];
    for k in (0..n).rev() {
        let mut s = rhs[k];
        for c in k + 1..n {
            let t = g.mul(a[k][c], x[c]);
            s = g.sub(s, t);
        }
        x[k] = g.mul(s, inverse[k]);
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    const NO_GROUP: [bool; 2] = [false, false];

    #[test]
    fn a_zero_first_pivot_takes_the_other_row() {
        // f = a0 b1 + a1 (b0 + 2 b1): r = (b1 + m0, b0 + 2 b1 + m1), J = [[0, 1], [1, 2]].
        let f = |_: &[Traced; 2], a: &[Traced; 2], b: &[Traced; 2]| a[0] * b[1] + a[1] * (b[0] + b[1] * 2.0);
        let step = LinearStep::new(Fixed, f, &[0.0; 2], &[0.1, 0.2], &[1.0, 1.0], &[1.0; 2], &[true; 2], &NO_GROUP)
            .unwrap()
            .unwrap();
        let s = step.solve(&[0.0; 2], &[3.0, 5.0]);
        assert_eq!(s.z, [1.0, -3.0]);
        assert_eq!(s.residual, [0.0, 0.0]);
        assert_eq!(s.solves(0.0), Some(0.0));
    }

    #[test]
    fn group_unknowns_are_eliminated_first() {
        // r_x = 3 b0 + b1 + m0, r_γ = 4 b1 + b0 − m1 (sign −1): γ* = (m1 − b0) / 4, then
        // (11/4) b0 + m1/4 + m0 = 0.
        let f = |_: &[Traced; 2], a: &[Traced; 2], b: &[Traced; 2]| {
            a[0] * (b[0] * 3.0 + b[1]) + a[1] * (b[1] * 4.0 + b[0]) + b[0] * b[0] * b[1]
        };
        let step = LinearStep::new(
            Fixed,
            f,
            &[0.0; 2],
            &[0.3, 0.1],
            &[0.5, 2.0],
            &[1.0, -1.0],
            &[true, false],
            &[false, true],
        )
        .unwrap()
        .unwrap();
        let (m0, m1) = (0.5, 2.0);
        let s = step.solve(&[0.0; 2], &[m0, m1]);
        let b0 = -(m1 / 4.0 + m0) * 4.0 / 11.0;
        assert!((s.z[0] - b0).abs() < 1e-15 && (s.z[1] - (m1 - b0) / 4.0).abs() < 1e-15, "{:?}", s.z);
        assert!(s.residual.iter().all(|r| r.abs() < 1e-15), "{:?}", s.residual);
        // ∂f/∂b0 at a = 0 is that of the last term, 2 b0 b1; m1 does not advance.
        assert!((s.momenta_next[0] - 2.0 * s.z[0] * s.z[1]).abs() < 1e-15 && s.momenta_next[1] == m1);
        assert!((s.value - s.z[0] * s.z[0] * s.z[1]).abs() < 1e-15);
    }

    #[test]
    fn nonlinear_equations_have_no_closed_form() {
        // r_0 = b0² + m0.
        let square = |_: &[Traced; 2], a: &[Traced; 2], b: &[Traced; 2]| a[0] * b[0] * b[0] + a[1] * b[1];
        let step =
            LinearStep::new(Fixed, square, &[0.0; 2], &[0.5, 0.5], &[-1.0, 0.0], &[1.0; 2], &[true; 2], &NO_GROUP);
        assert_eq!(step.unwrap().err(), Some(Refusal::NotAffine));
        // Linear in γ, but r_x = 3 b0 + γ*² + m0 is not linear in b0 once γ* = (m1 − b0) / 4 is in.
        let quadratic_after = |_: &[Traced; 2], a: &[Traced; 2], b: &[Traced; 2]| {
            a[0] * (b[0] * 3.0 + b[1] * b[1]) + a[1] * (b[1] * 4.0 + b[0])
        };
        let step = LinearStep::new(
            Fixed,
            quadratic_after,
            &[0.0; 2],
            &[0.3, 0.1],
            &[0.5, 2.0],
            &[1.0, -1.0],
            &[true, false],
            &[false, true],
        );
        assert_eq!(step.unwrap().err(), Some(Refusal::NotAffine));
        // Not linear in γ.
        let cubic = |_: &[Traced; 2], a: &[Traced; 2], b: &[Traced; 2]| a[0] * b[0] + a[1] * b[1] * b[1] * b[1];
        let step = LinearStep::new(
            Fixed,
            cubic,
            &[0.0; 2],
            &[0.3, 0.1],
            &[0.5, 2.0],
            &[1.0, -1.0],
            &[true, false],
            &[false, true],
        );
        assert_eq!(step.unwrap().err(), Some(Refusal::NotAffine));
    }

    #[test]
    fn a_singular_system_has_no_closed_form() {
        let f = |_: &[Traced; 2], a: &[Traced; 2], b: &[Traced; 2]| (a[0] + a[1]) * (b[0] + b[1]);
        // Affine, but its Jacobian is singular here: a property of the point, not of the equations.
        let step = LinearStep::new(Fixed, f, &[0.0; 2], &[0.1, 0.2], &[1.0, 1.0], &[1.0; 2], &[true; 2], &NO_GROUP);
        assert_eq!(step.unwrap().err(), Some(Refusal::AtThisPoint));
    }
}
