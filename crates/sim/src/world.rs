//! The simulated world: robots, movable bodies, physics step and sensor reads.

use std::sync::Arc;

use glam::DVec2;

use crate::geometry::{Aabb, Shape, ray_disc};
use crate::physics::{ParamError, PhysicsParams};
use crate::scenario::{Scenario, SurfaceKind};
use crate::sensors::{DistanceGrid, SurfaceGrid};

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
    dir: DVec2,
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
struct Statics {
    scenario: Scenario,
    /// Sensor reading per material id (same indexing as `here`); 256 entries so
    /// that indexing by a `u8` needs no bounds check.
    readings: Box<[f64; 256]>,
    /// Arena size in raster cells (the outside test of the fast look-up).
    limit: DVec2,
    /// 1 / cell size.
    inv_cell: f64,
    /// Indexed by material id (`scenario.materials`).
    here: Vec<SurfaceHere>,
}

/// A running simulation: `Clone` is cheap-ish (shares the scenario and raster).
#[derive(Clone, Debug)]
pub struct World {
    statics: Arc<Statics>,
    params: PhysicsParams,
    robots: Vec<Robot>,
    pucks: Vec<PuckState>,
    movables: Vec<MovableState>,
    prev_robots: Vec<DVec2>,
    prev_pucks: Vec<DVec2>,
    prev_movables: Vec<DVec2>,
    trajectories: Option<Vec<Vec<DVec2>>>,
    steps: u64,
}

/// Push needed to move a disc (centre `c`, radius `r`) out of `shape` seen
/// from offset `off`, or `None` when they do not overlap.
#[inline]
fn disc_out_of_shape(c: DVec2, r: f64, shape: &Shape, off: DVec2) -> Option<DVec2> {
    let p = c - off;
    if !shape.bbox.contains_with_margin(p, r) {
        return None;
    }
    let (q, d) = shape.closest_boundary_point(p);
    if shape.contains(p) {
        if d <= 0.0 {
            return None;
        }
        Some((q - p) * ((d + r) / d))
    } else if d < r && d > 0.0 {
        Some((p - q) * ((r - d) / d))
    } else {
        None
    }
}

/// Push that moves polygon `a` (at offset `oa`) out of polygon `b` (at `ob`):
/// the deepest vertex of either inside the other decides.
fn shape_out_of_shape(a: &Shape, oa: DVec2, b: &Shape, ob: DVec2) -> Option<DVec2> {
    let ba = Aabb {
        min: a.bbox.min + oa,
        max: a.bbox.max + oa,
    };
    let bb = Aabb {
        min: b.bbox.min + ob,
        max: b.bbox.max + ob,
    };
    if !ba.intersects(&bb) {
        return None;
    }
    let mut best: Option<DVec2> = None;
    let mut consider = |v: DVec2| {
        if best.is_none_or(|b| v.length_squared() > b.length_squared()) {
            best = Some(v);
        }
    };
    for v in a.rings.iter().flatten() {
        let p = *v + oa - ob;
        if b.contains(p) {
            let (q, _) = b.closest_boundary_point(p);
            consider(q - p);
        }
    }
    for v in b.rings.iter().flatten() {
        let p = *v + ob - oa;
        if a.contains(p) {
            let (q, _) = a.closest_boundary_point(p);
            consider(p - q);
        }
    }
    best
}

/// Push that keeps a box (at offset `off`) inside the arena.
#[inline]
fn box_into_arena(b: &Aabb, off: DVec2, w: f64, h: f64) -> DVec2 {
    let (min, max) = (b.min + off, b.max + off);
    let fix = |lo: f64, hi: f64, limit: f64| {
        if hi - lo > limit {
            0.0
        } else if lo < 0.0 {
            -lo
        } else if hi > limit {
            limit - hi
        } else {
            0.0
        }
    };
    DVec2::new(fix(min.x, max.x, w), fix(min.y, max.y, h))
}

