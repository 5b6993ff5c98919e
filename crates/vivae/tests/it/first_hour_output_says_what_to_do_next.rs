//! What a new user reads in the first hour (issue 25): the closing summary
//! names report.html and `vivae view`; every command names itself and says
//! what it wrote; a resumed run counts the generations it ran; replays are
//! named for their scenario and wiring; a multi-map run reports each map.

use crate::common::*;

fn stderr_of(out: &std::process::Output) -> String {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn closing_summary_names_the_report_and_the_viewer_and_resume_counts_its_generations() {
    let dir = scratch("first-hour-summary");
    let config = write_small_config(&dir, 2);
    let run_dir = dir.join("run");
    let err = stderr_of(&run(vivae()
        .arg("evolve")
        .arg("--config")
        .arg(&config)
        .arg("--out")
        .arg(&run_dir)));
    let shown = run_dir.display().to_string();
    assert!(err.starts_with("vivae evolve: "), "{err}");
    assert!(err.contains("done: 2 generations in "), "{err}");
    assert!(err.contains(&format!("{shown}/report.html")), "{err}");
    assert!(err.contains(&format!("vivae view {shown}")), "{err}");
    assert!(run_dir.join("report.html").is_file());

    let err = stderr_of(&run(vivae()
        .arg("resume")
        .arg(&run_dir)
        .args(["--generations", "3"])));
    assert!(err.starts_with("vivae resume: "), "{err}");
    assert!(
        err.contains("done: 1 generation (generations 3–3; 3 in all) in "),
        "{err}"
    );

    let err = stderr_of(&run(vivae()
        .arg("retrain")
        .arg(&run_dir)
        .args(["--neurons", "3x3", "--generations", "1", "--out"])
        .arg(dir.join("retrained"))));
    assert!(err.starts_with("vivae retrain: "), "{err}");
    assert!(err.contains("done: 1 generation in "), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn scenario_render_says_what_it_wrote() {
    let dir = scratch("first-hour-render");
    let out = dir.join("s.png");
    let err = stderr_of(&run(vivae().args(["scenario", "render", "-o"]).arg(&out)));
    assert_eq!(err.trim(), format!("figure: {}", out.display()));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn replays_are_named_for_the_scenario_and_their_wiring() {
    let dir = scratch("first-hour-replay");
    let config = write_small_config(&dir, 1);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &["--scenario", "oval"]);
    let figures = dir.join("replays");
    let mut names = Vec::new();
    for flags in [
        &[][..],
        &["--recurrence", "self"][..],
        &["--normalize-by", "area", "--normalize-self-loops", "false"][..],
    ] {
        let err = stderr_of(&run(vivae()
            .arg("replay")
            .arg(&run_dir)
            .args(flags)
            .arg("--out")
            .arg(&figures)));
        let figure = err
            .lines()
            .find_map(|l| l.strip_prefix("figure: "))
            .unwrap_or_else(|| panic!("no figure in {err}"));
        assert!(std::path::Path::new(figure).is_file(), "{figure}");
        names.push(
            std::path::Path::new(figure)
                .file_name()
                .unwrap()
                .to_string_lossy()
                .into_owned(),
        );
    }
    assert_eq!(
        names,
        [
            "replay-oval-s3x5-n3x3.png",
            "replay-oval-s3x5-n3x3-recurrence-self.png",
            "replay-oval-s3x5-n3x3-normalize-by-area-normalize-self-loops-false.png",
        ]
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_multi_map_run_reports_and_draws_every_map() {
    let dir = scratch("first-hour-multi-map");
    let config = write_small_config(&dir, 1);
    let run_dir = dir.join("run");
    let summary = evolve(
        &config,
        &run_dir,
        &["--scenario", "roads", "--scenario", "oval"],
    );
    let best = number(&summary, "best");
    let per_map: Vec<(&str, f64)> = field(&summary, "per_map")
        .split(',')
        .map(|p| {
            let (label, f) = p.split_once(':').unwrap();
            (label, f.parse().unwrap())
        })
        .collect();
    assert_eq!(
        per_map.iter().map(|p| p.0).collect::<Vec<_>>(),
        ["roads", "oval"]
    );
    let mean = (per_map[0].1 + per_map[1].1) / 2.0;
    assert!((mean - best).abs() < 1e-3, "{per_map:?} vs best {best}");
    for map in ["roads", "oval"] {
        let png = run_dir.join(format!("figures/trajectories-champion-{map}.png"));
        assert!(png.is_file(), "missing {}", png.display());
    }
    // The single-map summary has no per_map field.
    let single = evolve(&config, &dir.join("single"), &[]);
    assert!(!single.contains("per_map="), "{single}");
    std::fs::remove_dir_all(&dir).unwrap();
}
