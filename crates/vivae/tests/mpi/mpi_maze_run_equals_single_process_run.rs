//! A maze run (`--task maze`) spread over MPI ranks writes exactly the files
//! of the single-process run, and a solved one stops at the same evaluation.
use crate::common::*;
use crate::mpi_common::*;

#[test]
fn a_maze_run_gives_the_single_process_files_and_summary_under_mpi() {
    let dir = scratch("mpi-maze");
    let flags = ["--task", "maze", "--strategy", "novelty", "--seed", "1"];
    let reference = dir.join("reference");
    let single = ok(vivae()
        .args(["evolve", "-q", "--threads", "2"])
        .args(flags)
        .arg("--out")
        .arg(&reference));
    let out = dir.join("n3");
    let spread = ok(mpirun(3)
        .args(["evolve", "-q", "--threads", "1"])
        .args(flags)
        .arg("--out")
        .arg(&out));
    assert_same_results(&reference, &out);
    let fields = |line: &str| -> Vec<String> {
        (line.split_whitespace())
            .filter(|w| {
                ["solved=", "evals_to_solve=", "generations="]
                    .iter()
                    .any(|k| w.starts_with(k))
            })
            .map(String::from)
            .collect()
    };
    assert_eq!(fields(&single), fields(&spread), "{single}\n{spread}");
    assert_eq!(fields(&single).len(), 3, "{single}");
    std::fs::remove_dir_all(&dir).unwrap();
}
