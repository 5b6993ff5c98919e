//! Crossover aligned by innovation numbers.

use std::cmp::Ordering;

use rand::{Rng, RngExt};

use crate::genome::Genome;
use crate::params::NeatParams;

/// Which parent is fitter: higher fitness; on a tie the one with fewer links
/// (Stanley's parsimony rule), then the first.
fn first_is_fitter(a: &Genome, fa: f64, b: &Genome, fb: f64) -> bool {
    match fa.partial_cmp(&fb) {
        Some(Ordering::Greater) => true,
        Some(Ordering::Less) => false,
        _ => a.links.len() <= b.links.len(),
    }
}

/// Recombines two parents: matching genes (same innovation) come from either parent at
/// random, disjoint and excess genes from the fitter one; a gene disabled in either
/// parent stays disabled with `disabled_inherit_probability`. Node genes come from the
/// fitter parent, each matching hidden node taking its function from either parent.
pub fn crossover<R: Rng + ?Sized>(
    a: &Genome,
    fa: f64,
    b: &Genome,
    fb: f64,
    params: &NeatParams,
    rng: &mut R,
) -> Genome {
    let mut child = Genome::empty();
    crossover_into([(a, fa), (b, fb)], params, rng, &mut child);
    child
}

/// [`crossover`] of the two `(parent, fitness)` pairs into `child`,
/// whatever it held (its memory is reused).
pub(crate) fn crossover_into<R: Rng + ?Sized>(
    [(a, fa), (b, fb)]: [(&Genome, f64); 2],
    params: &NeatParams,
    rng: &mut R,
    child: &mut Genome,
) {
    let (fit, other) = if first_is_fitter(a, fa, b, fb) {
        (a, b)
    } else {
        (b, a)
    };
    let links = &mut child.links;
    links.clear();
    links.reserve(fit.links.len());
    let mut j = 0;
    for g in &fit.links {
        while j < other.links.len() && other.links[j].innovation < g.innovation {
            j += 1;
        }
        let matching = other.links.get(j).filter(|o| o.innovation == g.innovation);
        let mut gene = *g;
        let mut disabled = !g.enabled;
        if let Some(o) = matching {
            if rng.random_bool(0.5) {
                gene.weight = o.weight;
            }
            disabled |= !o.enabled;
        }
        gene.enabled = if disabled {
            !rng.random_bool(params.disabled_inherit_probability)
        } else {
            true
        };
        links.push(gene);
    }
    child.nodes.clone_from(&fit.nodes);
    for n in &mut child.nodes {
        if let Some(o) = other.node(n.id)
            && o.activation != n.activation
            && rng.random_bool(0.5)
        {
            n.activation = o.activation;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::activation::Activation;
    use crate::genome::{NodeGene, NodeKind};
    use crate::test_genes::link;
    use rand::SeedableRng;
    use rand_pcg::Pcg64;

    fn node(id: u32, kind: NodeKind) -> NodeGene {
        crate::test_genes::node(id, kind, Activation::Sigmoid)
    }

    #[test]
    fn aligned_by_innovation_disjoint_from_fitter() {
        let nodes_a = vec![
            node(0, NodeKind::Input),
            node(1, NodeKind::Input),
            node(2, NodeKind::Output),
            node(3, NodeKind::Hidden),
        ];
        let a = Genome::from_parts(
            nodes_a,
            vec![
                link(0, 0, 2, 1.0),
                link(1, 1, 2, 1.0),
                link(2, 0, 3, 1.0),
                link(3, 3, 2, 1.0),
            ],
        )
        .unwrap();
        let nodes_b = vec![
            node(0, NodeKind::Input),
            node(1, NodeKind::Input),
            node(2, NodeKind::Output),
        ];
        let b =
            Genome::from_parts(nodes_b, vec![link(0, 0, 2, -1.0), link(1, 1, 2, -1.0)]).unwrap();
        let params = NeatParams::default();
        let mut rng = Pcg64::seed_from_u64(7);
        let mut saw = [false; 2];
        for _ in 0..64 {
            // a fitter: child has a's four genes, matching weights from either parent.
            let c = crossover(&a, 2.0, &b, 1.0, &params, &mut rng);
            let inn: Vec<u32> = c.links().iter().map(|l| l.innovation).collect();
            assert_eq!(inn, vec![0, 1, 2, 3]);
            assert_eq!(c.num_hidden(), 1);
            for l in &c.links()[..2] {
                saw[(l.weight > 0.0) as usize] = true;
            }
            assert_eq!(c.links()[2].weight, 1.0);
            c.check().unwrap();
            // b fitter: only b's genes.
            let c = crossover(&a, 1.0, &b, 2.0, &params, &mut rng);
            let inn: Vec<u32> = c.links().iter().map(|l| l.innovation).collect();
            assert_eq!(inn, vec![0, 1]);
            assert_eq!(c.num_hidden(), 0);
        }
        assert_eq!(saw, [true, true], "matching genes come from both parents");
    }

    #[test]
    fn disabled_in_either_parent_mostly_stays_disabled() {
        let nodes = vec![node(0, NodeKind::Input), node(1, NodeKind::Output)];
        let a = Genome::from_parts(nodes.clone(), vec![link(0, 0, 1, 1.0)]).unwrap();
        let mut off = link(0, 0, 1, 1.0);
        off.enabled = false;
        let b = Genome::from_parts(nodes, vec![off]).unwrap();
        let params = NeatParams::default();
        let mut rng = Pcg64::seed_from_u64(9);
        let n = 4000;
        let disabled = (0..n)
            .filter(|_| !crossover(&a, 2.0, &b, 1.0, &params, &mut rng).links()[0].enabled)
            .count();
        let frac = disabled as f64 / n as f64;
        assert!((frac - 0.75).abs() < 0.03, "{frac}");
    }
}
