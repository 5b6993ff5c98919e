//! `--substrate es-hyperneat` evolves ES-HyperNEAT controllers through the
//! whole pipeline, a resumed run ends with exactly the files of one that went
//! straight through, and bad `[substrate.es]` keys are refused in one line.
//! The same holds with LEO and its locality seed (`substrate.es.leo`, `leo_seed`).

use std::path::{Path, PathBuf};

use crate::common::*;

/// Evolves `config` (4 generations) with `flags` in `dir/full`, and for 2
/// generations resumed to 4 in `dir/short`; both must end with the same
/// files. Returns the straight run.
fn evolve_and_resume_identically(dir: &Path, config: &Path, flags: &[&str]) -> PathBuf {
    let full = dir.join("full");
    evolve(config, &full, flags);
    let short = dir.join("short");
    evolve(config, &short, &[flags, &["--generations", "2"]].concat());
    ok(vivae()
        .args(["resume", "-q", "--generations", "4"])
        .arg(&short));
    assert_same_results(&full, &short);
    full
}

#[test]
fn es_hyperneat_run_evolves_and_resumes_identically() {
    let dir = scratch("es-resume");
    let config = write_small_config(&dir, 4);
    let full = evolve_and_resume_identically(&dir, &config, &["--substrate", "es-hyperneat"]);
    let text = String::from_utf8(read(&full, "config.toml")).unwrap();
    assert!(text.contains("kind = \"es-hyperneat\""), "{text}");
    let generations = String::from_utf8(read(&full, "generations.csv")).unwrap();
    let bests: Vec<f64> = generations
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    assert_eq!(bests.len(), 4);
    assert!(bests[3] > 0.0, "no ES controller moved: {generations}");

    // The run's champion replays to the fitness it was recorded with.
    let line = ok(vivae().arg("replay").arg(&full));
    assert!(line.starts_with("fitness="), "{line}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn es_leo_seeded_run_writes_its_keys_resumes_identically_and_replays() {
    let dir = scratch("es-leo-resume");
    let config = dir.join("leo.toml");
    let keys =
        "[substrate]\nkind = \"es-hyperneat\"\n\n[substrate.es]\nleo = true\nleo_seed = true\n";
    std::fs::write(&config, format!("{}{keys}", small_config(4))).unwrap();
    let full = evolve_and_resume_identically(&dir, &config, &[]);
    let text = String::from_utf8(read(&full, "config.toml")).unwrap();
    assert!(
        text.contains("leo = true") && text.contains("leo_seed = true"),
        "{text}"
    );

    // The champion replays to its recorded fitness, and its network figure
    // draws the ES neurons LEO kept.
    let line = ok(vivae().arg("replay").arg(&full));
    assert!(line.starts_with("fitness="), "{line}");
    let svg = String::from_utf8(read(&full, "figures/network.svg")).unwrap();
    assert!(svg.contains("hidden neurons found"), "{svg}");

    // Without the keys the run's config has none of them.
    let plain = dir.join("plain");
    evolve(
        &write_small_config(&dir, 1),
        &plain,
        &["--substrate", "es-hyperneat"],
    );
    let text = String::from_utf8(read(&plain, "config.toml")).unwrap();
    assert!(!text.contains("leo"), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_es_keys_are_refused_in_one_line() {
    let dir = scratch("es-bad-keys");
    for (extra, needle) in [
        (
            "[substrate.es]\nmax_depth = 11\n",
            "substrate.es.max_depth = 11",
        ),
        (
            "[substrate.es]\ninitial_depth = 4\n",
            "substrate.es.initial_depth = 4",
        ),
        (
            "[substrate.es]\nband_threshold = -0.1\n",
            "substrate.es.band_threshold",
        ),
        (
            "[substrate.es]\niteration_level = 17\n",
            "substrate.es.iteration_level",
        ),
        ("[substrate.es]\ndepth = 3\n", "depth"),
        ("[substrate.es]\nleo = true\n", "substrate.es.leo = true"),
        (
            "[substrate]\nkind = \"es-hyperneat\"\n[substrate.es]\nleo_seed = true\n",
            "substrate.es.leo_seed = true",
        ),
        (
            "[strategy]\nkind = \"nsga2\"\n[substrate]\nkind = \"es-hyperneat\"\n[substrate.es]\nleo = true\nleo_seed = true\n",
            "substrate.es.leo_seed",
        ),
        ("[substrate]\nkind = \"es\"\n", "es-hyperneat"),
        (
            "[substrate]\nkind = \"es-hyperneat\"\nrecurrence = \"self\"\n",
            "substrate.recurrence",
        ),
        (
            "[substrate]\nkind = \"es-hyperneat\"\n[distance_sensors]\nrays = 5\n",
            "distance_sensors.rays",
        ),
    ] {
        let path = dir.join("bad.toml");
        std::fs::write(&path, format!("{}{extra}", small_config(1))).unwrap();
        let out = run(vivae()
            .args(["evolve", "-q", "--config"])
            .arg(&path)
            .arg("--out")
            .arg(dir.join("run")));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{extra}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{extra}: {err}");
        assert!(err.contains(needle), "{extra}: {err}");
    }
    let out = run(vivae().args(["evolve", "-q", "--substrate", "dense"]));
    assert_eq!(out.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).unwrap();
}
