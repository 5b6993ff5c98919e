//! A run whose evaluations depend on the genome alone runs each distinct
//! genome once, reusing the evaluation of an equal genome of the same or the
//! last generation (NEAT's elites, children no mutation changed), and says
//! how many it reused; a run whose episodes are placed from the evaluation's
//! seed reuses none. That the reuse changes no bit is guarded by the pinned
//! hash of the default run and by the library's tests.

use crate::common::*;

/// The `evaluations_reused=` field of a summary line.
fn reused(summary: &str) -> u64 {
    field(summary, "evaluations_reused").parse().unwrap()
}

#[test]
fn repeated_genomes_are_run_once_unless_the_seed_places_the_episode() {
    let dir = scratch("reuse");
    let config = write_small_config(&dir, 4);
    let roads = evolve(&config, &dir.join("roads"), &[]);
    // Every generation after the first copies at least its elites.
    assert!(reused(&roads) >= 3, "{roads}");
    let placed = evolve(
        &config,
        &dir.join("placed"),
        &["--scenario", "obstacles-random"],
    );
    assert_eq!(reused(&placed), 0, "{placed}");
    std::fs::remove_dir_all(&dir).unwrap();
}
