//! Blocks in rows across a road (`data-along="ROUTE"` on an
//! `ObstacleRegion`): one block per row, rows evenly spaced along the route,
//! each block's place across the road uniform over the whole band, edges
//! included. The band is cut into lanes at most half a block wide and every
//! group of consecutive rows takes each lane once, in random order, so every
//! line through the band meets a block in every group: no line is safe.
//! The loader refuses a band or a spacing that could close the road.

use glam::DVec2;

use crate::geometry::{FillRule, Shape};

use super::attrs::{bad, number};
use super::{ObstacleRegion, Route, ScenarioError};

/// Least free gap beside a block and between consecutive blocks, px, when
/// `data-gap` is not given (a 12 px robot passes with room).
pub const DEFAULT_GAP: f64 = 16.0;

/// Most lanes a band may have (lanes are half a block wide).
pub const MAX_LANES: usize = 256;

/// How a route-bound `ObstacleRegion` places its blocks.
#[derive(Clone, Debug, PartialEq)]
pub struct Rows {
    /// The route's id (`data-along`).
    pub route_id: String,
    /// Index of the route in [`super::Scenario::routes`].
    pub route: usize,
    /// Width of the band across the route that blocks lie in, px (`data-width`).
    pub width: f64,
    /// Band centre, px to the right of the route's direction of travel
    /// (`data-offset`, default 0: centred on the route).
    pub offset: f64,
    /// Least free gap beside every block (within the band) and between
    /// consecutive blocks along the route, px (`data-gap`, default 16).
    pub gap: f64,
}

/// A problem with a route-bound region's attributes, naming the attribute.
fn problem(source: &str, id: &str, attribute: &str, problem: String) -> ScenarioError {
    ScenarioError::RegionAttribute {
        source_name: source.to_string(),
        id: id.to_string(),
        attribute: attribute.to_string(),
        problem,
    }
}

/// The rows of a region from its attributes: `None` without `data-along`
/// (then `data-width`, `data-offset` and `data-gap` are errors).
pub(super) fn rows<'v>(
    source: &str,
    id: &str,
    attr: impl Fn(&str) -> Option<&'v str>,
) -> Result<Option<Rows>, ScenarioError> {
    let Some(route_id) = attr("data-along") else {
        for key in ["data-width", "data-offset", "data-gap"] {
            if attr(key).is_some() {
                return Err(problem(source, id, key, "only with data-along".into()));
            }
        }
        return Ok(None);
    };
    if route_id.trim().is_empty() {
        return Err(bad(source, id, "data-along", route_id));
    }
    let read = |key: &str, default: f64, ok: fn(f64) -> bool| {
        number(attr(key), default, ok).map_err(|_| bad(source, id, key, attr(key).unwrap_or("")))
    };
    if attr("data-width").is_none() {
        return Err(problem(
            source,
            id,
            "data-width",
            "required with data-along".into(),
        ));
    }
    let width = read("data-width", 0.0, |w| w > 0.0 && w <= 10_000.0)?;
    let offset = read("data-offset", 0.0, |o| o.abs() <= 10_000.0)?;
    let gap = read("data-gap", DEFAULT_GAP, |g| (0.0..=10_000.0).contains(&g))?;
    Ok(Some(Rows {
        route_id: route_id.trim().to_string(),
        route: usize::MAX,
        width,
        offset,
        gap,
    }))
}

