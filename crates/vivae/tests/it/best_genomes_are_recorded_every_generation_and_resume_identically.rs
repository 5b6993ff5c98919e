//! `best-genomes.jsonl` holds every generation's best genome (small: repeats
//! are references), reads back to the genomes the run found, and a resumed
//! run writes the same file as an uninterrupted one.

use crate::common;

use crate::common::{evolve, read, scratch, vivae, write_small_config};
use vivae_lab::rundir::read_best_genomes;
use vivae_lab::tasks::read_champion;

#[test]
fn every_generation_is_recorded_and_resume_writes_the_same_file() {
    let dir = scratch("best-genomes");
    let config = write_small_config(&dir, 12);
    let whole = dir.join("whole");
    evolve(&config, &whole, &[]);
    let best = read_best_genomes(&whole.join("best-genomes.jsonl")).unwrap();
    assert_eq!(
        best.iter().map(|b| b.generation).collect::<Vec<_>>(),
        (1..=12).collect::<Vec<_>>()
    );
    let champion = read_champion(&whole.join("champion.json")).unwrap();
    let at = &best[champion.generation as usize - 1];
    assert_eq!(at.genome, champion.genome);
    assert_eq!(at.fitness, champion.fitness);
    for b in &best {
        let members: usize = b.species.iter().map(|s| s.1).sum();
        assert_eq!(members, 24, "generation {}", b.generation);
    }

    let part = dir.join("part");
    let short = dir.join("short.toml");
    std::fs::write(&short, common::small_config(5)).unwrap();
    evolve(&short, &part, &[]);
    common::ok(
        vivae()
            .args(["resume", "-q", "--generations", "12"])
            .arg(&part),
    );
    assert!(
        read(&whole, "best-genomes.jsonl") == read(&part, "best-genomes.jsonl"),
        "best-genomes.jsonl differs after resume"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
