//! The fast quadtree: the same algorithm as [`super::reference`], built
//! level by level so that each level's CPPN queries (and each exploration's
//! band-pruning queries) are one batch.

use super::query::{Cell, Exploration, Found, Query, variance};
use super::reference::{band, child_centres, neighbours};

/// A square in the arena and its first child (0 = none).
#[derive(Clone, Copy)]
struct Square {
    cell: Cell,
    first_child: usize,
}

/// Reusable buffers: an exploration allocates nothing once they have grown.
#[derive(Default)]
pub(crate) struct Explorer {
    squares: Vec<Square>,
    frontier: Vec<usize>,
    next: Vec<usize>,
    points: Vec<[f64; 2]>,
    values: Vec<f64>,
    leaves: Vec<f64>,
    candidates: Vec<usize>,
    stack: Vec<usize>,
    path: Vec<(usize, usize)>,
}

impl Explorer {
    /// As [`super::reference::explore`], with the same results bit for bit.
    pub(crate) fn explore<Q: Query>(&mut self, e: &mut Exploration<'_, Q>, found: &mut Vec<Found>) {
        self.divide(e);
        self.prune(e, found);
    }

    /// Division and initialisation, one batch of queries per level.
    fn divide<Q: Query>(&mut self, e: &mut Exploration<'_, Q>) {
        self.squares.clear();
        self.squares.push(Square {
            cell: Cell::ROOT,
            first_child: 0,
        });
        self.frontier.clear();
        self.frontier.push(0);
        while !self.frontier.is_empty() {
            self.points.clear();
            for &s in &self.frontier {
                let c = self.squares[s].cell;
                self.points.extend(child_centres(c.x, c.y, c.half));
            }
            self.values.resize(self.points.len(), 0.0);
            e.query(&self.points, &mut self.values);
            self.next.clear();
            for (k, &s) in self.frontier.iter().enumerate() {
                let first = self.squares.len();
                let sq = self.squares[s].cell;
                self.squares[s].first_child = first;
                let ws = &self.values[4 * k..4 * k + 4];
                for (c, &w) in ws.iter().enumerate() {
                    let cell = sq.child(self.points[4 * k + c], w);
                    let first_child = 0;
                    self.squares.push(Square { cell, first_child });
                }
                if e.divides(sq.level, ws) {
                    self.next.extend(first..first + 4);
                }
            }
            std::mem::swap(&mut self.frontier, &mut self.next);
        }
    }

    /// Leaf values under square `s`, depth first, into `self.leaves`.
    fn collect_leaves(&mut self, s: usize) {
        self.leaves.clear();
        self.stack.clear();
        self.stack.push(s);
        while let Some(t) = self.stack.pop() {
            let sq = self.squares[t];
            if sq.first_child == 0 {
                self.leaves.push(sq.cell.w);
            } else {
                // Reversed, so that children pop in order.
                self.stack
                    .extend((sq.first_child..sq.first_child + 4).rev());
            }
        }
    }

    /// Pruning and extraction: finds the band candidates in the reference's
    /// depth-first order, then queries all their neighbours in one batch.
    fn prune<Q: Query>(&mut self, e: &mut Exploration<'_, Q>, found: &mut Vec<Found>) {
        self.candidates.clear();
        self.points.clear();
        // (square, next child to examine): the reference's recursion, unrolled.
        self.path.clear();
        self.path.push((0, 0));
        while let Some(&mut (s, ref mut i)) = self.path.last_mut() {
            if *i == 4 {
                self.path.pop();
                continue;
            }
            let sq = self.squares[s];
            let c = sq.first_child + *i;
            *i += 1;
            self.collect_leaves(c);
            if variance(&self.leaves) > e.p.variance_threshold && self.squares[c].first_child != 0 {
                self.path.push((c, 0));
            } else {
                let ch = self.squares[c].cell;
                self.candidates.push(c);
                self.points.extend(neighbours(ch.x, ch.y, sq.cell.half));
            }
        }
        self.values.resize(self.points.len(), 0.0);
        e.query(&self.points, &mut self.values);
        for (k, &c) in self.candidates.iter().enumerate() {
            let ch = self.squares[c].cell;
            let near = [0, 1, 2, 3].map(|j| self.values[4 * k + j]);
            if band(ch.w, near) > e.p.band_threshold {
                found.push(ch.found());
            }
        }
    }
}
