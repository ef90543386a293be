//! `--out` naming a regular file failed with "File exists", which says the opposite of what is
//! wrong. The message now says that the output directory is not a directory, and which file is in
//! its place.

use crate::common;

use common::{ddirac, example, TempDir};

#[test]
fn an_output_directory_that_is_a_file_is_named_as_such() {
    let dir = TempDir::new("out-file");
    let file = dir.file("results", "my notes");
    let spec = example("charged_particle.toml");
    for (out, blocking) in [(file.clone(), file.clone()), (format!("{file}/run1"), file.clone())] {
        let output = ddirac(&["run", &spec, "--out", &out, "--quiet"], &dir.0);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(4), "{stderr}");
        let expected = format!("the output directory `{out}` is not a directory: `{blocking}` is a file");
        assert!(stderr.contains(&expected), "expected `{expected}`:\n{stderr}");
        assert!(!stderr.contains("File exists"), "{stderr}");
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "my notes");
    }
    // The same through `output.directory`, and for `--compare`.
    let output = ddirac(&["run", &spec, "--set", &format!("output.directory=\"{file}\""), "--quiet"], &dir.0);
    assert!(String::from_utf8_lossy(&output.stderr).contains("is not a directory"));
    let output = ddirac(&["run", &spec, "--compare", "--out", &file, "--quiet"], &dir.0);
    assert!(String::from_utf8_lossy(&output.stderr).contains("is not a directory"));
    assert_eq!(output.status.code(), Some(4));
}
