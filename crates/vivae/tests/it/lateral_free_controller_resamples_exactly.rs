//! `substrate.recurrence`: a controller without lateral links (`self`),
//! self-loops exempt from normalisation, drives exactly as well at 9×9 neurons
//! as at 3×3 (its wheel neurons keep their positions, inputs and memory), while
//! the same genome with the paper's full recurrence does not; and the setting
//! is recorded in the run's config and honoured by replay.

use crate::common::*;

fn fitness(line: &str) -> f64 {
    number(line, "fitness")
}

fn replay(run: &std::path::Path, extra: &[&str]) -> f64 {
    fitness(&ok(vivae()
        .arg("replay")
        .arg(run)
        .args(extra)
        .arg("-o")
        .arg(run.join("replays"))))
}

#[test]
fn lateral_free_controller_keeps_its_fitness_at_9x9() {
    let dir = scratch("lateral-free");
    let config = write_small_config(&dir, 3);
    let run = dir.join("run");
    evolve(
        &config,
        &run,
        &["--recurrence", "self", "--normalize-self-loops", "false"],
    );
    let recorded = std::fs::read_to_string(run.join("config.toml")).unwrap();
    assert!(recorded.contains(r#"recurrence = "self""#), "{recorded}");

    let own = replay(&run, &[]);
    assert!(own > 0.0, "the champion moves");
    assert_eq!(replay(&run, &["--neurons", "9x9"]), own);
    assert_eq!(replay(&run, &["--neurons", "15x15"]), own);

    // Putting the lateral links back changes what the 9x9 sheet does.
    let full_3 = replay(&run, &["--recurrence", "full"]);
    let full_9 = replay(&run, &["--recurrence", "full", "--neurons", "9x9"]);
    assert_ne!(full_3, full_9, "lateral links made no difference at 9x9");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn unknown_recurrence_is_refused() {
    let out = run(vivae().args(["evolve", "-q", "--recurrence", "some"]));
    // A usage error: clap's message, exit 2, nothing run.
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("full, self or none"), "{err}");
}
