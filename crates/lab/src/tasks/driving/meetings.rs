//! Meetings: every time a learner comes within [`APPROACH`] px (along the
//! route) of a block placed for the episode, what it did about it — the
//! line it was on, whether the block lay on that line, whether it touched
//! it, how far it moved sideways, and whether and how early a distance ray
//! showed it the block. `vivae replay --meetings` writes them, one per line,
//! to tell a robot that steers round blocks from one that keeps its line.

use serde::Serialize;
use vivae_sim::sensors::Sensor;
use vivae_sim::{DVec2, DistanceGrid, Route, World};

use crate::tasks::driving::contacts::touches_shape;
use crate::tasks::driving::episode::{Episode, EpisodeError};
use crate::tasks::driving::rollout::Drive;

/// Along-route distance (px) from a block at which a meeting begins and
/// ends: the distance rays' default range, and less than the 125 px between
/// the rows of `corridor`'s blocks.
pub const APPROACH: f64 = 100.0;

/// How a meeting ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Exit {
    /// The robot left the window on the block's far side: it got past.
    Passed,
    /// It left the window on the side it came from (turned back).
    Back,
    /// The episode ended with the robot still in the window.
    End,
}

impl Exit {
    /// The word the CSV writes.
    pub fn name(self) -> &'static str {
        match self {
            Exit::Passed => "passed",
            Exit::Back => "back",
            Exit::End => "end",
        }
    }
}

/// One learner meeting one placed block. Across the road is the signed
/// distance (px) from the route, positive to the right of its direction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Meeting {
    /// The learner (0-based).
    pub robot: usize,
    /// The placed block (0-based, in placing order).
    pub block: usize,
    /// Step at which the robot came within [`APPROACH`] px of the block.
    pub entry_step: usize,
    /// Step at which it left the window (or the episode's last).
    pub exit_step: usize,
    /// The block's centre across the road.
    pub block_across: f64,
    /// The robot's centre across the road when the meeting began: its line.
    pub entry_across: f64,
    /// Whether the block lay on that line: the robot would touch it
    /// driving on along it (|entry − block| < robot radius + half the block).
    pub on_line: bool,
    /// Contacts with the block begun during the meeting.
    pub touches: u32,
    /// Least gap between robot and block, px (0: they touched).
    pub clearance: f64,
    /// The robot's centre across the road at its first touch, or, untouched,
    /// where it was nearest the block along the route.
    pub pass_across: f64,
    /// How far the robot moved away from the block's side between entry and
    /// `pass_across`, px (negative: towards it).
    pub shift: f64,
    /// Along-route distance (px) to the block when a distance ray first
    /// showed it (the nearest thing on that ray), before any touch; `None`
    /// when no ray showed it before (or the robots carry no rays).
    pub seen_at: Option<f64>,
    /// Steps before the first touch (or the exit) in which a ray showed it.
    pub seen_steps: u32,
    /// The largest reading a ray gave of it before the first touch (0: never seen).
    pub peak: f64,
    /// How the meeting ended.
    pub exit: Exit,
}

impl Meeting {
    /// The CSV header of [`Meeting::csv_line`].
    pub const CSV_HEADER: &'static str = "robot,block,entry_step,exit_step,block_across,entry_across,on_line,touches,clearance,pass_across,shift,seen_at,seen_steps,peak,exit";

    /// One CSV line (robots and blocks 1-based, as figures name them).
    pub fn csv_line(&self) -> String {
        format!(
            "{},{},{},{},{:.2},{:.2},{},{},{:.2},{:.2},{:.2},{},{},{:.4},{}",
            self.robot + 1,
            self.block + 1,
            self.entry_step,
            self.exit_step,
            self.block_across,
            self.entry_across,
            self.on_line,
            self.touches,
            self.clearance,
            self.pass_across,
            self.shift,
            self.seen_at.map_or(String::new(), |s| format!("{s:.2}")),
            self.seen_steps,
            self.peak,
            self.exit.name()
        )
    }
}

/// Counts over an episode's meetings, as `vivae replay --meetings` prints them.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct MeetingCounts {
    /// Meetings.
    pub meetings: usize,
    /// Meetings with the block on the robot's line.
    pub on_line: usize,
    /// … of which the robot touched the block.
    pub on_line_touched: usize,
    /// … of which a ray showed the robot the block before any touch.
    pub on_line_seen: usize,
    /// Meetings with the block off the robot's line that it touched anyway.
    pub off_line_touched: usize,
}

