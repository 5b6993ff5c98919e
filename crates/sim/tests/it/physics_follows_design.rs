//! DESIGN §5 kinematics, collisions, odometer and determinism on hand-made worlds.

use crate::common::*;
use vivae_sim::{DVec2, PhysicsParams, World};

fn world(body: &str, w: f64, h: f64) -> World {
    World::new(&load(&svg(w, h, body)), &PhysicsParams::default()).unwrap()
}

#[test]
fn full_throttle_tends_to_5_on_road_and_half_on_grass() {
    let body = format!(
        r#"<rect id="road" inkscape:label="Road" x="0" y="0" width="100" height="5000"/>{}{}"#,
        robot("a", 50.0, 4990.0, 0.0),
        robot("b", 300.0, 4990.0, 0.0)
    );
    let mut w = world(&body, 400.0, 5000.0);
    for _ in 0..200 {
        w.step(&[[1.0, 1.0], [1.0, 1.0]]);
    }
    assert!(
        (w.robots()[0].speed - 5.0).abs() < 1e-6,
        "road {}",
        w.robots()[0].speed
    );
    assert!(
        (w.robots()[1].speed - 0.5).abs() < 1e-6,
        "grass {}",
        w.robots()[1].speed
    );
    assert!(w.robots()[0].pos.y < 4990.0 - 900.0);
    assert!((w.robots()[0].pos.x - 50.0).abs() < 1e-9, "straight line");
}

#[test]
fn robot_turns_toward_its_slower_wheel() {
    let mut w = world(&robot("a", 200.0, 200.0, 0.0), 400.0, 400.0);
    w.step(&[[1.0, 0.0]]);
    assert!(
        (w.robots()[0].heading - 0.1).abs() < 1e-12,
        "L > R turns clockwise by ω_max/2"
    );
    let mut w2 = world(&robot("a", 200.0, 200.0, 0.0), 400.0, 400.0);
    w2.step(&[[-1.0, 1.0]]);
    assert!((w2.robots()[0].heading + 0.2).abs() < 1e-12);
    assert_eq!(w2.robots()[0].speed, 0.0);
}

#[test]
fn steering_weakens_with_speed() {
    let mut w = world(
        &format!(
            r#"<rect id="road" inkscape:label="Road" x="0" y="0" width="400" height="400"/>{}"#,
            robot("a", 200.0, 390.0, 0.0)
        ),
        400.0,
        400.0,
    );
    for _ in 0..50 {
        w.step(&[[1.0, 1.0]]);
    }
    let v = w.robots()[0].speed;
    let h0 = w.robots()[0].heading;
    w.step(&[[1.0, 0.5]]);
    let dh = w.robots()[0].heading - h0;
    assert!(
        (dh - 0.2 * 0.25 * (1.0 - v / 5.0)).abs() < 1e-12,
        "ω scaled by 1 − v/v_max"
    );
}

#[test]
fn wall_stops_robot_and_odometer_counts_only_real_motion() {
    let mut w = world(&robot("a", 50.0, 20.0, 0.0), 100.0, 100.0);
    for _ in 0..100 {
        w.step(&[[1.0, 1.0]]);
    }
    let r = &w.robots()[0];
    assert!(
        (r.pos.y - 6.0).abs() < 1e-9,
        "robot rests against the top wall"
    );
    assert_eq!(r.speed, 0.0, "speed into the wall is removed");
    assert!((r.odometer - 14.0).abs() < 1e-9, "odometer {}", r.odometer);
}

#[test]
fn fixed_obstacle_blocks_robot_even_if_concave() {
    // A U-shaped obstacle opening downwards; the robot drives up into it.
    let body = format!(
        r#"<path id="u" inkscape:label="FixedObstacle" d="M 60,20 L 140,20 L 140,80 L 120,80 L 120,40 L 80,40 L 80,80 L 60,80 Z"/>{}"#,
        robot("a", 100.0, 150.0, 0.0)
    );
    let mut w = world(&body, 200.0, 200.0);
    for _ in 0..400 {
        w.step(&[[1.0, 1.0]]);
    }
    let r = &w.robots()[0];
    assert!(
        (r.pos.y - 46.0).abs() < 1e-6,
        "stopped 6 px below the U's inner top: {:?}",
        r.pos
    );
}

