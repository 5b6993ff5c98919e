//! The checkpoint reader on arbitrary text. The checksum header is computed
//! here, so the fuzzer reaches the JSON and population validation behind it.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(body) = std::str::from_utf8(data) {
        let text = vivae_lab::rundir::seal_checkpoint(body);
        let _ = vivae_lab::run::population_from_checkpoint_text(
            &text,
            std::path::Path::new("fuzz.ckpt"),
        );
    }
});