impl MeetingCounts {
    /// The counts of `meetings`.
    pub fn of(meetings: &[Meeting]) -> MeetingCounts {
        let on: Vec<&Meeting> = meetings.iter().filter(|m| m.on_line).collect();
        MeetingCounts {
            meetings: meetings.len(),
            on_line: on.len(),
            on_line_touched: on.iter().filter(|m| m.touches > 0).count(),
            on_line_seen: on.iter().filter(|m| m.seen_steps > 0).count(),
            off_line_touched: (meetings.iter())
                .filter(|m| !m.on_line && m.touches > 0)
                .count(),
        }
    }

    /// `key=value` pairs, as `replay --meetings` prints them.
    pub fn fields(&self) -> String {
        format!(
            "meetings={} on_line={} on_line_touched={} on_line_seen={} off_line_touched={}",
            self.meetings,
            self.on_line,
            self.on_line_touched,
            self.on_line_seen,
            self.off_line_touched
        )
    }
}

/// A block placed for the episode, where it is on the route.
struct Block {
    shape: vivae_sim::geometry::Shape,
    s: f64,
    across: f64,
    half: f64,
}

/// A meeting under way.
struct Open {
    meeting: Meeting,
    /// The side of the block it came from (+1: behind it along the route).
    side: f64,
    touching: bool,
    /// Least |along-route distance| so far, before any touch.
    nearest: f64,
}

/// Signed distance of `p` from `route` (positive to the right of its
/// direction) and its arc length, tracked from segment `near`.
fn across(route: &Route, p: DVec2, near: Option<usize>) -> (f64, f64, usize) {
    let place = route.locate(p, near);
    let (q, dir) = route.point_at(place.s);
    let d = p - q;
    (dir.x * d.y - dir.y * d.x, place.s, place.segment)
}

/// The reading a ray gives of a hit at `t` px from the robot's centre (as
/// [`DistanceGrid`] reads it).
fn reading(t: f64, r0: f64, range: f64) -> f64 {
    (1.0 - (t - r0).max(0.0) / range).clamp(0.0, 1.0)
}

/// The largest reading any of `rays` of robot `i` gives of `block` while it
/// is the nearest thing on that ray (0: no ray shows it); `seen` holds the
/// world's readings of robot `i`.
fn shown(world: &World, i: usize, rays: &DistanceGrid, seen: &[f64], block: &Block) -> f64 {
    let robot = &world.robots()[i];
    let (p, ahead, right) = (robot.pos, robot.ahead(), robot.right());
    let r0 = world.params().robot_radius;
    let mut best = 0.0f64;
    for (o, &v) in rays.dirs.iter().zip(seen) {
        let d = ahead * o.x + right * o.y;
        if let Some(t) = block.shape.ray_hit(p, d, rays.range + r0) {
            let b = reading(t, r0, rays.range);
            // Another thing nearer on the ray hides the block.
            if v > 0.0 && (b - v).abs() <= 1e-12 {
                best = best.max(b);
            }
        }
    }
    best
}

/// The blocks placed for the episode of `world`, where they are on `route`.
fn placed_blocks(world: &World, route: &Route) -> Vec<Block> {
    let sc = world.scenario();
    let fixed = &sc.fixed_obstacles;
    (fixed[fixed.len() - sc.placed_obstacles.min(fixed.len())..].iter())
        .map(|o| {
            let (a, s, _) = across(route, o.shape.bbox.center(), None);
            let size = o.shape.bbox.max - o.shape.bbox.min;
            Block {
                shape: o.shape.clone(),
                s,
                across: a,
                half: 0.5 * size.x.min(size.y),
            }
        })
        .collect()
}

/// Per (robot, block), robot-major: whether the block is in the robot's
/// window at the start but behind it. Such a block is met only once the
/// robot has left the window and come back (or touches it).
fn behind_at_start(world: &World, route: &Route, blocks: &[Block]) -> Vec<bool> {
    let robots = world.robots();
    (0..robots.len() * blocks.len())
        .map(|j| {
            let (robot, block) = (&robots[j / blocks.len()], &blocks[j % blocks.len()]);
            let s = route.locate(robot.pos, None).s;
            let centre = block.shape.bbox.center();
            route.advance(s, block.s).abs() <= APPROACH
                && (centre - robot.pos).dot(robot.ahead()) <= 0.0
        })
        .collect()
}

/// Where robot `robot` is at step `step`: its centre, across the road, and
/// along-route distance `ahead` to the block.
struct Here {
    robot: usize,
    step: usize,
    p: DVec2,
    across: f64,
    ahead: f64,
}

