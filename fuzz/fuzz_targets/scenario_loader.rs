//! The SVG scenario loader on arbitrary text: it may refuse, never panic, hang or blow up.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = vivae_sim::Scenario::from_svg(text, "fuzz.svg", &vivae_sim::LoadOptions::default());
    }
});
