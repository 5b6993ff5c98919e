//! The compatibility distance δ = C1·E + C2·D + C3·W̄ + C_ACT·A.

use crate::genome::Genome;
use crate::params::NeatParams;

/// Compatibility distance between two genomes.
///
/// E = excess link genes (innovation beyond the other genome's last), D = disjoint
/// link genes, W̄ = mean |weight difference| of matching link genes, A = matching link
/// genes whose target nodes have different activation functions. With
/// `normalize_distance`, E, D and A are divided by the larger genome's link count
/// (when it has at least `normalize_min_genes` links).
///
/// This is the reference definition; speciation computes the same value through
/// [`GeneTable`] and [`within`], which give the same bits and the same decisions.
pub fn distance(a: &Genome, b: &Genome, params: &NeatParams) -> f64 {
    let (la, lb) = (&a.links, &b.links);
    let (mut i, mut j) = (0, 0);
    let (mut disjoint, mut matching, mut act_diff) = (0usize, 0usize, 0usize);
    let mut weight_diff = 0.0;
    while i < la.len() && j < lb.len() {
        let (x, y) = (&la[i], &lb[j]);
        if x.innovation == y.innovation {
            matching += 1;
            weight_diff += (x.weight - y.weight).abs();
            let fa = a.node(x.to).map(|n| n.activation);
            let fb = b.node(y.to).map(|n| n.activation);
            if fa != fb {
                act_diff += 1;
            }
            i += 1;
            j += 1;
        } else if x.innovation < y.innovation {
            disjoint += 1;
            i += 1;
        } else {
            disjoint += 1;
            j += 1;
        }
    }
    let excess = (la.len() - i) + (lb.len() - j);
    let n = normaliser(la.len(), lb.len(), params);
    combine(params, excess, disjoint, act_diff, matching, weight_diff, n)
}

/// The divisor of the counts: the larger link count under normalisation, else 1.
fn normaliser(len_a: usize, len_b: usize, params: &NeatParams) -> f64 {
    let longest = len_a.max(len_b);
    if params.normalize_distance && longest >= params.normalize_min_genes {
        longest as f64
    } else {
        1.0
    }
}

/// δ from its counts, in the one operation order every path uses.
///
/// Every operation is monotone in each count (coefficients are non-negative and
/// IEEE rounding is monotone), which is what makes [`within`]'s early exit exact.
fn combine(
    params: &NeatParams,
    excess: usize,
    disjoint: usize,
    act_diff: usize,
    matching: usize,
    weight_diff: f64,
    n: f64,
) -> f64 {
    let w_bar = if matching > 0 {
        weight_diff / matching as f64
    } else {
        0.0
    };
    (params.c_excess * excess as f64
        + params.c_disjoint * disjoint as f64
        + params.c_activation * act_diff as f64)
        / n
        + params.c_weight * w_bar
}

/// The link genes of many genomes laid out for distance computations: innovation
/// numbers, weights and target-node functions as flat arrays, genome after genome.
///
/// Built once per genome per speciation, so that the genome × representative
/// comparisons walk contiguous arrays and never look a node up or allocate.
#[derive(Debug, Clone, Default)]
pub struct GeneTable {
    innovation: Vec<u32>,
    weight: Vec<f64>,
    /// Function of each link's target node (as its enum index); all 0 when
    /// `c_activation` is 0, as A then cannot change δ (c·A = +0 is exact).
    target_fn: Vec<u8>,
    /// Genome `k` is `start[k]..start[k + 1]`.
    start: Vec<usize>,
}

/// One genome's entry of a [`GeneTable`].
#[derive(Debug, Clone, Copy)]
pub struct GeneView<'a> {
    innovation: &'a [u32],
    weight: &'a [f64],
    target_fn: &'a [u8],
}

impl GeneTable {
    /// An empty table.
    pub fn new() -> GeneTable {
        GeneTable {
            start: vec![0],
            ..GeneTable::default()
        }
    }

