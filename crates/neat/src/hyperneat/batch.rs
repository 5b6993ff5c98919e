//! A CPPN genome compiled for batched substrate queries.

use super::layout::CPPN_INPUTS;
use crate::activation::Activation;
use crate::compile::Plan;
use crate::genome::Genome;
use crate::simd::{self, SimdLevel};

/// Queries per batch: the batch's node values (≈ 14 nodes × 256 × 8 bytes) stay in L1.
const BATCH: usize = 256;

/// A CPPN genome compiled for batched substrate queries.
///
/// Evaluates the same compiled plan as
/// [`FeedForwardNetwork`](crate::FeedForwardNetwork) (same nodes, same
/// per-node sum order, same activation functions), so its outputs are
/// bit-identical, but one output at a time for a whole batch of source nodes:
/// each node's weighted sum runs over contiguous arrays (vectorised),
/// activation functions run in tight loops, and only the nodes the requested
/// output depends on are computed.
#[derive(Debug, Clone)]
pub struct BatchCppn {
    /// The compiled genome (the same plan `FeedForwardNetwork` evaluates).
    plan: Plan,
    /// For each output: the computed nodes it depends on, in evaluation order.
    dependencies: Vec<Vec<usize>>,
    /// Node values, slot-major: `values[slot * BATCH + q]`.
    values: Vec<f64>,
    /// A forced instruction level (tests); `None`: the process-wide [`simd::level`].
    level: Option<SimdLevel>,
}

impl BatchCppn {
    /// Compiles `genome`; `None` if its enabled links form a cycle (use
    /// [`FeedForwardNetwork`](crate::FeedForwardNetwork) then, which breaks cycles).
    pub fn new(genome: &Genome) -> Option<BatchCppn> {
        let plan = Plan::compile(genome);
        if plan.cyclic {
            return None;
        }
        let dependencies = (0..plan.output_slots.len())
            .map(|o| plan.dependencies(o))
            .collect();
        Some(BatchCppn {
            values: vec![0.0; (plan.num_inputs + plan.acts.len()) * BATCH],
            plan,
            dependencies,
            level: None,
        })
    }

    /// Number of CPPN inputs.
    pub fn num_inputs(&self) -> usize {
        self.plan.num_inputs
    }

    /// Number of CPPN outputs.
    pub fn num_outputs(&self) -> usize {
        self.plan.output_slots.len()
    }

    /// Output `output` for target `target` and each of `sources`, into
    /// `out[q]` (`out.len() == sources.len()`); bias input 1.
    pub fn query_sources(
        &mut self,
        output: usize,
        target: [f64; 2],
        sources: &[[f64; 2]],
        out: &mut [f64],
    ) {
        self.query(output, Points::Many(sources), Points::One(target), out);
    }

    /// Output `output` for each of `targets` and source `source`, into
    /// `out[q]` (`out.len() == targets.len()`); bias input 1.
    pub fn query_targets(
        &mut self,
        output: usize,
        targets: &[[f64; 2]],
        source: [f64; 2],
        out: &mut [f64],
    ) {
        self.query(output, Points::One(source), Points::Many(targets), out);
    }

    fn query(&mut self, output: usize, sources: Points<'_>, targets: Points<'_>, out: &mut [f64]) {
        let level = self.level.unwrap_or_else(simd::level);
        assert_eq!(
            self.plan.num_inputs, CPPN_INPUTS,
            "substrate queries need 5 CPPN inputs"
        );
        assert!(
            output < self.plan.output_slots.len(),
            "no CPPN output {output}"
        );
        for points in [sources, targets] {
            if let Points::Many(p) = points {
                assert_eq!(p.len(), out.len(), "one output per point");
            }
        }
        for (start, out) in (0..).step_by(BATCH).zip(out.chunks_mut(BATCH)) {
            let b = out.len();
            let v = &mut self.values;
            // Input slots 0..5 = x1, y1, x2, y2, bias.
            for (slot, points) in [(0, targets), (2, sources)] {
                match points {
                    Points::One([x, y]) => {
                        v[slot * BATCH..slot * BATCH + b].fill(x);
                        v[(slot + 1) * BATCH..(slot + 1) * BATCH + b].fill(y);
                    }
                    Points::Many(points) => {
                        for (q, &[x, y]) in points[start..start + b].iter().enumerate() {
                            v[slot * BATCH + q] = x;
                            v[(slot + 1) * BATCH + q] = y;
                        }
                    }
                }
            }
            v[4 * BATCH..4 * BATCH + b].fill(1.0);
            let out_slot = self.plan.output_slots[output] as usize;
            evaluate(level, &self.plan, &self.dependencies[output], v, b);
            out.copy_from_slice(&v[out_slot * BATCH..out_slot * BATCH + b]);
        }
    }
}

/// Computes the nodes `dependencies` (in order) for the first `b` queries of
/// the batch in `v`, at instruction level `level` (clamped to the CPU's).
fn evaluate(level: SimdLevel, plan: &Plan, dependencies: &[usize], v: &mut [f64], b: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        if level >= SimdLevel::Avx512 && std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: this CPU supports AVX-512F (checked just above).
            return unsafe { evaluate_avx512(plan, dependencies, v, b) };
        }
        if level >= SimdLevel::Avx2 && std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: this CPU supports AVX2 (checked just above).
            return unsafe { evaluate_avx2(plan, dependencies, v, b) };
        }
    }
    let _ = level;
    evaluate_body(plan, dependencies, v, b);
}

