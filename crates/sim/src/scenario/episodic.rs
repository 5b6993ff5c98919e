//! What a scenario lets change from one episode to the next: regions where
//! obstacles are placed at random, and scripted robots (traffic) that follow
//! routes. The scenario only declares them; a task draws the placement from
//! an episode's seed.

use glam::DVec2;

use crate::geometry::Shape;

use super::ScenarioError;
use super::attrs::{bad, number, pair};
use super::rows::{self, Rows};

/// Most obstacles one region may ask for.
pub const MAX_REGION_COUNT: u32 = 256;

/// A region in which obstacles are placed at random each episode: an
/// element labelled `ObstacleRegion` with `data-count` (and optionally
/// `data-size`, `data-clearance`; `data-along` and its attributes for rows
/// across a road).
#[derive(Clone, Debug, PartialEq)]
pub struct ObstacleRegion {
    /// Element id.
    pub id: String,
    /// Where obstacle centres may fall (and the obstacle must lie on road).
    pub shape: Shape,
    /// Obstacles placed per episode.
    pub count: u32,
    /// Each obstacle's width and height, px (`data-size="16"` or `"16x22"`;
    /// default 16); for rows (`along`), its length along the route and its
    /// width across it.
    pub size: DVec2,
    /// Least distance from an obstacle's centre to any robot's start, px
    /// (`data-clearance`, default 40).
    pub clearance: f64,
    /// Rows across a road along a route instead of places anywhere in the
    /// region (`data-along="ROUTE_ID"`).
    pub along: Option<Rows>,
}

/// A scripted robot: drives its route at a throttle, counts as traffic (not
/// as a learner). A robot element with `data-traffic="ROUTE_ID"`.
#[derive(Clone, Debug, PartialEq)]
pub struct TrafficStart {
    /// Element id.
    pub id: String,
    /// Start position as drawn.
    pub pos: DVec2,
    /// Start heading as drawn (radians, 0 = up, clockwise).
    pub heading: f64,
    /// Index of its route in [`super::Scenario::routes`].
    pub route: usize,
    /// Throttle range in (0, 1] (`data-throttle="0.6"` or `"0.5-0.7"`;
    /// default 0.6): drawn per episode when a range.
    pub throttle: (f64, f64),
    /// Up to this many px further along its route per episode
    /// (`data-spread`, default 0: always where drawn).
    pub spread: f64,
}

/// The error of an obstacle region `id` that has no area.
pub(super) fn region_without_area(source: &str, id: &str) -> ScenarioError {
    ScenarioError::Region {
        source_name: source.to_string(),
        id: id.to_string(),
        problem: "has no area (zero width or height): obstacles are placed inside it".into(),
    }
}

/// The region of an `ObstacleRegion` element from its attributes, in an
/// arena of `arena` (width, height) px: refused when no obstacle could
/// fall in it (no area, or wholly outside the arena).
pub(super) fn region<'v>(
    source: &str,
    id: String,
    shape: Shape,
    arena: (f64, f64),
    attr: impl Fn(&str) -> Option<&'v str>,
) -> Result<ObstacleRegion, ScenarioError> {
    if shape.is_empty() || shape.area() <= 0.0 {
        return Err(region_without_area(source, &id));
    }
    let b = shape.bbox;
    if !(b.min.x < arena.0 && b.max.x > 0.0 && b.min.y < arena.1 && b.max.y > 0.0) {
        return Err(ScenarioError::Region {
            source_name: source.to_string(),
            problem: format!(
                "at ({:.1}, {:.1})..({:.1}, {:.1}) lies outside the {} x {} arena: no obstacle could be placed in it",
                b.min.x, b.min.y, b.max.x, b.max.y, arena.0, arena.1
            ),
            id,
        });
    }
    let count = attr("data-count").unwrap_or("");
    let count = match count.trim().parse::<u32>() {
        Ok(c) if c <= MAX_REGION_COUNT => c,
        _ => return Err(bad(source, &id, "data-count", count)),
    };
    let size = match attr("data-size") {
        None => DVec2::splat(16.0),
        Some(v) => match pair(v, 'x') {
            Some((w, h)) if w > 0.0 && h > 0.0 && w <= 1000.0 && h <= 1000.0 => DVec2::new(w, h),
            _ => return Err(bad(source, &id, "data-size", v)),
        },
    };
    let clearance = number(attr("data-clearance"), 40.0, |c| {
        (0.0..=10_000.0).contains(&c)
    })
    .map_err(|_| {
        bad(
            source,
            &id,
            "data-clearance",
            attr("data-clearance").unwrap_or(""),
        )
    })?;
    let along = rows::rows(source, &id, &attr)?;
    Ok(ObstacleRegion {
        id,
        shape,
        count,
        size,
        clearance,
        along,
    })
}

/// Throttle range and spread of a scripted robot from its attributes.
pub(super) fn traffic_settings<'v>(
    source: &str,
    id: &str,
    attr: impl Fn(&str) -> Option<&'v str>,
) -> Result<((f64, f64), f64), ScenarioError> {
    let throttle = match attr("data-throttle") {
        None => (0.6, 0.6),
        Some(v) => match pair(v, '-') {
            Some((a, b)) if 0.0 < a && a <= b && b <= 1.0 => (a, b),
            _ => return Err(bad(source, id, "data-throttle", v)),
        },
    };
    let spread = number(attr("data-spread"), 0.0, |s| (0.0..=1e6).contains(&s))
        .map_err(|_| bad(source, id, "data-spread", attr("data-spread").unwrap_or("")))?;
    Ok((throttle, spread))
}

/// Joins every robot's `data-route`, every scripted robot's `data-traffic`
/// and every region's `data-along` to its route; a name that is no route is
/// an error, and so are rows that could close the road.
pub(super) fn resolve_routes(
    sc: &mut super::Scenario,
    robot_routes: &[Option<String>],
    traffic_routes: &[String],
) -> Result<(), ScenarioError> {
    let source = sc.source.clone();
    let find =
        |routes: &[super::Route], name: &str| routes.iter().position(|r| r.id == name.trim());
    for (robot, name) in sc.robots.iter_mut().zip(robot_routes) {
        if let Some(name) = name {
            robot.route = Some(
                find(&sc.routes, name)
                    .ok_or_else(|| bad(&source, &robot.id, "data-route", name))?,
            );
        }
    }
    for (t, name) in sc.traffic.iter_mut().zip(traffic_routes) {
        t.route =
            find(&sc.routes, name).ok_or_else(|| bad(&source, &t.id, "data-traffic", name))?;
    }
    for region in &mut sc.obstacle_regions {
        let Some(along) = &mut region.along else {
            continue;
        };
        along.route = find(&sc.routes, &along.route_id)
            .ok_or_else(|| bad(&source, &region.id, "data-along", &along.route_id))?;
    }
    for region in &sc.obstacle_regions {
        if let Some(along) = &region.along {
            rows::check(&source, region, along, &sc.routes[along.route])?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_ranges_read_one_or_two_numbers() {
        assert_eq!(pair("16", 'x'), Some((16.0, 16.0)));
        assert_eq!(pair("16x22", 'x'), Some((16.0, 22.0)));
        assert_eq!(pair("0.5-0.7", '-'), Some((0.5, 0.7)));
        assert_eq!(pair("big", 'x'), None);
        let attrs = |k: &str| match k {
            "data-throttle" => Some("0.9-0.2"),
            _ => None,
        };
        let e = traffic_settings("t.svg", "car", attrs).unwrap_err();
        assert!(e.to_string().contains("data-throttle"), "{e}");
    }
}
