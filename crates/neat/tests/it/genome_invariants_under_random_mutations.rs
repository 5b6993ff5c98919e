//! Random sequences of mutations and crossovers keep every genome invariant.

use std::collections::BTreeMap;

use proptest::prelude::*;
use rand::SeedableRng;
use rand_pcg::Pcg64;
use vivae_neat::crossover;
use vivae_neat::mutation::{
    mutate_activation, mutate_add_link, mutate_add_node, mutate_toggle_enable, mutate_weights,
};
use vivae_neat::{FeedForwardNetwork, Network};
use vivae_neat::{Genome, GenomeSpec, InnovationTracker, NeatParams, RecurrentNetwork};

fn spec(recurrent: bool) -> GenomeSpec {
    GenomeSpec {
        allow_recurrent: recurrent,
        ..GenomeSpec::cppn()
    }
}

/// Every link's innovation maps to exactly one `(from, to)` across all genomes.
fn innovations_consistent(genomes: &[Genome]) -> bool {
    let mut seen = BTreeMap::new();
    genomes
        .iter()
        .flat_map(|g| g.links())
        .all(|l| *seen.entry(l.innovation).or_insert((l.from, l.to)) == (l.from, l.to))
}

fn has_cycle(g: &Genome) -> bool {
    // Depth-first search over all links (enabled or not).
    fn visit(g: &Genome, n: u32, state: &mut BTreeMap<u32, u8>) -> bool {
        match state.get(&n) {
            Some(1) => return true,
            Some(2) => return false,
            _ => {}
        }
        state.insert(n, 1);
        for l in g.links().iter().filter(|l| l.from == n) {
            if visit(g, l.to, state) {
                return true;
            }
        }
        state.insert(n, 2);
        false
    }
    let mut state = BTreeMap::new();
    g.nodes().iter().any(|n| visit(g, n.id, &mut state))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn invariants_hold(seed in any::<u64>(), ops in prop::collection::vec(0u8..6, 1..120), recurrent in any::<bool>(), start_hidden in 0usize..3) {
        let spec = spec(recurrent);
        let params = NeatParams { start_hidden, ..NeatParams::default() };
        let mut rng = Pcg64::seed_from_u64(seed);
        let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
        let mut genomes: Vec<Genome> = (0..4)
            .map(|_| Genome::minimal(&spec, &params, &mut tracker, &mut rng))
            .collect();
        for (k, op) in ops.iter().enumerate() {
            let i = k % genomes.len();
            let g = &mut genomes[i];
            match op {
                0 => { mutate_add_node(g, &spec, &mut tracker, &mut rng); }
                1 => { mutate_add_link(g, &spec, &params, &mut tracker, &mut rng); }
                2 => mutate_weights(g, &params, &mut rng),
                3 => { mutate_toggle_enable(g, &mut rng); }
                4 => { mutate_activation(g, &spec, &mut rng); }
                _ => {
                    let j = (i + 1) % genomes.len();
                    let child = crossover(&genomes[i], k as f64, &genomes[j], 1.0, &params, &mut rng);
                    genomes[i] = child;
                }
            }
        }
        for g in &genomes {
            // Sorted, no duplicate links, every link's nodes exist, no link into an input.
            prop_assert!(g.check().is_ok(), "{:?}", g.check());
            prop_assert!(g.links().iter().all(|l| l.weight.abs() <= params.weight_amplitude));
            if !recurrent {
                prop_assert!(!has_cycle(g));
            }
            let back: Genome = serde_json::from_str(&serde_json::to_string(g).unwrap()).unwrap();
            prop_assert_eq!(&back, g);
            // Both phenotypes build and produce finite outputs.
            let mut out = [0.0; 3];
            FeedForwardNetwork::from_genome(g).activate(&[0.1, -0.2, 0.3, 0.4, 1.0], &mut out);
            prop_assert!(out.iter().all(|o| o.is_finite()));
            RecurrentNetwork::from_genome(g).activate(&[0.1, -0.2, 0.3, 0.4, 1.0], &mut out);
            prop_assert!(out.iter().all(|o| o.is_finite()));
        }
        prop_assert!(innovations_consistent(&genomes));
    }
}

/// Lehman's maze start (`start_hidden = 1`): every input reaches the outputs
/// only through the one hidden node, which every genome of the start shares.
#[test]
fn start_hidden_routes_every_input_through_shared_hidden_nodes() {
    let spec = GenomeSpec::plain(11, 2);
    let params = NeatParams {
        start_hidden: 1,
        ..NeatParams::plain_neat()
    };
    let mut rng = Pcg64::seed_from_u64(7);
    let mut tracker = InnovationTracker::new(13);
    let a = Genome::minimal(&spec, &params, &mut tracker, &mut rng);
    let b = Genome::minimal(&spec, &params, &mut tracker, &mut rng);
    assert_eq!(a.num_hidden(), 1);
    assert_eq!(a.links().len(), 11 + 2);
    assert!(
        a.links()
            .iter()
            .all(|l| (l.from < 11 && l.to == 13) || (l.from == 13 && l.to >= 11))
    );
    let innovations = |g: &Genome| g.links().iter().map(|l| l.innovation).collect::<Vec<_>>();
    assert_eq!(innovations(&a), innovations(&b));
    assert_ne!(a.links()[0].weight, b.links()[0].weight);
    // Later hidden nodes never reuse the start's id.
    let mut c = a.clone();
    mutate_add_node(&mut c, &spec, &mut tracker, &mut rng);
    assert!(c.nodes().iter().filter(|n| n.id == 13).count() == 1 && c.num_hidden() == 2);
    // And 0 keeps NEAT's minimal start.
    let direct = Genome::minimal(
        &spec,
        &NeatParams::plain_neat(),
        &mut InnovationTracker::new(13),
        &mut rng,
    );
    assert_eq!((direct.num_hidden(), direct.links().len()), (0, 22));
}
