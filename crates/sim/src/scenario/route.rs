//! Routes: directed centre lines drawn as paths labelled `Route`. Scripted
//! robots follow them; a learner's route gives the direction its progress is
//! measured along.

use glam::DVec2;

/// Longest segment of a resampled route, px: short segments let a follower
/// search only the few segments around where it was last step.
const MAX_SEGMENT: f64 = 8.0;

/// Segments searched on either side of the last one when tracking a point.
const WINDOW: usize = 8;

/// A directed polyline (the drawing direction is the direction of travel).
#[derive(Clone, Debug, PartialEq)]
pub struct Route {
    /// Element id.
    pub id: String,
    /// Points, at most [`MAX_SEGMENT`] px apart; a closed route's last point
    /// connects back to the first.
    points: Vec<DVec2>,
    /// Arc length at each point (0 at the first).
    cum: Vec<f64>,
    /// Whether the route is a loop.
    pub closed: bool,
    /// Total length (including the closing segment of a loop).
    length: f64,
}

/// Where a point is along a route.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoutePlace {
    /// Index of the nearest segment (from point `segment` to the next).
    pub segment: usize,
    /// Arc length of the nearest point on the route.
    pub s: f64,
    /// Distance to the route.
    pub distance: f64,
}

impl Route {
    /// A route through `points`, or `None` when it has no length.
    pub fn new(id: impl Into<String>, points: &[DVec2], closed: bool) -> Option<Route> {
        let mut pts: Vec<DVec2> = Vec::with_capacity(points.len());
        let add = |q: DVec2, pts: &mut Vec<DVec2>| {
            if let Some(&last) = pts.last() {
                let d = q.distance(last);
                if d <= 1e-9 {
                    return;
                }
                let pieces = (d / MAX_SEGMENT).ceil() as usize;
                for k in 1..pieces {
                    pts.push(last + (q - last) * (k as f64 / pieces as f64));
                }
            }
            pts.push(q);
        };
        for &p in points {
            if !(p.x.is_finite() && p.y.is_finite()) {
                return None;
            }
            add(p, &mut pts);
        }
        if closed && pts.len() > 1 {
            // Split the closing segment too, then drop the repeated first point.
            let first = pts[0];
            add(first, &mut pts);
            if pts.last() == Some(&first) && pts.len() > 1 {
                pts.pop();
            }
        }
        if pts.len() < 2 {
            return None;
        }
        let mut cum = Vec::with_capacity(pts.len());
        let mut s = 0.0;
        cum.push(0.0);
        for w in pts.windows(2) {
            s += w[0].distance(w[1]);
            cum.push(s);
        }
        if closed {
            s += pts[pts.len() - 1].distance(pts[0]);
        }
        (s > 0.0).then(|| Route {
            id: id.into(),
            points: pts,
            cum,
            closed,
            length: s,
        })
    }

    /// Total length, px.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The resampled points.
    pub fn points(&self) -> &[DVec2] {
        &self.points
    }

    /// Number of segments.
    fn segments(&self) -> usize {
        if self.closed {
            self.points.len()
        } else {
            self.points.len() - 1
        }
    }

    /// Segment `i`'s ends and the arc length at its start.
    #[inline]
    fn segment(&self, i: usize) -> (DVec2, DVec2, f64) {
        let j = if i + 1 == self.points.len() { 0 } else { i + 1 };
        (self.points[i], self.points[j], self.cum[i])
    }

    /// Arc length `s` wrapped into the route (a loop) or clamped to it.
    fn wrap(&self, s: f64) -> f64 {
        if self.closed {
            s.rem_euclid(self.length)
        } else {
            s.clamp(0.0, self.length)
        }
    }

