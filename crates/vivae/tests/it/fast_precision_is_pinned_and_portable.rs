//! `--precision fast` (f32 decode, surface sensors and controller step,
//! polynomial functions) has its own pinned hash of the short run, gives
//! the same bits at every SIMD level, thread count and with glibc's
//! older-CPU code paths, as exact precision does; a checkpoint keeps the precision and resuming in the other one is
//! refused in one line.

use std::path::Path;

use crate::common;
use crate::common::{DETERMINISTIC_FILES, fnv1a_from, read, scratch};

/// FNV-1a 64 of `generations.csv`, `population.csv` and `champion.json` of
/// `vivae evolve --generations 12 --seed 2 --precision fast` (hashed as
/// `short_run_matches_pinned_hash` hashes the exact run).
const PINNED_FAST: u64 = 0x3526_b331_f07a_e072;

/// The exact run's pinned hash (`short_run_matches_pinned_hash`).
const PINNED_EXACT: u64 = 0x8b3b_eb74_273b_9cda;

/// A flag and its value, or an environment variable and its value.
type Pair = (&'static str, &'static str);

fn fast_run(out: &Path, extra: &[Pair], env: &[Pair]) {
    let mut cmd = common::short_run_command(out);
    cmd.args(["--precision", "fast"]);
    for (flag, value) in extra {
        cmd.args([flag, value]);
    }
    for (k, v) in env {
        cmd.env(k, v);
    }
    common::ok(&mut cmd);
}

fn hash(out: &Path) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325;
    for name in DETERMINISTIC_FILES {
        h = fnv1a_from(h, name.as_bytes());
        h = fnv1a_from(h, &read(out, name));
    }
    h
}

#[test]
fn fast_short_run_matches_pinned_hash() {
    let dir = scratch("pinned-fast");
    let out = dir.join("run");
    fast_run(&out, &[], &[]);
    let h = hash(&out);
    let config = String::from_utf8(read(&out, "config.toml")).unwrap();
    assert!(config.contains("precision = \"fast\""), "{config}");
    let _ = std::fs::remove_dir_all(&dir);
    assert_ne!(h, PINNED_EXACT, "fast precision computed the exact bits");
    assert_eq!(
        h, PINNED_FAST,
        "the fast short run's outputs hash to {h:#018x}, the repository pins {PINNED_FAST:#018x}"
    );
}

#[test]
fn fast_short_run_is_bit_identical_at_every_simd_level_thread_count_and_old_cpu_path() {
    let dir = scratch("fast-levels");
    let variants: [(&str, &[Pair], &[Pair]); 4] = [
        (
            "scalar-1",
            &[("--threads", "1")],
            &[("VIVAE_SIMD", "scalar")],
        ),
        ("avx2-2", &[("--threads", "2")], &[("VIVAE_SIMD", "avx2")]),
        (
            "avx512-3",
            &[("--threads", "3")],
            &[("VIVAE_SIMD", "avx512")],
        ),
        (
            "old-cpu",
            &[],
            &[("GLIBC_TUNABLES", "glibc.cpu.hwcaps=-AVX2,-FMA")],
        ),
    ];
    for (name, flags, env) in variants {
        fast_run(&dir.join(name), flags, env);
    }
    for (name, _, _) in &variants[1..] {
        for file in DETERMINISTIC_FILES {
            assert!(
                read(&dir.join("scalar-1"), file) == read(&dir.join(name), file),
                "{file} of the fast run differs between scalar on 1 thread and {name}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `vivae resume DIR --precision P`: its exit code and stderr.
fn resume(dir: &Path, precision: &str) -> (Option<i32>, String) {
    let out = common::run(
        common::vivae()
            .args(["resume", "-q", "--generations", "3"])
            .arg(dir)
            .args(["--precision", precision]),
    );
    (out.status.code(), String::from_utf8(out.stderr).unwrap())
}

#[test]
fn resuming_in_the_other_precision_exits_2_with_one_line() {
    let dir = scratch("precision-resume");
    for (precision, other) in [("exact", "fast"), ("fast", "exact")] {
        let out = dir.join(precision);
        let mut cmd = common::vivae();
        cmd.args(["evolve", "-q", "--generations", "2", "--population", "10"])
            .args(["--steps", "50", "--precision", precision, "--out"])
            .arg(&out);
        common::ok(&mut cmd);
        let checkpoint = std::fs::read_dir(out.join("checkpoints"))
            .unwrap()
            .map(|e| std::fs::read_to_string(e.unwrap().path()).unwrap())
            .next()
            .unwrap();
        // Exact checkpoints are written as before the switch existed.
        assert_eq!(checkpoint.contains("\"precision\""), precision == "fast");
        let before = read(&out, "generations.csv");
        let (code, stderr) = resume(&out, other);
        assert_eq!(code, Some(2), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr.contains(&format!("computes in {precision} precision")),
            "{stderr}"
        );
        assert_eq!(read(&out, "generations.csv"), before, "nothing changed");
        let (code, stderr) = resume(&out, precision);
        assert_eq!(code, Some(0), "{stderr}");
        assert_ne!(read(&out, "generations.csv"), before, "resumed");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fast_precision_where_it_has_no_fast_step_exits_2_with_one_line() {
    let dir = scratch("precision-refused");
    for extra in [["--substrate", "es-hyperneat"], ["--task", "maze"]] {
        let out = common::run(
            common::vivae()
                .args(["evolve", "-q", "--generations", "1", "--precision", "fast"])
                .args(extra)
                .arg("--out")
                .arg(dir.join(extra[1])),
        );
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains("precision"), "{stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `vivae replay DIR [--precision P]`'s fitness, as printed.
fn replay_fitness(dir: &Path, precision: Option<&str>) -> String {
    let mut cmd = common::vivae();
    cmd.arg("replay")
        .arg(dir)
        .arg("--out")
        .arg(dir.join("replay"));
    if let Some(p) = precision {
        cmd.args(["--precision", p]);
    }
    let out = common::run(&mut cmd);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    let field = stdout
        .split_whitespace()
        .find(|f| f.starts_with("fitness="));
    field.expect("a fitness= field").to_string()
}

#[test]
fn a_champion_replays_in_either_precision() {
    let dir = scratch("precision-replay");
    let out = dir.join("fast");
    let mut cmd = common::vivae();
    cmd.args(["evolve", "-q", "--generations", "2", "--population", "10"])
        .args(["--steps", "300", "--precision", "fast", "--out"])
        .arg(&out);
    common::ok(&mut cmd);
    let own = replay_fitness(&out, None);
    assert_eq!(
        own,
        replay_fitness(&out, Some("fast")),
        "the run's precision"
    );
    let exact = replay_fitness(&out, Some("exact"));
    assert_ne!(own, exact, "re-scored in exact precision: other arithmetic");
    let _ = std::fs::remove_dir_all(&dir);
}
