//! The two shapes of CPPN query ES-HyperNEAT makes: one node to many points.

use crate::hyperneat::batch::BatchCppn;
use crate::network::Network;

/// Queries of one CPPN output between a fixed node and many points.
pub(crate) trait Query {
    /// Number of CPPN outputs.
    fn num_outputs(&self) -> usize;
    /// `out[k]` = CPPN output `output` for the link `fixed → points[k]` when
    /// `outgoing`, else `points[k] → fixed` (queries take the target first).
    fn query(
        &mut self,
        output: usize,
        fixed: [f64; 2],
        outgoing: bool,
        points: &[[f64; 2]],
        out: &mut [f64],
    );
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

    fn query(
        &mut self,
        output: usize,
        fixed: [f64; 2],
        outgoing: bool,
        points: &[[f64; 2]],
        out: &mut [f64],
    ) {
        for (p, o) in points.iter().zip(out.iter_mut()) {
            let (target, source) = if outgoing { (*p, fixed) } else { (fixed, *p) };
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

    fn query(
        &mut self,
        output: usize,
        fixed: [f64; 2],
        outgoing: bool,
        points: &[[f64; 2]],
        out: &mut [f64],
    ) {
        if outgoing {
            self.query_targets(output, points, fixed, out);
        } else {
            self.query_sources(output, fixed, points, out);
        }
    }
}
