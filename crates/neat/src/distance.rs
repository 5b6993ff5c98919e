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
/// [`GeneTable`] and [`Compatibility`], which give the same bits and the same decisions.
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

/// The link genes of many genomes laid out for distance computations: for
/// each link its innovation number, weight and target-node function, in one
/// flat array, genome after genome.
///
/// Built once per genome per speciation, so that the genome × representative
/// comparisons walk contiguous memory and never look a node up or allocate.
#[derive(Debug, Clone, Default)]
pub struct GeneTable {
    genes: Vec<Gene>,
    /// Genome `k` is `start[k]..start[k + 1]`.
    start: Vec<usize>,
}

/// One link gene as the distance sees it (16 bytes: one walk step reads one
/// gene of each genome from one cache line).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Gene {
    weight: f64,
    innovation: u32,
    /// Function of the link's target node (its enum index); 0 for every gene
    /// when `c_activation` is 0, as A then cannot change δ (0·A = +0 is exact).
    target_fn: u32,
}

/// One genome's entry of a [`GeneTable`].
#[derive(Debug, Clone, Copy)]
pub struct GeneView<'a> {
    genes: &'a [Gene],
}

impl GeneTable {
    /// An empty table.
    pub fn new() -> GeneTable {
        GeneTable {
            genes: Vec::new(),
            start: vec![0],
        }
    }

    /// Removes every genome, keeping the memory.
    pub fn clear(&mut self) {
        self.genes.clear();
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

    /// Appends `genome` (the function column only when `params` weighs it).
    pub fn push(&mut self, genome: &Genome, params: &NeatParams) {
        if self.start.is_empty() {
            self.start.push(0);
        }
        let with_fn = params.c_activation != 0.0;
        self.genes.extend(genome.links.iter().map(|l| Gene {
            weight: l.weight,
            innovation: l.innovation,
            // A link's target always exists in a checked genome; a missing one
            // compares as "no function" exactly like the reference's `None`.
            target_fn: if with_fn {
                genome.node(l.to).map_or(u32::MAX, |n| n.activation as u32)
            } else {
                0
            },
        }));
        self.start.push(self.genes.len());
    }

    /// Genome `k` of the table.
    pub fn view(&self, k: usize) -> GeneView<'_> {
        GeneView {
            genes: &self.genes[self.start[k]..self.start[k + 1]],
        }
    }
}

/// The speciation test `distance(a, b) < threshold` for genomes laid out in
/// [`GeneTable`]s (built with the same `params`).
///
/// Gives exactly the reference's decision. It first counts the excess genes
/// exactly (two binary searches) and bounds the disjoint ones from below by
/// the difference of the overlapping lengths; the walk then stops as soon as
/// the disjoint genes seen, plus those the rest must still hold, reach the
/// count that with the excess genes alone puts δ at or above the threshold.
/// Every gene not yet seen can only raise δ (see `combine`), so no pair is
/// ever placed differently.
#[derive(Debug, Clone)]
pub struct Compatibility<'p> {
    params: &'p NeatParams,
    threshold: f64,
    /// `limits[e]`: the disjoint limit for `e` excess genes when the counts
    /// are not normalised (n = 1), for the usual small `e`.
    limits: [usize; LIMIT_TABLE],
}

/// Excess counts whose disjoint limit [`Compatibility`] keeps at hand.
const LIMIT_TABLE: usize = 48;

