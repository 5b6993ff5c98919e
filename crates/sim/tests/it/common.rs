//! Hand-made scenarios shared by the integration tests.
#![allow(dead_code)]

use std::io::Write as _;
use std::path::{Path, PathBuf};

use vivae_sim::{LoadOptions, Scenario};

/// The ViVAE scenario corpus, `../shared/vivae-scenarios` beside the clone
/// (a clone from the web lacks it). `None` when it is absent: the caller
/// returns, and the test counts as passed after a printed SKIPPED note, unless
/// `VIVAE_REQUIRE_SHARED=1` (as CI sets), which makes the absence a failure.
pub fn shared_corpus() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/vivae-scenarios");
    let required = std::env::var("VIVAE_REQUIRE_SHARED").is_ok_and(|v| v == "1");
    corpus_at(&dir, required)
}

/// `Some(dir)` if it is a directory; else fails when `required`, or prints a
/// note (straight to stderr, past the test harness's capture) and gives `None`.
pub fn corpus_at(dir: &Path, required: bool) -> Option<PathBuf> {
    if dir.is_dir() {
        return Some(dir.to_path_buf());
    }
    assert!(
        !required,
        "the scenario corpus {} is absent, and VIVAE_REQUIRE_SHARED=1 requires it: put ../shared/vivae-scenarios beside the clone",
        dir.display()
    );
    let _ = writeln!(
        std::io::stderr(),
        "SKIPPED: ../shared/vivae-scenarios is absent (a clone from the web); CI requires it (looked for {})",
        dir.display()
    );
    None
}

/// An SVG document of `w`×`h` px with `body` inside one Inkscape layer.
pub fn svg(w: f64, h: f64, body: &str) -> String {
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="{w}" height="{h}" id="svg1" inkscape:label="Pozadí"><g inkscape:groupmode="layer" inkscape:label="Layer 1" id="layer1">{body}</g></svg>"#
    )
}

/// Loads `text` with default options, panicking with the error message.
pub fn load(text: &str) -> Scenario {
    Scenario::from_svg(text, "test.svg", &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// A robot element (20×20 rect centred at `(x, y)`, rotated by `deg`).
pub fn robot(id: &str, x: f64, y: f64, deg: f64) -> String {
    format!(
        r#"<rect id="{id}" inkscape:label="vivae.example.FRNNControlledRobot" x="{}" y="{}" width="20" height="20" transform="rotate({deg} {x} {y})"/>"#,
        x - 10.0,
        y - 10.0
    )
}
