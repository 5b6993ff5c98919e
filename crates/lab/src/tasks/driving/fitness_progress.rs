//! Progress: distance driven along the road's direction of travel. Each
//! learner has a route (its start's `data-route`, else the route nearest
//! its start); every step adds how far it moved along that route, so driving
//! the wrong way counts against it and turning round does not pay.
//! `fitness.kind = "progress"`.

use vivae_sim::World;

use crate::tasks::driving::fitness::{Fitness, FitnessMeter};

/// Σ distance along each learner's route / robot-steps, px per step.
#[derive(Debug, Clone, Copy, Default)]
pub struct Progress;

/// One episode's progress: each learner's route and where it was on it.
struct ProgressMeter {
    /// (route, segment found last step, arc length there) per learner with a route.
    places: Vec<(Option<usize>, usize, f64)>,
    total: f64,
}

impl FitnessMeter for ProgressMeter {
    fn observe(&mut self, world: &World) {
        let routes = &world.scenario().routes;
        for (place, robot) in self.places.iter_mut().zip(world.robots()) {
            let (Some(r), segment, s) = *place else {
                continue;
            };
            let here = routes[r].locate(robot.pos, Some(segment));
            self.total += routes[r].advance(s, here.s);
            *place = (Some(r), here.segment, here.s);
        }
    }

    fn score(&self, _: &World, robot_steps: f64) -> f64 {
        self.total / robot_steps
    }
}

impl Fitness for Progress {
    fn name(&self) -> &str {
        "progress"
    }

    fn meter(&self, world: &World) -> Box<dyn FitnessMeter> {
        let sc = world.scenario();
        let places = (world.robots().iter().enumerate())
            .map(|(i, robot)| {
                let route = (sc.robots.get(i).and_then(|s| s.route))
                    .or_else(|| sc.nearest_route(robot.pos));
                match route {
                    Some(r) => {
                        let here = sc.routes[r].locate(robot.pos, None);
                        (Some(r), here.segment, here.s)
                    }
                    None => (None, 0, 0.0),
                }
            })
            .collect();
        Box::new(ProgressMeter { places, total: 0.0 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::driving::fitness::AverageSpeed;
    use vivae_sim::{LoadOptions, PhysicsParams, Scenario};

    fn drive(world: &mut World, fitness: &dyn Fitness, steps: u32, controls: [f64; 2]) -> f64 {
        let mut meter = fitness.meter(world);
        for _ in 0..steps {
            world.step(&vec![controls; world.robots().len()]);
            meter.observe(world);
        }
        meter.score(world, (world.robots().len() as u32 * steps) as f64)
    }

    fn oncoming() -> World {
        let s = crate::tasks::scenarios::find("oncoming").unwrap();
        let sc = Scenario::from_svg(s.svg, "oncoming", &LoadOptions::default()).unwrap();
        World::new(&sc, &PhysicsParams::default()).unwrap()
    }

    #[test]
    fn driving_along_the_route_scores_like_speed_and_turning_round_scores_against() {
        let mut w = oncoming();
        let forward = drive(&mut w.clone(), &Progress, 30, [1.0, 1.0]);
        let speed = drive(&mut w.clone(), &AverageSpeed, 30, [1.0, 1.0]);
        assert!(
            forward > 0.5 * speed && forward <= speed + 1e-9,
            "{forward} vs {speed}"
        );
        // Turn round on the spot first, then drive: progress goes negative.
        for i in 0..w.robots().len() {
            let r = &w.robots()[i];
            let (pos, heading) = (r.pos, r.heading + std::f64::consts::PI);
            w.set_pose(i, pos, heading);
        }
        let backward = drive(&mut w, &Progress, 30, [1.0, 1.0]);
        assert!(backward < 0.0, "{backward}");
    }
}
