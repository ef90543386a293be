//! The engine held against the paper oracle, one file per subject, built as one test binary (each
//! binary compiles the engine again for every system type it runs).

#[path = "../common/mod.rs"]
mod common;

mod dirac_structure;
mod trivialization;
mod variational;
