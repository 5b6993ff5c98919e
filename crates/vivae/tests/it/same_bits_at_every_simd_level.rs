//! The same config, scenario and seed give the same bits at every vector
//! instruction level the hot loops can be forced to (`VIVAE_SIMD`).
//!
//! The batched controller step and decoding are dispatched at run time to
//! baseline (SSE2), AVX2 or AVX-512F code; all must add the same terms in the
//! same order with no fused multiply-add. A level the CPU lacks falls back to
//! the best it has, so on such a CPU two of the runs take the same path (the
//! unit tests of `vivae_neat` compare every level the CPU has, bit for bit).

use crate::common;

use crate::common::{DETERMINISTIC_FILES, read, scratch};

fn short_run(out: &std::path::Path, level: &str) {
    let mut cmd = common::short_run_command(out);
    cmd.env("VIVAE_SIMD", level);
    common::ok(&mut cmd);
}

#[test]
fn short_run_is_bit_identical_at_every_simd_level() {
    let dir = scratch("simd-levels");
    let levels = ["scalar", "avx2", "avx512"];
    for level in levels {
        short_run(&dir.join(level), level);
    }
    for level in &levels[1..] {
        for name in DETERMINISTIC_FILES {
            assert!(
                read(&dir.join("scalar"), name) == read(&dir.join(level), name),
                "{name} differs between VIVAE_SIMD=scalar and VIVAE_SIMD={level}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn unknown_simd_level_exits_2_with_one_line() {
    let dir = scratch("simd-unknown");
    let out = common::run(common::short_run_command(&dir.join("run")).env("VIVAE_SIMD", "sse9"));
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("VIVAE_SIMD") && stderr.contains("sse9"),
        "{stderr}"
    );
    assert!(!dir.join("run").exists(), "nothing is written");
    let _ = std::fs::remove_dir_all(&dir);
}
