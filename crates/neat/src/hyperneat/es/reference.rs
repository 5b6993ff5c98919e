//! The reference quadtree: the paper's algorithms written as plainly as
//! possible (a recursive tree, one CPPN query per point).

use super::query::{Cell, Exploration, Found, Query, variance};

/// A square of the quadtree and its children.
struct Square {
    cell: Cell,
    children: Vec<Square>,
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

fn one<Q: Query>(e: &mut Exploration<'_, Q>, p: [f64; 2]) -> f64 {
    let mut o = [0.0];
    e.query(&[p], &mut o);
    o[0]
}

/// Division and initialisation: divides `sq` into four, and each child
/// again while above the initial depth, or while below the maximum depth
/// and the children's values vary more than the division threshold.
fn divide<Q: Query>(e: &mut Exploration<'_, Q>, sq: &mut Square) {
    let c = sq.cell;
    for centre in child_centres(c.x, c.y, c.half) {
        let w = one(e, centre);
        let cell = c.child(centre, w);
        let children = Vec::new();
        sq.children.push(Square { cell, children });
    }
    let ws: Vec<f64> = sq.children.iter().map(|c| c.cell.w).collect();
    if e.divides(c.level, &ws) {
        for c in &mut sq.children {
            divide(e, c);
        }
    }
}

/// The values of the leaves under `sq` (itself when it has no children), depth first.
fn leaves(sq: &Square, into: &mut Vec<f64>) {
    if sq.children.is_empty() {
        into.push(sq.cell.w);
    }
    for c in &sq.children {
        leaves(c, into);
    }
}

/// Pruning and extraction: descends where the leaves vary, and elsewhere
/// keeps the points that lie on a band (differ from both neighbours along x
/// or along y by more than the band threshold).
fn prune<Q: Query>(e: &mut Exploration<'_, Q>, sq: &Square, found: &mut Vec<Found>) {
    for c in &sq.children {
        let mut ls = Vec::new();
        leaves(c, &mut ls);
        if variance(&ls) > e.p.variance_threshold {
            prune(e, c, found);
        } else {
            let near = neighbours(c.cell.x, c.cell.y, sq.cell.half).map(|n| one(e, n));
            if band(c.cell.w, near) > e.p.band_threshold {
                found.push(c.cell.found());
            }
        }
    }
}

/// The points that express a link with the fixed node of `e`, in
/// depth-first order, with their CPPN output.
pub(crate) fn explore<Q: Query>(e: &mut Exploration<'_, Q>, found: &mut Vec<Found>) {
    let mut root = Square {
        cell: Cell::ROOT,
        children: Vec::new(),
    };
    divide(e, &mut root);
    prune(e, &root, found);
}