#[test]
fn robots_do_not_pass_through_each_other() {
    let body = format!(
        "{}{}",
        robot("a", 100.0, 150.0, 0.0),
        robot("b", 100.0, 50.0, 180.0)
    );
    let mut w = world(&body, 200.0, 200.0);
    for _ in 0..100 {
        w.step(&[[1.0, 1.0], [1.0, 1.0]]);
        let d = w.robots()[0].pos.distance(w.robots()[1].pos);
        assert!(d >= 12.0 - 1e-6, "overlap: {d}");
    }
    assert!(w.robots()[0].pos.y > w.robots()[1].pos.y);
}

#[test]
fn robot_pushes_a_puck_and_a_movable_obstacle() {
    let body = format!(
        r#"<rect id="road" inkscape:label="Road" x="0" y="0" width="400" height="300"/><circle id="p" inkscape:label="SmallPuck" cx="100" cy="100" r="8"/><rect id="o" inkscape:label="Obstacle" x="240" y="80" width="20" height="10"/>{}{}"#,
        robot("a", 100.0, 180.0, 0.0),
        robot("b", 250.0, 180.0, 0.0)
    );
    let mut w = world(&body, 400.0, 300.0);
    let start = (w.pucks()[0].pos, w.movables()[0].offset);
    for _ in 0..150 {
        w.step(&[[1.0, 1.0], [1.0, 1.0]]);
    }
    assert!(
        w.pucks()[0].pos.y < start.0.y - 20.0,
        "puck pushed up: {:?}",
        w.pucks()[0].pos
    );
    assert!(
        w.movables()[0].offset.y < start.1.y - 5.0,
        "obstacle pushed up: {:?}",
        w.movables()[0].offset
    );
    assert!(
        w.pucks()[0].pos.y >= 8.0 - 1e-9,
        "puck stays inside the walls"
    );
    assert!(
        w.movables()[0].offset.y >= -80.0 - 1e-9,
        "obstacle stays inside the walls"
    );
}

#[test]
fn same_controls_give_bit_identical_state_and_clones_are_independent() {
    let text = vivae_sim::ROADS_SVG;
    run_determinism(&World::new(&load(text), &PhysicsParams::default()).unwrap());
}

fn run_determinism(w0: &World) {
    let controls = |t: usize, i: usize| {
        let x = ((t * 7 + i * 13) % 17) as f64 / 8.0 - 1.0;
        [x, ((t * 3 + i * 5) % 11) as f64 / 5.0 - 1.0]
    };
    let run = |mut w: World| {
        let n = w.robots().len();
        let mut c = vec![[0.0; 2]; n];
        for t in 0..500 {
            for (i, ci) in c.iter_mut().enumerate() {
                *ci = controls(t, i);
            }
            w.step(&c);
        }
        w.robots()
            .iter()
            .map(|r| {
                (
                    r.pos.x.to_bits(),
                    r.pos.y.to_bits(),
                    r.heading.to_bits(),
                    r.odometer.to_bits(),
                )
            })
            .collect::<Vec<_>>()
    };
    let a = run(w0.clone());
    let b = run(w0.clone());
    assert_eq!(a, b);
    // Clones share the scenario; stepping one must not move another.
    let mut stepped = w0.clone();
    let untouched = w0.clone();
    stepped.step(&vec![[1.0, 1.0]; w0.robots().len()]);
    assert_ne!(
        stepped.robots(),
        w0.robots(),
        "full throttle moves the robots"
    );
    assert_eq!(
        untouched.robots(),
        w0.robots(),
        "a clone is independent of its siblings"
    );
    assert_eq!(untouched.steps(), w0.steps());
}

#[test]
fn trajectories_record_every_step() {
    let mut w = world(&robot("a", 100.0, 150.0, 0.0), 200.0, 200.0);
    assert!(w.trajectories().is_none());
    w.record_trajectories(10);
    for _ in 0..10 {
        w.step(&[[1.0, 1.0]]);
    }
    let t = w.trajectories().unwrap();
    assert_eq!(t[0].len(), 11);
    assert_eq!(t[0][0], DVec2::new(100.0, 150.0));
    assert_eq!(*t[0].last().unwrap(), w.robots()[0].pos);
}
