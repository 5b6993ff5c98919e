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
    let longest = la.len().max(lb.len());
    let n = if params.normalize_distance && longest >= params.normalize_min_genes {
        longest as f64
    } else {
        1.0
    };
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
}
