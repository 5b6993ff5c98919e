//! Per-generation statistics do not depend on the number of worker threads.

mod common;
use common::*;

#[test]
fn one_and_two_threads_give_identical_runs() {
    let dir = scratch("threads");
    let config = dir.join("c.toml");
    std::fs::write(&config, small_config(4)).unwrap();
    let one = dir.join("one");
    let two = dir.join("two");
    ok(vivae()
        .args(["evolve", "-q", "--threads", "1", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(&one));
    ok(vivae()
        .args(["evolve", "-q", "--threads", "2", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(&two));
    assert_same_results(&one, &two);
    std::fs::remove_dir_all(&dir).unwrap();
}