    /// Removes every genome, keeping the memory.
    pub fn clear(&mut self) {
        self.innovation.clear();
        self.weight.clear();
        self.target_fn.clear();
        self.start.clear();
        self.start.push(0);
    }

    /// Number of genomes in the table.
    pub fn len(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    /// Whether the table holds no genome.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Appends `genome` (the activation column only when `params` weighs it).
    pub fn push(&mut self, genome: &Genome, params: &NeatParams) {
        if self.start.is_empty() {
            self.start.push(0);
        }
        let with_fn = params.c_activation != 0.0;
        for l in &genome.links {
            self.innovation.push(l.innovation);
            self.weight.push(l.weight);
            // A link's target always exists in a checked genome; a missing one
            // compares as "no function" exactly like the reference's `None`.
            let f = if with_fn {
                genome.node(l.to).map_or(u8::MAX, |n| n.activation as u8)
            } else {
                0
            };
            self.target_fn.push(f);
        }
        self.start.push(self.innovation.len());
    }

    /// Genome `k` of the table.
    pub fn view(&self, k: usize) -> GeneView<'_> {
        let (s, e) = (self.start[k], self.start[k + 1]);
        GeneView {
            innovation: &self.innovation[s..e],
            weight: &self.weight[s..e],
            target_fn: &self.target_fn[s..e],
        }
    }
}

/// The speciation test `distance(a, b) < threshold` for genomes laid out in
/// [`GeneTable`]s (built with the same `params`).
///
/// Gives exactly the reference's decision: a walk stops early only once the
/// disjoint genes seen so far alone put δ at or above the threshold, which
/// every later gene can only raise (see [`combine`]).
#[derive(Debug, Clone)]
pub struct Compatibility<'p> {
    params: &'p NeatParams,
    threshold: f64,
    /// The disjoint-gene limit when the counts are not normalised (n = 1).
    limit_unnormalised: usize,
}

