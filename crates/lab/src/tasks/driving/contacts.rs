//! Contacts by kind: a learner touching another learner, a scripted robot,
//! an obstacle (fixed, movable or placed) or the arena's wall, counted when
//! the contact begins (the pair did not touch the step before).

use serde::Serialize;
use vivae_sim::World;
use vivae_sim::geometry::Shape;

/// Largest gap between outlines, in px, that still counts as touching.
pub const TOUCH: f64 = 0.05;

/// Contacts begun, by what the learner touched.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct ContactCounts {
    /// Learner–learner (each pair once).
    pub robot: u64,
    /// Learner–scripted robot.
    pub traffic: u64,
    /// Learner–obstacle (fixed, movable, or placed for the episode).
    pub obstacle: u64,
    /// Learner–arena wall.
    pub wall: u64,
    /// Learner–obstacle placed for the episode by an obstacle region (also
    /// counted in `obstacle`): the blocks, apart from kerbs and other fixed obstacles.
    pub placed: u64,
}

impl ContactCounts {
    /// The contacts the `collisions` measure counts: everything but walls.
    pub fn collisions(&self) -> u64 {
        self.robot + self.traffic + self.obstacle
    }
}

/// Contacts by kind per 1,000 robot-steps.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct ContactRates {
    /// Learner–learner.
    pub robot: f64,
    /// Learner–scripted robot.
    pub traffic: f64,
    /// Learner–obstacle.
    pub obstacle: f64,
    /// Learner–wall.
    pub wall: f64,
    /// Learner–obstacle placed for the episode (also in `obstacle`).
    pub placed: f64,
}

impl ContactRates {
    /// `counts` per 1,000 of `robot_steps` (all zero for none).
    pub fn of(counts: ContactCounts, robot_steps: u64) -> ContactRates {
        let per = |c: u64| {
            if robot_steps == 0 {
                0.0
            } else {
                1000.0 * c as f64 / robot_steps as f64
            }
        };
        ContactRates {
            robot: per(counts.robot),
            traffic: per(counts.traffic),
            obstacle: per(counts.obstacle),
            wall: per(counts.wall),
            placed: per(counts.placed),
        }
    }

    /// The rates under the keys `replay` prints them with.
    pub fn named(&self) -> [(&'static str, f64); 5] {
        [
            ("contacts_robot", self.robot),
            ("contacts_traffic", self.traffic),
            ("contacts_obstacle", self.obstacle),
            ("contacts_wall", self.wall),
            ("contacts_placed", self.placed),
        ]
    }

    /// `key=value` pairs, as `replay` prints them.
    pub fn fields(&self) -> String {
        let pairs = self.named().map(|(key, rate)| format!("{key}={rate:.3}"));
        pairs.join(" ")
    }
}

/// Counts contacts step by step (allocates only on creation).
#[derive(Debug, Clone)]
pub struct ContactCounter {
    /// Which pairs touched at the previous step, learner-major; per learner:
    /// learners, scripted robots, fixed obstacles, movable obstacles, the wall.
    touching: Vec<bool>,
    others: usize,
    counts: ContactCounts,
}

impl ContactCounter {
    /// A counter for `world`'s learners.
    pub fn new(world: &World) -> ContactCounter {
        let others = others(world);
        ContactCounter {
            touching: vec![false; world.robots().len() * others],
            others,
            counts: ContactCounts::default(),
        }
    }

    /// Counts the contacts that began in the step `world` just took.
    pub fn observe(&mut self, world: &World) {
        let (robots, traffic) = (world.robots(), world.traffic());
        let sc = world.scenario();
        let (n, m, f) = (robots.len(), traffic.len(), sc.fixed_obstacles.len());
        // The placed obstacles are the last fixed ones.
        let first_placed = n + m + f - sc.placed_obstacles.min(f);
        let r = world.params().robot_radius;
        let (w, h) = (sc.width(), sc.height());
        for (i, robot) in robots.iter().enumerate() {
            let p = robot.pos;
            let touched = &mut self.touching[i * self.others..(i + 1) * self.others];
            for (k, was_touching) in touched.iter_mut().enumerate() {
                let touches = if k < n {
                    k != i && robots[k].pos.distance(p) <= 2.0 * r + TOUCH
                } else if k < n + m {
                    traffic[k - n].pos.distance(p) <= 2.0 * r + TOUCH
                } else if k < n + m + f {
                    touches_shape(&sc.fixed_obstacles[k - n - m].shape, p, r)
                } else if k + 1 < self.others {
                    let j = k - n - m - f;
                    touches_shape(
                        &sc.movable_obstacles[j].shape,
                        p - world.movables()[j].offset,
                        r,
                    )
                } else {
                    let reach = r + TOUCH;
                    p.x <= reach || p.y <= reach || p.x >= w - reach || p.y >= h - reach
                };
                let was = std::mem::replace(was_touching, touches);
                if !touches || was {
                    continue;
                }
                // A learner pair is one contact, counted once (from its lower index).
                match k {
                    k if k < n => self.counts.robot += u64::from(i < k),
                    k if k < n + m => self.counts.traffic += 1,
                    k if k + 1 < self.others => {
                        self.counts.obstacle += 1;
                        self.counts.placed += u64::from((first_placed..n + m + f).contains(&k));
                    }
                    _ => self.counts.wall += 1,
                }
            }
        }
    }

    /// The contacts begun so far.
    pub fn counts(&self) -> ContactCounts {
        self.counts
    }
}

/// Slots per learner: every robot, every obstacle, the wall.
fn others(world: &World) -> usize {
    let sc = world.scenario();
    world.robots().len()
        + world.traffic().len()
        + sc.fixed_obstacles.len()
        + sc.movable_obstacles.len()
        + 1
}

/// Whether a disc of radius `r` at `p` touches (or overlaps) `shape`.
pub fn touches_shape(shape: &Shape, p: vivae_sim::DVec2, r: f64) -> bool {
    shape.bbox.contains_with_margin(p, r + TOUCH)
        && (shape.contains(p) || shape.closest_boundary_point(p).1 <= r + TOUCH)
}

#[cfg(test)]
mod tests {
    use super::*;
    use vivae_sim::{DVec2, LoadOptions, PhysicsParams, Scenario};

    #[test]
    fn contacts_with_placed_blocks_are_told_from_kerbs() {
        let s = crate::tasks::scenarios::find("kerbed-loop").unwrap();
        let sc = Scenario::from_svg(s.svg, "kerbed-loop", &LoadOptions::default()).unwrap();
        let mut p = crate::tasks::driving::placement::placed(&sc, 5);
        assert!(p.placed_obstacles > 0);
        p.robots[0].pos = p.fixed_obstacles.last().unwrap().shape.bbox.center();
        p.robots[1].pos = DVec2::new(400.0, 67.0); // on the outer kerb
        let world = World::new(&p, &PhysicsParams::default()).unwrap();
        let mut counter = ContactCounter::new(&world);
        counter.observe(&world);
        let c = counter.counts();
        assert_eq!(c.placed, 1, "{c:?}");
        assert!(
            c.obstacle >= 2,
            "the kerb is an obstacle but no placed one: {c:?}"
        );
        counter.observe(&world);
        assert_eq!(counter.counts(), c, "a contact is counted when it begins");
    }
}
