//! Plane geometry used by the loader, the physics and the sensors: flattened
//! shapes (polygons with holes), point-in-shape tests, closest points and rays.

use glam::DVec2;

/// How the inside of a shape with several rings is decided (SVG `fill-rule`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum FillRule {
    /// Inside where the winding number is not zero.
    NonZero,
    /// Inside where the winding number is odd.
    EvenOdd,
}

/// Axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: DVec2,
    /// Largest corner.
    pub max: DVec2,
}

impl Aabb {
    /// The empty box (grows with `include`).
    pub const EMPTY: Aabb = Aabb {
        min: DVec2::splat(f64::INFINITY),
        max: DVec2::splat(f64::NEG_INFINITY),
    };

    /// Grows the box to contain `p`.
    pub fn include(&mut self, p: DVec2) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    /// Centre of the box.
    pub fn center(&self) -> DVec2 {
        (self.min + self.max) * 0.5
    }

    /// Size of the box.
    pub fn size(&self) -> DVec2 {
        self.max - self.min
    }

    /// Whether the box, grown by `margin`, contains `p`.
    pub fn contains_with_margin(&self, p: DVec2, margin: f64) -> bool {
        p.x >= self.min.x - margin
            && p.x <= self.max.x + margin
            && p.y >= self.min.y - margin
            && p.y <= self.max.y + margin
    }

    /// Whether two boxes intersect.
    pub fn intersects(&self, o: &Aabb) -> bool {
        self.min.x <= o.max.x
            && o.min.x <= self.max.x
            && self.min.y <= o.max.y
            && o.min.y <= self.max.y
    }

    /// Whether the box is empty (no point was included).
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y)
    }
}

/// A flattened planar shape: closed polygonal rings and a fill rule.
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    /// Closed rings (the last point connects back to the first).
    pub rings: Vec<Vec<DVec2>>,
    /// Inside test for overlapping rings.
    pub fill_rule: FillRule,
    /// Bounding box of all rings.
    pub bbox: Aabb,
}

impl Shape {
    /// Builds a shape from rings, dropping rings with fewer than three points.
    pub fn new(rings: Vec<Vec<DVec2>>, fill_rule: FillRule) -> Shape {
        let rings: Vec<Vec<DVec2>> = rings.into_iter().filter(|r| r.len() >= 3).collect();
        let mut bbox = Aabb::EMPTY;
        for p in rings.iter().flatten() {
            bbox.include(*p);
        }
        Shape {
            rings,
            fill_rule,
            bbox,
        }
    }

    /// An axis-aligned rectangle.
    pub fn rect(min: DVec2, max: DVec2) -> Shape {
        Shape::new(
            vec![vec![
                min,
                DVec2::new(max.x, min.y),
                max,
                DVec2::new(min.x, max.y),
            ]],
            FillRule::NonZero,
        )
    }

    /// Whether the shape has no area-bearing ring.
    pub fn is_empty(&self) -> bool {
        self.rings.is_empty()
    }

    /// Winding number of the rings around `p`.
    pub fn winding(&self, p: DVec2) -> i32 {
        let mut w = 0;
        for ring in &self.rings {
            let n = ring.len();
            let mut a = ring[n - 1];
            for &b in ring {
                if a.y <= p.y {
                    if b.y > p.y && cross(b - a, p - a) > 0.0 {
                        w += 1;
                    }
                } else if b.y <= p.y && cross(b - a, p - a) < 0.0 {
                    w -= 1;
                }
                a = b;
            }
        }
        w
    }

    /// Whether `p` is inside the shape (exact geometry, the raster's oracle).
    pub fn contains(&self, p: DVec2) -> bool {
        if !self.bbox.contains_with_margin(p, 0.0) {
            return false;
        }
        let w = self.winding(p);
        match self.fill_rule {
            FillRule::NonZero => w != 0,
            FillRule::EvenOdd => w % 2 != 0,
        }
    }