    /// The point at arc length `s` (wrapped on a loop, clamped otherwise) and
    /// the unit direction of travel there.
    pub fn point_at(&self, s: f64) -> (DVec2, DVec2) {
        let s = self.wrap(s);
        let n = self.segments();
        // The last segment whose start is at or before s.
        let i = match self.cum.binary_search_by(|c| c.total_cmp(&s)) {
            Ok(i) => i,
            Err(i) => i.saturating_sub(1),
        }
        .min(n - 1);
        let (a, b, s0) = self.segment(i);
        let len = a.distance(b);
        let t = if len > 0.0 {
            ((s - s0) / len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let dir = if len > 0.0 { (b - a) / len } else { DVec2::X };
        (a + (b - a) * t, dir)
    }

    /// The nearest place on the route to `p`: over every segment, or (with
    /// `near`, the segment found last time) over the few around it.
    pub fn locate(&self, p: DVec2, near: Option<usize>) -> RoutePlace {
        let n = self.segments();
        let mut best = RoutePlace {
            segment: 0,
            s: 0.0,
            distance: f64::INFINITY,
        };
        let mut consider = |i: usize| {
            let (a, b, s0) = self.segment(i);
            let ab = b - a;
            let len2 = ab.length_squared();
            let t = if len2 > 0.0 {
                ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let q = a + ab * t;
            let d = q.distance(p);
            if d < best.distance {
                best = RoutePlace {
                    segment: i,
                    s: s0 + t * len2.sqrt(),
                    distance: d,
                };
            }
        };
        match near {
            Some(c) if n > 2 * WINDOW + 1 => {
                for k in 0..=2 * WINDOW {
                    let i = c as isize + k as isize - WINDOW as isize;
                    if self.closed {
                        consider(i.rem_euclid(n as isize) as usize);
                    } else if (0..n as isize).contains(&i) {
                        consider(i as usize);
                    }
                }
            }
            _ => (0..n).for_each(&mut consider),
        }
        best
    }

    /// Signed distance travelled along the route from arc length `from` to
    /// `to`: on a loop the shorter way round (crossing the start is no jump).
    pub fn advance(&self, from: f64, to: f64) -> f64 {
        let d = to - from;
        if self.closed {
            let half = self.length * 0.5;
            (d + half).rem_euclid(self.length) - half
        } else {
            d
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Route {
        let pts = [
            DVec2::new(0.0, 0.0),
            DVec2::new(100.0, 0.0),
            DVec2::new(100.0, 100.0),
            DVec2::new(0.0, 100.0),
        ];
        Route::new("sq", &pts, true).unwrap()
    }

    #[test]
    fn a_loop_measures_its_closing_segment() {
        let r = square();
        assert!((r.length() - 400.0).abs() < 1e-9);
        let (p, dir) = r.point_at(350.0);
        assert!(p.distance(DVec2::new(0.0, 50.0)) < 1e-9, "{p}");
        assert!(dir.distance(DVec2::new(0.0, -1.0)) < 1e-9);
        let (p, _) = r.point_at(-50.0);
        assert!(p.distance(DVec2::new(0.0, 50.0)) < 1e-9, "{p}");
    }

    #[test]
    fn tracking_near_the_last_segment_finds_the_same_place_as_a_full_search() {
        let r = square();
        // Outside the loop (left of the direction of travel) the nearest place is unique.
        let mut seg = r.locate(DVec2::new(1.0, -3.0), None).segment;
        let mut s_prev = r.locate(DVec2::new(1.0, -3.0), None).s;
        let mut travelled = 0.0;
        for k in 1..=440 {
            let (p, dir) = r.point_at(k as f64);
            let q = p - DVec2::new(-dir.y, dir.x) * 3.0;
            let tracked = r.locate(q, Some(seg));
            let full = r.locate(q, None);
            assert!(r.advance(tracked.s, full.s).abs() < 1e-9, "at {k}");
            travelled += r.advance(s_prev, tracked.s);
            (seg, s_prev) = (tracked.segment, tracked.s);
        }
        assert!((travelled - 439.0).abs() < 1e-6, "{travelled}");
    }

    #[test]
    fn an_open_route_clamps_and_does_not_wrap() {
        let pts = [DVec2::new(0.0, 0.0), DVec2::new(50.0, 0.0)];
        let r = Route::new("line", &pts, false).unwrap();
        assert_eq!(r.point_at(80.0).0, DVec2::new(50.0, 0.0));
        assert_eq!(r.advance(45.0, 5.0), -40.0);
        assert!(Route::new("dot", &[DVec2::ZERO, DVec2::ZERO], false).is_none());
    }
}
