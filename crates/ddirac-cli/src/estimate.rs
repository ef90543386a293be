//! The size of a run's output, estimated before the run: rows × bytes per row of each format.
//!
//! A row holds 2n + 3 + n_g numbers (t, q, p, H, L_d, J). In the CSV a number takes at most 24
//! characters and about [`CSV_BYTES`] on average with its separator (full-precision values of order
//! one; the shortest round-trip form makes round numbers shorter); in a `.npy` file it takes 8
//! bytes. A run whose output would exceed the free space of the file system it goes to is refused
//! before it starts, pointing at `[time]` and `output.every`; one that writes more than [`NOTICE`]
//! says so on stderr first.

use std::path::Path;

use miette::LabeledSpan;

use crate::diagnostics::{SpecError, SpecSource};
use crate::output::Formats;
use crate::spec::{Plan, Spec};

/// Average bytes of a CSV number with its separator.
pub const CSV_BYTES: u64 = 20;
/// Output size above which a run prints its estimate before starting: 1 GB.
pub const NOTICE: u64 = 1_000_000_000;

/// The estimated output of one run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Rows: k = 0, every, 2·every, … and the last step.
    pub rows: u64,
    /// Numbers per row.
    pub columns: u64,
    /// Bytes of `trajectory.csv` (0 if not written).
    pub csv: u64,
    /// Bytes of `npy/` (0 if not written).
    pub npy: u64,
}

impl Estimate {
    /// The output of `plan` in `formats`.
    pub fn new(plan: &Plan, formats: Formats) -> Self {
        let coordinates = plan.system.coordinates();
        let n = coordinates.len();
        let n_g = coordinates.iter().filter(|c| c.role == ddirac::Role::Group).count();
        Self::of(plan.problem.steps, plan.output.every, 2 * n + 3 + n_g, formats)
    }

    /// The output of `steps` steps with a row every `every` steps, of `columns` numbers each.
    pub fn of(steps: usize, every: usize, columns: usize, formats: Formats) -> Self {
        let (steps, every, columns) = (steps as u64, every.max(1) as u64, columns as u64);
        let rows = steps / every + 1 + u64::from(steps % every != 0);
        let values = rows.saturating_mul(columns);
        Self {
            rows,
            columns,
            csv: if formats.csv { values.saturating_mul(CSV_BYTES) } else { 0 },
            npy: if formats.npy {
                values.saturating_mul(8).saturating_add(columns * crate::npy::HEADER_LEN as u64)
            } else {
                0
            },
        }
    }

    /// Bytes in all formats.
    pub fn bytes(&self) -> u64 {
        self.csv.saturating_add(self.npy)
    }

    /// `4.0e8 rows of 12 columns: trajectory.csv ≈ 96 GB, npy/ ≈ 38 GB`.
    fn describe(&self) -> String {
        let mut parts = vec![];
        if self.csv > 0 {
            parts.push(format!("trajectory.csv ≈ {}", bytes(self.csv)));
        }
        if self.npy > 0 {
            parts.push(format!("npy/ ≈ {}", bytes(self.npy)));
        }
        format!("{} rows of {} columns: {}", count(self.rows), self.columns, parts.join(", "))
    }
}

/// Refuses `runs` runs of `plan` whose output would not fit in the free space where `dir` is (or
/// would be), pointing at the `[time]` keys of `spec` and at `output.every`; tells of a large one on
/// stderr unless `quiet`.
pub fn check(
    source: &SpecSource,
    spec: &Spec,
    plan: &Plan,
    formats: Formats,
    dir: &Path,
    runs: u64,
    quiet: bool,
) -> Result<(), Box<SpecError>> {
    let estimate = Estimate::new(plan, formats);
    check_estimate(source, spec, estimate, (plan.problem.steps, plan.output.every), dir, runs, quiet)
}

