//! Genome and champion JSON on arbitrary text: deserialising validates, never panics.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(g) = serde_json::from_str::<vivae_neat::Genome>(text) {
            let _ = vivae_neat::FeedForwardNetwork::from_genome(&g);
        }
        let _ = serde_json::from_str::<vivae_lab::rundir::Champion>(text);
    }
});
