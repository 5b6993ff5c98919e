//! The same config, scenario and seed give the same bits whatever the CPU.
//!
//! glibc picks its libm code paths per CPU (FMA/AVX2 variants of `sin`, `cos`,
//! `log`, …). `GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA` makes it take the
//! paths an older CPU would, so a run whose bits depend on the platform libm
//! differs between the two. (On a CPU without FMA both runs take the same path
//! and this test cannot tell; the pinned hash in `short_run_matches_pinned_hash`
//! covers that machine.)

use crate::common;

use crate::common::{DETERMINISTIC_FILES, read, scratch};

const OLD_CPU: &str = "glibc.cpu.hwcaps=-AVX2,-FMA";

fn short_run(out: &std::path::Path, tunables: Option<&str>) {
    let mut cmd = common::short_run_command(out);
    match tunables {
        Some(t) => cmd.env("GLIBC_TUNABLES", t),
        None => cmd.env_remove("GLIBC_TUNABLES"),
    };
    common::ok(&mut cmd);
}

#[test]
fn default_run_is_bit_identical_with_older_cpu_code_paths() {
    let dir = scratch("old-cpu");
    let (native, old) = (dir.join("native"), dir.join("old-cpu"));
    short_run(&native, None);
    short_run(&old, Some(OLD_CPU));
    for name in DETERMINISTIC_FILES {
        assert!(
            read(&native, name) == read(&old, name),
            "{name} differs when glibc takes older-CPU code paths ({OLD_CPU}): \
             some result depends on the platform libm"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