/// [`check`] of the estimate of runs of `(steps, every)`.
pub fn check_estimate(
    source: &SpecSource,
    spec: &Spec,
    estimate: Estimate,
    (steps, every): (usize, usize),
    dir: &Path,
    runs: u64,
    quiet: bool,
) -> Result<(), Box<SpecError>> {
    let total = estimate.bytes().saturating_mul(runs);
    let what = match runs {
        1 => estimate.describe(),
        runs => format!("{runs} runs of {}", estimate.describe()),
    };
    if let Some(free) = free_space(dir).filter(|&free| total > free) {
        let time = spec.time.get_ref();
        let labels = [
            time.steps.as_ref().map(|s| s.span()),
            time.step.as_ref().map(|s| s.span()),
            time.duration.as_ref().map(|s| s.span()),
        ]
        .into_iter()
        .flatten()
        .take(2)
        .enumerate()
        .map(|(i, span)| {
            let label = (i == 0).then(|| format!("{steps} steps, {} rows", count(estimate.rows)));
            LabeledSpan::new_with_span(label, span)
        })
        .chain(
            spec.output
                .every
                .as_ref()
                .map(|e| LabeledSpan::new_with_span(Some("a row every this many steps".into()), e.span())),
        )
        .collect();
        let thin = (total as f64 / (free as f64 / 2.0)).max(1.0);
        // At most i64::MAX, the largest value `output.every` takes.
        let every = (10f64.powf(thin.log10().ceil()) as u64).saturating_mul(every.max(1) as u64);
        let every = every.min(i64::MAX as u64);
        return Err(source
            .error_with(
                format!(
                    "the output of this run would not fit: about {} ({what}), and {} are free where `{}` is",
                    bytes(total),
                    bytes(free),
                    dir.display()
                ),
                labels,
            )
            .with_help(format!(
                "write a row every {every} steps (`output.every = {every}`, or `--set output.every={every}`), \
                 shorten the run, or write somewhere with more room"
            )));
    }
    if total >= NOTICE && !quiet {
        eprintln!("ddirac: this run writes about {} to `{}` ({what})", bytes(total), dir.display());
    }
    Ok(())
}

/// Free bytes on the file system of `dir`, or of its nearest existing ancestor; None where unknown.
#[cfg(unix)]
fn free_space(dir: &Path) -> Option<u64> {
    use std::os::unix::ffi::OsStrExt;
    let existing = dir.ancestors().find(|p| p.as_os_str().is_empty() || p.exists())?;
    let existing = if existing.as_os_str().is_empty() { Path::new(".") } else { existing };
    let path = std::ffi::CString::new(existing.as_os_str().as_bytes()).ok()?;
    let mut stat = std::mem::MaybeUninit::<libc::statvfs>::uninit();
    // SAFETY: `path` is a NUL-terminated string and `stat` a buffer of the size statvfs fills.
    if unsafe { libc::statvfs(path.as_ptr(), stat.as_mut_ptr()) } != 0 {
        return None;
    }
    // SAFETY: statvfs returned 0, so it filled `stat`.
    let stat = unsafe { stat.assume_init() };
    // The field types differ between platforms.
    #[allow(clippy::unnecessary_cast)]
    Some((stat.f_bavail as u64).saturating_mul(stat.f_frsize as u64))
}

#[cfg(not(unix))]
fn free_space(_dir: &Path) -> Option<u64> {
    None
}

/// `1.2 GB`, `240 TB`, `512 B`: decimal units, three digits.
pub fn bytes(n: u64) -> String {
    const UNITS: [&str; 6] = ["kB", "MB", "GB", "TB", "PB", "EB"];
    if n < 1000 {
        return format!("{n} B");
    }
    let mut value = n as f64;
    let mut unit = "B";
    for u in UNITS {
        if value < 1000.0 {
            break;
        }
        value /= 1000.0;
        unit = u;
    }
    if value < 10.0 {
        format!("{value:.1} {unit}")
    } else {
        format!("{value:.0} {unit}")
    }
}

/// A count as written for people: exact up to 10⁶, then `4.0e8`.
fn count(n: u64) -> String {
    if n < 1_000_000 {
        n.to_string()
    } else {
        format!("{:.1e}", n as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_written_in_decimal_units() {
        assert_eq!(bytes(999), "999 B");
        assert_eq!(bytes(1000), "1.0 kB");
        assert_eq!(bytes(1_234_567_890), "1.2 GB");
        assert_eq!(bytes(240_000_000_000_000), "240 TB");
        assert_eq!(count(400_000_001), "4.0e8");
    }
}
