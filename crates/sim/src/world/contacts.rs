//! Contacts: pushing overlapping bodies apart (DESIGN §5).

use glam::DVec2;

use crate::geometry::{Aabb, Shape};
use crate::scenario::Obstacle;
use crate::world::{MovableState, PuckState, Robot, TeamContact, World};

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

impl World {
    /// Pushes overlapping bodies apart: soft contacts (shared by mass) first,
    /// then the hard constraints (walls, fixed obstacles) last in each pass.
    pub(super) fn resolve_contacts(&mut self) {
        let World {
            statics,
            params,
            robots,
            pucks,
            movables,
            team_contacts,
            ..
        } = self;
        team_contacts.clear();
        let sc = &statics.scenario;
        let arena = (sc.width(), sc.height());
        let (rr, rm) = (params.robot_radius, params.robot_mass);
        let (loose, fixed) = (&sc.movable_obstacles[..], &sc.fixed_obstacles[..]);
        for _ in 0..params.collision_iterations {
            // `|=` on bool does not short-circuit: every pass runs in order.
            let mut any = robots_apart(robots, rr, &statics.teams, team_contacts);
            any |= robots_push_loose_bodies(robots, pucks, movables, loose, rr, rm);
            any |= pucks_apart(pucks, movables, loose);
            any |= movables_apart(movables, loose);
            // Hard constraints: fixed obstacles, then walls (walls win).
            any |= movables_against_fixed(movables, loose, fixed, arena);
            any |= discs_against_fixed(
                pucks.iter_mut().map(|p| (&mut p.pos, p.radius)),
                fixed,
                arena,
            );
            any |= discs_against_fixed(robots.iter_mut().map(|r| (&mut r.pos, rr)), fixed, arena);
            if !any {
                break;
            }
        }
    }
}

/// Robot–robot contacts (equal masses); whether any robot moved. A contact
/// between robots of different teams (`teams`: 0 = none) is added to
/// `contacts` once per step.
fn robots_apart(
    robots: &mut [Robot],
    rr: f64,
    teams: &[u16],
    contacts: &mut Vec<TeamContact>,
) -> bool {
    let mut any = false;
    let n = robots.len();
    for i in 0..n {
        for j in (i + 1)..n {
            let d = robots[j].pos - robots[i].pos;
            let dist2 = d.length_squared();
            if dist2 < 4.0 * rr * rr {
                // Scripted robots (traffic) follow the learners and have no team.
                let team = |k: usize| teams.get(k).copied().unwrap_or(0);
                let (ti, tj) = (team(i), team(j));
                if ti != tj && ti != 0 && tj != 0 {
                    let c = TeamContact { a: i, b: j };
                    if !contacts.contains(&c) {
                        contacts.push(c);
                    }
                }
                let dist = dist2.sqrt();
                let nrm = if dist > 1e-12 { d / dist } else { DVec2::X };
                let push = nrm * ((2.0 * rr - dist) * 0.5);
                robots[i].pos -= push;
                robots[j].pos += push;
                any = true;
            }
        }
    }
    any
}

/// Robot–puck and robot–movable obstacle contacts: momentum shared by mass.
fn robots_push_loose_bodies(
    robots: &mut [Robot],
    pucks: &mut [PuckState],
    movables: &mut [MovableState],
    loose: &[Obstacle],
    rr: f64,
    rm: f64,
) -> bool {
    let mut any = false;
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
        for (ob, m) in loose.iter().zip(movables.iter_mut()) {
            if let Some(push) = disc_out_of_shape(rb.pos, rr, &ob.shape, m.offset) {
                let total = rm + m.mass;
                rb.pos += push * (m.mass / total);
                m.offset -= push * (rm / total);
                any = true;
            }
        }
    }
    any
}

/// Puck–puck and puck–movable obstacle contacts, shared by mass.
fn pucks_apart(pucks: &mut [PuckState], movables: &mut [MovableState], loose: &[Obstacle]) -> bool {
    let mut any = false;
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
        for (ob, m) in loose.iter().zip(movables.iter_mut()) {
            let pk = &mut pucks[i];
            if let Some(push) = disc_out_of_shape(pk.pos, pk.radius, &ob.shape, m.offset) {
                let total = pk.mass + m.mass;
                pk.pos += push * (m.mass / total);
                m.offset -= push * (pk.mass / total);
                any = true;
            }
        }
    }
    any
}

/// Movable–movable obstacle contacts, shared by mass.
fn movables_apart(movables: &mut [MovableState], loose: &[Obstacle]) -> bool {
    let mut any = false;
    let nm = movables.len();
    for i in 0..nm {
        for j in (i + 1)..nm {
            let (a, b) = (&loose[i].shape, &loose[j].shape);
            if let Some(push) = shape_out_of_shape(a, movables[i].offset, b, movables[j].offset) {
                let (ma, mb) = (movables[i].mass, movables[j].mass);
                let total = ma + mb;
                movables[i].offset += push * (mb / total);
                movables[j].offset -= push * (ma / total);
                any = true;
            }
        }
    }
    any
}

/// Pushes movable obstacles out of fixed ones, then into the `(w, h)` arena.
fn movables_against_fixed(
    movables: &mut [MovableState],
    loose: &[Obstacle],
    fixed: &[Obstacle],
    (w, h): (f64, f64),
) -> bool {
    let mut any = false;
    for (ob, m) in loose.iter().zip(movables.iter_mut()) {
        for fx in fixed {
            if let Some(push) = shape_out_of_shape(&ob.shape, m.offset, &fx.shape, DVec2::ZERO) {
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
    any
}

/// Pushes discs `(centre, radius)` out of fixed obstacles, then into the
/// `(w, h)` arena.
fn discs_against_fixed<'a>(
    discs: impl Iterator<Item = (&'a mut DVec2, f64)>,
    fixed: &[Obstacle],
    (w, h): (f64, f64),
) -> bool {
    let mut any = false;
    for (pos, r) in discs {
        for fx in fixed {
            if let Some(push) = disc_out_of_shape(*pos, r, &fx.shape, DVec2::ZERO) {
                *pos += push;
                any = true;
            }
        }
        let c = clamp_disc(*pos, r, w, h);
        if c != *pos {
            *pos = c;
            any = true;
        }
    }
    any
}
