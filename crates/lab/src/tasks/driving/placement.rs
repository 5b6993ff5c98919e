//! An episode's placement: obstacles at random in the scenario's obstacle
//! regions and the scripted robots' throttles and starts, drawn from the
//! episode's seed. A pure function of (scenario, seed), so evaluations stay
//! deterministic, resumable and independent of the thread count.

use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;
use vivae_sim::geometry::Shape;
use vivae_sim::world::traffic::heading_of;
use vivae_sim::{DVec2, Obstacle, Scenario, SurfaceKind};

/// Tries to place one obstacle before giving up on it (then the episode has one fewer).
const TRIES: u32 = 200;
/// Least gap between two obstacles, px (a robot fits through).
const GAP: f64 = 14.0;

/// The seed of placement `k` of an evaluation with seed `seed`
/// (`experiment.placements`): the evaluation's own seed for `k = 0` (what a
/// one-placement run uses), `splitmix64(seed ^ k)` for every other `k`.
pub fn placement_seed(seed: u64, k: u32) -> u64 {
    match k {
        0 => seed,
        k => vivae_neat::eval::splitmix64(seed ^ u64::from(k)),
    }
}

/// `scenario` as episode `seed` has it: every obstacle region's obstacles
/// placed (as fixed obstacles, after the drawn ones) and every scripted
/// robot's throttle and start drawn. The result varies no more
/// ([`Scenario::varies`] is false); a scenario that does not vary comes back unchanged.
pub fn placed(scenario: &Scenario, seed: u64) -> Scenario {
    let mut sc = scenario.clone();
    if !scenario.varies() {
        return sc;
    }
    let mut rng = Pcg64::seed_from_u64(seed);
    for t in &mut sc.traffic {
        let (lo, hi) = t.throttle;
        let throttle = if hi > lo {
            rng.random_range(lo..=hi)
        } else {
            lo
        };
        t.throttle = (throttle, throttle);
        if t.spread > 0.0 {
            let route = &scenario.routes[t.route];
            let along = rng.random_range(0.0..t.spread);
            let (pos, dir) = route.point_at(route.locate(t.pos, None).s + along);
            (t.pos, t.heading) = (pos, heading_of(dir));
            t.spread = 0.0;
        }
    }
    let starts: Vec<DVec2> = (sc.robots.iter().map(|r| r.pos))
        .chain(sc.traffic.iter().map(|t| t.pos))
        .collect();
    let mut taken: Vec<Shape> = (sc.fixed_obstacles.iter().chain(&sc.movable_obstacles))
        .map(|o| o.shape.clone())
        .collect();
    for region in std::mem::take(&mut sc.obstacle_regions) {
        if let Some(rows) = &region.along {
            // Rows across a road: their own rule (vivae_sim's `row_blocks`), not kept
            // clear of other obstacles (their bands are drawn apart).
            let route = &scenario.routes[rows.route];
            let blocks = region.row_blocks(route, &starts, || rng.random_range(0.0..1.0));
            for (k, shape) in blocks {
                taken.push(shape.clone());
                sc.fixed_obstacles.push(Obstacle {
                    id: format!("{}-{}", region.id, k + 1),
                    shape,
                });
            }
            continue;
        }
        for k in 0..region.count {
            let Some(shape) = (0..TRIES).find_map(|_| {
                let b = region.shape.bbox;
                let c = DVec2::new(
                    rng.random_range(b.min.x..=b.max.x),
                    rng.random_range(b.min.y..=b.max.y),
                );
                fits(scenario, &region, c, &starts, &taken)
            }) else {
                continue;
            };
            taken.push(shape.clone());
            sc.fixed_obstacles.push(Obstacle {
                id: format!("{}-{}", region.id, k + 1),
                shape,
            });
        }
    }
    sc.placed_obstacles = sc.fixed_obstacles.len() - scenario.fixed_obstacles.len();
    sc
}

