//! `vivae replay RUN --elite CELL` and `--front N` run the archive's or the
//! front's genome: the fitness it was recorded with, a figure of its own
//! (the champion's replay is not overwritten), and a one-line refusal of a
//! cell or member that is not there.

use std::path::Path;

use crate::common::*;

/// The first data row of a run's CSV file, split at commas.
fn first_row(dir: &Path, name: &str) -> Vec<String> {
    let text = String::from_utf8(read(dir, name)).unwrap();
    let row = text
        .lines()
        .nth(1)
        .unwrap_or_else(|| panic!("{name} is empty"));
    row.split(',').map(String::from).collect()
}

/// The `fitness=` value of a replay's summary line.
fn replayed_fitness(stdout: &str) -> String {
    let field = stdout
        .split_whitespace()
        .find(|f| f.starts_with("fitness="));
    field.unwrap_or_else(|| panic!("no fitness in {stdout}"))["fitness=".len()..].to_string()
}

/// The figures of a replay folder whose names end with `suffix`.
fn figures_ending(dir: &Path, suffix: &str) -> usize {
    std::fs::read_dir(dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .ends_with(suffix)
        })
        .count()
}

#[test]
fn an_elite_and_a_front_member_replay_with_their_recorded_fitness() {
    let dir = scratch("replay-members");
    let config = write_small_config(&dir, 3);
    let elites = dir.join("elites");
    evolve(&config, &elites, &["--strategy", "map-elites"]);
    let row = first_row(&elites, "archive.csv");
    let (cell, fitness) = (&row[0], &row[row.len() - 2]);
    let out = ok(vivae().args(["replay", "--elite", cell]).arg(&elites));
    assert_eq!(&replayed_fitness(&out), fitness, "{out}");
    ok(vivae().arg("replay").arg(&elites));
    let replays = elites.join("replay");
    assert_eq!(figures_ending(&replays, &format!("-elite{cell}.png")), 1);
    assert_eq!(
        figures_ending(&replays, "n3x3.png"),
        1,
        "the champion's own replay"
    );

    let missing = run(vivae().args(["replay", "--elite", "100000"]).arg(&elites));
    assert_eq!(missing.status.code(), Some(2));
    let err = String::from_utf8_lossy(&missing.stderr);
    assert!(
        err.contains("no elite in cell 100000") && err.lines().count() == 1,
        "{err}"
    );

    let front = dir.join("front");
    evolve(&config, &front, &["--strategy", "nsga2"]);
    let row = first_row(&front, "front.csv");
    assert_eq!(row[0], "0");
    let out = ok(vivae().args(["replay", "--front", "0"]).arg(&front));
    assert_eq!(replayed_fitness(&out), row[1], "{out}");
    assert_eq!(figures_ending(&front.join("replay"), "-front0.png"), 1);
    let neat = run(vivae().args(["replay", "--front", "0"]).arg(&elites));
    assert_eq!(neat.status.code(), Some(2), "a map-elites run has no front");
    std::fs::remove_dir_all(&dir).unwrap();
}
