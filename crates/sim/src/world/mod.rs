//! The simulated world: robots, movable bodies and the physics step.

mod contacts;
pub mod traffic;

use std::sync::Arc;

use glam::DVec2;

use crate::physics::{ParamError, PhysicsParams};
use crate::scenario::{Scenario, SurfaceKind};
use traffic::TrafficState;

/// A robot's state.
#[derive(Clone, Debug, PartialEq)]
pub struct Robot {
    /// Centre, px.
    pub pos: DVec2,
    /// Heading in radians, 0 = up (−y), clockwise positive, kept in (−π, π].
    pub heading: f64,
    /// Forward speed, px/step, in [0, v_max].
    pub speed: f64,
    /// Distance actually travelled, px.
    pub odometer: f64,
    /// Cached unit vector of `heading` (updated whenever the heading changes).
    pub(crate) dir: DVec2,
}

impl Robot {
    /// Unit vector the robot faces.
    #[inline]
    pub fn ahead(&self) -> DVec2 {
        self.dir
    }

    /// Unit vector to the robot's right.
    #[inline]
    pub fn right(&self) -> DVec2 {
        DVec2::new(-self.dir.y, self.dir.x)
    }

    fn set_heading(&mut self, heading: f64) {
        self.heading = wrap_angle(heading);
        let (s, c) = libm::sincos(self.heading);
        self.dir = DVec2::new(s, -c);
    }
}

/// Two robots of different teams that touched during a step (a catch, for
/// a predator–prey task): robot indices in scenario order, `a < b`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TeamContact {
    /// The first robot.
    pub a: usize,
    /// The second robot.
    pub b: usize,
}

/// A movable puck's state.
#[derive(Clone, Debug, PartialEq)]
pub struct PuckState {
    /// Centre.
    pub pos: DVec2,
    /// Velocity, px/step.
    pub vel: DVec2,
    /// Radius.
    pub radius: f64,
    /// Mass.
    pub mass: f64,
}

/// A movable obstacle's state: its loaded shape moved by `offset`.
#[derive(Clone, Debug, PartialEq)]
pub struct MovableState {
    /// Translation from the loaded position.
    pub offset: DVec2,
    /// Velocity, px/step.
    pub vel: DVec2,
    /// Mass.
    pub mass: f64,
}

/// The surface under a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHere {
    /// Kind of surface.
    pub kind: SurfaceKind,
    /// Friction in force there.
    pub friction: f64,
    /// What a surface sensor reads there (road 1 … grass 0).
    pub reading: f64,
}

/// Per-surface-id constants shared by all clones of a world.
#[derive(Debug)]
pub(crate) struct Statics {
    pub(crate) scenario: Scenario,
    /// Sensor reading per material id (same indexing as `here`); 256 entries so
    /// that indexing by a `u8` needs no bounds check.
    pub(crate) readings: Box<[f64; 256]>,
    /// `readings` rounded to f32, for the single-precision read.
    pub(crate) readings_f32: Box<[f32; 256]>,
    /// Friction per material id, 256 entries like `readings`.
    pub(crate) frictions: Box<[f64; 256]>,
    /// Arena size in raster cells (the outside test of the fast look-up).
    pub(crate) limit: DVec2,
    /// 1 / cell size.
    pub(crate) inv_cell: f64,
    /// Whether the scenario has at most 16 materials (every raster id below 16).
    pub(crate) few_materials: bool,
    /// Whether the cell side is a power of two (so dividing by it is multiplying by `inv_cell`).
    pub(crate) cell_pow2: bool,
    /// Whether every in-arena cell's tiled index fits in 31 bits (`limit` within
    /// the raster, under 2³¹ ids, padded for gathers), so the sensors may
    /// compute it in u32 lanes.
    pub(crate) lanes: bool,
    /// Indexed by material id (`scenario.materials()`).
    pub(crate) here: Vec<SurfaceHere>,
    /// Each robot's team as a number: 0 for none, else 1 + the index of its
    /// name among the scenario's teams in order of first appearance.
    pub(crate) teams: Vec<u16>,
}

