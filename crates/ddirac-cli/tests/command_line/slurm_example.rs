//! examples/slurm/ensemble.sbatch, run as Slurm would run its 16 array tasks (the environment
//! variables Slurm sets, `sbatch` replaced by a script that records its arguments): the shards
//! merge, as the job the script submits merges them, into the unsharded ensemble's files.

#![cfg(unix)]

use crate::common;

use std::path::Path;
use std::process::Command;

use common::{ddirac, example, stderr, TempDir};

#[test]
fn the_slurm_array_and_its_merge_job_give_the_unsharded_ensemble() {
    let dir = TempDir::new("slurm");
    let spec = example("magnetic_mirror.toml");
    let text = std::fs::read_to_string(&spec).unwrap().replace("steps = 20000", "steps = 200");
    let spec = dir.file("mirror.toml", &text);
    // `sbatch` records its arguments; `ddirac` is the binary under test.
    let bin = dir.0.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let sbatch = bin.join("sbatch");
    std::fs::write(&sbatch, "#!/bin/sh\nprintf '%s\\n' \"$@\" >> \"$(dirname \"$0\")/submitted\"\n").unwrap();
    Command::new("chmod").arg("+x").arg(&sbatch).status().unwrap();
    let ddirac_dir = Path::new(env!("CARGO_BIN_EXE_ddirac")).parent().unwrap();
    let path = format!("{}:{}:{}", bin.display(), ddirac_dir.display(), std::env::var("PATH").unwrap_or_default());
    let script = format!("{}/../../examples/slurm/ensemble.sbatch", env!("CARGO_MANIFEST_DIR"));
    let out = dir.0.join("out");
    for task in 0..16 {
        let status = Command::new("bash")
            .arg(&script)
            .current_dir(&dir.0)
            .env("PATH", &path)
            .env("SLURM_ARRAY_TASK_ID", task.to_string())
            .env("SLURM_ARRAY_JOB_ID", "4242")
            .env("SLURM_CPUS_PER_TASK", "1")
            .env("SPEC", &spec)
            .env("OUT", &out)
            .output()
            .unwrap();
        assert!(status.status.success(), "task {task}: {}", String::from_utf8_lossy(&status.stderr));
    }
    // The merge job, submitted once, by task 0, after the whole array.
    let submitted = std::fs::read_to_string(bin.join("submitted")).unwrap();
    assert_eq!(submitted.matches("--dependency=afterok:4242").count(), 1, "{submitted}");
    let wrap = submitted.lines().find_map(|l| l.strip_prefix("--wrap=")).expect("a --wrap command");
    let merged = Command::new("sh").arg("-c").arg(wrap).current_dir(&dir.0).env("PATH", &path).output().unwrap();
    assert!(merged.status.success(), "{}", String::from_utf8_lossy(&merged.stderr));

    let whole = dir.0.join("whole");
    let output = ddirac(&["ensemble", &spec, "--out", whole.to_str().unwrap(), "--quiet"], &dir.0);
    assert!(output.status.success(), "{}", stderr(&output));
    for name in
        ["final.csv", "members.csv", "npy/final_q.npy", "npy/final_p.npy", "npy/status.npy", "npy/energy_error.npy"]
    {
        assert!(
            std::fs::read(whole.join(name)).unwrap() == std::fs::read(out.join("all").join(name)).unwrap(),
            "{name}"
        );
    }
}
