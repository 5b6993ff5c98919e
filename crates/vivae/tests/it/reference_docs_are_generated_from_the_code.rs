//! The reference pages, docs/reference/config.md and docs/reference/cli.md,
//! are exactly what the program generates from its config structs and its
//! command-line definitions, and a page that embeds the config key table
//! embeds the current one: a key or option added, renamed or re-documented
//! without regenerating the pages fails here.

use std::path::{Path, PathBuf};

use crate::common::*;

/// The command that rewrites every generated page.
const REGENERATE: &str = "scripts/update-reference.sh";

fn docs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs")
}

/// Fails, naming the page, the first differing line and the command that
/// regenerates it, unless the page `relative` (under docs/) is `generated`.
fn assert_page_is(relative: &str, generated: &str) {
    let path = docs().join(relative);
    let page = std::fs::read_to_string(&path).unwrap_or_default();
    if page == generated {
        return;
    }
    let line = page
        .lines()
        .zip(generated.lines())
        .position(|(a, b)| a != b)
        .unwrap_or_else(|| page.lines().count().min(generated.lines().count()));
    panic!(
        "docs/{relative} differs from what the program generates (first at line {}: \
         {:?} where the program writes {:?}): run {REGENERATE}",
        line + 1,
        page.lines().nth(line).unwrap_or("<end of file>"),
        generated.lines().nth(line).unwrap_or("<end of file>"),
    );
}

#[test]
fn config_reference_page_is_current() {
    let generated = ok(vivae().args(["config", "reference"]));
    assert!(generated.starts_with("# Config reference\n"), "{generated}");
    assert!(
        generated.contains("| `neat.population_size` | `100` |"),
        "{generated}"
    );
    assert_page_is("reference/config.md", &generated);
}

#[test]
fn cli_reference_page_is_current() {
    let generated = ok(vivae().arg("help-reference"));
    // Every command the program has is on the page, with its options.
    for section in [
        "## vivae evolve\n",
        "## vivae scenario render\n",
        "## vivae config reference\n",
    ] {
        assert!(generated.contains(section), "{section}: {generated}");
    }
    assert!(generated.contains("- `--generations <N>`"), "{generated}");
    assert!(
        !generated.contains("help-reference"),
        "a hidden command is left out"
    );
    assert_page_is("reference/cli.md", &generated);
}

/// A page may embed the key table between `<!-- BEGIN CONFIG REFERENCE -->`
/// and `<!-- END CONFIG REFERENCE -->`; it must be the current one.
#[test]
fn embedded_config_tables_are_current() {
    let table = ok(vivae().args(["config", "reference", "--table"]));
    assert!(table.starts_with("| key | default |"), "{table}");
    let begin = "<!-- BEGIN CONFIG REFERENCE -->\n";
    let end = "<!-- END CONFIG REFERENCE -->";
    let mut pages = vec![docs()];
    while let Some(dir) = pages.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pages.push(path);
                continue;
            }
            if path.extension().is_none_or(|e| e != "md") {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            let Some(start) = text.find(begin) else {
                continue;
            };
            let start = start + begin.len();
            let stop = text[start..]
                .find(end)
                .map(|at| start + at)
                .unwrap_or_else(|| panic!("{}: a BEGIN marker without its END", path.display()));
            let name = path.strip_prefix(docs()).unwrap_or(&path).display();
            assert!(
                text[start..stop] == table,
                "docs/{name}: its config key table differs from `vivae config reference --table`: \
                 run {REGENERATE}"
            );
        }
    }
}