impl<'p> Compatibility<'p> {
    /// The test for `params` and `threshold`.
    pub fn new(params: &'p NeatParams, threshold: f64) -> Compatibility<'p> {
        Compatibility {
            params,
            threshold,
            limit_unnormalised: disjoint_limit(params, threshold, 1.0, u32::MAX as usize),
        }
    }

    /// Whether `distance(a, b) < threshold`.
    pub fn within(&self, a: GeneView<'_>, b: GeneView<'_>) -> bool {
        let (na, nb) = (a.innovation.len(), b.innovation.len());
        let n = normaliser(na, nb, self.params);
        let limit = if n == 1.0 {
            self.limit_unnormalised
        } else {
            disjoint_limit(self.params, self.threshold, n, na + nb)
        };
        walk(a, b, self.params, n, limit).is_some_and(|d| d < self.threshold)
    }
}

/// `distance` computed from [`GeneTable`] entries (same bits as [`distance`]).
pub fn distance_of(a: GeneView<'_>, b: GeneView<'_>, params: &NeatParams) -> f64 {
    let n = normaliser(a.innovation.len(), b.innovation.len(), params);
    walk(a, b, params, n, usize::MAX).unwrap_or(f64::INFINITY)
}

/// The smallest disjoint count that alone makes δ ≥ `threshold` (E = A = W̄ = 0),
/// or `usize::MAX` if even `most` disjoint genes do not.
fn disjoint_limit(params: &NeatParams, threshold: f64, n: f64, most: usize) -> usize {
    let alone = |d: usize| combine(params, 0, d, 0, 0, 0.0, n);
    if alone(most) < threshold {
        return usize::MAX;
    }
    // δ(d) is monotone in d: bisect for the first d with δ(d) ≥ threshold.
    let (mut lo, mut hi) = (0usize, most);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if alone(mid) >= threshold {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    lo
}

/// The merge walk over two innovation-sorted gene lists; `None` once `limit`
/// disjoint genes have been seen (δ is then known to reach the threshold).
#[inline]
fn walk(
    a: GeneView<'_>,
    b: GeneView<'_>,
    params: &NeatParams,
    n: f64,
    limit: usize,
) -> Option<f64> {
    let (ia, ib) = (a.innovation, b.innovation);
    let (na, nb) = (ia.len(), ib.len());
    if limit == 0 {
        return None;
    }
    let (mut i, mut j) = (0, 0);
    let (mut disjoint, mut matching, mut act_diff) = (0usize, 0usize, 0usize);
    let mut weight_diff = 0.0;
    while i < na && j < nb {
        let (x, y) = (ia[i], ib[j]);
        if x == y {
            matching += 1;
            weight_diff += (a.weight[i] - b.weight[j]).abs();
            act_diff += usize::from(a.target_fn[i] != b.target_fn[j]);
            i += 1;
            j += 1;
        } else {
            disjoint += 1;
            if disjoint >= limit {
                return None;
            }
            i += usize::from(x < y);
            j += usize::from(y < x);
        }
    }
    let excess = (na - i) + (nb - j);
    Some(combine(
        params,
        excess,
        disjoint,
        act_diff,
        matching,
        weight_diff,
        n,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::activation::Activation;
    use crate::genome::{LinkGene, NodeGene, NodeKind};

    fn node(id: u32, kind: NodeKind, activation: Activation) -> NodeGene {
        NodeGene {
            id,
            kind,
            activation,
        }
    }

    fn link(innovation: u32, from: u32, to: u32, weight: f64) -> LinkGene {
        LinkGene {
            innovation,
            from,
            to,
            weight,
            enabled: true,
        }
    }

    /// Hand-made pair: a has innovations {0,1,2,3,7}, b has {0,1,4,5}.
    /// Matching {0,1}; disjoint {2,3} ∪ {4,5} = 4; excess {7} = 1.
    fn pair(target_fn_b: Activation) -> (Genome, Genome) {
        use Activation::*;
        use NodeKind::*;
        let a = Genome::from_parts(
            vec![
                node(0, Input, Linear),
                node(1, Input, Linear),
                node(2, Output, BipolarSigmoid),
                node(3, Hidden, Gaussian),
                node(4, Hidden, Sine),
            ],
            vec![
                link(0, 0, 3, 1.0),
                link(1, 3, 2, 0.5),
                link(2, 1, 2, 0.0),
                link(3, 0, 2, 0.0),
                link(7, 1, 4, 0.0),
            ],
        )
        .unwrap();
        let b = Genome::from_parts(
            vec![
                node(0, Input, Linear),
                node(1, Input, Linear),
                node(2, Output, BipolarSigmoid),
                node(3, Hidden, target_fn_b),
                node(5, Hidden, Abs),
            ],
            vec![
                link(0, 0, 3, -1.0),
                link(1, 3, 2, 1.5),
                link(4, 1, 5, 0.0),
                link(5, 5, 2, 0.0),
            ],
        )
        .unwrap();
        (a, b)
    }

    #[test]
    fn hand_made_genomes() {
        let p = NeatParams::default();
        let (a, b) = pair(Activation::Gaussian);
        // W̄ = (|1 - -1| + |0.5 - 1.5|) / 2 = 1.5; A = 0.
        let want = 2.0 * 1.0 + 2.0 * 4.0 + 0.5 * 1.5;
        assert_eq!(distance(&a, &b, &p), want);
        assert_eq!(distance(&b, &a, &p), want);
        // Node 3 now differs: the one matching link into it (innovation 0) counts.
        let (a, b) = pair(Activation::Cosine);
        assert_eq!(distance(&a, &b, &p), want + 1.0);
        assert_eq!(distance(&a, &a, &p), 0.0);
    }

    #[test]
    fn normalisation_divides_counts_by_larger_genome() {
        let p = NeatParams {
            normalize_distance: true,
            normalize_min_genes: 0,
            ..NeatParams::default()
        };
        let (a, b) = pair(Activation::Cosine);
        let want = (2.0 * 1.0 + 2.0 * 4.0 + 1.0) / 5.0 + 0.5 * 1.5;
        assert!((distance(&a, &b, &p) - want).abs() < 1e-12);
    }

    /// Genomes related by random mutations and crossovers (one shared history).
    fn relatives(seed: u64, ops: &[u8], params: &NeatParams) -> Vec<Genome> {
        use crate::innovation::InnovationTracker;
        use crate::mutation::{
            mutate_activation, mutate_add_link, mutate_add_node, mutate_toggle_enable,
            mutate_weights,
        };
        use crate::{GenomeSpec, crossover};
        use rand::SeedableRng;
        let spec = GenomeSpec::cppn();
        let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
        let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
        let mut genomes: Vec<Genome> = (0..5)
            .map(|_| Genome::minimal(&spec, params, &mut tracker, &mut rng))
            .collect();
        for (k, op) in ops.iter().enumerate() {
            let i = k % genomes.len();
            let g = &mut genomes[i];
            match op {
                0 => {
                    mutate_add_node(g, &spec, &mut tracker, &mut rng);
                }
                1 | 2 => {
                    mutate_add_link(g, &spec, params, &mut tracker, &mut rng);
                }
                3 => mutate_weights(g, params, &mut rng),
                4 => {
                    mutate_toggle_enable(g, &mut rng);
                }
                5 => {
                    mutate_activation(g, &spec, &mut rng);
                }
                _ => {
                    let j = (i + 1) % genomes.len();
                    genomes[i] = crossover(&genomes[i], 1.0, &genomes[j], 0.5, params, &mut rng);
                }
            }
        }
        genomes
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]

        /// The table walk gives the reference's bits, and the early-exiting
        /// test the reference's decision, even at thresholds equal to δ.
        #[test]
        fn fast_distance_matches_reference(
            seed in proptest::prelude::any::<u64>(),
            ops in proptest::collection::vec(0u8..8, 0..150),
            c in proptest::collection::vec(0.0f64..3.0, 4),
            zero_fn in proptest::prelude::any::<bool>(),
            normalize in proptest::prelude::any::<bool>(),
            min_genes in 0usize..40,
            thresholds in proptest::collection::vec(0.0f64..30.0, 3),
        ) {
            let params = NeatParams {
                c_excess: c[0],
                c_disjoint: c[1],
                c_weight: c[2],
                c_activation: if zero_fn { 0.0 } else { c[3] },
                normalize_distance: normalize,
                normalize_min_genes: min_genes,
                ..NeatParams::default()
            };
            let genomes = relatives(seed, &ops, &params);
            let mut table = GeneTable::new();
            for g in &genomes {
                table.push(g, &params);
            }
            proptest::prop_assert_eq!(table.len(), genomes.len());
            for (i, a) in genomes.iter().enumerate() {
                for (j, b) in genomes.iter().enumerate() {
                    let want = distance(a, b, &params);
                    let got = distance_of(table.view(i), table.view(j), &params);
                    proptest::prop_assert_eq!(got.to_bits(), want.to_bits());
                    let mut probes = thresholds.clone();
                    probes.extend([want, want.next_up(), want.next_down(), 0.0]);
                    for t in probes {
                        let test = Compatibility::new(&params, t);
                        proptest::prop_assert_eq!(
                            test.within(table.view(i), table.view(j)),
                            want < t,
                            "threshold {} distance {}", t, want
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn table_clear_keeps_working() {
        let p = NeatParams::default();
        let (a, b) = pair(Activation::Cosine);
        let mut t = GeneTable::new();
        t.push(&a, &p);
        t.clear();
        assert!(t.is_empty());
        t.push(&b, &p);
        t.push(&a, &p);
        assert_eq!(distance_of(t.view(1), t.view(0), &p), distance(&a, &b, &p));
    }
}