/// A new meeting of `here`'s robot with block `k`.
fn open_meeting(here: &Here, k: usize, block: &Block, r: f64) -> Open {
    Open {
        meeting: Meeting {
            robot: here.robot,
            block: k,
            entry_step: here.step,
            exit_step: here.step,
            block_across: block.across,
            entry_across: here.across,
            on_line: (here.across - block.across).abs() < r + block.half,
            touches: 0,
            clearance: f64::INFINITY,
            pass_across: here.across,
            shift: 0.0,
            seen_at: None,
            seen_steps: 0,
            peak: 0.0,
            exit: Exit::End,
        },
        side: if here.ahead >= 0.0 { 1.0 } else { -1.0 },
        touching: false,
        nearest: f64::INFINITY,
    }
}

impl Open {
    /// One step of the meeting: touches and clearance; before any touch,
    /// the nearest approach along the route and `shown`, the reading a ray
    /// gives of the block now (0: none shows it).
    fn observe(&mut self, here: &Here, block: &Block, r: f64, shown: impl FnOnce() -> f64) {
        let touches = touches_shape(&block.shape, here.p, r);
        let m = &mut self.meeting;
        if touches && !self.touching {
            if m.touches == 0 {
                m.pass_across = here.across;
            }
            m.touches += 1;
        }
        self.touching = touches;
        let gap = match block.shape.contains(here.p) || touches {
            true => 0.0,
            false => (block.shape.closest_boundary_point(here.p).1 - r).max(0.0),
        };
        m.clearance = m.clearance.min(gap);
        if m.touches > 0 {
            return;
        }
        if here.ahead.abs() < self.nearest {
            self.nearest = here.ahead.abs();
            m.pass_across = here.across;
        }
        let v = shown();
        if v > 0.0 {
            m.seen_steps += 1;
            m.peak = m.peak.max(v);
            m.seen_at.get_or_insert(here.ahead.abs());
        }
    }
}

/// The meetings of one episode of `episode` driven by `controller`: every
/// learner with every block placed for the episode, along the scenario's
/// first route. `rays`: the distance rays whose sight is recorded (the
/// robots' own, or any sheet, for a controller that has none or has them
/// blinded: what they would have shown). Errors when the scenario has no
/// route.
pub fn meetings(
    episode: &Episode,
    controller: &(impl Drive + ?Sized),
    rays: Option<&DistanceGrid>,
) -> Result<Vec<Meeting>, EpisodeError> {
    let mut world = episode.world().clone();
    let sc = world.scenario();
    let route = (sc.routes.first().cloned()).ok_or_else(|| {
        EpisodeError::Scenario(format!(
            "{}: meetings are measured along a route (a path labelled Route), and the scenario has none",
            sc.source
        ))
    })?;
    let blocks = placed_blocks(&world, &route);
    let mut waiting = behind_at_start(&world, &route, &blocks);
    let (n, nb) = (world.robots().len(), blocks.len());
    let r = world.params().robot_radius;
    let mut rollout = episode.rollout(controller);
    let mut segments: Vec<Option<usize>> = vec![None; n];
    let mut open: Vec<Option<Open>> = (0..n * nb).map(|_| None).collect();
    let mut done = Vec::new();
    let mut seen = vec![0.0; rays.map_or(0, |g| g.dirs.len())];
    let steps = episode.steps() as usize;
    for step in 1..=steps {
        rollout.step(&mut world, controller, None);
        for i in 0..n {
            let p = world.robots()[i].pos;
            let (a, s, segment) = across(&route, p, segments[i]);
            segments[i] = Some(segment);
            let mut read = false;
            for (k, block) in blocks.iter().enumerate() {
                let ahead = route.advance(s, block.s);
                let (slot, wait) = (&mut open[i * nb + k], &mut waiting[i * nb + k]);
                if ahead.abs() > APPROACH {
                    *wait = false;
                    if let Some(o) = slot.take() {
                        let exit = match ahead.signum() != o.side {
                            true => Exit::Passed,
                            false => Exit::Back,
                        };
                        done.push(close(o, step, exit));
                    }
                    continue;
                }
                // Touching one ends the wait: every contact is in a meeting.
                *wait &= !touches_shape(&block.shape, p, r);
                if *wait {
                    continue;
                }
                let here = Here {
                    robot: i,
                    step,
                    p,
                    across: a,
                    ahead,
                };
                let o = slot.get_or_insert_with(|| open_meeting(&here, k, block, r));
                // What the rays show now is what the controller reads next step.
                o.observe(&here, block, r, || match rays {
                    None => 0.0,
                    Some(g) => {
                        if !read {
                            g.read(&world, i, &mut seen);
                            read = true;
                        }
                        shown(&world, i, g, &seen, block)
                    }
                });
            }
        }
    }
    done.extend(
        open.into_iter()
            .flatten()
            .map(|o| close(o, steps, Exit::End)),
    );
    done.sort_by_key(|m| (m.entry_step, m.robot, m.block));
    Ok(done)
}

