//! A CPPN genome compiled for batched substrate queries, in f64 (exact
//! precision) or f32 (fast precision).

use super::layout::CPPN_INPUTS;
use crate::activation::Activation;
use crate::compile::{Plan, links_of};
use crate::genome::Genome;
use crate::precision::{bipolar_sigmoid_f32, cos_f32_in_place, exp_f32, sin_f32_in_place};
use crate::simd::{self, SimdLevel};

/// Queries per batch: the batch's node values (≈ 14 nodes × 256 × 8 bytes) stay in L1.
const BATCH: usize = 256;

/// The number type a [`BatchCppn`] computes in: `f64` (exact precision,
/// the bits of [`FeedForwardNetwork`](crate::FeedForwardNetwork)) or `f32`
/// (fast precision: weights and coordinates rounded to f32, f32 sums and
/// the portable f32 functions of [`precision`](crate::precision)).
pub trait CppnElement:
    Copy + Default + std::ops::AddAssign + std::ops::Mul<Output = Self> + sealed::Sealed + 'static
{
    /// `x` in this type (rounded to nearest for f32).
    fn from_f64(x: f64) -> Self;
    /// `x` as f64 (exact).
    fn to_f64(self) -> f64;
    /// Applies `act` to every element, one tight loop per function.
    fn apply_all(act: Activation, xs: &mut [Self]);
}

mod sealed {
    /// Only f64 and f32 are CPPN elements.
    pub trait Sealed {}
    impl Sealed for f64 {}
    impl Sealed for f32 {}
}

/// Applies `$f` to every element of `$xs`.
macro_rules! each {
    ($xs:expr, $f:expr) => {
        for x in $xs.iter_mut() {
            *x = $f(*x);
        }
    };
}

impl CppnElement for f64 {
    #[inline(always)]
    fn from_f64(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline(always)]
    fn apply_all(act: Activation, xs: &mut [f64]) {
        match act {
            Activation::Linear => {}
            // Lane-wise copies of libm's sin/cos (the same bits), so they vectorise.
            Activation::Sine => crate::math::sin_in_place(xs),
            Activation::Cosine => crate::math::cos_in_place(xs),
            Activation::BipolarSigmoid => each!(xs, |x| Activation::BipolarSigmoid.apply(x)),
            Activation::Gaussian => each!(xs, |x| Activation::Gaussian.apply(x)),
            Activation::Abs => each!(xs, f64::abs),
            Activation::Sigmoid => each!(xs, |x| Activation::Sigmoid.apply(x)),
        }
    }
}

