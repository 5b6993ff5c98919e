//! The reference quadtree: the paper's algorithms written as plainly as
//! possible (a recursive tree, one CPPN query per point).

use super::discover::Found;
use super::params::EsParams;
use super::query::Query;

/// A square of the quadtree: centre, half side, level and the CPPN weight
/// output at its centre.
struct Square {
    x: f64,
    y: f64,
    half: f64,
    level: u32,
    w: f64,
    children: Vec<Square>,
}

/// The population variance of `xs` (mean first, then mean squared deviation, in order).
pub(crate) fn variance(xs: &[f64]) -> f64 {
    if xs.is_empty() {
        return 0.0;
    }
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n
}

/// The band level of a point of value `w` between neighbours left/right
/// (`l`, `r`) and bottom/top (`b`, `t`).
pub(crate) fn band(w: f64, [l, r, b, t]: [f64; 4]) -> f64 {
    let (dl, dr, db, dt) = ((w - l).abs(), (w - r).abs(), (w - b).abs(), (w - t).abs());
    dt.min(db).max(dl.min(dr))
}

/// The four children of a square, in the order both implementations use:
/// (−,−), (−,+), (+,+), (+,−).
pub(crate) fn child_centres(x: f64, y: f64, half: f64) -> [[f64; 2]; 4] {
    let h = half / 2.0;
    [
        [x - h, y - h],
        [x - h, y + h],
        [x + h, y + h],
        [x + h, y - h],
    ]
}

/// Neighbours at distance `d` of `(x, y)`: left, right, bottom, top.
pub(crate) fn neighbours(x: f64, y: f64, d: f64) -> [[f64; 2]; 4] {
    [[x - d, y], [x + d, y], [x, y - d], [x, y + d]]
}

fn one<Q: Query>(q: &mut Q, output: usize, node: [f64; 2], outgoing: bool, p: [f64; 2]) -> f64 {
    let mut o = [0.0];
    q.query(output, node, outgoing, &[p], &mut o);
    o[0]
}

/// Division and initialisation: divides `sq` into four, and each child
/// again while above the initial depth, or while below the maximum depth
/// and the children's values vary more than the division threshold.
fn divide<Q: Query>(
    q: &mut Q,
    out: usize,
    node: [f64; 2],
    outgoing: bool,
    sq: &mut Square,
    p: &EsParams,
) {
    for [x, y] in child_centres(sq.x, sq.y, sq.half) {
        let w = one(q, out, node, outgoing, [x, y]);
        sq.children.push(Square {
            x,
            y,
            half: sq.half / 2.0,
            level: sq.level + 1,
            w,
            children: Vec::new(),
        });
    }
    let ws: Vec<f64> = sq.children.iter().map(|c| c.w).collect();
    if sq.level < p.initial_depth
        || (sq.level < p.max_depth && variance(&ws) > p.division_threshold)
    {
        for c in &mut sq.children {
            divide(q, out, node, outgoing, c, p);
        }
    }
}

/// The values of the leaves under `sq` (itself when it has no children), depth first.
fn leaves(sq: &Square, into: &mut Vec<f64>) {
    if sq.children.is_empty() {
        into.push(sq.w);
    }
    for c in &sq.children {
        leaves(c, into);
    }
}

/// Pruning and extraction: descends where the leaves vary, and elsewhere
/// keeps the points that lie on a band (differ from both neighbours along x
/// or along y by more than the band threshold).
#[allow(clippy::too_many_arguments)]
fn prune<Q: Query>(
    q: &mut Q,
    out: usize,
    node: [f64; 2],
    outgoing: bool,
    sq: &Square,
    p: &EsParams,
    found: &mut Vec<Found>,
) {
    for c in &sq.children {
        let mut ls = Vec::new();
        leaves(c, &mut ls);
        if variance(&ls) > p.variance_threshold {
            prune(q, out, node, outgoing, c, p, found);
        } else {
            let near = neighbours(c.x, c.y, sq.half).map(|n| one(q, out, node, outgoing, n));
            if band(c.w, near) > p.band_threshold {
                found.push(Found {
                    point: [c.x, c.y],
                    o: c.w,
                });
            }
        }
    }
}

/// The points that express a link with `node` (as source when `outgoing`),
/// in depth-first order, with their CPPN output `output`.
pub(crate) fn explore<Q: Query>(
    q: &mut Q,
    output: usize,
    node: [f64; 2],
    outgoing: bool,
    p: &EsParams,
    found: &mut Vec<Found>,
) {
    let mut root = Square {
        x: 0.0,
        y: 0.0,
        half: 1.0,
        level: 1,
        w: 0.0,
        children: Vec::new(),
    };
    divide(q, output, node, outgoing, &mut root, p);
    prune(q, output, node, outgoing, &root, p, found);
}
