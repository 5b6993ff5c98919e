//! A rank started with another config, scenario or binary, or whose own
//! set-up failed, is refused at start-up with a one-line message (exit 2)
//! before rank 0 writes anything; a good job is unaffected.
use crate::common::*;
use crate::mpi_common::*;
use std::path::{Path, PathBuf};
use std::process::Output;

/// `mpirun -n 1 RANK0 evolve … : -n 1 RANK1 evolve …` with the given configs.
fn two_rank_job(binaries: [&Path; 2], configs: [&Path; 2], out: &Path) -> Output {
    let mut cmd = mpirun_bare();
    for (i, (bin, config)) in binaries.iter().zip(configs).enumerate() {
        if i > 0 {
            cmd.arg(":");
        }
        cmd.args(["-n", "1"])
            .arg(bin)
            .args(["evolve", "-q", "--threads", "1", "--config"])
            .arg(config)
            .arg("--out")
            .arg(out);
    }
    run(&mut cmd)
}

fn assert_refused(out: &Output, run_dir: &Path, expected: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    let ours: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(ours.len(), 1, "{stderr}");
    assert!(ours[0].contains(expected), "{stderr}");
    assert!(!run_dir.exists(), "rank 0 wrote {}", run_dir.display());
}

#[test]
fn mismatched_ranks_are_refused_at_start_up() {
    let dir = scratch("mpi-refused");
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_vivae"));
    let config = write_small_config(&dir, 1);
    let other = dir.join("other.toml");
    std::fs::write(
        &other,
        small_config(1).replace("steps = 150", "steps = 151"),
    )
    .unwrap();
    // Only the generation count differs: evaluations are the same, so accepted.
    let longer = dir.join("longer.toml");
    std::fs::write(&longer, small_config(3)).unwrap();

    let out = dir.join("config");
    let job = two_rank_job([&bin, &bin], [&config, &other], &out);
    assert_refused(
        &job,
        &out,
        "rank 1 was started with a different config than rank 0",
    );

    let missing = dir.join("missing-scenario.toml");
    std::fs::write(
        &missing,
        small_config(1).replace(
            "[experiment]\n",
            "[experiment]\nscenario = \"nowhere.svg\"\n",
        ),
    )
    .unwrap();
    let out = dir.join("setup");
    let job = two_rank_job([&bin, &bin], [&config, &missing], &out);
    assert_refused(&job, &out, "rank 1 could not start:");

    // Another build of vivae: the same program with one byte more.
    let copy = dir.join("vivae-other-build");
    let mut bytes = std::fs::read(&bin).unwrap();
    bytes.push(0);
    std::fs::write(&copy, bytes).unwrap();
    std::fs::set_permissions(&copy, std::os::unix::fs::PermissionsExt::from_mode(0o755)).unwrap();
    let out = dir.join("binary");
    let job = two_rank_job([&bin, &copy], [&config, &config], &out);
    assert_refused(
        &job,
        &out,
        "rank 1 runs a different vivae executable than rank 0",
    );

    let out = dir.join("accepted");
    let job = two_rank_job([&bin, &bin], [&config, &longer], &out);
    assert!(
        job.status.success(),
        "{}",
        String::from_utf8_lossy(&job.stderr)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
