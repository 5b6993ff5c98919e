//! `vivae compare`: several runs side by side.
//!
//! Reads each run directory's `generations.csv` (best fitness per generation)
//! and `timing.csv` (wall seconds per generation), groups the runs (by
//! `--label`, else by their substrate from `config.toml`, e.g. `3x5→3x3`, or
//! for a task without one by task and strategy, e.g. `cartpole (neat)`),
//! and draws one figure with two panels — best fitness per generation and
//! best-so-far fitness per cumulative wall-clock second — with a thin line per
//! run and a thick median line per group. The same comparison as numbers is
//! a Markdown table (stdout) and optionally a CSV file.

//!
//! `runs` reads and groups the runs, `table` makes the numbers, `plot`
//! draws the figure; [`run`](crate::figures::compare::run) does all three for the command.

mod plot;
mod runs;
mod table;

use std::path::{Path, PathBuf};

use vivae_lab::error::Result;
use vivae_lab::io::{bad_input, write_atomic};

use plot::draw;
pub use plot::{CompareOptions, render};
pub use runs::{
    Group, LabelRule, RunData, assign_labels, glob_match, group, load_groups, read_run, run_label,
    substrate_label,
};
pub use table::{
    AT_GENERATIONS, AT_SECONDS, Median, Summary, csv, markdown, median_per_generation,
    median_per_second, summarise,
};

/// Runs `vivae compare` on the run directories `runs`, grouped by `rules`:
/// writes the figure to `out` (.png or .svg) and the table as CSV to `csv_out`,
/// and returns the table in Markdown.
pub fn run(
    runs: &[PathBuf],
    rules: &[LabelRule],
    out: &Path,
    csv_out: Option<&Path>,
    opts: &CompareOptions,
) -> Result<String> {
    let svg_out = match out.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("svg") => true,
        Some(e) if e.eq_ignore_ascii_case("png") => false,
        _ => {
            return Err(bad_input(format!(
                "{}: the figure must be a .png or .svg file",
                out.display()
            )));
        }
    };
    let groups = load_groups(runs, rules)?;
    let summaries: Vec<Summary> = groups.iter().map(summarise).collect();
    let bytes = if svg_out {
        draw(&groups, opts)?.into_bytes()
    } else {
        render(&groups, opts)?.png
    };
    // Both outputs' folders are made first (as `evolve` and `replay` make
    // theirs), so that one is not written without the other.
    for path in std::iter::once(out).chain(csv_out) {
        if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
            vivae_lab::io::create_dirs_for(parent, path)?;
        }
    }
    if let Some(path) = csv_out {
        write_atomic(path, csv(&summaries).as_bytes())?;
    }
    write_atomic(out, &bytes)?;
    Ok(markdown(&summaries))
}

#[cfg(test)]
mod tests {
    use super::plot::*;
    use super::table::*;
    use super::*;
    use crate::figures::FigureError;
    use crate::figures::test_util::{distinct_colours, png_size};

    fn run(name: &str, best: &[f64], seconds: &[f64]) -> RunData {
        RunData {
            dir: PathBuf::from(name),
            best: best.to_vec(),
            seconds: seconds.to_vec(),
        }
    }

    #[test]
    fn globs_match_within_path_components() {
        assert!(glob_match("cam16-s*", "cam16-s1"));
        assert!(glob_match("runs/cam16-s?", "runs/cam16-s3"));
        assert!(glob_match("*", "x"));
        assert!(glob_match("a*b*c", "aXbYbc"));
        assert!(!glob_match("runs/*", "runs/a/b"), "* does not cross /");
        assert!(!glob_match("cam16-s?", "cam16-s12"));
        assert!(!glob_match("paper", "paper-seed-1"));
        assert!(glob_match("", ""));
    }

    #[test]
    fn label_rules_parse_and_match_path_or_folder_name() {
        let rule: LabelRule = "camera 16=/work/runs/cam16-s*".parse().unwrap();
        assert_eq!(rule.name, "camera 16");
        assert!(rule.matches(Path::new("/work/runs/cam16-s2/")));
        let by_name: LabelRule = "paper=paper-seed-*".parse().unwrap();
        assert!(by_name.matches(Path::new("../main/runs/paper-seed-4")));
        assert!(!by_name.matches(Path::new("runs/cam16-s1")));
        for bad in ["noequals", "=x", "x="] {
            assert!(bad.parse::<LabelRule>().is_err(), "{bad}");
        }
    }

    #[test]
    fn first_matching_label_wins_and_unused_labels_are_refused() {
        let dirs = [
            PathBuf::from("r/a-1"),
            PathBuf::from("r/a-2"),
            PathBuf::from("r/b"),
        ];
        let rules: Vec<LabelRule> = ["one=a-1", "rest=a-*"]
            .iter()
            .map(|s| s.parse().unwrap())
            .collect();
        let labels = assign_labels(&dirs, &rules).unwrap();
        assert_eq!(
            labels,
            [Some("one".to_string()), Some("rest".to_string()), None]
        );
        let typo = vec!["x=zzz*".parse().unwrap()];
        let err = assign_labels(&dirs, &typo).unwrap_err();
        assert!(err.is_bad_input());
        assert!(err.to_string().contains("matches none"), "{err}");
    }

