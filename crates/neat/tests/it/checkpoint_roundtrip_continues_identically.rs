//! A population serialised to JSON mid-run and restored continues bit-identically.

use vivae_neat::{Genome, GenomeSpec, NeatParams, Population};

fn fitness(g: &Genome, seed: u64) -> f64 {
    g.links()
        .iter()
        .map(|l| (l.weight * 1.7).cos())
        .sum::<f64>()
        + 0.3 * g.num_hidden() as f64
        + (seed % 7) as f64 * 0.1
}

fn params() -> NeatParams {
    NeatParams {
        target_species: Some(6),
        add_node_probability: 0.2,
        ..NeatParams::default()
    }
}

#[test]
fn restored_after_next_generation_continues_identically() {
    let (k, total) = (6, 14);
    let mut straight = Population::new(params(), GenomeSpec::cppn(), 2024).unwrap();
    let mut restored: Option<Population> = None;
    for g in 0..total {
        if g == k {
            let json = straight.to_json().unwrap();
            restored = Some(Population::from_json(&json).unwrap());
        }
        straight.evaluate(|g, ctx| fitness(g, ctx.seed));
        straight.next_generation();
    }
    let mut resumed = restored.unwrap();
    assert_eq!(resumed.generation(), k);
    for _ in k..total {
        resumed.evaluate(|g, ctx| fitness(g, ctx.seed));
        resumed.next_generation();
    }
    assert_eq!(resumed, straight);
    assert_eq!(resumed.best_ever(), straight.best_ever());
}

#[test]
fn restored_after_evaluate_continues_identically() {
    let mut a = Population::new(params(), GenomeSpec::cppn(), 9).unwrap();
    for _ in 0..5 {
        a.evaluate(|g, ctx| fitness(g, ctx.seed));
        a.next_generation();
    }
    a.evaluate(|g, ctx| fitness(g, ctx.seed));
    let mut b = Population::from_json(&a.to_json().unwrap()).unwrap();
    assert_eq!(a, b);
    for _ in 0..5 {
        a.next_generation();
        b.next_generation();
        a.evaluate(|g, ctx| fitness(g, ctx.seed));
        b.evaluate(|g, ctx| fitness(g, ctx.seed));
    }
    assert_eq!(a, b);
}

#[test]
fn corrupt_checkpoint_is_an_error() {
    let a = Population::new(params(), GenomeSpec::cppn(), 1).unwrap();
    let json = a.to_json().unwrap();
    assert!(Population::from_json(&json[..json.len() / 2]).is_err());
    let bad = json.replace("\"population_size\":100", "\"population_size\":0");
    assert!(Population::from_json(&bad).is_err());
}