/// [`evaluate_body`] compiled with AVX-512F (no FMA: the same bits).
///
/// # Safety
/// The CPU must support AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn evaluate_avx512(plan: &Plan, dependencies: &[usize], v: &mut [f64], b: usize) {
    evaluate_body(plan, dependencies, v, b)
}

/// [`evaluate_body`] compiled with AVX2 (no FMA: the same bits).
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn evaluate_avx2(plan: &Plan, dependencies: &[usize], v: &mut [f64], b: usize) {
    evaluate_body(plan, dependencies, v, b)
}

/// Each node's weighted sum in link order, lane-wise over the queries (so
/// vectorised across queries, never re-associated), then its activation.
#[inline(always)]
fn evaluate_body(plan: &Plan, dependencies: &[usize], v: &mut [f64], b: usize) {
    for &k in dependencies {
        let slot = plan.num_inputs + k;
        let (before, rest) = v.split_at_mut(slot * BATCH);
        let acc = &mut rest[..b];
        acc.fill(0.0);
        let (sources, weights) = plan.links(k);
        for (&src, &w) in sources.iter().zip(weights) {
            let src = src as usize;
            let x = &before[src * BATCH..src * BATCH + b];
            for (a, &x) in acc.iter_mut().zip(x) {
                *a += x * w;
            }
        }
        apply_all(plan.acts[k], acc);
    }
}

/// One fixed point or one point per query.
#[derive(Clone, Copy)]
enum Points<'a> {
    One([f64; 2]),
    Many(&'a [[f64; 2]]),
}

/// Applies `act` to every element, one tight loop per function.
#[inline(always)]
fn apply_all(act: Activation, xs: &mut [f64]) {
    macro_rules! each {
        ($f:expr) => {
            for x in xs.iter_mut() {
                *x = $f.apply(*x);
            }
        };
    }
    match act {
        Activation::BipolarSigmoid => each!(Activation::BipolarSigmoid),
        Activation::Linear => {}
        Activation::Gaussian => each!(Activation::Gaussian),
        Activation::Abs => each!(Activation::Abs),
        // Lane-wise copies of libm's sin/cos (the same bits), so they vectorise.
        Activation::Sine => crate::math::sin_in_place(xs),
        Activation::Cosine => crate::math::cos_in_place(xs),
        Activation::Sigmoid => each!(Activation::Sigmoid),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::feedforward::FeedForwardNetwork;
    use crate::hyperneat::test_util::random_genomes;
    use crate::network::Network;

    #[test]
    fn every_simd_level_gives_the_same_bits() {
        let sources: Vec<[f64; 2]> = (0..700)
            .map(|i| {
                let t = i as f64;
                [(t * 0.37).sin() * 4.0, (t * 0.011).cos() * 30.0 - 2.0]
            })
            .collect();
        for g in random_genomes(30, 5) {
            let mut expected: Option<Vec<u64>> = None;
            for level in simd::available() {
                let mut b = BatchCppn::new(&g).unwrap();
                b.level = Some(level);
                let mut all = Vec::new();
                for output in 0..3 {
                    let mut out = vec![0.0; sources.len()];
                    b.query_sources(output, [0.25, -0.5], &sources, &mut out);
                    all.extend(out.iter().map(|v| v.to_bits()));
                    b.query_targets(output, &sources, [-0.7, 0.9], &mut out);
                    all.extend(out.iter().map(|v| v.to_bits()));
                }
                match &expected {
                    None => expected = Some(all),
                    Some(e) => assert!(e == &all, "{level:?} differs from the baseline"),
                }
            }
        }
    }

    #[test]
    fn batch_cppn_matches_single_queries() {
        for g in random_genomes(10, 11) {
            let mut ff = FeedForwardNetwork::from_genome(&g);
            let mut b = BatchCppn::new(&g).unwrap();
            let sources: Vec<[f64; 2]> = (0..300)
                .map(|i| [(i as f64 * 0.37).sin(), i as f64 / 300.0])
                .collect();
            for output in 0..3 {
                let mut batched = vec![0.0; sources.len()];
                b.query_sources(output, [0.25, -0.5], &sources, &mut batched);
                for (q, &[x2, y2]) in sources.iter().enumerate() {
                    let mut out = [0.0; 3];
                    ff.activate(&[0.25, -0.5, x2, y2, 1.0], &mut out);
                    assert_eq!(out[output].to_bits(), batched[q].to_bits());
                }
                b.query_targets(output, &sources, [0.7, 0.1], &mut batched);
                for (q, &[x1, y1]) in sources.iter().enumerate() {
                    let mut out = [0.0; 3];
                    ff.activate(&[x1, y1, 0.7, 0.1, 1.0], &mut out);
                    assert_eq!(out[output].to_bits(), batched[q].to_bits());
                }
            }
        }
    }
}