    #[test]
    fn groups_keep_first_appearance_order() {
        let runs = vec![
            run("a", &[1.0], &[1.0]),
            run("b", &[2.0], &[1.0]),
            run("c", &[3.0], &[1.0]),
        ];
        let names = ["x".to_string(), "y".into(), "x".into()];
        let groups = group(runs, &names);
        assert_eq!(groups.len(), 2);
        assert_eq!(groups[0].name, "x");
        assert_eq!(groups[0].runs.len(), 2);
        assert_eq!(groups[0].runs[1].dir, PathBuf::from("c"));
        assert_eq!(groups[1].runs[0].dir, PathBuf::from("b"));
    }

    #[test]
    fn best_so_far_at_wall_seconds() {
        let r = run("a", &[1.0, 3.0, 2.0, 4.0], &[10.0, 10.0, 10.0, 10.0]);
        assert_eq!(r.best_so_far(), [1.0, 3.0, 3.0, 4.0]);
        assert_eq!(r.cumulative_seconds(), [10.0, 20.0, 30.0, 40.0]);
        assert_eq!(r.best_at_seconds(5.0), None, "no generation done yet");
        assert_eq!(r.best_at_seconds(10.0), Some(1.0));
        assert_eq!(r.best_at_seconds(35.0), Some(3.0));
        assert_eq!(r.best_at_seconds(40.0), Some(4.0));
        assert_eq!(r.best_at_seconds(41.0), None, "the run stopped before");
    }

    #[test]
    fn summary_medians_count_only_runs_that_got_there() {
        let g = Group {
            name: "g".into(),
            runs: vec![
                run("a", &[1.0; 10], &[1.0; 10]),
                run("b", &[2.0; 50], &[2.0; 50]),
                run("c", &[4.0; 60], &[3.0; 60]),
            ],
        };
        let s = summarise(&g);
        assert_eq!(s.seeds, 3);
        assert_eq!(s.generations, (10, 60));
        assert_eq!(
            s.at_generation[0],
            (
                10,
                Median {
                    value: Some(2.0),
                    runs: 3
                }
            )
        );
        assert_eq!(
            s.at_generation[1],
            (
                50,
                Median {
                    value: Some(3.0),
                    runs: 2
                }
            )
        );
        assert_eq!(
            s.at_generation[2],
            (
                100,
                Median {
                    value: None,
                    runs: 0
                }
            )
        );
        assert_eq!(s.seconds_per_generation, 2.0);
        // 30 s: a ran 10 s only; b (100 s) and c (180 s) did.
        assert_eq!(
            s.at_seconds[0].1,
            Median {
                value: Some(3.0),
                runs: 2
            }
        );
        assert_eq!(
            s.at_seconds[1].1,
            Median {
                value: Some(4.0),
                runs: 1
            }
        );
        assert_eq!(s.at_seconds[2].1.value, None);
        assert_eq!(s.final_best, 2.0);

        let table = markdown(std::slice::from_ref(&s));
        let lines: Vec<&str> = table.lines().collect();
        assert_eq!(lines.len(), 3);
        assert!(lines[0].contains("best @ gen 50") && !lines[0].contains("gen 100"));
        assert_eq!(
            lines[2],
            "| g | 3 | 10–60 | 2.000 | 3.000 (2/3) | 2.000 | 3.000 (2/3) | 4.000 (1/3) | — | 2.000 |"
        );
        let csv = csv(&[s]);
        let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
        assert_eq!(rows[0].len(), rows[1].len());
        let col = |name: &str| rows[1][rows[0].iter().position(|h| *h == name).unwrap()];
        assert_eq!(col("best_gen_50"), "3");
        assert_eq!(col("best_gen_50_runs"), "2");
        assert_eq!(col("best_gen_400"), "");
        assert_eq!(col("best_so_far_120s"), "4");
    }

    #[test]
    fn median_lines_span_what_every_run_reached() {
        let g = Group {
            name: "g".into(),
            runs: vec![
                run("a", &[1.0, 2.0, 3.0], &[1.0, 1.0, 1.0]),
                run("b", &[3.0, 4.0], &[2.0, 2.0]),
            ],
        };
        assert_eq!(median_per_generation(&g), [2.0, 3.0]);
        // From 2 s (b's first generation) to 3 s (a's end).
        assert_eq!(median_per_second(&g), [(2.0, 2.5), (3.0, 2.5), (3.0, 3.0)]);
    }

    #[test]
    fn renders_both_panels_with_legend() {
        let rising = |k: f64| {
            (1..=80)
                .map(|g| 4.0 * (1.0 - (-(g as f64) / k).exp()))
                .collect::<Vec<_>>()
        };
        let groups = vec![
            Group {
                name: "3x5→3x3".into(),
                runs: vec![
                    run("a", &rising(20.0), &[0.1; 80]),
                    run("b", &rising(25.0), &[0.12; 80]),
                ],
            },
            Group {
                name: "16x48→9x9".into(),
                runs: vec![run("c", &rising(10.0), &[2.0; 80])],
            },
        ];
        let fig = render(&groups, &CompareOptions::default()).unwrap();
        assert_eq!(png_size(&fig.png), (2600, 1160));
        assert!(distinct_colours(&fig.png) > 50);
        for text in [
            "generation",
            "wall-clock seconds",
            "best-so-far fitness",
            "3x5→3x3 (2 runs, median)",
            "16x48→9x9 (1 run)",
        ] {
            assert!(fig.svg.contains(text), "missing {text:?}");
        }
        assert!(matches!(
            render(&[], &CompareOptions::default()),
            Err(FigureError::NoData(_))
        ));
    }
}
