//! `ensemble`: what running members together buys.
//!
//! - *Threads*: 64 members of the double spherical pendulum (paper §7.2, midpoint, reduced (+),
//!   h = 0.01, 10⁴ steps, φ₁ varied) on 2 threads against 1 (target: ≥ 1.8× faster).
//! - *Set-up amortised*: 10³ members of 10² steps against one run of 10⁵ steps (the sum of the
//!   members' step times, its own set-up spread over 10⁵ steps), both on one thread and both with
//!   dual-number derivatives (what `auto` chooses for runs of 10² steps), so that the ratio is the
//!   members' set-up and bookkeeping (target: ≤ 2). The members are built from the spec as `ddirac
//!   ensemble` builds them (initial entries set by name on the shared system).
//! - *Sharing*: 64 compiled members of 5000 steps on one thread, sharing the system (each renews the
//!   stepper of the member before it, with its traced programs) against each with a system of its
//!   own (each traces anew; the native code comes from the cache): the cost of a member's trace.
//! - *Memory*: the peak resident memory of `ddirac ensemble` runs of 10³ … 10⁵ members of 10² steps
//!   with final states only, measured for each child process, against the size of their output and
//!   against what members × trajectory would take.

use std::path::{Path, PathBuf};

use ddirac::ensemble::MemberSystem;
use ddirac::systems::DoubleSphericalPendulum;
use ddirac::{Differentiation, OutputError, Problem, Rule, Variant};
use serde::Serialize;
use serde_json::Value;

use super::harness::{compare, Comparison, Contender, Pair, Target};
use super::{method, print, to_json, Settings, LAST_ROW_ONLY};
use crate::ensemble::{Ensemble, MemberRows, MembersFrom};

#[derive(Serialize)]
struct Report {
    threads: Comparison,
    setup: Comparison,
    sharing: Comparison,
    memory: Vec<Memory>,
}

/// Peak memory of one `ddirac ensemble` process.
#[derive(Serialize)]
struct Memory {
    members: usize,
    steps: usize,
    /// Peak resident set of the process, bytes.
    peak_rss: u64,
    /// Bytes of the files it wrote.
    output_bytes: u64,
    /// Bytes the members' rows (q, p, energy) would take.
    trajectory_bytes: u64,
}

/// The initial data of member `i` of `count`: φ₁ from the paper's 2.25 to 2.35 (a range in which no
/// member passes close enough to a pole of its chart to fail within 10⁴ steps).
fn member_problem(i: usize, count: usize, steps: usize) -> Problem {
    let mut problem = Problem { steps, ..DoubleSphericalPendulum::paper_problem(10_000) };
    problem.q0[1] = 2.25 + 0.1 * (i as f64 / count.max(1) as f64);
    problem
}

/// Runs the group.
pub fn run(settings: &Settings) -> Result<Value, miette::Report> {
    print::heading("ensemble", "members run together: threads, set-up, memory");
    let threads = threads(settings)?;
    let setup = setup(settings)?;
    let sharing = sharing(settings)?;
    let memory = memory(settings)?;
    to_json(&Report { threads, setup, sharing, memory })
}

/// The sink of a benchmark's ensemble: a member that fails stops the benchmark with its error.
fn every_member_finishes(_: usize, outcome: ddirac::ensemble::Outcome) -> Result<(), OutputError> {
    match outcome.status {
        ddirac::ensemble::Status::Finished(_) => Ok(()),
        ddirac::ensemble::Status::Failed { error, .. } => Err(Box::new(error)),
    }
}

fn threads(settings: &Settings) -> Result<Comparison, miette::Report> {
    let (members, steps) = if settings.quick { (8, 1000) } else { (64, 10_000) };
    let system = super::built_in("double_spherical_pendulum")?;
    let reduced = method(Rule::Midpoint, true, Variant::Plus);
    let problems: Vec<Problem> = (0..members).map(|i| member_problem(i, members, steps)).collect();
    let contender = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a thread pool");
        let (system, problems, method) = (system.as_ref(), &problems, reduced.clone());
        let run = move || {
            let member =
                |i: usize| -> Result<_, OutputError> { Ok((MemberSystem::Shared(system), problems[i].clone())) };
            pool.install(|| {
                ddirac::ensemble::run(
                    0..problems.len(),
                    &member,
                    &method,
                    &LAST_ROW_ONLY,
                    false,
                    &every_member_finishes,
                )
            })
            .map(drop)
            .map_err(|e| miette::miette!("a member of the threads benchmark failed: {e}"))
        };
        Contender::new(format!("{threads} thread{}", if threads == 1 { "" } else { "s" }), members * steps, run)
    };
    let title = format!("{members} members of the double spherical pendulum, midpoint, reduced (+), {steps} steps");
    // A speed-up of 1.8 or more: the time ratio at most 1/1.8 = 0.556.
    let pair = Pair::new("2 threads", "1 thread").target(Target::AtMost(0.556));
    let comparison = compare(title, settings.schedule, vec![contender(1), contender(2)], &[pair])?;
    print::comparison(&comparison);
    if let Some(ratio) = comparison.ratios.first() {
        println!("    speed-up of 2 threads over 1: {:.2}× (median over the rounds)", 1.0 / ratio.spread.median);
    }
    Ok(comparison)
}

