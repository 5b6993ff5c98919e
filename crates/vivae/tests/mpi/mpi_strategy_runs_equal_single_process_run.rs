//! A novelty, map-elites or nsga2 run spread over MPI ranks writes exactly
//! the files of the single-process run: evaluations (fitness, behaviour and
//! metrics) travel whole.
use crate::common::*;
use crate::mpi_common::*;

#[test]
fn every_strategy_gives_the_single_process_files_under_mpi() {
    let dir = scratch("mpi-strategies");
    let config = write_small_config(&dir, 3);
    for (strategy, own) in [
        ("novelty", None),
        ("map-elites", Some("archive.jsonl")),
        ("nsga2", Some("front.jsonl")),
    ] {
        let reference = dir.join(format!("{strategy}-reference"));
        evolve(
            &config,
            &reference,
            &["--threads", "2", "--strategy", strategy],
        );
        let out = dir.join(format!("{strategy}-n3"));
        mpi_evolve(3, &config, &out, &["--strategy", strategy]);
        assert_same_results(&reference, &out);
        if let Some(own) = own {
            assert!(
                read(&reference, own) == read(&out, own),
                "{strategy}: {own}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
