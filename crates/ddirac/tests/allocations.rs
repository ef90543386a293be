//! `integrate` allocates nothing per step for fixed-size systems.
//!
//! A counting global allocator wraps the system allocator. The count that matters is per thread: the
//! test harness runs tests on several threads and allocates on its own (result printing, spawning),
//! so a process-wide counter would pick up allocations that have nothing to do with the run being
//! measured. The process-wide total is kept as well, as a check that the counter sees allocations
//! at all.
//!
//! For each system and method, a run of 2000 steps must allocate exactly as often as a run of 200
//! steps with the same step size (rows reported only at k = 0 and k = N, observer doing nothing):
//! any per-step allocation would add 1800 or more. When the counts differ, the assertion message
//! names the per-step building blocks (public calls the step loop relies on) that allocate.

use std::alloc::{GlobalAlloc, Layout, System as SystemAllocator};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

use ddirac::chart::Configuration;
use ddirac::mechanics::legendre;
use ddirac::newton::{self, NewtonOptions};
use ddirac::systems::{ChargedParticle, DoubleSphericalPendulum, HeavyTop, Kepler, PendulumChain};
use ddirac::{
    integrate, Differentiation, DiscreteLagrangian, InitialMomentum, Method, OutputOptions, Problem, Rule, System,
    Variant,
};
use nalgebra::SVector;

struct Counting;

static TOTAL: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    // Const-initialised and without destructor: reading it never allocates.
    static ON_THIS_THREAD: Cell<usize> = const { Cell::new(0) };
}

fn note_allocation() {
    TOTAL.fetch_add(1, Ordering::Relaxed);
    let _ = ON_THIS_THREAD.try_with(|c| c.set(c.get() + 1));
}

// SAFETY: every call is forwarded unchanged to the system allocator; the counters only add.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note_allocation();
        SystemAllocator.alloc(layout)
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note_allocation();
        SystemAllocator.alloc_zeroed(layout)
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note_allocation();
        SystemAllocator.realloc(ptr, layout, new_size)
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        SystemAllocator.dealloc(ptr, layout)
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The number of allocations (including reallocations) `f` makes on this thread.
fn allocations<R>(f: impl FnOnce() -> R) -> (R, usize) {
    let before = ON_THIS_THREAD.with(Cell::get);
    let r = f();
    (r, ON_THIS_THREAD.with(Cell::get) - before)
}

/// Allocations of one `integrate` call with `steps` steps of size `h`.
fn run_allocations<S: System<N>, const N: usize>(
    system: &S,
    h: f64,
    steps: usize,
    q0: &[f64; N],
    p0: &[f64; N],
    method: &Method,
) -> usize {
    let problem = Problem::new(h, steps, q0.to_vec(), InitialMomentum::Momentum(p0.to_vec()));
    let output = OutputOptions { every: 1_000_000, wrap_angles: false };
    let mut rows = 0;
    let mut observer = |_: &ddirac::Row<'_>| {
        rows += 1;
        Ok(())
    };
    let (summary, count) =
        allocations(|| integrate(system, &problem, method, &output, &mut observer).expect("the run succeeds"));
    assert_eq!(summary.steps, steps);
    assert_eq!(rows, 2, "only the first and the last rows are reported");
    count
}

/// Allocations per call of the public building blocks a step relies on, at a typical state.
fn building_blocks<S: System<N>, const N: usize>(
    system: &S,
    rule: Rule,
    h: f64,
    q0: &[f64; N],
    p0: &[f64; N],
) -> Vec<(&'static str, usize)> {
    let kinds = system.coordinates().each_ref().map(|c| c.kind);
    let ld = DiscreteLagrangian::new(system, rule, h);
    let (v0, _) = legendre::velocity(system, q0, p0);
    let dq = SVector::from(v0.map(|v| v * h));
    let mut config = Configuration::new(*q0, kinds);
    let mut z = dq;
    vec![
        ("DiscreteLagrangian::derivatives_local", allocations(|| ld.derivatives_local(q0, &SVector::zeros(), &dq)).1),
        (
            "newton::solve",
            allocations(|| {
                newton::solve(&mut z, 1.0, &NewtonOptions::default(), |z| {
                    let d = ld.derivatives_local(q0, &SVector::zeros(), z);
                    (d.d1 + SVector::from(*p0), d.d1d2)
                })
            })
            .1,
        ),
        ("chart::Configuration::advance", allocations(|| config.advance(&dq.into())).1),
        ("legendre::hamiltonian", allocations(|| legendre::hamiltonian(system, q0, p0)).1),
        ("System::coordinates", allocations(|| system.coordinates()).1),
    ]
}