/// The obstacle of `region` centred at `c`, when it lies in the region, on
/// road, clear of the robots' starts and of every obstacle in `taken`.
fn fits(
    sc: &Scenario,
    region: &vivae_sim::ObstacleRegion,
    c: DVec2,
    starts: &[DVec2],
    taken: &[Shape],
) -> Option<Shape> {
    let half = region.size * 0.5;
    let corners = [
        c,
        c - half,
        c + half,
        c + DVec2::new(half.x, -half.y),
        c + DVec2::new(-half.x, half.y),
    ];
    let on_road = |p: DVec2| {
        sc.surface_exact(p)
            .is_some_and(|(k, _)| k == SurfaceKind::Road)
    };
    let clear = |o: &Shape| {
        let (lo, hi) = (
            o.bbox.min - DVec2::splat(GAP),
            o.bbox.max + DVec2::splat(GAP),
        );
        c.x + half.x < lo.x || c.x - half.x > hi.x || c.y + half.y < lo.y || c.y - half.y > hi.y
    };
    (region.shape.contains(c)
        && corners.iter().all(|&p| on_road(p))
        && starts.iter().all(|s| s.distance(c) >= region.clearance)
        && taken.iter().all(clear))
    .then(|| Shape::rect(c - half, c + half))
}

#[cfg(test)]
mod tests {
    use super::*;
    use vivae_sim::LoadOptions;

    fn shipped(name: &str) -> Scenario {
        let s = crate::tasks::scenarios::find(name).expect("shipped");
        Scenario::from_svg(s.svg, name, &LoadOptions::default()).unwrap()
    }

    #[test]
    fn a_placement_is_a_function_of_the_seed() {
        let sc = shipped("obstacles-random");
        assert!(sc.varies());
        let (a, b, c) = (placed(&sc, 7), placed(&sc, 7), placed(&sc, 8));
        assert!(!a.varies());
        let added = a.fixed_obstacles.len() - sc.fixed_obstacles.len();
        let asked: u32 = sc.obstacle_regions.iter().map(|r| r.count).sum();
        assert_eq!(added, asked as usize, "every obstacle found a place");
        let boxes = |s: &Scenario| {
            s.fixed_obstacles
                .iter()
                .map(|o| o.shape.bbox)
                .collect::<Vec<_>>()
        };
        assert_eq!(boxes(&a), boxes(&b));
        assert_ne!(boxes(&a), boxes(&c));
    }

    #[test]
    fn placed_obstacles_lie_on_road_away_from_every_start() {
        let sc = shipped("obstacles-random");
        for seed in 0..20 {
            let p = placed(&sc, seed);
            for o in &p.fixed_obstacles[sc.fixed_obstacles.len()..] {
                let c = o.shape.bbox.center();
                assert_eq!(p.surface_exact(c).unwrap().0, SurfaceKind::Road);
                for r in &p.robots {
                    assert!(r.pos.distance(c) >= 40.0, "seed {seed}: {} too close", o.id);
                }
            }
        }
    }

    #[test]
    fn rows_across_the_road_are_a_function_of_the_seed_and_leave_the_kerbs_in_place() {
        for name in ["corridor", "kerbed-loop", "oncoming-edges"] {
            let sc = shipped(name);
            let (a, b, c) = (placed(&sc, 3), placed(&sc, 3), placed(&sc, 4));
            assert!(!a.varies());
            let fixed = sc.fixed_obstacles.len();
            assert_eq!(a.fixed_obstacles[..fixed], sc.fixed_obstacles[..], "{name}");
            let asked: u32 = sc.obstacle_regions.iter().map(|r| r.count).sum();
            let added = a.fixed_obstacles.len() - fixed;
            // Only rows near a start are left out: at most one per start and region.
            let starts = sc.robots.len() + sc.traffic.len();
            assert!(
                added + starts * sc.obstacle_regions.len() >= asked as usize,
                "{name}: {added}"
            );
            assert_eq!(a.placed_obstacles, added, "{name}");
            assert_eq!(a.fixed_obstacles, b.fixed_obstacles);
            assert_ne!(a.fixed_obstacles, c.fixed_obstacles);
        }
    }

    #[test]
    fn traffic_starts_and_throttles_vary_with_the_seed_within_their_ranges() {
        let sc = shipped("oncoming");
        assert!(!sc.traffic.is_empty());
        let (a, b) = (placed(&sc, 1), placed(&sc, 2));
        for ((t, u), drawn) in a.traffic.iter().zip(&b.traffic).zip(&sc.traffic) {
            assert!(drawn.throttle.0 <= t.throttle.0 && t.throttle.0 <= drawn.throttle.1);
            assert_eq!(t.throttle.0, t.throttle.1);
            if drawn.spread > 0.0 {
                assert_ne!(t.pos, u.pos);
            }
        }
    }
}
