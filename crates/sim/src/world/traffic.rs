//! Scripted robots: each follows its route by pure pursuit (steer towards
//! the point a little further along the route) at its own throttle.

use glam::DVec2;

use crate::scenario::Route;
use crate::world::Robot;

/// How far ahead along its route a scripted robot aims, px.
pub const LOOKAHEAD: f64 = 24.0;
/// Steering per radian of heading error (saturates at ±1).
const STEER_GAIN: f64 = 2.0;

/// A scripted robot's driver: its route, throttle and where it was on the route.
#[derive(Clone, Debug, PartialEq)]
pub struct TrafficState {
    /// Index into the scenario's routes.
    pub route: usize,
    /// Throttle in (0, 1].
    pub throttle: f64,
    /// The route segment found last step (`None` before the first).
    segment: Option<usize>,
}

impl TrafficState {
    /// A driver on `route` at `throttle`.
    pub fn new(route: usize, throttle: f64) -> TrafficState {
        TrafficState {
            route,
            throttle,
            segment: None,
        }
    }

    /// Wheel commands `[L, R]` that keep `robot` on `route`. Allocation-free.
    pub fn controls(&mut self, robot: &Robot, route: &Route) -> [f64; 2] {
        let here = route.locate(robot.pos, self.segment);
        self.segment = Some(here.segment);
        let (target, _) = route.point_at(here.s + LOOKAHEAD);
        let d = target - robot.pos;
        let ahead = robot.ahead();
        // Positive when the target is to the robot's right (clockwise on screen).
        let cross = ahead.x * d.y - ahead.y * d.x;
        let error = libm::atan2(cross, ahead.dot(d));
        let steer = (STEER_GAIN * error).clamp(-1.0, 1.0);
        let t = self.throttle;
        [(t + steer).clamp(-1.0, 1.0), (t - steer).clamp(-1.0, 1.0)]
    }
}

/// The heading (0 = up, clockwise) of direction `dir`.
pub fn heading_of(dir: DVec2) -> f64 {
    libm::atan2(dir.x, -dir.y)
}

#[cfg(test)]
mod tests {
    use crate::{LoadOptions, PhysicsParams, Scenario, World};

    #[test]
    fn scripted_robots_keep_to_their_route_and_learners_do_not_count_them() {
        let svg = include_str!("../../../../scenarios/oncoming.svg");
        let sc = Scenario::from_svg(svg, "oncoming.svg", &LoadOptions::default()).unwrap();
        let mut w = World::new(&sc, &PhysicsParams::default()).unwrap();
        assert_eq!((w.robots().len(), w.traffic().len()), (5, 4));
        w.record_trajectories(3000);
        for _ in 0..3000 {
            // Learners stand still; only the traffic moves.
            w.step(&[]);
        }
        assert!(w.robots().iter().all(|r| r.odometer == 0.0));
        assert_eq!(w.trajectories().unwrap().len(), 5);
        let paths = w.traffic_trajectories().unwrap();
        for ((t, drv), path) in w.traffic().iter().zip(w.traffic_drivers()).zip(paths) {
            let route = &sc.routes[drv.route];
            // A lap and more, never far from the lane's centre line.
            assert!(t.odometer > route.length(), "{}", t.odometer);
            for p in &path[100..] {
                assert!(route.locate(*p, None).distance < 6.0, "{p}");
            }
        }
    }
}
