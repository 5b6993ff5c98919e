//! HyperNEAT-LEO (Verbancsics & Stanley 2011): a link expression output
//! decides which links exist, and a Gaussian locality seed to start from.

use rand::{Rng, SeedableRng};

use super::params::HyperParams;
use crate::activation::Activation;
use crate::genome::{Genome, GenomeSpec, LinkGene, NodeGene, NodeKind};
use crate::innovation::InnovationTracker;
use crate::params::NeatParams;

/// The weight of a link from the CPPN weight output `o` and, with LEO, the
/// link expression output `leo`; `None` when no link is expressed.
///
/// Without LEO this is [`HyperParams::express`] (the weight threshold).
/// With LEO the link exists iff `leo > 0` and its weight is
/// `clamp(o, −1, 1)·amplitude`: the threshold no longer applies (a zero or
/// non-finite weight still expresses nothing).
#[inline]
pub fn express_link(params: &HyperParams, o: f64, leo: Option<f64>) -> Option<f64> {
    match leo {
        None => params.express(o),
        Some(l) if l > 0.0 => {
            let w = o.clamp(-1.0, 1.0) * params.amplitude;
            (w.is_finite() && w != 0.0).then_some(w)
        }
        Some(_) => None,
    }
}

/// Index of the CPPN input `x1` (target x) and `x2` (source x).
const X1: u32 = 0;
const X2: u32 = 2;
/// Index of the bias input.
const BIAS: u32 = 4;

/// A minimal CPPN genome with the LEO locality seed along x: a Gaussian
/// hidden node of `Δx = x1 − x2` feeding output `leo_output`, whose other
/// incoming links start at 0 except the bias at −0.5, so that at first only
/// links with `|Δx| ≲ 0.53` are expressed (`e^(−2.5Δx²) > 0.5`).
///
/// Use one `tracker` for a whole population so that every seeded genome
/// numbers the seed's genes alike.
pub fn leo_seeded_genome<R: Rng + ?Sized>(
    spec: &GenomeSpec,
    params: &NeatParams,
    tracker: &mut InnovationTracker,
    rng: &mut R,
    leo_output: usize,
) -> Genome {
    assert!(spec.inputs == 5, "a substrate CPPN has 5 inputs");
    assert!(leo_output < spec.outputs, "no CPPN output {leo_output}");
    let leo = (spec.inputs + leo_output) as u32;
    let g = Genome::minimal(spec, params, tracker, rng);
    let mut nodes = g.nodes().to_vec();
    let mut links: Vec<LinkGene> = g.links().to_vec();
    for l in links.iter_mut().filter(|l| l.to == leo) {
        l.weight = if l.from == BIAS { -0.5 } else { 0.0 };
    }
    let split = tracker.link_innovation(X1, leo);
    let gaussian = tracker.split_node(split, |id| g.has_node(id));
    nodes.push(NodeGene {
        id: gaussian,
        kind: NodeKind::Hidden,
        activation: Activation::Gaussian,
    });
    for (from, to, weight) in [
        (X1, gaussian, 1.0),
        (X2, gaussian, -1.0),
        (gaussian, leo, 1.0),
    ] {
        links.push(LinkGene {
            innovation: tracker.link_innovation(from, to),
            from,
            to,
            weight,
            enabled: true,
        });
    }
    links.sort_by_key(|l| l.innovation);
    Genome::from_parts(nodes, links).expect("the seed keeps every genome invariant")
}

/// `count` genomes of [`leo_seeded_genome`] over one innovation history,
/// drawn from a `Pcg64` seeded with `seed`: the same arguments give the same
/// genomes on every platform. Their link genes are numbered as
/// [`Population::from_genomes`](crate::Population::from_genomes) requires.
pub fn leo_seeded_genomes(
    spec: &GenomeSpec,
    params: &NeatParams,
    count: usize,
    seed: u64,
    leo_output: usize,
) -> Vec<Genome> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
    (0..count)
        .map(|_| leo_seeded_genome(spec, params, &mut tracker, &mut rng, leo_output))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::feedforward::FeedForwardNetwork;
    use crate::network::Network;
    use rand::SeedableRng;

    #[test]
    fn leo_decides_existence_and_threshold_no_longer_applies() {
        let p = HyperParams::default();
        assert_eq!(express_link(&p, 0.1, None), None);
        assert_eq!(express_link(&p, 0.6, None), p.express(0.6));
        assert_eq!(express_link(&p, 0.1, Some(0.3)), Some(0.1 * 3.0));
        assert_eq!(express_link(&p, 0.9, Some(-0.3)), None);
        assert_eq!(express_link(&p, 0.9, Some(0.0)), None);
        assert_eq!(express_link(&p, 0.9, Some(f64::NAN)), None);
        assert_eq!(express_link(&p, 0.0, Some(1.0)), None);
        assert_eq!(express_link(&p, -7.0, Some(1.0)), Some(-3.0));
    }

    #[test]
    fn seeded_genomes_are_drawn_from_the_seed_and_evolve_together() {
        let spec = GenomeSpec {
            outputs: 3,
            ..GenomeSpec::cppn()
        };
        let params = NeatParams::default();
        let a = leo_seeded_genomes(&spec, &params, 12, 5, 2);
        assert_eq!(a, leo_seeded_genomes(&spec, &params, 12, 5, 2));
        assert_ne!(a, leo_seeded_genomes(&spec, &params, 12, 6, 2));
        assert!(a.iter().all(|g| g.num_hidden() == 1));
        crate::Population::from_genomes(params, spec, a, 1).unwrap();
    }

    #[test]
    fn seeded_cppn_expresses_local_links_only() {
        let spec = GenomeSpec {
            outputs: 2,
            ..GenomeSpec::cppn()
        };
        let params = NeatParams::default();
        let mut tracker = InnovationTracker::new(7);
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        let a = leo_seeded_genome(&spec, &params, &mut tracker, &mut rng, 1);
        let b = leo_seeded_genome(&spec, &params, &mut tracker, &mut rng, 1);
        // The seed's genes are numbered alike in every genome.
        let seed_genes = |g: &Genome| -> Vec<(u32, u32, u32)> {
            g.links()
                .iter()
                .filter(|l| l.from >= 7 || l.to >= 7)
                .map(|l| (l.innovation, l.from, l.to))
                .collect()
        };
        assert_eq!(seed_genes(&a), seed_genes(&b));
        assert_eq!(a.num_hidden(), 1);
        let mut net = FeedForwardNetwork::from_genome(&a);
        let mut out = [0.0; 2];
        for (x1, x2, local) in [
            (0.0, 0.1, true),
            (0.5, 0.2, true),
            (-1.0, 1.0, false),
            (0.9, -0.1, false),
        ] {
            net.activate(&[x1, 0.3, x2, -0.7, 1.0], &mut out);
            assert_eq!(out[1] > 0.0, local, "Δx = {}", x1 - x2);
        }
    }
}
