//! Surface and distance sensors on hand-made worlds.

use crate::common::*;
use vivae_sim::{DistanceSensors, PhysicsParams, Sensor, SurfaceSensors, World};

fn vertical_road(robot_deg: f64) -> World {
    let body = format!(
        r#"<rect id="road" inkscape:label="Road" x="80" y="0" width="40" height="300"/>{}"#,
        robot("r1", 100.0, 150.0, robot_deg)
    );
    World::new(&load(&svg(200.0, 300.0, &body)), &PhysicsParams::default()).unwrap()
}

fn horizontal_road(robot_deg: f64) -> World {
    let body = format!(
        r#"<rect id="road" inkscape:label="Road" x="0" y="80" width="300" height="40"/>{}"#,
        robot("r1", 150.0, 100.0, robot_deg)
    );
    World::new(&load(&svg(300.0, 200.0, &body)), &PhysicsParams::default()).unwrap()
}

#[test]
fn robot_on_straight_road_sees_road_ahead_and_grass_beside() {
    let w = vertical_road(0.0);
    let grid = SurfaceSensors::default().grid();
    let mut out = vec![f64::NAN; grid.len()];
    grid.read(&w, 0, &mut out);
    // Ring-major, angles left→right: −90, −45, 0, 45, 90 at d = 10, 30, 50.
    for ring in 0..3 {
        assert_eq!(out[ring * 5 + 2], 1.0, "straight ahead, ring {ring}");
    }
    assert_eq!(out[0], 1.0, "10 px to the left is still on the 40 px road");
    for ring in 1..3 {
        assert_eq!(out[ring * 5], 0.0, "left, ring {ring} is grass");
        assert_eq!(out[ring * 5 + 4], 0.0, "right, ring {ring} is grass");
    }
}

#[test]
fn rotating_the_robot_rotates_the_pattern() {
    let grid = SurfaceSensors {
        rings: 4,
        angles: 9,
        ..Default::default()
    }
    .grid();
    let mut a = vec![0.0; grid.len()];
    let mut b = vec![0.0; grid.len()];
    grid.read(&vertical_road(0.0), 0, &mut a);
    grid.read(&horizontal_road(90.0), 0, &mut b);
    assert_eq!(a, b);
    let mut c = vec![0.0; grid.len()];
    grid.read(&vertical_road(90.0), 0, &mut c);
    assert_ne!(a, c, "facing across the road must look different");
    // Facing across the road: ahead (ring ≥ 1) is grass, sideways is road.
    assert_eq!(c[9 + 4], 0.0);
    assert_eq!(c[3 * 9], 1.0);
}

#[test]
fn sensors_outside_the_arena_read_zero() {
    let body = format!(
        r#"<rect id="road" inkscape:label="Road" x="0" y="0" width="100" height="100"/>{}"#,
        robot("r1", 50.0, 8.0, 0.0)
    );
    let w = World::new(&load(&svg(100.0, 100.0, &body)), &PhysicsParams::default()).unwrap();
    let grid = SurfaceSensors::default().grid();
    let mut out = vec![0.0; grid.len()];
    grid.read(&w, 0, &mut out);
    assert_eq!(out[2], 0.0, "10 px ahead is above the top edge");
    assert_eq!(out[0], 1.0, "10 px to the left is road");
}

#[test]
fn sand_and_water_read_between_road_and_grass() {
    let body = format!(
        r#"<rect id="s" inkscape:label="Sand" x="0" y="0" width="100" height="50"/><rect id="w" inkscape:label="water" x="0" y="50" width="100" height="50"/>{}"#,
        robot("r1", 50.0, 50.0, 0.0)
    );
    let w = World::new(&load(&svg(100.0, 100.0, &body)), &PhysicsParams::default()).unwrap();
    let sand = w.surface_at(vivae_sim::DVec2::new(10.0, 10.0)).unwrap();
    let water = w.surface_at(vivae_sim::DVec2::new(10.0, 90.0)).unwrap();
    assert!((sand.reading - 6.5 / 9.0).abs() < 1e-12);
    assert!((water.reading - 3.5 / 9.0).abs() < 1e-12);
}

#[test]
fn wall_at_known_distance_reads_one_minus_d_over_range() {
    let w = vertical_road(0.0);
    let grid = DistanceSensors {
        rays: 3,
        fov: 180.0,
        range: 200.0,
    }
    .grid();
    let mut out = vec![f64::NAN; 3];
    grid.read(&w, 0, &mut out);
    // Robot at (100, 150), radius 6: top wall 144 px from its rim; side walls 94 px.
    assert!((out[1] - (1.0 - 144.0 / 200.0)).abs() < 1e-9, "{out:?}");
    assert!((out[0] - (1.0 - 94.0 / 200.0)).abs() < 1e-9, "{out:?}");
    assert!((out[2] - (1.0 - 94.0 / 200.0)).abs() < 1e-9, "{out:?}");
    let short = DistanceSensors {
        rays: 1,
        fov: 0.0,
        range: 50.0,
    }
    .grid();
    let mut one = [f64::NAN];
    short.read(&w, 0, &mut one);
    assert_eq!(one[0], 0.0, "nothing within range reads 0");
}

#[test]
fn distance_sensors_see_robots_and_obstacles() {
    let body = format!(
        r#"<rect id="box" inkscape:label="FixedObstacle" x="90" y="20" width="20" height="10"/>{}{}"#,
        robot("r1", 100.0, 150.0, 0.0),
        robot("r2", 150.0, 150.0, 0.0)
    );
    let w = World::new(&load(&svg(300.0, 300.0, &body)), &PhysicsParams::default()).unwrap();
    let grid = DistanceSensors {
        rays: 3,
        fov: 180.0,
        range: 200.0,
    }
    .grid();
    let mut out = [0.0; 3];
    grid.read(&w, 0, &mut out);
    // Obstacle bottom at y = 30: 120 − 6 = 114 px from the rim.
    assert!((out[1] - (1.0 - 114.0 / 200.0)).abs() < 1e-6, "{out:?}");
    // Other robot to the right: centres 50 apart, rims 38 apart.
    assert!((out[2] - (1.0 - 38.0 / 200.0)).abs() < 1e-6, "{out:?}");
}
