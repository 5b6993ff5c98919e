//! The run directory: its file names and formats, and every read and write
//! of them. A run directory holds `config.toml`, `scenario.svg` (or
//! `scenarios/` for a multi-map run), `generations.csv`, `population.csv`,
//! `timing.csv`, `best-genomes.jsonl`, `champion.json`, `checkpoints/` and,
//! at the end, `figures/` and `report.html` (then `figures/drawn-generations.txt`,
//! the record that they are complete). CSV files are appended once per
//! generation; a checkpoint records their lengths, so resuming truncates
//! whatever a crash left after the last checkpoint and the finished files
//! are byte-identical to an uninterrupted run's. Other modules and the
//! program ask this one; none of them names a file of a run itself.

use std::fmt::Write as _;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use vivae_neat::Genome;

use crate::config::Config;
use crate::error::{Error, Result};
use crate::io::{bad_input, fnv1a, read_text, safe_file_stem, write_atomic};

mod champion;
mod checkpoint;
mod lifecycle;
mod maps;
pub mod pictures;
pub mod replace;
mod rows;

pub use champion::*;
pub use checkpoint::*;
pub use lifecycle::*;
pub use maps::*;
pub use rows::*;

/// File names inside a run directory.
pub mod files {
    /// The fully resolved configuration.
    pub const CONFIG: &str = "config.toml";
    /// The scenario the run uses.
    pub const SCENARIO: &str = "scenario.svg";
    /// Per-generation statistics.
    pub const GENERATIONS: &str = "generations.csv";
    /// Every individual's fitness per generation (Fig. 8).
    pub const POPULATION: &str = "population.csv";
    /// Wall-clock time per generation.
    pub const TIMING: &str = "timing.csv";
    /// The best genome ever.
    pub const CHAMPION: &str = "champion.json";
    /// Checkpoint folder.
    pub const CHECKPOINTS: &str = "checkpoints";
    /// Figure folder.
    pub const FIGURES: &str = "figures";
    /// A copy of the population a run starts from (retrain).
    pub const INIT_POPULATION: &str = "init-population.json";
    /// Each generation's best genome and species sizes, one JSON line per generation.
    pub const BEST_GENOMES: &str = "best-genomes.jsonl";
    /// The self-contained HTML report of the run.
    pub const REPORT: &str = "report.html";
    /// The champion's validation on fresh episodes (a task with a reward
    /// threshold; [`crate::tasks::validation`]).
    pub const VALIDATION: &str = "validation.json";
    /// In `figures/`: how many generations the figures and `report.html`
    /// show, written last once they are all drawn ([`super::mark_drawn`]).
    pub const DRAWN: &str = "drawn-generations.txt";
}

/// Whether `dir` is a run directory: it holds `config.toml` and a
/// checkpoint (`checkpoints/`, or `checkpoint.json` for a task on a driver
/// of its own). Outputs the user names are refused inside one
/// ([`crate::output_path`]): its files are the run's.
pub fn is_run_dir(dir: &Path) -> bool {
    dir.join(files::CONFIG).is_file()
        && (dir.join(files::CHECKPOINTS).is_dir() || dir.join("checkpoint.json").is_file())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh, empty folder for the test that names it `name` (unique
    /// among this module's tests, which run side by side in one process).
    pub(in crate::rundir) fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("vivae-rundir-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// `text` written as a file of a fresh folder, read by `read`.
    fn read_back<T>(name: &str, text: &str, read: impl Fn(&Path) -> Result<T>) -> Result<T> {
        let dir = scratch(name);
        let path = dir.join(name);
        fs::write(&path, text).unwrap();
        let out = read(&path);
        fs::remove_dir_all(&dir).unwrap();
        out
    }

    #[test]
    fn population_rows_out_of_order_are_refused_without_allocating_for_them() {
        // Found while writing the `rundir_reader` fuzz target (and confirmed
        // with it): this 40-byte file made `report` allocate 24 GB, one
        // empty generation per number skipped.
        let e = read_back(
            files::POPULATION,
            "generation,rank,fitness\n999999999,1,1\n",
            read_population_csv,
        )
        .unwrap_err();
        let message = e.to_string();
        assert!(e.is_bad_input(), "{e:?}");
        assert!(
            message.contains("line 2: generation 999999999 where 1 was expected"),
            "{message}"
        );
        for (text, line) in [
            ("1,1,0.5\n3,1,0.5\n", 3),
            ("1,1,0.5\n2,1,0.5\n1,2,0.1\n", 4),
            ("18446744073709551615,1,1\n", 2),
        ] {
            let e = read_back(
                files::POPULATION,
                &format!("generation,rank,fitness\n{text}"),
                read_population_csv,
            )
            .unwrap_err();
            assert!(
                e.to_string().contains(&format!("line {line}: generation")),
                "{e}"
            );
        }
        let ok = read_back(
            files::POPULATION,
            "generation,rank,fitness\n1,1,0.5\n1,2,0.25\n2,1,0.75\n",
            read_population_csv,
        )
        .unwrap();
        assert_eq!(ok, [vec![0.5, 0.25], vec![0.75]]);
    }

    #[test]
    fn best_genome_references_are_looked_up_not_searched_and_bounded_in_memory() {
        let genome: Genome = serde_json::from_str(
            r#"{"nodes":[{"id":0,"kind":"input","activation":"linear"},{"id":1,"kind":"output","activation":"linear"}],"links":[{"innovation":0,"from":0,"to":1,"weight":0.5,"enabled":true}]}"#,
        )
        .unwrap();
        let first =
            serde_json::json!({"generation": 1, "fitness": 1.0, "species": [], "genome": genome});
        let line =
            |k: u32| format!("{{\"generation\":{k},\"fitness\":1,\"species\":[],\"same_as\":1}}\n");
        // 200 000 lines that all name the first: read at once (it used to
        // search every earlier line for each, 2·10¹⁰ steps).
        let mut text = format!("{first}\n");
        for k in 2..=200_000 {
            text.push_str(&line(k));
        }
        let best = read_back(files::BEST_GENOMES, &text, read_best_genomes).unwrap();
        assert_eq!(best.len(), 200_000);
        assert_eq!(best[199_999].genome, genome);
        // Past the memory bound (here 1 MiB), refused, naming the line.
        let path = Path::new(files::BEST_GENOMES);
        let fits = (1u64 << 20) / genome_size(&genome);
        let e = parse_best_genomes(&text, path, 1 << 20).unwrap_err();
        assert!(e.is_bad_input(), "{e:?}");
        assert!(
            e.to_string().contains(&format!(
                "line {}: its genomes would take more than 1 MiB",
                fits + 1
            )),
            "{e}"
        );
    }
}