    /// Closest point on the boundary to `p` and its distance.
    pub fn closest_boundary_point(&self, p: DVec2) -> (DVec2, f64) {
        let mut best = (p, f64::INFINITY);
        for ring in &self.rings {
            let n = ring.len();
            let mut a = ring[n - 1];
            for &b in ring {
                let q = closest_on_segment(a, b, p);
                let d = q.distance_squared(p);
                if d < best.1 {
                    best = (q, d);
                }
                a = b;
            }
        }
        (best.0, best.1.sqrt())
    }

    /// Distance along the ray `origin + t·dir` (|dir| = 1) to the first boundary
    /// crossing within `max_t`, if any.
    pub fn ray_hit(&self, origin: DVec2, dir: DVec2, max_t: f64) -> Option<f64> {
        let mut best: Option<f64> = None;
        for ring in &self.rings {
            let n = ring.len();
            let mut a = ring[n - 1];
            for &b in ring {
                if let Some(t) = ray_segment(origin, dir, a, b)
                    && t <= max_t
                    && best.is_none_or(|bt| t < bt)
                {
                    best = Some(t);
                }
                a = b;
            }
        }
        best
    }

    /// Area enclosed by the rings (absolute value of the signed area, summed).
    pub fn area(&self) -> f64 {
        self.rings
            .iter()
            .map(|ring| {
                let n = ring.len();
                let mut s = 0.0;
                let mut a = ring[n - 1];
                for &b in ring {
                    s += cross(a, b);
                    a = b;
                }
                (s * 0.5).abs()
            })
            .sum()
    }

    /// The shape moved by `d`.
    pub fn translated(&self, d: DVec2) -> Shape {
        Shape {
            rings: self
                .rings
                .iter()
                .map(|r| r.iter().map(|p| *p + d).collect())
                .collect(),
            fill_rule: self.fill_rule,
            bbox: Aabb {
                min: self.bbox.min + d,
                max: self.bbox.max + d,
            },
        }
    }

    /// SVG path data (`d`) of the rings, absolute coordinates.
    pub fn to_path_data(&self) -> String {
        use std::fmt::Write;
        let mut s = String::new();
        for ring in &self.rings {
            for (i, p) in ring.iter().enumerate() {
                let _ = write!(
                    s,
                    "{}{} {} ",
                    if i == 0 { "M" } else { "L" },
                    fmt_num(p.x),
                    fmt_num(p.y)
                );
            }
            s.push_str("Z ");
        }
        s.pop();
        s
    }
}

/// Formats a coordinate compactly for SVG output (round-trips through f32).
pub(crate) fn fmt_num(x: f64) -> String {
    let r = (x * 1e4).round() / 1e4;
    if r == 0.0 {
        "0".to_string()
    } else {
        format!("{r}")
    }
}

/// 2D cross product (z of the 3D cross product).
#[inline]
pub fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Closest point to `p` on the segment `a`–`b`.
#[inline]
pub fn closest_on_segment(a: DVec2, b: DVec2, p: DVec2) -> DVec2 {
    let ab = b - a;
    let len2 = ab.length_squared();
    if len2 <= 0.0 {
        return a;
    }
    let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
    a + ab * t
}

/// Parameter `t ≥ 0` at which the ray `o + t·d` crosses the segment `a`–`b`.
#[inline]
pub fn ray_segment(o: DVec2, d: DVec2, a: DVec2, b: DVec2) -> Option<f64> {
    let e = b - a;
    let den = cross(d, e);
    if den.abs() < 1e-12 {
        return None;
    }
    let ao = a - o;
    let t = cross(ao, e) / den;
    let u = cross(ao, d) / den;
    if t >= 0.0 && (0.0..=1.0).contains(&u) {
        Some(t)
    } else {
        None
    }
}