/// Asserts that runs of 200 and 2000 steps allocate equally often for the reduced (+), reduced (−)
/// and unreduced methods, with compiled derivatives and with dual numbers.
fn assert_no_per_step_allocation<S: System<N>, const N: usize>(
    name: &str,
    system: &S,
    rule: Rule,
    h: f64,
    q0: [f64; N],
    p0: [f64; N],
) {
    let choices = [(true, Variant::Plus), (true, Variant::Minus), (false, Variant::Plus)]
        .into_iter()
        .flat_map(|c| [(c, Differentiation::Compiled), (c, Differentiation::Dual)]);
    for ((reduced, variant), differentiation) in choices {
        // In one chart: a switch between the charts of an atlas prepares the new chart's stepper
        // (and allocates), which is not a per-step cost.
        let method = Method { rule, variant, reduced, differentiation, atlas: false, ..Method::default() };
        // Warm-up: one-time lazy initialisations must not count as per-step costs.
        run_allocations(system, h, 10, &q0, &p0, &method);
        let short = run_allocations(system, h, 200, &q0, &p0, &method);
        let long = run_allocations(system, h, 2000, &q0, &p0, &method);
        eprintln!(
            "{name}, reduced = {reduced}, {}, {differentiation:?}: {short} allocations for 200 steps, {long} for 2000",
            variant.name()
        );
        if short != long {
            let blocks = building_blocks(system, rule, h, &q0, &p0);
            panic!(
                "{name}, reduced = {reduced}, {}: {short} allocations for 200 steps but {long} for 2000 \
                 ({:.2} per step). Allocations per call of the building blocks of a step: {blocks:?}. \
                 If none of them allocates, the allocation is in the scheme evaluation or the step loop \
                 (integrator.rs, reduction/reduced.rs, mechanics/dirac.rs).",
                variant.name(),
                (long as f64 - short as f64) / 1800.0
            );
        }
    }
}

#[test]
fn the_counter_sees_allocations() {
    let total_before = TOTAL.load(Ordering::Relaxed);
    let (v, count) = allocations(|| std::hint::black_box(vec![1.0f64; 16]));
    assert_eq!(v.len(), 16);
    assert_eq!(count, 1);
    assert!(TOTAL.load(Ordering::Relaxed) > total_before);
    // A solve keeps its rows, so it allocates more for a longer run: the comparison below can fail.
    let method = Method { rule: Rule::Left, reduced: true, ..Method::default() };
    let solve_allocations = |steps| {
        let problem = ChargedParticle::paper_problem(steps);
        allocations(|| ddirac::solve(&ChargedParticle::default(), &problem, &method, &OutputOptions::default())).1
    };
    assert!(solve_allocations(2000) > solve_allocations(200) + 1800);
}

#[test]
fn charged_particle_steps_do_not_allocate() {
    for rule in [Rule::Left, Rule::Midpoint] {
        assert_no_per_step_allocation(
            &format!("charged particle ({})", rule.name()),
            &ChargedParticle::default(),
            rule,
            0.02,
            [0.0; 4],
            [1.0, 0.0, 1.0, 1.0],
        );
    }
}

#[test]
fn double_spherical_pendulum_steps_do_not_allocate() {
    // The paper's problem (§7.2), h = 0.01.
    assert_no_per_step_allocation(
        "double spherical pendulum",
        &DoubleSphericalPendulum::default(),
        Rule::Midpoint,
        0.01,
        [0.0, 2.25, 2.0, 3.0],
        [0.0, 0.0, 1.0, 1.0],
    );
}

