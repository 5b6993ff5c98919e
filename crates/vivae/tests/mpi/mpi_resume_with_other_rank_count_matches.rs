//! A run started with N ranks resumes with M ranks (or without MPI), and
//! `retrain` under MPI, end with the files of the uninterrupted single-process run.
use crate::common::*;
use crate::mpi_common::*;

#[test]
fn resume_with_another_rank_count_matches() {
    let dir = scratch("mpi-resume");
    let config = write_small_config(&dir, 6);
    let reference = dir.join("reference");
    evolve(&config, &reference, &[]);

    // 3 ranks, then 2 ranks.
    let a = dir.join("three-then-two");
    mpi_evolve(3, &config, &a, &["--generations", "3"]);
    ok(mpirun(2)
        .args(["resume", "-q", "--threads", "1", "--generations", "6"])
        .arg(&a));
    assert_same_results(&reference, &a);

    // 4 ranks, then no MPI at all.
    let b = dir.join("four-then-none");
    mpi_evolve(4, &config, &b, &["--generations", "2"]);
    ok(vivae().args(["resume", "-q", "--generations", "6"]).arg(&b));
    assert_same_results(&reference, &b);

    // No MPI, then 3 ranks.
    let c = dir.join("none-then-three");
    evolve(&config, &c, &["--generations", "4"]);
    ok(mpirun(3)
        .args(["resume", "-q", "--threads", "1", "--generations", "6"])
        .arg(&c));
    assert_same_results(&reference, &c);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn retrain_under_mpi_matches_single_process_retrain() {
    let dir = scratch("mpi-retrain");
    let config = write_small_config(&dir, 2);
    let base = dir.join("base");
    evolve(&config, &base, &[]);
    let retrain = |out: &std::path::Path, mpi: Option<usize>| {
        let mut cmd = match mpi {
            Some(n) => mpirun(n),
            None => vivae(),
        };
        ok(cmd
            .args(["retrain", "-q", "--threads", "1", "--sensors", "4x6"])
            .args(["--generations", "2"])
            .arg(&base)
            .arg("--out")
            .arg(out));
    };
    let single = dir.join("retrain-single");
    retrain(&single, None);
    let distributed = dir.join("retrain-mpi");
    retrain(&distributed, Some(3));
    assert_same_results(&single, &distributed);
    std::fs::remove_dir_all(&dir).unwrap();
}
