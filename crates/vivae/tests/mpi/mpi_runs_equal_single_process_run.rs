//! `mpirun -n N vivae evolve` writes exactly the files of the single-process
//! run of the same config, for N = 1…4 and any threads per rank.
use crate::common::*;
use crate::mpi_common::*;

const GENERATIONS: u32 = 4;

#[test]
fn any_rank_count_gives_the_single_process_files() {
    let dir = scratch("mpi-equal");
    let config = write_small_config(&dir, GENERATIONS);
    let reference = dir.join("reference");
    evolve(&config, &reference, &["--threads", "2"]);
    for n in 1..=4 {
        let out = dir.join(format!("n{n}"));
        mpi_evolve(n, &config, &out, &[]);
        assert_same_results(&reference, &out);
        // Rank 0 alone writes: no stray temporary files from other ranks.
        let stray: Vec<_> = std::fs::read_dir(&out)
            .unwrap()
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains(".tmp-"))
            .collect();
        assert!(stray.is_empty(), "n={n}: {stray:?}");
    }
    // Threads per rank change speed, not results.
    let out = dir.join("n2-threads3");
    ok(mpirun(2)
        .args(["evolve", "-q", "--threads", "3", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(&out));
    assert_same_results(&reference, &out);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn rank_zero_reports_traffic_unless_quiet() {
    let dir = scratch("mpi-traffic");
    let config = write_small_config(&dir, 2);
    let out = run(mpirun(2)
        .args(["evolve", "--threads", "1", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(dir.join("run")));
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    let line = stderr
        .lines()
        .find(|l| l.starts_with("mpi: 2 ranks, 2 generations"))
        .unwrap_or_else(|| panic!("no traffic line in: {stderr}"));
    assert!(line.contains("bytes sent to workers"), "{line}");
    std::fs::remove_dir_all(&dir).unwrap();
}