/// A meeting ended at `step` by `exit`.
fn close(o: Open, step: usize, exit: Exit) -> Meeting {
    let mut m = o.meeting;
    m.exit_step = step;
    m.exit = exit;
    let away = if m.entry_across >= m.block_across {
        1.0
    } else {
        -1.0
    };
    m.shift = away * (m.pass_across - m.entry_across);
    m
}

/// All of `meetings` as a CSV file's text.
pub fn csv(meetings: &[Meeting]) -> String {
    let mut s = String::from(Meeting::CSV_HEADER);
    s.push('\n');
    for m in meetings {
        s += &m.csv_line();
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;
    use vivae_neat::Population;
    use vivae_sim::Scenario;

    fn corridor(config: &Config, placement: u64) -> Episode {
        let sc = crate::tasks::scenarios::find("corridor").unwrap();
        let scenario = Scenario::from_svg(sc.svg, "corridor", &Default::default()).unwrap();
        (Episode::new(config, &scenario).unwrap()).with_placement_seed(placement)
    }

    #[test]
    fn meetings_hold_every_block_contact_and_rays_show_blocks() {
        let mut config = Config::default();
        config.experiment.steps = 400;
        config.distance_sensors.rays = 5;
        let rays = config.distance_sensors.layout().unwrap().grid();
        let (mut touched, mut shown, mut moving) = (0, 0, 0);
        for placement in 1..=3 {
            let seeing = corridor(&config, placement);
            let pop = Population::new(config.neat.clone(), seeing.cppn_spec(), 7).unwrap();
            for g in pop.genomes().iter().take(6) {
                let c = seeing.robot_controller(g).unwrap();
                let record = seeing.run(&c, true);
                let b = record.behaviour.unwrap();
                let robot_steps = (seeing.robots() * seeing.steps() as usize) as f64;
                let placed = (b.contacts.placed * robot_steps / 1000.0).round() as u32;
                let ms = meetings(&seeing, &c, Some(&rays)).unwrap();
                // Every contact with a placed block falls in a meeting.
                assert_eq!(ms.iter().map(|m| m.touches).sum::<u32>(), placed);
                for m in &ms {
                    assert!(m.entry_step <= m.exit_step && m.exit_step <= 400);
                    assert_eq!(m.touches > 0, m.clearance == 0.0, "{m:?}");
                    assert!((0.0..=1.0).contains(&m.peak));
                    assert_eq!(m.seen_steps > 0, m.seen_at.is_some());
                    assert_eq!(m.seen_steps > 0, m.peak > 0.0);
                }
                touched += ms.iter().filter(|m| m.touches > 0).count();
                shown += ms.iter().filter(|m| m.seen_steps > 0).count();
                moving += usize::from(!ms.is_empty());
                // The rays' sight is geometry: blinded, the same paths show the same.
                let blind = seeing.clone().with_blind_rays().unwrap();
                if blind.run(&c, true).trajectories == record.trajectories {
                    assert_eq!(meetings(&blind, &c, Some(&rays)).unwrap(), ms);
                }
            }
        }
        assert!(
            moving > 0 && touched > 0 && shown > 0,
            "{moving} {touched} {shown}"
        );
    }

    #[test]
    fn without_rays_nothing_is_seen_and_the_csv_has_a_line_per_meeting() {
        let mut config = Config::default();
        config.experiment.steps = 300;
        let e = corridor(&config, 2);
        let pop = Population::new(config.neat.clone(), e.cppn_spec(), 3).unwrap();
        let all: Vec<Meeting> = (pop.genomes().iter().take(10))
            .flat_map(|g| meetings(&e, &e.robot_controller(g).unwrap(), None).unwrap())
            .collect();
        assert!(!all.is_empty());
        assert!(all.iter().all(|m| m.seen_steps == 0 && m.seen_at.is_none()));
        let text = csv(&all);
        assert_eq!(text.lines().count(), all.len() + 1);
        let counts = MeetingCounts::of(&all);
        assert_eq!(counts.meetings, all.len());
        assert!(counts.on_line_touched <= counts.on_line);
        // A scenario without a route has no meetings to measure.
        let paper = crate::tasks::scenarios::load_scenario(None)
            .unwrap()
            .scenario;
        assert!(paper.routes.is_empty());
        let e = Episode::new(&config, &paper).unwrap();
        let g = &pop.genomes()[0];
        let err = meetings(&e, &e.robot_controller(g).unwrap(), None).unwrap_err();
        assert!(err.to_string().contains("route"), "{err}");
    }
}
