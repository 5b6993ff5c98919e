//! Colours and SVG text helpers shared by drawings and snapshots, so that a
//! snapshot and a picture of the same world look alike.

use crate::scenario::SurfaceKind;

/// Distinct colours for robots and their trajectories (cycled).
const ROBOT_COLORS: [&str; 10] = [
    "#e41a1c", "#377eb8", "#ff7f00", "#984ea3", "#ffff33", "#00d0d0", "#f781bf", "#a65628",
    "#4daf4a", "#ffffff",
];

/// Colour of robot `i` (and of its trajectory).
pub fn robot_color(i: usize) -> &'static str {
    ROBOT_COLORS[i % ROBOT_COLORS.len()]
}

/// Fill colour of a surface kind.
pub fn surface_color(kind: SurfaceKind) -> &'static str {
    match kind {
        SurfaceKind::Road => "#2b2b2b",
        SurfaceKind::Grass => "#3a8a2e",
        SurfaceKind::Sand => "#d4aa00",
        SurfaceKind::Water => "#3b8fd9",
    }
}

/// Escapes text for XML attributes and content.
pub(crate) fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
