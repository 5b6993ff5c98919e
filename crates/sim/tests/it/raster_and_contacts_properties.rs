//! Property tests: the surface raster agrees with exact geometry away from
//! edges, and no two bodies overlap after any step.

use crate::common::*;
use proptest::prelude::*;
use vivae_sim::{DVec2, LoadOptions, PhysicsParams, Scenario, World};

/// A scenario with overlapping rects, a stroked Bézier road, an arc lake and a rotated sand patch.
fn surfaces_svg() -> String {
    svg(
        300.0,
        200.0,
        r#"<rect id="a" inkscape:label="Road" x="10" y="10" width="120" height="60"/>
        <rect id="b" inkscape:label="Sand" x="60" y="40" width="100" height="80" transform="rotate(20 110 80)"/>
        <path id="c" inkscape:label="Road" d="M 20,180 C 100,60 200,220 290,40" style="fill:none;stroke:#000;stroke-width:25"/>
        <path id="d" inkscape:label="Water" d="M 200,100 A 50,30 0 1 1 200,101 Z" style="fill-rule:evenodd"/>
        <path id="e" inkscape:label="Grass" d="M 220,20 L 280,20 L 280,80 L 220,80 Z M 235,35 L 265,35 L 265,65 L 235,65 Z" style="fill-rule:evenodd"/>"#,
    )
}

fn near_any_edge(sc: &Scenario, p: DVec2, margin: f64) -> bool {
    sc.surfaces().iter().any(|s| {
        s.shape.bbox.contains_with_margin(p, margin) && s.shape.closest_boundary_point(p).1 < margin
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn raster_matches_exact_geometry_away_from_edges(
        cell in prop_oneof![Just(1.0), Just(0.5), Just(2.0)],
        pts in prop::collection::vec((0.0f64..300.0, 0.0f64..200.0), 50),
    ) {
        let sc = Scenario::from_svg(&surfaces_svg(), "p.svg", &LoadOptions { cell_size: cell, ..Default::default() }).unwrap();
        let w = World::new(&sc, &PhysicsParams::default()).unwrap();
        for (x, y) in pts {
            let p = DVec2::new(x, y);
            if near_any_edge(&sc, p, 1.5 * cell) {
                continue;
            }
            let exact = sc.surface_exact(p).unwrap().0;
            prop_assert_eq!(w.surface_at(p).unwrap().kind, exact, "at {:?}", p);
        }
    }

    #[test]
    fn no_two_bodies_overlap_after_any_step(
        starts in prop::collection::vec((20.0f64..280.0, 20.0f64..180.0, -3.2f64..3.2), 2..8),
        controls in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 40),
    ) {
        let mut robots = String::new();
        let mut placed: Vec<DVec2> = Vec::new();
        for (i, (x, y, h)) in starts.iter().enumerate() {
            let p = DVec2::new(*x, *y);
            // Start apart from each other and from the obstacles.
            if placed.iter().any(|q| q.distance(p) < 13.0)
                || (p.x > 94.0 && p.x < 166.0 && p.y > 64.0 && p.y < 116.0)
                || (p.x > 184.0 && p.x < 246.0 && p.y > 114.0 && p.y < 176.0)
            {
                continue;
            }
            placed.push(p);
            robots.push_str(&robot(&format!("r{i}"), *x, *y, h.to_degrees()));
        }
        let body = format!(
            r#"<rect id="road" inkscape:label="Road" x="0" y="0" width="300" height="200"/>
            <path id="fx" inkscape:label="FixedObstacle" d="M 100,70 L 160,70 L 160,110 L 140,110 L 140,90 L 120,90 L 120,110 L 100,110 Z"/>
            <rect id="fx2" inkscape:label="FixedObstacle" x="190" y="120" width="50" height="50" transform="rotate(30 215 145)"/>{robots}"#
        );
        let sc = Scenario::from_svg(&svg(300.0, 200.0, &body), "p.svg", &LoadOptions::default()).unwrap();
        let params = PhysicsParams::default();
        let mut w = World::new(&sc, &params).unwrap();
        let n = w.robots().len();
        let tol = 0.5;
        let r = params.robot_radius;
        for (t, (l, rr)) in controls.iter().enumerate() {
            let c: Vec<[f64; 2]> = (0..n).map(|i| if i % 2 == 0 { [*l, *rr] } else { [*rr, *l] }).collect();
            for _ in 0..5 {
                w.step(&c);
            }
            for (i, a) in w.robots().iter().enumerate() {
                prop_assert!(a.pos.x >= r - 1e-9 && a.pos.x <= 300.0 - r + 1e-9 && a.pos.y >= r - 1e-9 && a.pos.y <= 200.0 - r + 1e-9,
                    "robot {} left the walls at step {}: {:?}", i, t, a.pos);
                for b in &w.robots()[i + 1..] {
                    prop_assert!(a.pos.distance(b.pos) >= 2.0 * r - tol, "robots overlap at step {}", t);
                }
                for ob in &sc.fixed_obstacles {
                    let (_, d) = ob.shape.closest_boundary_point(a.pos);
                    prop_assert!(!ob.shape.contains(a.pos) && d >= r - tol, "robot {} in obstacle {} at step {}: {:?}", i, ob.id, t, a.pos);
                }
            }
        }
    }
}
