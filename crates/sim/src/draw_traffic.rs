//! Scripted robots (traffic) in pictures: white discs ringed in black, and
//! their paths as dashed white lines, so they never pass for learners.

use std::fmt::Write;

use crate::geometry::fmt_num;
use crate::world::World;

/// Fill of a scripted robot.
pub(crate) const TRAFFIC_FILL: &str = "#ffffff";

/// The scripted robots' recorded paths (when `trajectories`) and their discs.
pub(crate) fn draw_traffic(s: &mut String, world: &World, trajectories: bool) {
    if trajectories && let Some(trajs) = world.traffic_trajectories() {
        for t in trajs.iter().filter(|t| t.len() > 1) {
            let mut pts = String::new();
            for p in t {
                let _ = write!(pts, "{},{} ", fmt_num(p.x), fmt_num(p.y));
            }
            let _ = writeln!(
                s,
                r##"<polyline points="{}" fill="none" stroke="{TRAFFIC_FILL}" stroke-width="1.2" stroke-dasharray="4 3" stroke-opacity="0.8"/>"##,
                pts.trim_end()
            );
        }
    }
    let r = world.params().robot_radius;
    for rb in world.traffic() {
        let tip = rb.pos + rb.ahead() * r;
        let _ = writeln!(
            s,
            r##"<circle cx="{}" cy="{}" r="{}" fill="{TRAFFIC_FILL}" stroke="#000000" stroke-width="2"/><line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#000000" stroke-width="1.5"/>"##,
            fmt_num(rb.pos.x),
            fmt_num(rb.pos.y),
            fmt_num(r),
            fmt_num(rb.pos.x),
            fmt_num(rb.pos.y),
            fmt_num(tip.x),
            fmt_num(tip.y)
        );
    }
}
