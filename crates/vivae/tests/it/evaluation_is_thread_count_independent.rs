//! Per-generation statistics do not depend on the number of worker threads.

use crate::common::*;

#[test]
fn one_and_two_threads_give_identical_runs() {
    let dir = scratch("threads");
    let config = write_small_config(&dir, 4);
    let one = dir.join("one");
    let two = dir.join("two");
    evolve(&config, &one, &["--threads", "1"]);
    evolve(&config, &two, &["--threads", "2"]);
    assert_same_results(&one, &two);
    std::fs::remove_dir_all(&dir).unwrap();
}