/// Checks that the region's rows always leave their gap, once its route is known.
pub(super) fn check(
    source: &str,
    region: &ObstacleRegion,
    rows: &Rows,
    route: &Route,
) -> Result<(), ScenarioError> {
    let (along, across) = (region.size.x, region.size.y);
    let id = &region.id;
    if across > rows.width {
        return Err(problem(
            source,
            id,
            "data-size",
            format!(
                "a block {across} px across is wider than data-width {}",
                rows.width
            ),
        ));
    }
    let beside = (rows.width - across) / 2.0;
    if beside < rows.gap {
        return Err(problem(
            source,
            id,
            "data-gap",
            format!(
                "a block in the band's middle leaves {beside} px beside it, less than data-gap {}",
                rows.gap
            ),
        ));
    }
    if lanes(rows.width, across) > MAX_LANES {
        return Err(problem(
            source,
            id,
            "data-width",
            format!("a band over {MAX_LANES} half-blocks wide"),
        ));
    }
    if region.count > 0 {
        let between = route.length() / f64::from(region.count) - along;
        if between < rows.gap {
            return Err(problem(
                source,
                id,
                "data-count",
                format!(
                    "{} rows on route '{}' ({:.0} px) leave {between:.1} px between blocks, less than data-gap {}",
                    region.count,
                    rows.route_id,
                    route.length(),
                    rows.gap
                ),
            ));
        }
    }
    Ok(())
}

/// Lanes of a band `width` wide for blocks `across` wide: each at most half
/// a block wide, so a block anywhere in a lane covers the lane's every line.
pub fn lanes(width: f64, across: f64) -> usize {
    let free = (width - across).max(0.0);
    ((free / (across * 0.5)).ceil() as usize).max(1)
}

