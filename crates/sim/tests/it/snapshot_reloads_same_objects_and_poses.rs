//! `world.to_svg()` loads back to the same objects at the same poses; drawings render.

use crate::common::*;
use vivae_sim::{
    DistanceSensors, DrawOptions, LoadOptions, PhysicsParams, Scenario, Sensor, SurfaceSensors,
    World,
};

fn busy_world() -> World {
    let body = format!(
        r#"<rect id="road" inkscape:label="Road" x="0" y="50" width="400" height="90"/>
        <path id="lake" inkscape:label="Water" data-friction="7" d="M 300,200 A 40,30 0 1 1 300,201 Z"/>
        <rect id="fx" inkscape:label="FixedObstacle" x="20" y="20" width="30" height="20"/>
        <rect id="mv" inkscape:label="Obstacle" x="200" y="60" width="30" height="10"/>
        <circle id="pk" inkscape:label="BigPuck" cx="100" cy="60" r="9"/>
        <rect id="m1" inkscape:label="PositionMark" x="350" y="250" width="20" height="20"/>
        {}{}"#,
        robot("a", 100.0, 120.0, 0.0),
        robot("b", 215.0, 120.0, 10.0)
    );
    World::new(&load(&svg(400.0, 300.0, &body)), &PhysicsParams::default()).unwrap()
}

#[test]
fn snapshot_reloads_to_the_same_objects_at_the_same_poses() {
    let mut w = busy_world();
    for t in 0..60 {
        w.step(&[[1.0, 0.95 + (t % 3) as f64 * 0.02], [1.0, 1.0]]);
    }
    assert!(
        w.movables()[0].offset.length() > 1.0,
        "the obstacle was pushed"
    );
    assert!(
        w.pucks()[0]
            .pos
            .distance(vivae_sim::DVec2::new(100.0, 60.0))
            > 1.0,
        "the puck was pushed"
    );
    let text = w.to_svg();
    let sc2 = Scenario::from_svg(&text, "snap.svg", &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert!(sc2.warnings.is_empty(), "{:?}", sc2.warnings);
    let sc = w.scenario();
    assert_eq!((sc2.width(), sc2.height()), (sc.width(), sc.height()));
    assert_eq!(sc2.surfaces().len(), sc.surfaces().len());
    for (a, b) in sc.surfaces().iter().zip(sc2.surfaces()) {
        assert_eq!((a.kind, &a.id, a.friction), (b.kind, &b.id, b.friction));
        assert!(
            (a.shape.area() - b.shape.area()).abs() < 0.5,
            "{} area",
            a.id
        );
    }
    assert_eq!(sc2.fixed_obstacles.len(), 1);
    assert_eq!(sc2.movable_obstacles.len(), 1);
    let moved = sc.movable_obstacles[0]
        .shape
        .translated(w.movables()[0].offset);
    assert!((moved.bbox.center() - sc2.movable_obstacles[0].shape.bbox.center()).length() < 1e-3);
    assert_eq!(sc2.pucks.len(), 1);
    assert!((sc2.pucks[0].pos - w.pucks()[0].pos).length() < 1e-3);
    assert!((sc2.pucks[0].radius - 9.0).abs() < 1e-3);
    assert_eq!(sc2.marks.len(), 1);
    assert!((sc2.marks[0].pos - sc.marks[0].pos).length() < 1e-3);
    assert_eq!(sc2.robots.len(), 2);
    for (r, s) in w.robots().iter().zip(&sc2.robots) {
        assert!(
            (r.pos - s.pos).length() < 1e-3,
            "{:?} vs {:?}",
            r.pos,
            s.pos
        );
        let dh = (r.heading - s.heading).rem_euclid(std::f64::consts::TAU);
        assert!(
            dh.min(std::f64::consts::TAU - dh) < 1e-5,
            "heading {} vs {}",
            r.heading,
            s.heading
        );
    }
    // The reloaded world reads the same surfaces where the robots are.
    let w2 = World::new(&sc2, &PhysicsParams::default()).unwrap();
    let grid = SurfaceSensors {
        rings: 5,
        angles: 7,
        ..Default::default()
    }
    .grid();
    let (mut a, mut b) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
    for i in 0..2 {
        grid.read(&w, i, &mut a);
        grid.read(&w2, i, &mut b);
        assert_eq!(a, b);
    }
}

#[test]
fn drawings_render_to_svg_and_png_with_title_and_sensors() {
    let mut w = busy_world();
    w.record_trajectories(20);
    for _ in 0..20 {
        w.step(&[[1.0, 1.0], [0.5, 1.0]]);
    }
    let opts = DrawOptions {
        title: Some("Fig. 1 & <test>".into()),
        surface_sensors: Some(SurfaceSensors::default()),
        distance_sensors: Some(DistanceSensors::default()),
        ..Default::default()
    };
    let svg = vivae_sim::render_svg(&w, &opts);
    assert!(svg.contains("Fig. 1 &amp; &lt;test&gt;"));
    assert_eq!(
        svg.matches("<polyline").count(),
        2,
        "one trajectory per robot"
    );
    assert_eq!(
        svg.lines()
            .filter(|l| l.starts_with("<polyline") && l.contains(r##"stroke="#e41a1c""##))
            .count(),
        1,
        "robot 0's trajectory colour"
    );
    assert_eq!(
        svg.lines()
            .filter(|l| l.starts_with("<circle") && l.contains(r##"fill="none" stroke="#e41a1c""##))
            .count(),
        1,
        "robot 0's start pose is marked"
    );
    assert!(
        svg.contains("start (hollow), end (filled)"),
        "a legend explains the marks"
    );
    assert!(svg.matches("<circle").count() >= 2 * 15 + 2);
    let png = vivae_sim::render_png(&w, &DrawOptions { scale: 0.5, ..opts }).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert!(
        vivae_sim::render_png(
            &w,
            &DrawOptions {
                scale: 0.0,
                ..Default::default()
            }
        )
        .is_err()
    );
}

#[test]
fn default_scenario_has_five_robots_on_the_road() {
    let sc =
        Scenario::from_svg(vivae_sim::ROADS_SVG, "roads.svg", &LoadOptions::default()).unwrap();
    assert!(sc.warnings.is_empty(), "{:?}", sc.warnings);
    assert_eq!(sc.robots.len(), 5);
    assert!((sc.width(), sc.height()) == (800.0, 600.0));
    let w = World::new(&sc, &PhysicsParams::default()).unwrap();
    for i in 0..5 {
        assert!(w.on_road(i), "robot {i} starts on the road");
    }
}
