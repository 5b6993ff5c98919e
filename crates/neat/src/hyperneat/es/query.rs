//! The two shapes of CPPN query ES-HyperNEAT makes: one node to many points.

use super::params::EsParams;
use crate::hyperneat::batch::BatchCppn;
use crate::network::Network;

/// A quadtree point that expresses a link, with its CPPN weight output.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Found {
    pub(crate) point: [f64; 2],
    pub(crate) o: f64,
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

/// A fixed node and the side of its links queried: to many points when
/// `outgoing` (it is their source), else from them.
#[derive(Clone, Copy)]
pub(crate) struct Fixed {
    /// The node's position.
    pub(crate) node: [f64; 2],
    /// Whether the node is the links' source.
    pub(crate) outgoing: bool,
}

/// Queries of one CPPN output between a fixed node and many points.
pub(crate) trait Query {
    /// Number of CPPN outputs.
    fn num_outputs(&self) -> usize;
    /// `out[k]` = CPPN output `output` for the link between `fixed` and
    /// `points[k]` (queries take the target first).
    fn query(&mut self, output: usize, fixed: Fixed, points: &[[f64; 2]], out: &mut [f64]);
}

/// Any [`Network`] queried one point at a time.
pub(crate) struct OneByOne<'a, N: Network> {
    pub(crate) net: &'a mut N,
    pub(crate) out: Vec<f64>,
}

impl<'a, N: Network> OneByOne<'a, N> {
    pub(crate) fn new(net: &'a mut N) -> Self {
        let out = vec![0.0; net.num_outputs()];
        OneByOne { net, out }
    }
}

impl<N: Network> Query for OneByOne<'_, N> {
    fn num_outputs(&self) -> usize {
        self.net.num_outputs()
    }

    fn query(&mut self, output: usize, fixed: Fixed, points: &[[f64; 2]], out: &mut [f64]) {
        for (p, o) in points.iter().zip(out.iter_mut()) {
            let (target, source) = if fixed.outgoing {
                (*p, fixed.node)
            } else {
                (fixed.node, *p)
            };
            let q = [target[0], target[1], source[0], source[1], 1.0];
            self.net.activate(&q, &mut self.out);
            *o = self.out[output];
        }
    }
}

impl Query for BatchCppn {
    fn num_outputs(&self) -> usize {
        BatchCppn::num_outputs(self)
    }

    fn query(&mut self, output: usize, fixed: Fixed, points: &[[f64; 2]], out: &mut [f64]) {
        if fixed.outgoing {
            self.query_targets(output, points, fixed.node, out);
        } else {
            self.query_sources(output, fixed.node, points, out);
        }
    }
}

/// One quadtree exploration around a fixed node: the queries it makes
/// (CPPN output `output` through `q`) and the settings it follows.
pub(crate) struct Exploration<'a, Q> {
    pub(crate) q: &'a mut Q,
    pub(crate) output: usize,
    pub(crate) fixed: Fixed,
    pub(crate) p: &'a EsParams,
}

impl<Q: Query> Exploration<'_, Q> {
    /// `out[k]` = the output for the link between the fixed node and `points[k]`.
    pub(crate) fn query(&mut self, points: &[[f64; 2]], out: &mut [f64]) {
        self.q.query(self.output, self.fixed, points, out);
    }

    /// Whether a square of `level` whose children have the values `ws` is
    /// divided further: above the initial depth, or below the maximum
    /// depth where the values vary more than the division threshold.
    pub(crate) fn divides(&self, level: u32, ws: &[f64]) -> bool {
        let p = self.p;
        level < p.initial_depth || (level < p.max_depth && variance(ws) > p.division_threshold)
    }
}

/// A square of the quadtree: centre, half side, level and the CPPN output
/// at its centre.
#[derive(Clone, Copy)]
pub(crate) struct Cell {
    pub(crate) x: f64,
    pub(crate) y: f64,
    pub(crate) half: f64,
    pub(crate) level: u32,
    pub(crate) w: f64,
}

impl Cell {
    /// The whole plane `[−1, 1]²`, level 1.
    pub(crate) const ROOT: Cell = Cell {
        x: 0.0,
        y: 0.0,
        half: 1.0,
        level: 1,
        w: 0.0,
    };

    /// Its child centred at `[x, y]` (one of the reference's
    /// `child_centres`), of value `w`.
    pub(crate) fn child(&self, [x, y]: [f64; 2], w: f64) -> Cell {
        Cell {
            x,
            y,
            half: self.half / 2.0,
            level: self.level + 1,
            w,
        }
    }

    /// Its centre and value, as a point found on a band.
    pub(crate) fn found(&self) -> Found {
        Found {
            point: [self.x, self.y],
            o: self.w,
        }
    }
}
