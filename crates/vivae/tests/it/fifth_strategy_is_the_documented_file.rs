//! The (1+λ) evolution strategy docs/architecture.md shows, as a strategy
//! costs, is the shipped file word for word (with `crate::` read as
//! `vivae_lab::`); its run writes its settings section with every key, and
//! a bad setting in its section is refused in one line naming the key.

use crate::common::*;

/// The `rust` block between the page's one-plus-lambda markers, without its
/// hidden (`# `) lines.
fn documented() -> String {
    let page = include_str!("../../../../docs/architecture.md");
    let start = page.find("<!-- one-plus-lambda: begin -->\n```\n").unwrap();
    let block = &page[start..];
    let block = &block[block.find("```\n").unwrap() + 4..];
    let block = &block[..block.find("```\n").unwrap()];
    let shown: Vec<&str> = (block.lines())
        .filter(|l| *l != "#" && !l.starts_with("# "))
        .collect();
    shown.join("\n") + "\n"
}

#[test]
fn the_documented_strategy_is_the_shipped_file() {
    let file = include_str!("../../../lab/src/search/one_plus_lambda.rs");
    let body: Vec<&str> = file.lines().skip_while(|l| l.starts_with("//!")).collect();
    let body = body
        .join("\n")
        .trim_start()
        .replace("crate::", "vivae_lab::")
        + "\n";
    assert!(
        documented() == body,
        "docs/architecture.md's (1+λ) block is not one_plus_lambda.rs"
    );
}

#[test]
fn a_registered_strategy_section_is_written_whole_and_checked() {
    let dir = scratch("one-plus-lambda-settings");
    let config = write_small_config(&dir, 2);
    let run = dir.join("run");
    let line = evolve(&config, &run, &["--strategy", "one-plus-lambda"]);
    assert_eq!(field(&line, "strategy"), "one-plus-lambda");
    let written = String::from_utf8(read(&run, "config.toml")).unwrap();
    assert!(
        written.contains("[strategy.one_plus_lambda]\nlambda = 10\n"),
        "{written}"
    );
    // λ = 10 genomes a generation, as the section says.
    let csv = String::from_utf8(read(&run, "population.csv")).unwrap();
    let generation = |l: &&str| l.split(',').next().map(str::to_string);
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    let first = rows.first().and_then(generation);
    assert_eq!(
        rows.iter().filter(|l| generation(l) == first).count(),
        10,
        "{csv}"
    );
    for (section, needle) in [
        (
            "lambda = 0",
            "strategy.one_plus_lambda.lambda = 0: must be in 1..=",
        ),
        ("lamda = 3", "unknown field `lamda`"),
    ] {
        let bad = dir.join("bad.toml");
        let text = format!(
            "[strategy]\nkind = \"one-plus-lambda\"\n\n[strategy.one_plus_lambda]\n{section}\n"
        );
        std::fs::write(&bad, text).unwrap();
        let out = run_cmd(
            vivae()
                .args(["evolve", "-q", "--config"])
                .arg(&bad)
                .arg("--out")
                .arg(dir.join("no")),
        );
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.contains(needle) && err.trim_end().lines().count() == 1,
            "{needle}: {err}"
        );
        assert!(!dir.join("no").exists());
    }
    // A key of [strategy] that is neither a field nor a registered section.
    let typo = dir.join("typo.toml");
    std::fs::write(&typo, "[strategy]\nknd = \"neat\"\n").unwrap();
    let out = run_cmd(
        vivae()
            .args(["evolve", "-q", "--config"])
            .arg(&typo)
            .arg("--out")
            .arg(dir.join("no")),
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("unknown field `knd`") && err.contains("`one_plus_lambda`"),
        "{err}"
    );
}

/// [`run`] (the common helper), named apart from this file's run folders.
fn run_cmd(cmd: &mut std::process::Command) -> std::process::Output {
    run(cmd)
}
