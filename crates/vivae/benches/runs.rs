//! Speed of whole runs, the first two rows of the speed table
//! (docs/benchmarks.md): the default run (400 generations, 3×5 → 3×3) and
//! the camera run (8 generations, 32×96 → 9×9), each in both precisions,
//! on every core, as `vivae evolve` runs them. Timed is the evolution with
//! its checkpoints; not timed are creating the run directory and the figures
//! and report `evolve` draws afterwards (the `figures` benchmarks time those).
//!
//! A sample is a whole run (10–30 s), so each benchmark takes 3 samples;
//! `scripts/speed-table.sh` times the same runs through the program.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use vivae_lab::run::Run;
use vivae_lab::run::prepare::{Overrides, config, prepare};

fn main() {
    divan::main();
}

/// A directory this benchmark creates (it refuses one that exists) and
/// removes when dropped, with the run in `run/` inside it.
struct Scratch(PathBuf);

impl Scratch {
    fn new() -> Scratch {
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        let k = NEXT.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("vivae-bench-runs-{}-{k}", std::process::id()));
        std::fs::create_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
        Scratch(dir)
    }

    fn run_dir(&self) -> PathBuf {
        self.0.join("run")
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// `vivae evolve --precision PRECISION` with `settings` (key, value) as its
/// other options, created in a fresh directory before each sample and
/// evolved to its end in the sample.
fn whole_run(bencher: divan::Bencher, precision: &str, settings: &[(&str, &str)]) {
    let mut overrides = Overrides::default();
    for (key, value) in settings.iter().chain(&[("precision", precision)]) {
        overrides.set(key, value).unwrap();
    }
    let config = config(None, &overrides, "benchmark").unwrap();
    bencher
        .with_inputs(|| {
            let scratch = Scratch::new();
            let run = prepare(config.clone(), false)
                .unwrap()
                .create(&scratch.run_dir(), false)
                .unwrap();
            (scratch, run)
        })
        .bench_local_values(|(scratch, mut run): (Scratch, Run)| {
            run.run(&AtomicBool::new(false), |_| {}).unwrap();
            (scratch, run)
        });
}

/// The default run: `vivae evolve --precision exact|fast`.
#[divan::bench(args = ["exact", "fast"], sample_count = 3, sample_size = 1)]
fn default_run(bencher: divan::Bencher, precision: &str) {
    whole_run(bencher, precision, &[]);
}

/// The camera run: `vivae evolve --sensors 32x96 --neurons 9x9 --generations 8`.
#[divan::bench(args = ["exact", "fast"], sample_count = 3, sample_size = 1)]
fn camera_run(bencher: divan::Bencher, precision: &str) {
    whole_run(
        bencher,
        precision,
        &[
            ("sensors", "32x96"),
            ("neurons", "9x9"),
            ("generations", "8"),
        ],
    );
}
