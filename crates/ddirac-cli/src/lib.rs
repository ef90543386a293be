//! The command line's machinery as a library: spec files (parsing, `--set` overrides, validation into
//! a run's plan), runs into output directories (staged, locked, committed as a set), figures,
//! comparisons, convergence studies, `check`, `bench`. The binary `ddirac` (`main.rs`) parses the
//! command line and calls into it; the Python package uses it for `ddirac.load`.

pub mod bench;
pub mod check;
pub mod compare;
pub mod convergence;
pub mod diagnostics;
pub mod ensemble;
pub mod equilibria;
pub mod estimate;
pub mod exact;
pub mod initial_entries;
pub mod keys;
pub mod lock;
pub mod manifest;
pub mod npy;
pub mod output;
pub mod overrides;
pub mod plot;
pub mod progress;
pub mod report;
pub mod rigid;
pub mod run;
pub mod run_dir;
pub mod signals;
pub mod spec;
