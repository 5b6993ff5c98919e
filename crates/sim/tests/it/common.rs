//! Hand-made scenarios shared by the integration tests.
#![allow(dead_code)]

use vivae_sim::{LoadOptions, Scenario};

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
