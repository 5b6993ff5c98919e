//! The JSON formats the Python package reads (`Population.from_json`, the
//! strategies' `from_json`, `Genome.from_json`, `params={...}`) on arbitrary
//! text; the first byte picks the format. A state that loads is driven one
//! ask/tell further, a genome that loads is compiled both ways: refused or
//! used, never a panic or an unbounded allocation.
#![no_main]
use libfuzzer_sys::fuzz_target;
use vivae_neat::driver::{Evaluation, Strategy};
use vivae_neat::strategies as st;

/// One `ask` and a `tell` of zeros (with an empty behaviour and metrics).
fn drive(mut s: impl Strategy) {
    let n = s.ask().genomes.len().min(10_000);
    let told: Vec<Evaluation> = (0..n)
        .map(|_| Evaluation {
            fitness: 0.0,
            metrics: Vec::new(),
            behaviour: Vec::new(),
        })
        .collect();
    let _ = s.tell(&told);
}

/// A state of strategy `S` read from `text` (as `from_json` reads it), driven once if it loads.
fn drive_json<S: Strategy>(text: &str) {
    if let Ok(s) = serde_json::from_str::<S>(text) {
        drive(s);
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&which, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    match which % 6 {
        0 => drive_json::<vivae_neat::Population>(text),
        1 => drive_json::<st::NoveltySearch>(text),
        2 => drive_json::<st::MapElites>(text),
        3 => drive_json::<st::Nsga2>(text),
        4 => {
            if let Ok(g) = serde_json::from_str::<vivae_neat::Genome>(text) {
                let _ = vivae_neat::FeedForwardNetwork::from_genome(&g);
                let _ = vivae_neat::RecurrentNetwork::from_genome(&g);
            }
        }
        _ => {
            if let Ok(p) = serde_json::from_str::<vivae_neat::NeatParams>(text) {
                let _ = p.validate();
            }
        }
    }
});