/// A running simulation: `Clone` is cheap-ish (shares the scenario and raster).
#[derive(Clone, Debug)]
pub struct World {
    pub(crate) statics: Arc<Statics>,
    pub(crate) params: PhysicsParams,
    /// Learners first, then the scripted robots (traffic): contacts and
    /// sensors see them all.
    pub(crate) robots: Vec<Robot>,
    /// How many of `robots` are learners (driven by the caller's controls).
    learners: usize,
    /// The scripted robots' drivers, in `robots[learners..]` order.
    traffic: Vec<TrafficState>,
    pub(crate) pucks: Vec<PuckState>,
    pub(crate) movables: Vec<MovableState>,
    prev_robots: Vec<DVec2>,
    prev_pucks: Vec<DVec2>,
    prev_movables: Vec<DVec2>,
    trajectories: Option<Vec<Vec<DVec2>>>,
    steps: u64,
    /// Contacts between teams in the last step.
    pub(crate) team_contacts: Vec<TeamContact>,
}

/// The per-material surface table (`scenario.materials()` order): friction
/// from `params` unless the scenario overrides it, and the sensor reading.
fn surface_table(scenario: &Scenario, params: &PhysicsParams) -> Vec<SurfaceHere> {
    let (lo, hi) = params.friction.range();
    let here = |kind: SurfaceKind, over: Option<f64>| {
        let friction = over.unwrap_or(params.friction.of(kind));
        SurfaceHere {
            kind,
            friction,
            reading: ((hi - friction) / (hi - lo)).clamp(0.0, 1.0),
        }
    };
    scenario
        .materials()
        .iter()
        .map(|(k, f)| here(*k, *f))
        .collect()
}

impl Statics {
    /// The shared, never-changing part of a world on `scenario`.
    fn new(scenario: &Scenario, table: Vec<SurfaceHere>) -> Statics {
        let limit = DVec2::new(scenario.width(), scenario.height()) / scenario.raster().cell;
        Statics {
            readings: {
                let mut r = Box::new([0.0; 256]);
                for (slot, h) in r.iter_mut().zip(&table) {
                    *slot = h.reading;
                }
                r
            },
            readings_f32: {
                let mut r = Box::new([0.0f32; 256]);
                for (slot, h) in r.iter_mut().zip(&table) {
                    *slot = h.reading as f32;
                }
                r
            },
            frictions: {
                let mut f = Box::new([0.0; 256]);
                for (slot, h) in f.iter_mut().zip(&table) {
                    *slot = h.friction;
                }
                f
            },
            limit,
            lanes: {
                let ras = scenario.raster();
                let n = ras.tiles().0.len();
                limit.x <= ras.cols as f64
                    && limit.y <= ras.rows as f64
                    && n > crate::raster::PAD
                    && n < 1 << 31
            },
            inv_cell: 1.0 / scenario.raster().cell,
            few_materials: table.len() <= 16,
            cell_pow2: is_normal_pow2(scenario.raster().cell)
                && is_normal_pow2(1.0 / scenario.raster().cell),
            teams: team_numbers(scenario),
            scenario: scenario.clone(),
            here: table,
        }
    }
}

impl World {
    /// A world at the scenario's start state. Fails if `params` is invalid.
    pub fn new(scenario: &Scenario, params: &PhysicsParams) -> Result<World, ParamError> {
        params.validate()?;
        let robots: Vec<Robot> = (scenario.robots.iter().map(|r| (r.pos, r.heading)))
            .chain(scenario.traffic.iter().map(|t| (t.pos, t.heading)))
            .map(|(pos, heading)| {
                let mut rb = Robot {
                    pos,
                    heading: 0.0,
                    speed: 0.0,
                    odometer: 0.0,
                    dir: DVec2::ZERO,
                };
                rb.set_heading(heading);
                rb
            })
            .collect();
        let traffic = (scenario.traffic.iter())
            .map(|t| TrafficState::new(t.route, 0.5 * (t.throttle.0 + t.throttle.1)))
            .collect();
        let pucks: Vec<PuckState> = scenario
            .pucks
            .iter()
            .map(|p| PuckState {
                pos: p.pos,
                vel: DVec2::ZERO,
                radius: p.radius,
                mass: params.puck_density * std::f64::consts::PI * p.radius * p.radius,
            })
            .collect();
        let movables: Vec<MovableState> = scenario
            .movable_obstacles
            .iter()
            .map(|o| MovableState {
                offset: DVec2::ZERO,
                vel: DVec2::ZERO,
                mass: params.obstacle_density * o.shape.area(),
            })
            .collect();
        Ok(World {
            prev_robots: vec![DVec2::ZERO; robots.len()],
            prev_pucks: vec![DVec2::ZERO; pucks.len()],
            prev_movables: vec![DVec2::ZERO; movables.len()],
            statics: Arc::new(Statics::new(scenario, surface_table(scenario, params))),
            params: params.clone(),
            learners: scenario.robots.len(),
            traffic,
            robots,
            pucks,
            movables,
            trajectories: None,
            steps: 0,
            team_contacts: Vec::new(),
        })
    }