impl CppnElement for f32 {
    #[inline(always)]
    fn from_f64(x: f64) -> f32 {
        x as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    #[inline(always)]
    fn apply_all(act: Activation, xs: &mut [f32]) {
        match act {
            Activation::Linear => {}
            Activation::Sine => sin_f32_in_place(xs),
            Activation::Cosine => cos_f32_in_place(xs),
            Activation::BipolarSigmoid => each!(xs, bipolar_sigmoid_f32),
            Activation::Gaussian => each!(xs, |x: f32| exp_f32(-2.5 * x * x)),
            Activation::Abs => each!(xs, f32::abs),
            Activation::Sigmoid => each!(xs, |x: f32| 1.0 / (1.0 + exp_f32(-4.9 * x))),
        }
    }
}

/// A CPPN genome compiled for batched substrate queries.
///
/// `BatchCppn<f64>` evaluates the same compiled plan as
/// [`FeedForwardNetwork`](crate::FeedForwardNetwork) (same nodes, same
/// per-node sum order, same activation functions), so its outputs are
/// bit-identical, but one output at a time for a whole batch of source nodes:
/// each node's weighted sum runs over contiguous arrays (vectorised),
/// activation functions run in tight loops, and only the nodes the requested
/// output depends on are computed. `BatchCppn<f32>` does the same in single
/// precision (the fast precision's decode): twice the lanes per vector and
/// cheaper functions, other bits, the same on every CPU.
#[derive(Debug, Clone)]
pub struct BatchCppn<E: CppnElement = f64> {
    /// The compiled genome (the same plan `FeedForwardNetwork` evaluates).
    plan: Plan,
    /// The plan's link weights in `E`.
    weights: Vec<E>,
    /// For each output: the computed nodes it depends on, in evaluation order.
    dependencies: Vec<Vec<usize>>,
    /// Node values, slot-major: `values[slot * BATCH + q]`.
    values: Vec<E>,
    /// A forced instruction level (tests); `None`: the process-wide [`simd::level`].
    level: Option<SimdLevel>,
}

impl<E: CppnElement> BatchCppn<E> {
    /// Compiles `genome`; `None` if its enabled links form a cycle (use
    /// [`FeedForwardNetwork`](crate::FeedForwardNetwork) then, which breaks cycles).
    pub fn new(genome: &Genome) -> Option<BatchCppn<E>> {
        let plan = Plan::compile(genome);
        if plan.cyclic {
            return None;
        }
        let dependencies = (0..plan.output_slots.len())
            .map(|o| plan.dependencies(o))
            .collect();
        Some(BatchCppn {
            values: vec![E::default(); (plan.num_inputs + plan.acts.len()) * BATCH],
            weights: plan.conn_weight.iter().map(|&w| E::from_f64(w)).collect(),
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
        out: &mut [E],
    ) {
        let points = Points::Many(sources);
        assert_eq!(sources.len(), out.len(), "one output per point");
        self.query(output, points, Points::One(target), |start, v| {
            out[start..start + v.len()].copy_from_slice(v);
        });
    }

    /// Output `output` for each of `targets` and source `source`, into
    /// `out[q]` (`out.len() == targets.len()`); bias input 1.
    pub fn query_targets(
        &mut self,
        output: usize,
        targets: &[[f64; 2]],
        source: [f64; 2],
        out: &mut [E],
    ) {
        assert_eq!(targets.len(), out.len(), "one output per point");
        self.query_targets_with(output, targets, source, |start, v| {
            out[start..start + v.len()].copy_from_slice(v);
        });
    }

    /// Output `output` for each of `targets` and source `source`, handed to
    /// `sink(start, values)` a batch at a time (`values[q]` is target
    /// `start + q`'s), so the caller can use them without a copy.
    pub fn query_targets_with(
        &mut self,
        output: usize,
        targets: &[[f64; 2]],
        source: [f64; 2],
        sink: impl FnMut(usize, &[E]),
    ) {
        self.query(output, Points::One(source), Points::Many(targets), sink);
    }

    fn query(
        &mut self,
        output: usize,
        sources: Points<'_>,
        targets: Points<'_>,
        mut sink: impl FnMut(usize, &[E]),
    ) {
        let level = self.level.unwrap_or_else(simd::level);
        assert_eq!(
            self.plan.num_inputs, CPPN_INPUTS,
            "substrate queries need 5 CPPN inputs"
        );
        assert!(
            output < self.plan.output_slots.len(),
            "no CPPN output {output}"
        );
        let len = match (sources, targets) {
            (Points::Many(p), _) | (_, Points::Many(p)) => p.len(),
            (Points::One(_), Points::One(_)) => 1,
        };
        let graph = Graph {
            conn_start: &self.plan.conn_start,
            conn_src: &self.plan.conn_src,
            weights: &self.weights,
            acts: &self.plan.acts,
            num_inputs: self.plan.num_inputs,
            dependencies: &self.dependencies[output],
        };
        for start in (0..len).step_by(BATCH) {
            let b = BATCH.min(len - start);
            let v = &mut self.values;
            // Input slots 0..5 = x1, y1, x2, y2, bias.
            for (slot, points) in [(0, targets), (2, sources)] {
                match points {
                    Points::One([x, y]) => {
                        v[slot * BATCH..slot * BATCH + b].fill(E::from_f64(x));
                        v[(slot + 1) * BATCH..(slot + 1) * BATCH + b].fill(E::from_f64(y));
                    }
                    Points::Many(points) => {
                        for (q, &[x, y]) in points[start..start + b].iter().enumerate() {
                            v[slot * BATCH + q] = E::from_f64(x);
                            v[(slot + 1) * BATCH + q] = E::from_f64(y);
                        }
                    }
                }
            }
            v[4 * BATCH..4 * BATCH + b].fill(E::from_f64(1.0));
            let out_slot = self.plan.output_slots[output] as usize;
            evaluate(level, &graph, v, b);
            sink(start, &v[out_slot * BATCH..out_slot * BATCH + b]);
        }
    }
}

/// What one output's evaluation reads of the compiled plan.
struct Graph<'a, E> {
    conn_start: &'a [u32],
    conn_src: &'a [u32],
    weights: &'a [E],
    acts: &'a [Activation],
    num_inputs: usize,
    /// The computed nodes to evaluate, in order.
    dependencies: &'a [usize],
}

/// Computes `g`'s nodes for the first `b` queries of the batch in `v`, at
/// instruction level `level` (clamped to the CPU's).
fn evaluate<E: CppnElement>(level: SimdLevel, g: &Graph<'_, E>, v: &mut [E], b: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        if level >= SimdLevel::Avx512 && std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: this CPU supports AVX-512F (checked just above).
            return unsafe { evaluate_avx512(g, v, b) };
        }
        if level >= SimdLevel::Avx2 && std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: this CPU supports AVX2 (checked just above).
            return unsafe { evaluate_avx2(g, v, b) };
        }
    }
    let _ = level;
    evaluate_body(g, v, b);
}