#[test]
fn kepler_and_heavy_top_steps_do_not_allocate() {
    assert_no_per_step_allocation("Kepler", &Kepler::default(), Rule::Midpoint, 0.01, [1.0, 0.3], [0.2, 1.2]);
    let top = HeavyTop::default();
    let q0 = [0.0, 0.6, 0.0];
    let p0 = legendre::momentum(&top, &q0, &[0.4, 0.0, 30.0]);
    assert_no_per_step_allocation("heavy top", &top, Rule::Midpoint, 1e-3, q0, p0);
}

#[test]
fn the_building_blocks_of_a_step_do_not_allocate() {
    let blocks = building_blocks(
        &DoubleSphericalPendulum::default(),
        Rule::Midpoint,
        0.01,
        &[0.0, 2.25, 2.0, 3.0],
        &[0.0, 0.0, 1.0, 1.0],
    );
    eprintln!("{blocks:?}");
    for (name, count) in &blocks {
        if *name == "System::coordinates" {
            // Names are Strings: called once per run, never per step.
            assert!(*count > 0, "the counter must see the coordinate names");
        } else {
            assert_eq!(*count, 0, "{name} allocates");
        }
    }
}

#[test]
fn a_long_chain_steps_do_not_allocate() {
    // 16 coordinates: the mixed block in column chunks, the Jacobian kept across steps.
    const N: usize = 16;
    let chain = PendulumChain::<N>::default();
    let q0: [f64; N] = std::array::from_fn(|i| 0.5 * ((i + 1) as f64 * std::f64::consts::PI / (N + 1) as f64).sin());
    let p0 = [0.0; N];
    for differentiation in [Differentiation::Compiled, Differentiation::Dual] {
        let method = Method { rule: Rule::Midpoint, differentiation, ..Method::default() };
        run_allocations(&chain, 0.01, 10, &q0, &p0, &method);
        let short = run_allocations(&chain, 0.01, 200, &q0, &p0, &method);
        let long = run_allocations(&chain, 0.01, 2000, &q0, &p0, &method);
        eprintln!("chain of {N} pendula, {differentiation:?}: {short} allocations for 200 steps, {long} for 2000");
        assert_eq!(short, long, "allocations per step: {:.2}", (long as f64 - short as f64) / 1800.0);
    }
}

#[test]
fn a_run_with_an_atlas_steps_without_allocating() {
    // A conical motion 1.3 rad from the lower pole (the main chart's measure sin φ = 0.96 throughout,
    // where it alone has weight: `ddirac::blend`): each step chooses its chart and saves the progress
    // it would take again in another chart. (The glued steps where charts overlap take dual numbers
    // through every chart with weight and allocate.)
    let system = ddirac::systems::SphericalPendulum::default();
    let (phi, rate) = (std::f64::consts::PI - 1.3, (system.g / (system.l * 1.3f64.cos())).sqrt());
    let q0 = [0.0, phi];
    let p0 = [system.m * system.l * system.l * phi.sin().powi(2) * rate, 0.0];
    for reduced in [false, true] {
        let method = Method { rule: Rule::Midpoint, reduced, ..Method::default() };
        assert!(method.atlas);
        let problem = Problem::new(0.01, 2000, q0.to_vec(), InitialMomentum::Momentum(p0.to_vec()));
        let summary = integrate(&system, &problem, &method, &OutputOptions::default(), &mut |_| Ok(())).unwrap();
        assert_eq!(summary.chart_switches, 0, "the motion stays in the main chart");
        run_allocations(&system, 0.01, 10, &q0, &p0, &method);
        let short = run_allocations(&system, 0.01, 200, &q0, &p0, &method);
        let long = run_allocations(&system, 0.01, 2000, &q0, &p0, &method);
        eprintln!("spherical pendulum with its atlas, reduced = {reduced}: {short} allocations for 200 steps, {long} for 2000");
        assert_eq!(short, long, "allocations per step: {:.2}", (long as f64 - short as f64) / 1800.0);
    }
}