/// Parameter `t ≥ 0` at which the ray `o + t·d` (|d| = 1) enters the disc.
#[inline]
pub fn ray_disc(o: DVec2, d: DVec2, c: DVec2, r: f64) -> Option<f64> {
    let oc = o - c;
    let b = oc.dot(d);
    let cc = oc.length_squared() - r * r;
    if cc <= 0.0 {
        return Some(0.0);
    }
    let disc = b * b - cc;
    if disc < 0.0 || b > 0.0 {
        return None;
    }
    Some(-b - disc.sqrt())
}

/// Flattens a tiny-skia path (as usvg gives it) under a transform into rings.
pub(crate) fn flatten_path(
    path: &tiny_skia::Path,
    ts: tiny_skia::Transform,
    tolerance: f64,
) -> Vec<Vec<DVec2>> {
    use kurbo::{BezPath, PathEl, Point};
    use tiny_skia::PathSegment;
    let map = |p: tiny_skia::Point| {
        let mut q = p;
        ts.map_point(&mut q);
        Point::new(q.x as f64, q.y as f64)
    };
    let mut bez = BezPath::new();
    for seg in path.segments() {
        match seg {
            PathSegment::MoveTo(p) => bez.push(PathEl::MoveTo(map(p))),
            PathSegment::LineTo(p) => bez.push(PathEl::LineTo(map(p))),
            PathSegment::QuadTo(a, b) => bez.push(PathEl::QuadTo(map(a), map(b))),
            PathSegment::CubicTo(a, b, c) => bez.push(PathEl::CurveTo(map(a), map(b), map(c))),
            PathSegment::Close => bez.push(PathEl::ClosePath),
        }
    }
    let mut rings: Vec<Vec<DVec2>> = Vec::new();
    let mut cur: Vec<DVec2> = Vec::new();
    kurbo::flatten(bez, tolerance, |el| match el {
        PathEl::MoveTo(p) => {
            if !cur.is_empty() {
                rings.push(std::mem::take(&mut cur));
            }
            cur.push(DVec2::new(p.x, p.y));
        }
        PathEl::LineTo(p) => {
            let q = DVec2::new(p.x, p.y);
            if cur.last() != Some(&q) {
                cur.push(q);
            }
        }
        PathEl::ClosePath if !cur.is_empty() => rings.push(std::mem::take(&mut cur)),
        _ => {}
    });
    if !cur.is_empty() {
        rings.push(cur);
    }
    for r in &mut rings {
        if r.len() > 1 && r.first() == r.last() {
            r.pop();
        }
    }
    rings
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_contains_inside_not_outside() {
        let s = Shape::rect(DVec2::ZERO, DVec2::splat(10.0));
        assert!(s.contains(DVec2::new(5.0, 5.0)));
        assert!(!s.contains(DVec2::new(15.0, 5.0)));
        assert_eq!(s.area(), 100.0);
    }

    #[test]
    fn evenodd_hole_is_outside() {
        let outer = vec![
            DVec2::ZERO,
            DVec2::new(10.0, 0.0),
            DVec2::new(10.0, 10.0),
            DVec2::new(0.0, 10.0),
        ];
        let inner = vec![
            DVec2::splat(3.0),
            DVec2::new(7.0, 3.0),
            DVec2::splat(7.0),
            DVec2::new(3.0, 7.0),
        ];
        let s = Shape::new(vec![outer, inner], FillRule::EvenOdd);
        assert!(!s.contains(DVec2::splat(5.0)));
        assert!(s.contains(DVec2::new(1.0, 5.0)));
    }

    #[test]
    fn ray_hits_disc_front() {
        let t = ray_disc(DVec2::ZERO, DVec2::X, DVec2::new(10.0, 0.0), 2.0).unwrap();
        assert!((t - 8.0).abs() < 1e-12);
        assert!(ray_disc(DVec2::ZERO, -DVec2::X, DVec2::new(10.0, 0.0), 2.0).is_none());
    }
}