impl<'p> Compatibility<'p> {
    /// The test for `params` and `threshold`.
    pub fn new(params: &'p NeatParams, threshold: f64) -> Compatibility<'p> {
        let mut limits = [0; LIMIT_TABLE];
        let mut most = u32::MAX as usize;
        for (e, l) in limits.iter_mut().enumerate() {
            *l = disjoint_limit(params, threshold, 1.0, e, most);
            // The limit never grows with more excess genes.
            if *l != usize::MAX {
                most = *l;
            }
        }
        Compatibility {
            params,
            threshold,
            limits,
        }
    }

    /// Whether `distance(a, b) < threshold`.
    pub fn within(&self, a: GeneView<'_>, b: GeneView<'_>) -> bool {
        let (na, nb) = (a.genes.len(), b.genes.len());
        let n = normaliser(na, nb, self.params);
        let (oa, ob) = overlap(a, b);
        let excess = (na - oa) + (nb - ob);
        let limit = if n == 1.0 && excess < LIMIT_TABLE {
            self.limits[excess]
        } else {
            disjoint_limit(self.params, self.threshold, n, excess, na + nb)
        };
        walk(a, b, oa, ob, self.params, n, limit).is_some_and(|d| d < self.threshold)
    }
}

/// `distance` computed from [`GeneTable`] entries (same bits as [`distance`]).
pub fn distance_of(a: GeneView<'_>, b: GeneView<'_>, params: &NeatParams) -> f64 {
    let n = normaliser(a.genes.len(), b.genes.len(), params);
    let (oa, ob) = overlap(a, b);
    walk(a, b, oa, ob, params, n, usize::MAX).unwrap_or(f64::INFINITY)
}

/// How many genes of each list lie within the other's innovation range
/// (up to its last); the rest are the excess genes.
fn overlap(a: GeneView<'_>, b: GeneView<'_>) -> (usize, usize) {
    let (ga, gb) = (a.genes, b.genes);
    match (ga.last(), gb.last()) {
        (Some(la), Some(lb)) => {
            // Scanned from the end: excess genes are few, and a short linear
            // scan beats a binary search's unpredictable branches.
            let within =
                |g: &[Gene], last: u32| g.iter().rev().take_while(|x| x.innovation > last).count();
            (
                ga.len() - within(ga, lb.innovation),
                gb.len() - within(gb, la.innovation),
            )
        }
        // Against an empty list every gene is excess.
        _ => (0, 0),
    }
}

/// The smallest disjoint count that with `excess` excess genes alone
/// (A = W̄ = 0) makes δ ≥ `threshold`, or `usize::MAX` if even `most` do not.
fn disjoint_limit(
    params: &NeatParams,
    threshold: f64,
    n: f64,
    excess: usize,
    most: usize,
) -> usize {
    let alone = |d: usize| combine(params, excess, d, 0, 0, 0.0, n);
    // (Also when δ or the threshold is NaN: then no count decides early.)
    if alone(most)
        .partial_cmp(&threshold)
        .is_none_or(|o| o.is_lt())
    {
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

/// The merge walk over the overlapping parts (`a[..oa]`, `b[..ob]`, see
/// [`overlap`]) of two innovation-sorted gene lists; genes past them are
/// excess. `None` once the disjoint genes are known to reach `limit`.
///
/// Decides on the counts first, in a walk that reads innovation numbers only,
/// and sums the weights only for pairs it cannot reject: the weight sum is one
/// chain of dependent additions (its order fixes the bits), the slowest part
/// of a walk, and most pairs of a speciation are rejected on counts alone.
#[inline]
fn walk(
    a: GeneView<'_>,
    b: GeneView<'_>,
    oa: usize,
    ob: usize,
    params: &NeatParams,
    n: f64,
    limit: usize,
) -> Option<f64> {
    let (ga, gb) = (&a.genes[..oa], &b.genes[..ob]);
    let excess = (a.genes.len() - oa) + (b.genes.len() - ob);
    if limit != usize::MAX && too_many_disjoint(ga, gb, limit) {
        return None;
    }
    let (mut i, mut j) = (0, 0);
    let (mut disjoint, mut matching, mut act_diff) = (0usize, 0usize, 0usize);
    let mut weight_diff = 0.0;
    while i < oa && j < ob {
        let (x, y) = (ga[i], gb[j]);
        if x.innovation == y.innovation {
            matching += 1;
            weight_diff += (x.weight - y.weight).abs();
            act_diff += usize::from(x.target_fn != y.target_fn);
            i += 1;
            j += 1;
        } else {
            disjoint += 1;
            i += usize::from(x.innovation < y.innovation);
            j += usize::from(y.innovation < x.innovation);
        }
    }
    // Genes left in the overlapping parts are below the other list's last
    // gene: disjoint, not excess.
    disjoint += (oa - i) + (ob - j);
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

/// Whether two overlapping parts hold at least `limit` disjoint genes; stops
/// as soon as the disjoint genes seen plus those the rest must still hold
/// (the longer rest keeps at least the difference unmatched) reach it.
#[inline]
fn too_many_disjoint(ga: &[Gene], gb: &[Gene], limit: usize) -> bool {
    let (oa, ob) = (ga.len(), gb.len());
    if oa.abs_diff(ob) >= limit {
        return true;
    }
    let (mut i, mut j) = (0, 0);
    let mut disjoint = 0usize;
    while i < oa && j < ob {
        let (x, y) = (ga[i].innovation, gb[j].innovation);
        if x == y {
            i += 1;
            j += 1;
        } else {
            disjoint += 1;
            i += usize::from(x < y);
            j += usize::from(y < x);
            if disjoint + (oa - i).abs_diff(ob - j) >= limit {
                return true;
            }
        }
    }
    disjoint + (oa - i) + (ob - j) >= limit
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::activation::Activation;
    use crate::test_genes::genome;

    /// Hand-made pair: a has innovations {0,1,2,3,7}, b has {0,1,4,5}.
    /// Matching {0,1}; disjoint {2,3} ∪ {4,5} = 4; excess {7} = 1.
    fn pair(target_fn_b: Activation) -> (Genome, Genome) {
        let a = genome(
            "0 input linear, 1 input linear, 2 output bipolar_sigmoid, 3 hidden gaussian, \
             4 hidden sine",
            "0: 0 -> 3 1.0, 1: 3 -> 2 0.5, 2: 1 -> 2 0.0, 3: 0 -> 2 0.0, 7: 1 -> 4 0.0",
        );
        let target_fn_b = serde_json::to_string(&target_fn_b).unwrap();
        let b = genome(
            &format!(
                "0 input linear, 1 input linear, 2 output bipolar_sigmoid, \
                 3 hidden {}, 5 hidden abs",
                target_fn_b.trim_matches('"')
            ),
            "0: 0 -> 3 -1.0, 1: 3 -> 2 1.5, 4: 1 -> 5 0.0, 5: 5 -> 2 0.0",
        );
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
