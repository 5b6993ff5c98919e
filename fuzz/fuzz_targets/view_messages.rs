//! The viewer's WebSocket messages: arbitrary text, split at newlines into up
//! to eight messages, sent to a fresh page of `vivae view` on a champion
//! genome (so robots are driven by a decoded controller), each handled as the
//! server handles it and followed by a frame. Every message must be obeyed or
//! answered with an error; none may panic, hang or allocate without bound,
//! and none may cost more than the bounded work per message.
#![no_main]
use std::path::Path;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use vivae::tasks::driving::view::fuzzing::PageHarness;

/// Most messages one input sends (each may cost up to about a second of work).
const MAX_MESSAGES: usize = 8;

fn harness() -> &'static PageHarness {
    static HARNESS: OnceLock<PageHarness> = OnceLock::new();
    HARNESS.get_or_init(|| {
        let champion = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../crates/vivae/tests/data/paper-champion.json");
        PageHarness::new(Some(&champion)).expect("the test champion loads")
    })
}

fuzz_target!(|data: &[u8]| {
    // A WebSocket text message is UTF-8 (the socket refuses anything else).
    let text = String::from_utf8_lossy(data);
    let _ = harness().session(text.split('\n').take(MAX_MESSAGES));
});