fn setup(settings: &Settings) -> Result<Comparison, miette::Report> {
    let (members, steps) = if settings.quick { (100, 100) } else { (1000, 100) };
    let spec = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/double_spherical_pendulum.toml");
    let count = members;
    let columns =
        vec![("initial.q.phi1".to_owned(), (0..count).map(|i| member_problem(i, count, steps).q0[1]).collect())];
    let set = [
        format!("time.steps={steps}"),
        format!("time.duration={}", steps as f64 * 0.01),
        "method.derivatives=\"dual\"".to_owned(),
        format!("output.every={}", usize::MAX >> 1),
    ];
    let ensemble = Ensemble::load(&spec, &set, MembersFrom::Columns(columns))
        .map_err(|e| miette::Report::new(e).wrap_err("the set-up benchmark's spec"))?;
    let ensemble_run = || {
        let none = |_: usize, _: &MemberRows| -> Result<(), OutputError> { Ok(()) };
        let results = ensemble
            .run(0..count, Some(1), &none, &|_| {})
            .map_err(|e| miette::Report::new(e).wrap_err("the set-up benchmark's ensemble"))?;
        match results.failures.first() {
            Some(f) => Err(miette::miette!("member {} of the set-up benchmark failed: {}", f.member, f.error)),
            None => Ok(()),
        }
    };
    let system = super::built_in("double_spherical_pendulum")?;
    let long = member_problem(0, count, members * steps);
    let dual = ddirac::Method { differentiation: Differentiation::Dual, ..method(Rule::Midpoint, true, Variant::Plus) };
    let long_run = || {
        system
            .integrate(&long, &dual, &LAST_ROW_ONLY, &mut |_| Ok(()))
            .map(drop)
            .map_err(|e| miette::miette!("the long run of the set-up benchmark failed: {e}"))
    };
    let contenders = vec![
        Contender::new(format!("{members} members of {steps} steps"), members * steps, ensemble_run),
        Contender::new(format!("one run of {} steps", members * steps), members * steps, long_run),
    ];
    let names: Vec<String> = contenders.iter().map(|c| c.name.clone()).collect();
    let title = "double spherical pendulum, midpoint, reduced (+), dual numbers, one thread: members against the sum \
                 of their steps";
    let pair = Pair::new(&names[0], &names[1]).target(Target::AtMost(2.0));
    let comparison = compare(title, settings.schedule, contenders, &[pair])?;
    print::comparison(&comparison);
    Ok(comparison)
}

fn sharing(settings: &Settings) -> Result<Comparison, miette::Report> {
    let (members, steps) = if settings.quick { (8, 5000) } else { (64, 5000) };
    let shared = super::built_in("double_spherical_pendulum")?;
    let reduced = method(Rule::Midpoint, true, Variant::Plus);
    let problems: Vec<Problem> = (0..members).map(|i| member_problem(i, members, steps)).collect();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("a thread pool");
    let contender = |own: bool| {
        let (shared, problems, method, pool) = (shared.as_ref(), &problems, reduced.clone(), &pool);
        let run = move || {
            let member = |i: usize| -> Result<_, OutputError> {
                let system = if own {
                    MemberSystem::Own(super::built_in("double_spherical_pendulum").map_err(|e| format!("{e}"))?)
                } else {
                    MemberSystem::Shared(shared)
                };
                Ok((system, problems[i].clone()))
            };
            pool.install(|| {
                ddirac::ensemble::run(
                    0..problems.len(),
                    &member,
                    &method,
                    &LAST_ROW_ONLY,
                    false,
                    &every_member_finishes,
                )
            })
            .map(drop)
            .map_err(|e| miette::miette!("a member of the sharing benchmark failed: {e}"))
        };
        let name = if own { "a system each (traced each)" } else { "shared system (renewed)" };
        Contender::new(name, members * steps, run)
    };
    let title = format!("{members} members of the double spherical pendulum, {steps} steps, compiled, one thread");
    let contenders = vec![contender(false), contender(true)];
    let pair = Pair::new("shared system (renewed)", "a system each (traced each)");
    let comparison = compare(title, settings.schedule, contenders, &[pair])?;
    print::comparison(&comparison);
    if let (Some(a), Some(b)) =
        (comparison.timing("shared system (renewed)"), comparison.timing("a system each (traced each)"))
    {
        let per_member = (b.ns_per_step.median - a.ns_per_step.median) * steps as f64 * 1e-9;
        println!("    a member's own trace and preparation: {:.0} µs", per_member * 1e6);
    }
    Ok(comparison)
}