    /// The scenario this world was built from.
    pub fn scenario(&self) -> &Scenario {
        &self.statics.scenario
    }

    /// The physics constants in force.
    pub fn params(&self) -> &PhysicsParams {
        &self.params
    }

    /// The learners (robots driven by the caller's controls) in scenario order.
    pub fn robots(&self) -> &[Robot] {
        &self.robots[..self.learners]
    }

    /// The scripted robots (traffic) in scenario order.
    pub fn traffic(&self) -> &[Robot] {
        &self.robots[self.learners..]
    }

    /// The scripted robots' drivers (route and throttle), in [`World::traffic`] order.
    pub fn traffic_drivers(&self) -> &[TrafficState] {
        &self.traffic
    }

    /// Places robot `i` by hand (position, heading) and stops it; false if no such robot.
    pub fn set_pose(&mut self, i: usize, pos: DVec2, heading: f64) -> bool {
        match self.robots[..self.learners].get_mut(i) {
            Some(r) => {
                r.pos = pos;
                r.set_heading(heading);
                r.speed = 0.0;
                true
            }
            None => false,
        }
    }

    /// Robot `i`'s team (`data-team`), empty for none or no such robot.
    pub fn team(&self, i: usize) -> &str {
        self.scenario()
            .robots
            .get(i)
            .map_or("", |r| r.team.as_str())
    }

    /// Whether robots `i` and `j` are of different teams (both having one).
    #[inline]
    pub fn opponents(&self, i: usize, j: usize) -> bool {
        let t = &self.statics.teams;
        match (t.get(i), t.get(j)) {
            (Some(&a), Some(&b)) => a != b && a != 0 && b != 0,
            _ => false,
        }
    }

    /// The contacts between robots of different teams during the last step
    /// (empty before the first step, and when `collision_iterations` is 0).
    pub fn team_contacts(&self) -> &[TeamContact] {
        &self.team_contacts
    }

    /// Pucks in scenario order.
    pub fn pucks(&self) -> &[PuckState] {
        &self.pucks
    }

    /// Movable obstacles in scenario order.
    pub fn movables(&self) -> &[MovableState] {
        &self.movables
    }

    /// Steps taken since the start.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Starts recording every robot's position after each step (the current
    /// position is the first point). Recording allocates; stepping without it does not.
    pub fn record_trajectories(&mut self, capacity: usize) {
        let mut t: Vec<Vec<DVec2>> = self
            .robots
            .iter()
            .map(|_| Vec::with_capacity(capacity + 1))
            .collect();
        for (v, r) in t.iter_mut().zip(&self.robots) {
            v.push(r.pos);
        }
        self.trajectories = Some(t);
    }

    /// Recorded trajectories (one per learner), if recording.
    pub fn trajectories(&self) -> Option<&[Vec<DVec2>]> {
        self.trajectories.as_deref().map(|t| &t[..self.learners])
    }

    /// Recorded trajectories of the scripted robots, if recording.
    pub fn traffic_trajectories(&self) -> Option<&[Vec<DVec2>]> {
        self.trajectories.as_deref().map(|t| &t[self.learners..])
    }

    /// Surface at `p` (via the raster); `None` outside the arena.
    #[inline]
    pub fn surface_at(&self, p: DVec2) -> Option<SurfaceHere> {
        self.id_at(p).map(|id| self.statics.here[id as usize])
    }

    /// Material id at `p` (via the raster); `None` outside the arena.
    #[inline(always)]
    fn id_at(&self, p: DVec2) -> Option<u8> {
        let st = &*self.statics;
        let sc = &st.scenario;
        if !(p.x >= 0.0 && p.y >= 0.0 && p.x < sc.width() && p.y < sc.height()) {
            return None;
        }
        let ras = sc.raster();
        if st.cell_pow2 {
            // x / 2^k and x · 2^-k are the same correctly rounded number: no division.
            ras.id_at_cell(p.x * st.inv_cell, p.y * st.inv_cell)
        } else {
            ras.id_at(p)
        }
    }

