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
    /// `ObstacleRegion`: obstacles placed at random each episode.
    Region,
    /// `Route`: a directed centre line.
    Route,
}

/// Kind named by a label part (case-insensitive).
pub(super) fn surface_kind(s: &str) -> Option<SurfaceKind> {
    SurfaceKind::ALL
        .into_iter()
        .find(|k| k.name().eq_ignore_ascii_case(s))
}

/// `name` without a trailing number and the separator before it: Inkscape
/// labels copies "Road 1", "road-2", "Road_3" or "road4".
fn without_number(name: &str) -> &str {
    let stem = name.trim_end_matches(|c: char| c.is_ascii_digit());
    if stem.len() == name.len() {
        return name;
    }
    let stem = stem.trim_end_matches([' ', '-', '_', '#']);
    if stem.is_empty() { name } else { stem }
}

/// Classifies a label: the last dot-separated part, case-insensitively,
/// ignoring a trailing number ("Road 1", "road-2").
pub(super) fn classify(label: &str) -> Option<Class> {
    let last = label.trim().rsplit('.').next().unwrap_or("").trim();
    let last = without_number(last).to_ascii_lowercase();
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
        "obstacleregion" => Some(Class::Region),
        "route" => Some(Class::Route),
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
        assert_eq!(classify("ObstacleRegion 2"), Some(Class::Region));
        assert_eq!(classify("route"), Some(Class::Route));
        assert_eq!(classify("Layer 1"), None);
        assert_eq!(classify("SmallPuck"), Some(Class::Puck(PuckKind::Small)));
    }

    #[test]
    fn numbered_copies_keep_their_class() {
        let road = Some(Class::Surface(SurfaceKind::Road));
        for label in ["Road 1", "road-2", "Road_3", "road4", "ROAD 12", " Road 7 "] {
            assert_eq!(classify(label), road, "{label}");
        }
        assert_eq!(
            classify("Water 2"),
            Some(Class::Surface(SurfaceKind::Water))
        );
        assert_eq!(classify("fixedObstacle-3"), Some(Class::Fixed));
        assert_eq!(classify("SmallPuck 2"), Some(Class::Puck(PuckKind::Small)));
        assert_eq!(classify("PositionMark_1"), Some(Class::Mark));
        assert_eq!(classify("Robot 3"), Some(Class::Robot));
        assert_eq!(classify("Layer 1"), None);
        assert_eq!(classify("Roadside 1"), None);
        assert_eq!(classify("1"), None);
    }
}
