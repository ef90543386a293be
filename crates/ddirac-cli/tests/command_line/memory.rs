//! Bounded memory: rows are streamed to the output files and the library keeps no trajectory, so the
//! peak resident memory of `ddirac run` does not grow with the number of steps.
//!
//! The peak is the child's own `ru_maxrss`, returned by `wait4(2)` when the child is reaped. That is
//! exact (the kernel's high-water mark, not a sample), needs no extra crate (one FFI declaration of a
//! function std already links) and, unlike `getrusage(RUSAGE_CHILDREN)`, is not mixed with the other
//! children this test process may have. Linux only (`ru_maxrss` is in KiB there).

#![cfg(target_os = "linux")]

use std::os::raw::{c_int, c_long};
use std::process::{Command, Stdio};

const CHARGED_PARTICLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/charged_particle.toml");

/// `struct timeval` of the Linux C library (`time_t` and `suseconds_t` are `long`). Laid out for C;
/// only `ru_maxrss` is read.
#[repr(C)]
#[derive(Default)]
#[allow(dead_code)]
struct Timeval {
    seconds: c_long,
    microseconds: c_long,
}

/// `struct rusage`: two times, then fourteen `long` counters, the first of which is `ru_maxrss`.
#[repr(C)]
#[derive(Default)]
#[allow(dead_code)]
struct Rusage {
    user: Timeval,
    system: Timeval,
    maxrss: c_long,
    other: [c_long; 13],
}

extern "C" {
    fn wait4(pid: c_int, status: *mut c_int, options: c_int, usage: *mut Rusage) -> c_int;
}

/// Runs the charged-particle example for `steps` steps of h = 0.2 with every 1000th row written as
/// CSV and NPY; returns the peak resident set size in KiB and the wall time.
fn peak_rss_kib(steps: u64) -> (c_long, f64) {
    let dir = std::env::temp_dir().join(format!("ddirac-memory-{}-{steps}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let started = std::time::Instant::now();
    let child = Command::new(env!("CARGO_BIN_EXE_ddirac"))
        .args(["run", CHARGED_PARTICLE, "--quiet", "--format", "csv,npy", "--out", dir.to_str().unwrap()])
        .args(["--set", &format!("time.steps={steps}"), "--set", &format!("time.duration={}", steps / 5)])
        .args(["--set", "output.every=1000"])
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    let pid = c_int::try_from(child.id()).unwrap();
    let mut status: c_int = 0;
    let mut usage = Rusage::default();
    // SAFETY: both pointers are valid for writes for the duration of the call; the child was not
    // waited for before (its `Child` handle is dropped without waiting, which std allows).
    let reaped = unsafe { wait4(pid, &mut status, 0, &mut usage) };
    let seconds = started.elapsed().as_secs_f64();
    drop(child);
    assert_eq!(reaped, pid, "wait4 failed: {}", std::io::Error::last_os_error());
    assert_eq!(status, 0, "`ddirac run` for {steps} steps failed (wait status {status:#x})");
    let rows = std::fs::read_to_string(dir.join("trajectory.csv")).unwrap().lines().count() as u64;
    assert_eq!(rows, 1 + steps / 1000 + 1, "header, every 1000th row from row 0");
    std::fs::remove_dir_all(&dir).unwrap();
    (usage.maxrss, seconds)
}

#[test]
fn peak_memory_does_not_grow_with_the_number_of_steps() {
    // A release build does 10⁶ steps in a few seconds; an unoptimised one gets 10⁵.
    let large = if cfg!(debug_assertions) { 100_000 } else { 1_000_000 };
    let (small_kib, small_seconds) = peak_rss_kib(10_000);
    let (large_kib, large_seconds) = peak_rss_kib(large);
    eprintln!(
        "10^4 steps: {small_kib} KiB in {small_seconds:.2} s; {large} steps: {large_kib} KiB in {large_seconds:.2} s"
    );
    assert!(small_kib > 0 && large_kib > 0);
    let ratio = large_kib as f64 / small_kib as f64;
    assert!(ratio <= 2.0, "peak RSS grew {ratio:.2}× from 10^4 to {large} steps ({small_kib} → {large_kib} KiB)");
}