    /// Whether robot `i`'s centre is on a road.
    pub fn on_road(&self, i: usize) -> bool {
        self.robots
            .get(i)
            .and_then(|r| self.surface_at(r.pos))
            .is_some_and(|s| s.kind == SurfaceKind::Road)
    }
    /// One time step: `controls[i] = [L, R]` in [−1, 1] for learner `i` (missing
    /// entries count as [0, 0], extra ones are ignored; scripted robots drive themselves). Allocation-free
    /// unless trajectories are being recorded.
    pub fn step(&mut self, controls: &[[f64; 2]]) {
        let pp = &self.params;
        let (v_max, a_max, om_max, k) = (pp.v_max, pp.a_max, pp.omega_max, pp.k);
        let outside = pp.friction.of(self.statics.scenario.background());
        for i in 0..self.robots.len() {
            let [l, r] = if i < self.learners {
                // Two 8-byte loads: the caller has usually just written each
                // command on its own, and one 16-byte load of two fresh 8-byte
                // stores cannot be forwarded from the store buffer (it waits
                // for them to reach the cache: 2-3 % of the default run).
                // `black_box` keeps the compiler from merging the loads.
                controls.get(i).map_or([0.0, 0.0], |c| {
                    [std::hint::black_box(c[0]), std::hint::black_box(c[1])]
                })
            } else {
                let t = &mut self.traffic[i - self.learners];
                t.controls(&self.robots[i], &self.statics.scenario.routes[t.route])
            };
            let l = if l.is_nan() { 0.0 } else { l.clamp(-1.0, 1.0) };
            let r = if r.is_nan() { 0.0 } else { r.clamp(-1.0, 1.0) };
            let mu = self
                .id_at(self.robots[i].pos)
                .map_or(outside, |id| self.statics.frictions[id as usize]);
            let rb = &mut self.robots[i];
            self.prev_robots[i] = rb.pos;
            let a = a_max * (l + r) * 0.5;
            let omega = om_max * (l - r) * 0.5 * (1.0 - rb.speed / v_max);
            rb.speed = (rb.speed + a - k * mu * rb.speed).clamp(0.0, v_max);
            if omega != 0.0 {
                rb.set_heading(rb.heading + omega);
            }
            rb.pos += rb.dir * rb.speed;
        }
        let (pd, od) = (self.params.puck_damping, self.params.obstacle_damping);
        for (i, pk) in self.pucks.iter_mut().enumerate() {
            self.prev_pucks[i] = pk.pos;
            pk.vel *= 1.0 - pd;
            pk.pos += pk.vel;
        }
        for (i, m) in self.movables.iter_mut().enumerate() {
            self.prev_movables[i] = m.offset;
            m.vel *= 1.0 - od;
            m.offset += m.vel;
        }
        self.resolve_contacts();
        for (i, rb) in self.robots.iter_mut().enumerate() {
            let moved = rb.pos - self.prev_robots[i];
            // Inelastic: only the part of the motion along the heading survives as speed.
            rb.speed = moved.dot(rb.dir).clamp(0.0, rb.speed);
            rb.odometer += moved.length();
        }
        for (i, pk) in self.pucks.iter_mut().enumerate() {
            pk.vel = pk.pos - self.prev_pucks[i];
        }
        for (i, m) in self.movables.iter_mut().enumerate() {
            m.vel = m.offset - self.prev_movables[i];
        }
        if let Some(t) = &mut self.trajectories {
            for (v, r) in t.iter_mut().zip(&self.robots) {
                v.push(r.pos);
            }
        }
        self.steps += 1;
    }
}

/// Each robot's team number (see [`Statics::teams`]).
fn team_numbers(scenario: &Scenario) -> Vec<u16> {
    let mut names: Vec<&str> = Vec::new();
    (scenario.robots.iter())
        .map(|r| {
            if r.team.is_empty() {
                return 0;
            }
            let k = names.iter().position(|n| *n == r.team).unwrap_or_else(|| {
                names.push(&r.team);
                names.len() - 1
            });
            u16::try_from(k + 1).unwrap_or(u16::MAX)
        })
        .collect()
}

/// Whether `x` is a power of two with a normal exponent (a positive, normal
/// number with an all-zero mantissa).
fn is_normal_pow2(x: f64) -> bool {
    x.is_normal() && x > 0.0 && x.to_bits() & ((1u64 << 52) - 1) == 0
}

/// Wraps an angle into (−π, π].
#[inline]
pub fn wrap_angle(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    if a > -PI && a <= PI {
        return a;
    }
    let r = (a + PI).rem_euclid(TAU) - PI;
    if r <= -PI { r + TAU } else { r }
}