/// [`evaluate_body`] compiled with AVX-512F (no FMA: the same bits).
///
/// # Safety
/// The CPU must support AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn evaluate_avx512<E: CppnElement>(g: &Graph<'_, E>, v: &mut [E], b: usize) {
    evaluate_body(g, v, b)
}

/// [`evaluate_body`] compiled with AVX2 (no FMA: the same bits).
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn evaluate_avx2<E: CppnElement>(g: &Graph<'_, E>, v: &mut [E], b: usize) {
    evaluate_body(g, v, b)
}

/// Each node's weighted sum in link order, lane-wise over the queries (so
/// vectorised across queries, never re-associated), then its activation.
#[inline(always)]
fn evaluate_body<E: CppnElement>(g: &Graph<'_, E>, v: &mut [E], b: usize) {
    for &k in g.dependencies {
        let slot = g.num_inputs + k;
        let (before, rest) = v.split_at_mut(slot * BATCH);
        let acc = &mut rest[..b];
        acc.fill(E::default());
        let (sources, weights) = links_of(g.conn_start, g.conn_src, g.weights, k);
        for (&src, &w) in sources.iter().zip(weights) {
            let src = src as usize;
            let x = &before[src * BATCH..src * BATCH + b];
            for (a, &x) in acc.iter_mut().zip(x) {
                *a += x * w;
            }
        }
        E::apply_all(g.acts[k], acc);
    }
}

/// One fixed point or one point per query.
#[derive(Clone, Copy)]
enum Points<'a> {
    One([f64; 2]),
    Many(&'a [[f64; 2]]),
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::feedforward::FeedForwardNetwork;
    use crate::hyperneat::test_util::random_genomes;
    use crate::network::Network;

    fn test_sources() -> Vec<[f64; 2]> {
        (0..700)
            .map(|i| {
                let t = i as f64;
                [(t * 0.37).sin() * 4.0, (t * 0.011).cos() * 30.0 - 2.0]
            })
            .collect()
    }

    /// Every output of `b` for `sources` as targets and as sources, as f64.
    fn all_outputs<E: CppnElement>(b: &mut BatchCppn<E>, sources: &[[f64; 2]]) -> Vec<f64> {
        let mut all = Vec::new();
        for output in 0..3 {
            let mut out = vec![E::default(); sources.len()];
            b.query_sources(output, [0.25, -0.5], sources, &mut out);
            all.extend(out.iter().map(|v| v.to_f64()));
            b.query_targets(output, sources, [-0.7, 0.9], &mut out);
            all.extend(out.iter().map(|v| v.to_f64()));
        }
        all
    }

    fn levels_agree<E: CppnElement>() {
        let sources = test_sources();
        for g in random_genomes(30, 5) {
            let mut expected: Option<Vec<u64>> = None;
            for level in simd::available() {
                let mut b = BatchCppn::<E>::new(&g).unwrap();
                b.level = Some(level);
                let all: Vec<u64> = all_outputs(&mut b, &sources)
                    .iter()
                    .map(|v| v.to_bits())
                    .collect();
                match &expected {
                    None => expected = Some(all),
                    Some(e) => assert!(e == &all, "{level:?} differs from the baseline"),
                }
            }
        }
    }

    #[test]
    fn every_simd_level_gives_the_same_bits() {
        levels_agree::<f64>();
        levels_agree::<f32>();
    }

    #[test]
    fn single_precision_queries_stay_close_to_exact_ones() {
        let sources = test_sources();
        let mut worst = 0.0f64;
        for g in random_genomes(30, 9) {
            let exact = all_outputs(&mut BatchCppn::<f64>::new(&g).unwrap(), &sources);
            let fast = all_outputs(&mut BatchCppn::<f32>::new(&g).unwrap(), &sources);
            assert_ne!(exact, fast, "f32 queries computed the f64 bits");
            for (e, f) in exact.iter().zip(&fast) {
                worst = worst.max((e - f).abs());
            }
        }
        // Measured: 6.5e-6 (30 random genomes, 8,400 queries each).
        assert!(worst < 2e-5, "largest difference {worst:e}");
    }

    #[test]
    fn batch_cppn_matches_single_queries() {
        for g in random_genomes(10, 11) {
            let mut ff = FeedForwardNetwork::from_genome(&g);
            let mut b = BatchCppn::<f64>::new(&g).unwrap();
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
