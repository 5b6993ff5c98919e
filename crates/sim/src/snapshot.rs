//! Writing a world state back to a loadable ViVAE scenario (ViVAE's snapshot).

use std::fmt::Write;

use crate::geometry::{FillRule, fmt_num};
use crate::scenario::{SurfaceKind, heading_degrees};
use crate::style::{robot_color, surface_color, xml_escape};
use crate::world::World;

fn fill_rule(r: FillRule) -> &'static str {
    match r {
        FillRule::NonZero => "nonzero",
        FillRule::EvenOdd => "evenodd",
    }
}

impl World {
    /// The current state as a scenario SVG in the same label format: loading
    /// it gives the same objects at the same poses (robots at their current
    /// position and heading, movable bodies where they were pushed).
    pub fn to_svg(&self) -> String {
        let mut s = String::new();
        self.write_svg_header(&mut s);
        self.write_surfaces_layer(&mut s);
        self.write_objects_layer(&mut s);
        self.write_robots_layer(&mut s);
        s.push_str("  </g>\n</svg>\n");
        s
    }

    /// The XML declaration, the `<svg>` element and the background rect.
    fn write_svg_header(&self, s: &mut String) {
        let sc = self.scenario();
        let _ = writeln!(
            s,
            r##"<?xml version="1.0" encoding="UTF-8" standalone="no"?>
<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="{w}" height="{h}" viewBox="0 0 {w} {h}" id="snapshot"{bg} data-step="{step}">"##,
            w = fmt_num(sc.width()),
            h = fmt_num(sc.height()),
            bg = if sc.background() == SurfaceKind::Grass {
                String::new()
            } else {
                format!(r##" data-background="{}""##, sc.background().name())
            },
            step = self.steps()
        );
        let _ = writeln!(
            s,
            r##"  <rect id="background" x="0" y="0" width="{}" height="{}" style="fill:{}"/>"##,
            fmt_num(sc.width()),
            fmt_num(sc.height()),
            surface_color(sc.background())
        );
    }

    /// Opens the surfaces layer and writes every surface.
    fn write_surfaces_layer(&self, s: &mut String) {
        let sc = self.scenario();
        s.push_str("  <g inkscape:groupmode=\"layer\" inkscape:label=\"Surfaces\" id=\"layer-surfaces\">\n");
        for surf in sc.surfaces() {
            let fr = surf
                .friction
                .map(|f| format!(r##" data-friction="{f}""##))
                .unwrap_or_default();
            let _ = writeln!(
                s,
                r##"    <path id="{}" inkscape:label="{}"{fr} style="fill:{};fill-rule:{};stroke:none" d="{}"/>"##,
                xml_escape(&surf.id),
                surf.kind.label(),
                surface_color(surf.kind),
                fill_rule(surf.shape.fill_rule),
                surf.shape.to_path_data()
            );
        }
    }

    /// Closes the previous layer, opens the objects layer and writes the
    /// obstacles (movable ones where they were pushed), pucks and marks.
    fn write_objects_layer(&self, s: &mut String) {
        let sc = self.scenario();
        s.push_str("  </g>\n  <g inkscape:groupmode=\"layer\" inkscape:label=\"Objects\" id=\"layer-objects\">\n");
        for ob in &sc.fixed_obstacles {
            let _ = writeln!(
                s,
                r##"    <path id="{}" inkscape:label="FixedObstacle" style="fill:#c0392b;fill-rule:{};stroke:none" d="{}"/>"##,
                xml_escape(&ob.id),
                fill_rule(ob.shape.fill_rule),
                ob.shape.to_path_data()
            );
        }
        for (ob, m) in sc.movable_obstacles.iter().zip(self.movables()) {
            let _ = writeln!(
                s,
                r##"    <path id="{}" inkscape:label="Obstacle" style="fill:#999999;fill-rule:{};stroke:none" d="{}"/>"##,
                xml_escape(&ob.id),
                fill_rule(ob.shape.fill_rule),
                ob.shape.translated(m.offset).to_path_data()
            );
        }
        for (pk, st) in sc.pucks.iter().zip(self.pucks()) {
            let _ = writeln!(
                s,
                r##"    <circle id="{}" inkscape:label="{}" cx="{}" cy="{}" r="{}" style="fill:#f0f0f0;stroke:none"/>"##,
                xml_escape(&pk.id),
                pk.kind.label(),
                fmt_num(st.pos.x),
                fmt_num(st.pos.y),
                fmt_num(st.radius)
            );
        }
        for mk in &sc.marks {
            let _ = writeln!(
                s,
                r##"    <rect id="{}" inkscape:label="PositionMark" x="{}" y="{}" width="{}" height="{}" style="fill:none;stroke:#ff00ff;stroke-width:1"/>"##,
                xml_escape(&mk.id),
                fmt_num(mk.pos.x - mk.size.x / 2.0),
                fmt_num(mk.pos.y - mk.size.y / 2.0),
                fmt_num(mk.size.x),
                fmt_num(mk.size.y)
            );
        }
    }

    /// Closes the previous layer, opens the robots layer and writes every
    /// robot at its current pose.
    fn write_robots_layer(&self, s: &mut String) {
        let sc = self.scenario();
        s.push_str("  </g>\n  <g inkscape:groupmode=\"layer\" inkscape:label=\"Robots\" id=\"layer-robots\">\n");
        let r = self.params().robot_radius;
        for (i, (start, rb)) in sc.robots.iter().zip(self.robots()).enumerate() {
            let label = if start.label.is_empty() {
                "Robot"
            } else {
                &start.label
            };
            let team = if start.team.is_empty() {
                String::new()
            } else {
                format!(r#" data-team="{}""#, xml_escape(&start.team))
            };
            let _ = writeln!(
                s,
                r##"    <rect id="{}" inkscape:label="{}"{team} x="{}" y="{}" width="{}" height="{}" transform="rotate({} {} {})" style="fill:{}"/>"##,
                xml_escape(&start.id),
                xml_escape(label),
                fmt_num(rb.pos.x - r),
                fmt_num(rb.pos.y - r),
                fmt_num(2.0 * r),
                fmt_num(2.0 * r),
                heading_degrees(rb.heading),
                fmt_num(rb.pos.x),
                fmt_num(rb.pos.y),
                robot_color(i)
            );
        }
    }
}
