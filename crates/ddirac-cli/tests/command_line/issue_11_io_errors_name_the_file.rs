//! An I/O failure (a permission denied, a name taken by a directory) was reported as "cannot write
//! the output in `DIR`", naming the directory instead of the file the failed operation concerned.
//! The report now names that file.

use crate::common;

use std::path::Path;

use common::{ddirac, example, TempDir};

fn run(out: &Path, format: &str, dir: &TempDir) -> (Option<i32>, String) {
    let spec = example("charged_particle.toml");
    let output = ddirac(&["run", &spec, "--out", out.to_str().unwrap(), "--quiet", "--format", format], &dir.0);
    (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned())
}

#[test]
fn a_directory_in_the_place_of_an_output_file_is_named() {
    let dir = TempDir::new("in-the-way");
    let out = dir.out();
    std::fs::create_dir_all(out.join("trajectory.csv")).unwrap();
    let (code, stderr) = run(&out, "csv", &dir);
    assert_eq!(code, Some(4), "{stderr}");
    let expected = format!("cannot write `{}`", out.join("trajectory.csv").display());
    assert!(stderr.contains(&expected), "expected `{expected}`:\n{stderr}");
    assert!(out.join("trajectory.csv").is_dir());
    let left: Vec<_> = std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left, ["trajectory.csv"], "the failed run left files behind");

    // A file in the place of the `npy/` directory.
    let dir = TempDir::new("npy-in-the-way");
    let out = dir.out();
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("npy"), "mine").unwrap();
    let (code, stderr) = run(&out, "npy", &dir);
    assert_eq!(code, Some(4), "{stderr}");
    let expected = format!("cannot write `{}`", out.join("npy").display());
    assert!(stderr.contains(&expected), "expected `{expected}`:\n{stderr}");
    assert!(!stderr.contains(&format!("in `{}`", out.display())), "{stderr}");
    assert_eq!(std::fs::read_to_string(out.join("npy")).unwrap(), "mine");
}

/// A directory without write permission: the report names the file that could not be created in
/// it. Skipped where permissions do not apply (as root).
#[cfg(unix)]
#[test]
fn a_permission_denied_names_the_file() {
    use std::os::unix::fs::PermissionsExt;
    let dir = TempDir::new("read-only");
    let out = dir.out();
    std::fs::create_dir_all(&out).unwrap();
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o555)).unwrap();
    if std::fs::write(out.join("probe"), "").is_ok() {
        eprintln!("a_permission_denied_names_the_file: skipped, permissions do not apply to this user");
        return;
    }
    let (code, stderr) = run(&out, "csv", &dir);
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o755)).unwrap();
    assert_eq!(code, Some(4), "{stderr}");
    assert!(stderr.contains("Permission denied"), "{stderr}");
    assert!(stderr.contains(&format!("cannot write `{}/", out.display())), "no file named:\n{stderr}");
}