impl World {
    /// A world at the scenario's start state. Fails if `params` is invalid.
    pub fn new(scenario: &Scenario, params: &PhysicsParams) -> Result<World, ParamError> {
        params.validate()?;
        let (lo, hi) = params.friction.range();
        let here = |kind: SurfaceKind, over: Option<f64>| {
            let friction = over.unwrap_or(params.friction.of(kind));
            SurfaceHere {
                kind,
                friction,
                reading: ((hi - friction) / (hi - lo)).clamp(0.0, 1.0),
            }
        };
        let table: Vec<SurfaceHere> = scenario
            .materials
            .iter()
            .map(|(k, f)| here(*k, *f))
            .collect();
        let robots: Vec<Robot> = scenario
            .robots
            .iter()
            .map(|r| {
                let mut rb = Robot {
                    pos: r.pos,
                    heading: 0.0,
                    speed: 0.0,
                    odometer: 0.0,
                    dir: DVec2::ZERO,
                };
                rb.set_heading(r.heading);
                rb
            })
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
            statics: Arc::new(Statics {
                readings: {
                    let mut r = Box::new([0.0; 256]);
                    for (slot, h) in r.iter_mut().zip(&table) {
                        *slot = h.reading;
                    }
                    r
                },
                limit: DVec2::new(scenario.width, scenario.height) / scenario.raster.cell,
                inv_cell: 1.0 / scenario.raster.cell,
                scenario: scenario.clone(),
                here: table,
            }),
            params: params.clone(),
            robots,
            pucks,
            movables,
            trajectories: None,
            steps: 0,
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

    /// Robots in scenario order.
    pub fn robots(&self) -> &[Robot] {
        &self.robots
    }
    /// Places robot `i` by hand (position, heading) and stops it; false if no such robot.
    pub fn set_pose(&mut self, i: usize, pos: DVec2, heading: f64) -> bool {
        match self.robots.get_mut(i) {
            Some(r) => {
                r.pos = pos;
                r.set_heading(heading);
                r.speed = 0.0;
                true
            }
            None => false,
        }
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

    /// Recorded trajectories (one per robot), if recording.
    pub fn trajectories(&self) -> Option<&[Vec<DVec2>]> {
        self.trajectories.as_deref()
    }

    /// Surface at `p` (via the raster); `None` outside the arena.
    #[inline]
    pub fn surface_at(&self, p: DVec2) -> Option<SurfaceHere> {
        let sc = &self.statics.scenario;
        if !(p.x >= 0.0 && p.y >= 0.0 && p.x < sc.width && p.y < sc.height) {
            return None;
        }
        sc.raster.id_at(p).map(|id| self.statics.here[id as usize])
    }

    /// Whether robot `i`'s centre is on a road.
    pub fn on_road(&self, i: usize) -> bool {
        self.robots
            .get(i)
            .and_then(|r| self.surface_at(r.pos))
            .is_some_and(|s| s.kind == SurfaceKind::Road)
    }
    /// World position of a robot-frame offset (x ahead, y right) of robot `i`.
    #[inline]
    fn frame(&self, i: usize) -> (DVec2, DVec2, DVec2) {
        let r = &self.robots[i];
        (r.pos, r.dir, r.right())
    }

    /// World positions of robot `i`'s surface sensors (for drawing).
    pub fn surface_sensor_positions(&self, i: usize, grid: &SurfaceGrid) -> Vec<DVec2> {
        let (p, ahead, right) = self.frame(i);
        grid.offsets
            .iter()
            .map(|o| p + ahead * o.x + right * o.y)
            .collect()
    }

    /// Reads robot `i`'s surface sensors into `out` (`out.len()` ≥ `grid.len()`;
    /// extra entries untouched). Allocation-free.
    pub fn read_surface(&self, i: usize, grid: &SurfaceGrid, out: &mut [f64]) {
        let (p, ahead, right) = self.frame(i);
        let st = &*self.statics;
        // Hoisted out of the loop: the compiler cannot prove `out` does not alias them.
        let (ras, readings) = (&*st.scenario.raster, &*st.readings);
        let inv = st.inv_cell;
        let lim = st.limit;
        let (base, ax, rx) = (p * inv, ahead * inv, right * inv);
        for (o, v) in grid.offsets.iter().zip(out.iter_mut()) {
            let c = base + ax * o.x + rx * o.y;
            // Non-short-circuit tests compile to one branch.
            *v = if (c.x >= 0.0) & (c.y >= 0.0) & (c.x < lim.x) & (c.y < lim.y) {
                // i32 conversions are cheaper than usize ones; the range test keeps them exact.
                readings[ras.get_in_arena(c.x as i32 as usize, c.y as i32 as usize) as usize]
            } else {
                0.0
            };
        }
    }

    /// Reads robot `i`'s distance sensors into `out`: `1 − d/range` for the
    /// nearest robot, obstacle, puck or wall along each ray, `d` measured from
    /// the robot's rim; 0 when nothing is in range. Allocation-free.
    pub fn read_distance(&self, i: usize, grid: &DistanceGrid, out: &mut [f64]) {
        let (p, ahead, right) = self.frame(i);
        let r0 = self.params.robot_radius;
        let max_t = grid.range + r0;
        let sc = &self.statics.scenario;
        for (o, v) in grid.dirs.iter().zip(out.iter_mut()) {
            let d = ahead * o.x + right * o.y;
            let mut t = max_t;
            // Walls: the arena boundary, seen from inside.
            if d.x > 1e-12 {
                t = t.min((sc.width - p.x) / d.x);
            } else if d.x < -1e-12 {
                t = t.min(-p.x / d.x);
            }
            if d.y > 1e-12 {
                t = t.min((sc.height - p.y) / d.y);
            } else if d.y < -1e-12 {
                t = t.min(-p.y / d.y);
            }
            for (j, other) in self.robots.iter().enumerate() {
                if j != i
                    && let Some(h) = ray_disc(p, d, other.pos, r0)
                {
                    t = t.min(h);
                }
            }
            for pk in &self.pucks {
                if let Some(h) = ray_disc(p, d, pk.pos, pk.radius) {
                    t = t.min(h);
                }
            }
            let end = p + d * t;
            let ray_box = Aabb {
                min: p.min(end),
                max: p.max(end),
            };
            for ob in &sc.fixed_obstacles {
                if ob.shape.bbox.intersects(&ray_box)
                    && let Some(h) = ob.shape.ray_hit(p, d, t)
                {
                    t = t.min(h);
                }
            }
            for (ob, m) in sc.movable_obstacles.iter().zip(&self.movables) {
                let b = Aabb {
                    min: ob.shape.bbox.min + m.offset,
                    max: ob.shape.bbox.max + m.offset,
                };
                if b.intersects(&ray_box)
                    && let Some(h) = ob.shape.ray_hit(p - m.offset, d, t)
                {
                    t = t.min(h);
                }
            }
            let dist = (t - r0).max(0.0);
            *v = if t < max_t {
                (1.0 - dist / grid.range).clamp(0.0, 1.0)
            } else {
                0.0
            };
        }
    }

    /// One time step: `controls[i] = [L, R]` in [−1, 1] for robot `i` (missing
    /// entries count as [0, 0], extra ones are ignored). Allocation-free
    /// unless trajectories are being recorded.
    pub fn step(&mut self, controls: &[[f64; 2]]) {
        let pp = &self.params;
        let (v_max, a_max, om_max, k) = (pp.v_max, pp.a_max, pp.omega_max, pp.k);
        for i in 0..self.robots.len() {
            let [l, r] = controls.get(i).copied().unwrap_or([0.0, 0.0]);
            let l = if l.is_nan() { 0.0 } else { l.clamp(-1.0, 1.0) };
            let r = if r.is_nan() { 0.0 } else { r.clamp(-1.0, 1.0) };
            let mu = self.surface_at(self.robots[i].pos).map_or(
                self.params.friction.of(self.statics.scenario.background),
                |s| s.friction,
            );
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

    /// Pushes overlapping bodies apart: soft contacts (shared by mass) first,
    /// then the hard constraints (walls, fixed obstacles) last in each pass.
    fn resolve_contacts(&mut self) {
        let World {
            statics,
            params,
            robots,
            pucks,
            movables,
            ..
        } = self;
        let sc = &statics.scenario;
        let (w, h) = (sc.width, sc.height);
        let rr = params.robot_radius;
        let rm = params.robot_mass;
        for _ in 0..params.collision_iterations {
            let mut any = false;
            // Robot–robot (equal masses).
            let n = robots.len();
            for i in 0..n {
                for j in (i + 1)..n {
                    let d = robots[j].pos - robots[i].pos;
                    let dist2 = d.length_squared();
                    if dist2 < 4.0 * rr * rr {
                        let dist = dist2.sqrt();
                        let nrm = if dist > 1e-12 { d / dist } else { DVec2::X };
                        let push = nrm * ((2.0 * rr - dist) * 0.5);
                        robots[i].pos -= push;
                        robots[j].pos += push;
                        any = true;
                    }
                }
            }
            // Robot–puck and robot–movable obstacle: momentum shared by mass.
            for rb in robots.iter_mut() {
                for pk in pucks.iter_mut() {
                    let d = pk.pos - rb.pos;
                    let min = rr + pk.radius;
                    let dist2 = d.length_squared();
                    if dist2 < min * min {
                        let dist = dist2.sqrt();
                        let nrm = if dist > 1e-12 { d / dist } else { DVec2::X };
                        let pen = min - dist;
                        let total = rm + pk.mass;
                        rb.pos -= nrm * (pen * pk.mass / total);
                        pk.pos += nrm * (pen * rm / total);
                        any = true;
                    }
                }
                for (ob, m) in sc.movable_obstacles.iter().zip(movables.iter_mut()) {
                    if let Some(push) = disc_out_of_shape(rb.pos, rr, &ob.shape, m.offset) {
                        let total = rm + m.mass;
                        rb.pos += push * (m.mass / total);
                        m.offset -= push * (rm / total);
                        any = true;
                    }
                }
            }
            // Puck–puck, puck–movable, movable–movable.
            let np = pucks.len();
            for i in 0..np {
                for j in (i + 1)..np {
                    let (a, b) = (&pucks[i], &pucks[j]);
                    let d = b.pos - a.pos;
                    let min = a.radius + b.radius;
                    let dist2 = d.length_squared();
                    if dist2 < min * min {
                        let dist = dist2.sqrt();
                        let nrm = if dist > 1e-12 { d / dist } else { DVec2::X };
                        let pen = min - dist;
                        let total = a.mass + b.mass;
                        let (ma, mb) = (a.mass, b.mass);
                        pucks[i].pos -= nrm * (pen * mb / total);
                        pucks[j].pos += nrm * (pen * ma / total);
                        any = true;
                    }
                }
                for (ob, m) in sc.movable_obstacles.iter().zip(movables.iter_mut()) {
                    let pk = &mut pucks[i];
                    if let Some(push) = disc_out_of_shape(pk.pos, pk.radius, &ob.shape, m.offset) {
                        let total = pk.mass + m.mass;
                        pk.pos += push * (m.mass / total);
                        m.offset -= push * (pk.mass / total);
                        any = true;
                    }
                }
            }
            let nm = movables.len();
            for i in 0..nm {
                for j in (i + 1)..nm {
                    let (a, b) = (
                        &sc.movable_obstacles[i].shape,
                        &sc.movable_obstacles[j].shape,
                    );
                    if let Some(push) =
                        shape_out_of_shape(a, movables[i].offset, b, movables[j].offset)
                    {
                        let (ma, mb) = (movables[i].mass, movables[j].mass);
                        let total = ma + mb;
                        movables[i].offset += push * (mb / total);
                        movables[j].offset -= push * (ma / total);
                        any = true;
                    }
                }
            }
            // Hard constraints: fixed obstacles, then walls (walls win).
            for (ob, m) in sc.movable_obstacles.iter().zip(movables.iter_mut()) {
                for fx in &sc.fixed_obstacles {
                    if let Some(push) =
                        shape_out_of_shape(&ob.shape, m.offset, &fx.shape, DVec2::ZERO)
                    {
                        m.offset += push;
                        any = true;
                    }
                }
                let push = box_into_arena(&ob.shape.bbox, m.offset, w, h);
                if push != DVec2::ZERO {
                    m.offset += push;
                    any = true;
                }
            }
            for pk in pucks.iter_mut() {
                for fx in &sc.fixed_obstacles {
                    if let Some(push) = disc_out_of_shape(pk.pos, pk.radius, &fx.shape, DVec2::ZERO)
                    {
                        pk.pos += push;
                        any = true;
                    }
                }
                let c = clamp_disc(pk.pos, pk.radius, w, h);
                if c != pk.pos {
                    pk.pos = c;
                    any = true;
                }
            }
            for rb in robots.iter_mut() {
                for fx in &sc.fixed_obstacles {
                    if let Some(push) = disc_out_of_shape(rb.pos, rr, &fx.shape, DVec2::ZERO) {
                        rb.pos += push;
                        any = true;
                    }
                }
                let c = clamp_disc(rb.pos, rr, w, h);
                if c != rb.pos {
                    rb.pos = c;
                    any = true;
                }
            }
            if !any {
                break;
            }
        }
    }
}

/// Keeps a disc inside the arena walls.
#[inline]
fn clamp_disc(p: DVec2, r: f64, w: f64, h: f64) -> DVec2 {
    let cx = if w > 2.0 * r {
        p.x.clamp(r, w - r)
    } else {
        w / 2.0
    };
    let cy = if h > 2.0 * r {
        p.y.clamp(r, h - r)
    } else {
        h / 2.0
    };
    DVec2::new(cx, cy)
}

/// Wraps an angle into (−π, π].
#[inline]
fn wrap_angle(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    if a > -PI && a <= PI {
        return a;
    }
    let r = (a + PI).rem_euclid(TAU) - PI;
    if r <= -PI { r + TAU } else { r }
}
