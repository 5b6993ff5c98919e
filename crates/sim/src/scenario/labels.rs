//! Label matching: what an element's `inkscape:label` says it is.

use super::{PuckKind, SurfaceKind};

/// What an `inkscape:label` says an element is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Class {
    Surface(SurfaceKind),
    Fixed,
    Movable,
    Puck(PuckKind),
    Robot,
    Mark,
}

/// Kind named by a label part (case-insensitive).
pub(super) fn surface_kind(s: &str) -> Option<SurfaceKind> {
    SurfaceKind::ALL
        .into_iter()
        .find(|k| k.name().eq_ignore_ascii_case(s))
}

/// Classifies a label: the last dot-separated part, case-insensitively.
pub(super) fn classify(label: &str) -> Option<Class> {
    let last = label
        .trim()
        .rsplit('.')
        .next()
        .unwrap_or("")
        .to_ascii_lowercase();
    if let Some(k) = surface_kind(&last) {
        return Some(Class::Surface(k));
    }
    match last.as_str() {
        "fixedobstacle" | "fixed" => Some(Class::Fixed),
        "obstacle" => Some(Class::Movable),
        "smallpuck" => Some(Class::Puck(PuckKind::Small)),
        "bigpuck" => Some(Class::Puck(PuckKind::Big)),
        "puck" => Some(Class::Puck(PuckKind::Plain)),
        "positionmark" => Some(Class::Mark),
        s if s.contains("robot") => Some(Class::Robot),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_classify_by_last_dotted_part_case_insensitively() {
        assert_eq!(classify("Road"), Some(Class::Surface(SurfaceKind::Road)));
        assert_eq!(classify("road"), Some(Class::Surface(SurfaceKind::Road)));
        assert_eq!(
            classify("vivae.arena.parts.PositionMark"),
            Some(Class::Mark)
        );
        assert_eq!(classify("fixed"), Some(Class::Fixed));
        assert_eq!(
            classify("hyper.experiments.robots.friction.NetControlledRobotFriction"),
            Some(Class::Robot)
        );
        assert_eq!(
            classify("vivae.example.FRNNControlledRobot"),
            Some(Class::Robot)
        );
        assert_eq!(classify("Layer 1"), None);
        assert_eq!(classify("SmallPuck"), Some(Class::Puck(PuckKind::Small)));
    }
}