impl ObstacleRegion {
    /// This episode's blocks of a route-bound region (`data-along`), with
    /// their row numbers (0-based); empty for other regions. `draw` gives
    /// uniform numbers in [0, 1): one for the rows' phase along the route,
    /// one per lane drawn for each group's order and one per row for its
    /// place in its lane, always as many, so the rows left out (outside
    /// the region's shape, or nearer a start than `clearance`) do not move
    /// the others.
    pub fn row_blocks(
        &self,
        route: &Route,
        starts: &[DVec2],
        mut draw: impl FnMut() -> f64,
    ) -> Vec<(usize, Shape)> {
        let Some(rows) = &self.along else {
            return Vec::new();
        };
        let n = self.count as usize;
        if n == 0 {
            return Vec::new();
        }
        let (along, across) = (self.size.x, self.size.y);
        let spacing = route.length() / n as f64;
        let phase = draw();
        let m = lanes(rows.width, across);
        let free = (rows.width - across).max(0.0);
        let lane_width = free / m as f64;
        let mut order: Vec<usize> = Vec::with_capacity(m);
        let mut blocks = Vec::new();
        for k in 0..n {
            if k % m == 0 {
                // The first rows of a random order of the lanes (partial Fisher–Yates).
                order.clear();
                order.extend(0..m);
                for i in 0..m.min(n - k) {
                    let j = i + ((draw() * (m - i) as f64) as usize).min(m - i - 1);
                    order.swap(i, j);
                }
            }
            let lane = order[k % m];
            let lateral = rows.offset - free * 0.5 + (lane as f64 + draw()) * lane_width;
            let (p, dir) = route.point_at((k as f64 + phase) * spacing);
            let right = DVec2::new(-dir.y, dir.x);
            let c = p + right * lateral;
            if !self.shape.contains(c) || starts.iter().any(|s| s.distance(c) < self.clearance) {
                continue;
            }
            let (l, a) = (dir * (along * 0.5), right * (across * 0.5));
            let ring = vec![c - l - a, c + l - a, c + l + a, c - l + a];
            blocks.push((k, Shape::new(vec![ring], FillRule::NonZero)));
        }
        blocks
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::scenario::{LoadOptions, Scenario, SurfaceKind};

    const CORRIDOR: &str = include_str!("../../../../scenarios/corridor.svg");
    const KERBED: &str = include_str!("../../../../scenarios/kerbed-loop.svg");
    const ONCOMING: &str = include_str!("../../../../scenarios/oncoming-edges.svg");

    fn load(svg: &str) -> Scenario {
        Scenario::from_svg(svg, "t.svg", &LoadOptions::default()).unwrap()
    }

    /// Uniform numbers in [0, 1) from splitmix64: the tests' stand-in for a task's RNG.
    fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut x = seed;
        move || {
            x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = x;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Where a block lies: arc length along its route and offset to the right of it.
    fn place(route: &Route, block: &Shape) -> (f64, f64) {
        let c = block.rings[0].iter().copied().sum::<DVec2>() / 4.0;
        let at = route.locate(c, None);
        let (p, dir) = route.point_at(at.s);
        (at.s, (c - p).dot(DVec2::new(-dir.y, dir.x)))
    }

    fn rows_of(sc: &Scenario) -> Vec<(&ObstacleRegion, &Rows, &Route)> {
        (sc.obstacle_regions.iter())
            .filter_map(|r| r.along.as_ref().map(|a| (r, a, &sc.routes[a.route])))
            .collect()
    }

    #[test]
    fn the_shipped_courses_load_with_their_rows_bound_to_routes() {
        for (svg, regions) in [(CORRIDOR, 1), (KERBED, 1), (ONCOMING, 2)] {
            let sc = load(svg);
            assert_eq!(rows_of(&sc).len(), regions);
            assert!(sc.varies());
        }
        let kerbed = load(KERBED);
        // A kerb is a band along the road in short pieces: their area, not what they enclose.
        let kerb = |p: DVec2| kerbed.fixed_obstacles.iter().any(|o| o.shape.contains(p));
        assert!(kerbed.fixed_obstacles.len() > 8);
        assert!(kerb(DVec2::new(400.0, 67.0)) && kerb(DVec2::new(400.0, 133.0)));
        assert!(
            kerb(DVec2::new(640.0 + 80.0, 180.0 - 80.0)),
            "round a corner"
        );
        assert!(!kerb(DVec2::new(400.0, 100.0)) && !kerb(DVec2::new(400.0, 300.0)));
        assert!(load(CORRIDOR).fixed_obstacles.len() > 8);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn blocks_lie_on_the_road_in_their_band_clear_of_kerbs_and_starts(seed in any::<u64>()) {
            for svg in [CORRIDOR, KERBED, ONCOMING] {
                let sc = load(svg);
                let starts: Vec<DVec2> = (sc.robots.iter().map(|r| r.pos))
                    .chain(sc.traffic.iter().map(|t| t.pos)).collect();
                for (region, rows, route) in rows_of(&sc) {
                    let blocks = region.row_blocks(route, &starts, uniform(seed));
                    prop_assert!(blocks.len() + sc.robots.len() + sc.traffic.len() >= region.count as usize);
                    for (k, b) in &blocks {
                        let c = b.rings[0].iter().copied().sum::<DVec2>() / 4.0;
                        // Each side pulled in by 1 px: a block flush with an edge is on the
                        // road (on a curve, a straight block's outer corners stick out a little).
                        let r = &b.rings[0];
                        let inset = |v: DVec2| v * (1.0 - 1.0 / v.length());
                        let (l, a) = (inset((r[1] - r[0]) / 2.0), inset((r[3] - r[0]) / 2.0));
                        for q in [c - l - a, c + l - a, c + l + a, c - l + a] {
                            prop_assert_eq!(sc.surface_exact(q).unwrap().0, SurfaceKind::Road, "{} row {}", region.id, k);
                            prop_assert!(sc.fixed_obstacles.iter().all(|o| !o.shape.contains(q)));
                        }
                        prop_assert!(starts.iter().all(|s| s.distance(c) >= region.clearance));
                        let (_, lateral) = place(route, b);
                        prop_assert!((lateral - rows.offset).abs() <= (rows.width - region.size.y) / 2.0 + 0.01);
                    }
                }
            }
        }

        #[test]
        fn every_line_across_the_road_meets_a_block_in_every_group_of_rows(seed in any::<u64>()) {
            let sc = load(KERBED);
            let (region, rows, route) = rows_of(&sc)[0];
            let m = lanes(rows.width, region.size.y);
            let blocks = region.row_blocks(route, &[], uniform(seed));
            prop_assert_eq!(blocks.len(), region.count as usize);
            let places: Vec<(f64, f64)> = blocks.iter().map(|(_, b)| place(route, b)).collect();
            let (r, half) = (6.0, region.size.y / 2.0);
            for group in places.chunks_exact(m) {
                // Every line a 12 px robot can drive on the road, edges included.
                for i in 0..=96 {
                    let y = -(rows.width / 2.0 - r) + i as f64 * (rows.width - 2.0 * r) / 96.0;
                    prop_assert!(
                        group.iter().any(|&(_, o)| (o - y).abs() < half + r - 0.5),
                        "line {y} never blocked in {group:?}"
                    );
                }
            }
            // A gap is always left: beside every block and between consecutive ones.
            for (i, &(s, o)) in places.iter().enumerate() {
                let free = rows.width / 2.0 + (o - rows.offset).abs() - half;
                prop_assert!(free >= rows.gap - 0.01);
                let next = places[(i + 1) % places.len()].0;
                prop_assert!(route.advance(s, next).abs() - region.size.x >= rows.gap - 0.5);
            }
        }
    }

    #[test]
    fn over_many_episodes_blocks_reach_both_edges_and_the_same_draws_place_them_alike() {
        let sc = load(CORRIDOR);
        let (region, rows, route) = rows_of(&sc)[0];
        let edge = (rows.width - region.size.y) / 2.0;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for seed in 0..200 {
            let blocks = region.row_blocks(route, &[], uniform(seed));
            assert_eq!(blocks, region.row_blocks(route, &[], uniform(seed)));
            assert_ne!(blocks, region.row_blocks(route, &[], uniform(seed + 1000)));
            for (_, b) in &blocks {
                let (_, o) = place(route, b);
                (lo, hi) = (lo.min(o), hi.max(o));
            }
        }
        assert!(lo < -edge + 0.5 && hi > edge - 0.5, "{lo}..{hi} of ±{edge}");
    }

    #[test]
    fn bad_row_attributes_are_one_line_errors_naming_the_element_and_attribute() {
        let base = r#"data-count="16" data-size="16" data-clearance="40" data-along="lane-cw" data-width="60""#;
        let with = |attrs: &str| {
            let svg = KERBED.replace(
                base,
                &format!(r#"data-count="16" data-clearance="40" {attrs}"#),
            );
            Scenario::from_svg(&svg, "k.svg", &LoadOptions::default())
        };
        assert!(with(r#"data-along="lane-cw" data-width="60""#).is_ok());
        for (attrs, key) in [
            (r#"data-along="nowhere" data-width="60""#, "data-along"),
            (r#"data-along="" data-width="60""#, "data-along"),
            (r#"data-along="lane-cw""#, "data-width"),
            (r#"data-along="lane-cw" data-width="-3""#, "data-width"),
            (r#"data-along="lane-cw" data-width="NaN""#, "data-width"),
            (r#"data-along="lane-cw" data-width="1e9""#, "data-width"),
            (r#"data-along="lane-cw" data-width="10""#, "data-size"),
            (r#"data-along="lane-cw" data-width="40""#, "data-gap"),
            (
                r#"data-along="lane-cw" data-width="60" data-gap="-1""#,
                "data-gap",
            ),
            (
                r#"data-along="lane-cw" data-width="60" data-size="110x16""#,
                "data-count",
            ),
            (
                r#"data-along="lane-cw" data-width="60" data-offset="x""#,
                "data-offset",
            ),
            (
                r#"data-along="lane-cw" data-width="9000" data-gap="0""#,
                "data-width",
            ),
            (r#"data-width="60""#, "data-width"),
            (r#"data-gap="6""#, "data-gap"),
        ] {
            let e = with(attrs).unwrap_err().to_string();
            assert!(
                !e.contains('\n') && e.contains("'rows'") && e.contains(key),
                "{attrs}: {e}"
            );
        }
    }
}
