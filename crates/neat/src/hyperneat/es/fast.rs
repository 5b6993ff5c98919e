//! The fast quadtree: the same algorithm as [`super::reference`], built
//! level by level so that each level's CPPN queries (and each exploration's
//! band-pruning queries) are one batch.

use super::discover::Found;
use super::params::EsParams;
use super::query::Query;
use super::reference::{band, child_centres, neighbours, variance};

/// A square in the arena: centre, half side, level, value and its first child (0 = none).
#[derive(Clone, Copy)]
struct Square {
    x: f64,
    y: f64,
    half: f64,
    level: u32,
    w: f64,
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
    pub(crate) fn explore<Q: Query>(
        &mut self,
        q: &mut Q,
        output: usize,
        node: [f64; 2],
        outgoing: bool,
        p: &EsParams,
        found: &mut Vec<Found>,
    ) {
        self.divide(q, output, node, outgoing, p);
        self.prune(q, output, node, outgoing, p, found);
    }

    /// Division and initialisation, one batch of queries per level.
    fn divide<Q: Query>(
        &mut self,
        q: &mut Q,
        output: usize,
        node: [f64; 2],
        outgoing: bool,
        p: &EsParams,
    ) {
        self.squares.clear();
        self.squares.push(Square {
            x: 0.0,
            y: 0.0,
            half: 1.0,
            level: 1,
            w: 0.0,
            first_child: 0,
        });
        self.frontier.clear();
        self.frontier.push(0);
        while !self.frontier.is_empty() {
            self.points.clear();
            for &s in &self.frontier {
                let sq = self.squares[s];
                self.points.extend(child_centres(sq.x, sq.y, sq.half));
            }
            self.values.resize(self.points.len(), 0.0);
            q.query(output, node, outgoing, &self.points, &mut self.values);
            self.next.clear();
            for (k, &s) in self.frontier.iter().enumerate() {
                let first = self.squares.len();
                let sq = self.squares[s];
                self.squares[s].first_child = first;
                let ws = &self.values[4 * k..4 * k + 4];
                for (c, &w) in ws.iter().enumerate() {
                    let [x, y] = self.points[4 * k + c];
                    self.squares.push(Square {
                        x,
                        y,
                        half: sq.half / 2.0,
                        level: sq.level + 1,
                        w,
                        first_child: 0,
                    });
                }
                if sq.level < p.initial_depth
                    || (sq.level < p.max_depth && variance(ws) > p.division_threshold)
                {
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
                self.leaves.push(sq.w);
            } else {
                // Reversed, so that children pop in order.
                self.stack
                    .extend((sq.first_child..sq.first_child + 4).rev());
            }
        }
    }

    /// Pruning and extraction: finds the band candidates in the reference's
    /// depth-first order, then queries all their neighbours in one batch.
    fn prune<Q: Query>(
        &mut self,
        q: &mut Q,
        output: usize,
        node: [f64; 2],
        outgoing: bool,
        p: &EsParams,
        found: &mut Vec<Found>,
    ) {
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
            if variance(&self.leaves) > p.variance_threshold && self.squares[c].first_child != 0 {
                self.path.push((c, 0));
            } else {
                let ch = self.squares[c];
                self.candidates.push(c);
                self.points.extend(neighbours(ch.x, ch.y, sq.half));
            }
        }
        self.values.resize(self.points.len(), 0.0);
        q.query(output, node, outgoing, &self.points, &mut self.values);
        for (k, &c) in self.candidates.iter().enumerate() {
            let ch = self.squares[c];
            let near = [0, 1, 2, 3].map(|j| self.values[4 * k + j]);
            if band(ch.w, near) > p.band_threshold {
                found.push(Found {
                    point: [ch.x, ch.y],
                    o: ch.w,
                });
            }
        }
    }
}
