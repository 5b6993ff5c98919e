//! The run-directory readers on arbitrary bytes. The bytes are written, in
//! turn, as each file of a run directory (a real one on disk: the readers
//! take paths, and check the file's kind and size as the commands do), then
//! read back through the same checked readers `report`, `compare`, `view`,
//! `resume` and `replay` use. Every reader must refuse or load; none may
//! panic, hang or allocate without bound.
#![no_main]
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use vivae_lab::rundir::{self, files};

/// This process's run directory (one per fuzzing process, reused).
fn run_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("vivae-fuzz-rundir-{}", std::process::id()));
        std::fs::create_dir_all(dir.join(files::FIGURES)).unwrap();
        dir
    })
}

fuzz_target!(|data: &[u8]| {
    let dir = run_dir();
    let put = |name: &str| std::fs::write(dir.join(name), data).unwrap();
    put(files::GENERATIONS);
    let _ = rundir::read_generations(&dir.join(files::GENERATIONS));
    put(files::TIMING);
    let _ = rundir::read_timing(&dir.join(files::TIMING));
    put(files::POPULATION);
    let _ = rundir::read_population_csv(&dir.join(files::POPULATION));
    put(files::BEST_GENOMES);
    let _ = rundir::read_best_genomes(&dir.join(files::BEST_GENOMES));
    put(files::CHAMPION);
    let _ = vivae_lab::tasks::read_champion(&dir.join(files::CHAMPION));
    // `replay RUN_DIR` and `view RUN_DIR`: champion.json and config.toml.
    put(files::CONFIG);
    let _ = vivae_lab::tasks::load_genome_source(dir);
    // `resume` on a finished run: are the figures and report up to date?
    std::fs::write(dir.join(files::FIGURES).join(files::DRAWN), data).unwrap();
    let _ = rundir::drawn_generations(dir);
});
