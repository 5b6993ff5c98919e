//! The checkpoint reader on arbitrary text. The checksum header is computed
//! here, so the fuzzer reaches the JSON and population validation behind it.
#![no_main]
use libfuzzer_sys::fuzz_target;

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

fuzz_target!(|data: &[u8]| {
    if let Ok(body) = std::str::from_utf8(data) {
        let text = format!(
            "vivae-checkpoint v1 {:016x}\n{body}",
            fnv1a(body.as_bytes())
        );
        let _ = vivae_lab::rundir::population_from_checkpoint_text(
            &text,
            std::path::Path::new("fuzz.ckpt"),
        );
    }
});