fn memory(settings: &Settings) -> Result<Vec<Memory>, miette::Report> {
    let counts: &[usize] = if settings.quick { &[100, 1000] } else { &[1000, 10_000, 100_000] };
    let steps = 100;
    let dir = std::env::temp_dir().join(format!("ddirac-bench-ensemble-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| miette::miette!("cannot create {}: {e}", dir.display()))?;
    println!(
        "  peak memory of `ddirac ensemble` (double spherical pendulum, {steps} steps, final states only, 2 threads):"
    );
    println!("    {:>8}  {:>12}  {:>12}  {:>14}", "members", "peak RSS", "output", "trajectories");
    let mut rows = vec![];
    for &members in counts {
        let spec = dir.join("spec.toml");
        let base = std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/double_spherical_pendulum.toml"),
        )
        .map_err(|e| miette::miette!("cannot read the example spec: {e}"))?;
        let text = format!(
            "{base}\n[ensemble]\n[[ensemble.grid]]\nkey = \"initial.q.phi1\"\nfrom = 2.25\nto = 2.35\ncount = {members}\n"
        );
        std::fs::write(&spec, text).map_err(|e| miette::miette!("cannot write {}: {e}", spec.display()))?;
        let out = dir.join(format!("out-{members}"));
        let args: Vec<String> = vec![
            "ensemble".into(),
            spec.display().to_string(),
            "--out".into(),
            out.display().to_string(),
            "--threads".into(),
            "2".into(),
            "--quiet".into(),
            "--set".into(),
            format!("time.steps={steps}"),
            "--set".into(),
            format!("time.duration={}", steps as f64 * 0.01),
        ];
        let peak_rss = peak_memory(&args)?;
        let output_bytes = directory_bytes(&out);
        let n = 4u64;
        let rows_per_member = steps as u64 + 1;
        let trajectory_bytes = members as u64 * rows_per_member * (2 * n + 1) * 8;
        println!(
            "    {members:>8}  {:>9.1} MB  {:>9.1} MB  {:>11.1} MB",
            peak_rss as f64 / 1e6,
            output_bytes as f64 / 1e6,
            trajectory_bytes as f64 / 1e6
        );
        rows.push(Memory { members, steps, peak_rss, output_bytes, trajectory_bytes });
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(rows)
}

/// Runs this executable with `args` and returns its peak resident set in bytes.
#[cfg(unix)]
fn peak_memory(args: &[String]) -> Result<u64, miette::Report> {
    let exe: PathBuf = std::env::current_exe().map_err(|e| miette::miette!("cannot find this executable: {e}"))?;
    let child = std::process::Command::new(exe)
        .args(args)
        .stdout(std::process::Stdio::null())
        .spawn()
        .map_err(|e| miette::miette!("cannot start `ddirac ensemble`: {e}"))?;
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: an all-zero `rusage` is a valid value, and `wait4` writes only into `status` and `usage`.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: `pid` is our child, not yet waited for.
    let waited = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    if waited != pid || !libc::WIFEXITED(status) || libc::WEXITSTATUS(status) != 0 {
        return Err(miette::miette!("`ddirac {}` failed (status {status})", args.join(" ")));
    }
    // Linux reports ru_maxrss in kilobytes.
    Ok(usage.ru_maxrss as u64 * 1024)
}

#[cfg(not(unix))]
fn peak_memory(_args: &[String]) -> Result<u64, miette::Report> {
    Err(miette::miette!("the memory benchmark needs a Unix system (wait4)"))
}

/// The bytes of the files under `dir`.
fn directory_bytes(dir: &Path) -> u64 {
    let Ok(entries) = std::fs::read_dir(dir) else { return 0 };
    entries
        .filter_map(Result::ok)
        .map(|e| match e.metadata() {
            Ok(m) if m.is_dir() => directory_bytes(&e.path()),
            Ok(m) => m.len(),
            Err(_) => 0,
        })
        .sum()
}
