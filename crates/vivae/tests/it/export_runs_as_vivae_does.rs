//! `vivae export --format c` runs as vivae does: the how-to's C example,
//! compiled with the exported file, replays recorded episodes with vivae's
//! wheel commands to the last bit — a dense run, a 360° run re-sampled, an
//! ES-HyperNEAT run; and `vivae drive-image` on frames drawn from the
//! simulator drives as the simulator's sensors do.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use vivae_lab::controller::substrate::PolarGrid;
use vivae_lab::export::choose::{Pick, choose};
use vivae_lab::export::frames::{Recording, record};

use crate::common::*;

/// The C example of docs/howto/export-to-a-robot.md (between its `c-example` markers).
fn guide_example() -> String {
    let guide = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/howto/export-to-a-robot.md"
    ))
    .unwrap();
    let start = guide
        .find("<!-- c-example -->\n```c\n")
        .expect("the how-to's C example")
        + 24;
    let end = start + guide[start..].find("```\n<!-- /c-example -->").unwrap();
    guide[start..end].to_string()
}

/// A small run of `config_text` (plus the small config's keys) in `dir/name`.
fn run_of(dir: &Path, name: &str, config_text: &str) -> PathBuf {
    run_with(dir, name, config_text, &[])
}

/// [`run_of`] with `extra` flags to `vivae evolve`.
fn run_with(dir: &Path, name: &str, config_text: &str, extra: &[&str]) -> PathBuf {
    let config = dir.join(format!("{name}.toml"));
    std::fs::write(&config, format!("{}{config_text}", small_config(3))).unwrap();
    let out = dir.join(name);
    evolve(&config, &out, extra);
    out
}

/// Exports `run` as C (with `extra` flags) and builds the guide's example
/// with it, with `cflags` (and then libm) for the compiler.
fn build_c_with(dir: &Path, run: &Path, extra: &[&str], cflags: &[&str]) -> PathBuf {
    let c = dir.join("controller.c");
    ok(vivae()
        .arg("export")
        .arg(run)
        .args(["--format", "c", "-o"])
        .arg(&c)
        .args(extra));
    std::fs::write(dir.join("drive.c"), guide_example()).unwrap();
    let exe = dir.join("drive");
    let libm: &[&str] = if cflags.is_empty() { &[] } else { &["-lm"] };
    let sources = [dir.join("drive.c"), c];
    assert!(
        cc(&exe, cflags, &sources, libm),
        "the exported C file and the guide's example compile"
    );
    exe
}

/// Compiles `sources` into `exe` with `cc` (the C compiler Rust links
/// with) as C99, warnings as errors and no FMA contraction, plus `cflags`
/// and then `libs`; whether it succeeded.
fn cc(exe: &Path, cflags: &[&str], sources: &[PathBuf], libs: &[&str]) -> bool {
    Command::new("cc")
        .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror"])
        .args(["-ffp-contract=off", "-o"])
        .arg(exe)
        .args(cflags)
        .args(sources)
        .args(libs)
        .status()
        .expect("cc runs")
        .success()
}

/// The wheel commands `exe` prints for `rec`'s inputs, one line a step.
fn drive(exe: &Path, rec: &Recording) -> Vec<[f64; 2]> {
    let mut input = String::new();
    for step in rec.sensors.chunks_exact(rec.inputs) {
        let line: Vec<String> = step.iter().map(|v| format!("{v:e}")).collect();
        input.push_str(&line.join(" "));
        input.push('\n');
    }
    let mut child = Command::new(exe)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    text.lines()
        .map(|l| {
            let v: Vec<f64> = l.split(' ').map(|t| t.parse().unwrap()).collect();
            [v[0], v[1]]
        })
        .collect()
}

/// Records robot 1 of `run`'s episode at the resolution given, exports it as
/// C, runs it and asserts every step's wheel commands equal vivae's bits.
fn c_matches(dir: &Path, run: &Path, sensors: Option<&str>, neurons: Option<&str>) -> usize {
    c_matches_in(dir, run, (sensors, neurons), None, &[])
}

/// [`c_matches`] in `precision` (default: the run's), the C compiled with `cflags`.
fn c_matches_in(
    dir: &Path,
    run: &Path,
    (sensors, neurons): (Option<&str>, Option<&str>),
    precision: Option<&str>,
    cflags: &[&str],
) -> usize {
    let grid = |g: Option<&str>| g.map(|g| g.parse::<PolarGrid>().unwrap());
    let p = precision.map(|p| p.parse().unwrap());
    let chosen = choose(run, Pick::Champion, grid(sensors), grid(neurons), p).unwrap();
    let rec = record(&chosen.episode, &chosen.controller, 1, 300).unwrap();
    let mut extra = Vec::new();
    for (flag, v) in [
        ("--sensors", sensors),
        ("--neurons", neurons),
        ("--precision", precision),
    ] {
        if let Some(v) = v {
            extra.extend([flag, v]);
        }
    }
    let exe = build_c_with(dir, run, &extra, cflags);
    let got = drive(&exe, &rec);
    assert_eq!(got.len(), rec.wheels.len());
    for (t, (g, w)) in got.iter().zip(&rec.wheels).enumerate() {
        assert_eq!(
            g.map(f64::to_bits),
            w.map(f64::to_bits),
            "step {t}: C {g:?}, vivae {w:?}"
        );
    }
    // A controller that never turns would make the comparison weak.
    let turning = rec.wheels.iter().filter(|w| w[0] != w[1]).count();
    assert!(turning > 0, "the recorded wheels never differ");
    rec.wheels.len()
}

#[test]
fn the_guides_c_example_drives_an_exported_champion() {
    let dir = scratch("export-c");
    let run = run_of(&dir, "dense", "");
    assert_eq!(c_matches(&dir, &run, None, None), 300);
    assert_eq!(c_matches(&dir, &run, Some("8x16"), Some("5x5")), 300);
}

#[test]
fn a_fast_champion_exports_to_float_c_bit_for_bit() {
    let dir = scratch("export-fast");
    let run = run_with(&dir, "fast", "", &["--precision", "fast"]);
    let header = |dir: &Path| std::fs::read_to_string(dir.join("controller.h")).unwrap();
    // The run's precision by default; the portable fused multiply-add, then the C library's.
    assert_eq!(c_matches(&dir, &run, None, None), 300);
    assert!(header(&dir).contains("typedef float vivae_real;"));
    c_matches_in(&dir, &run, (None, None), None, &["-DVIVAE_USE_FMAF"]);
    c_matches_in(&dir, &run, (Some("8x16"), Some("5x5")), None, &[]);
    // An exact run's champion decoded and exported in f32, and a fast one's in f64.
    let exact = run_of(&dir, "exact", "");
    c_matches_in(&dir, &exact, (None, None), Some("fast"), &[]);
    assert!(header(&dir).contains("#define VIVAE_FAST 1"));
    c_matches_in(&dir, &run, (None, None), Some("exact"), &[]);
    assert!(header(&dir).contains("typedef double vivae_real;"));
}

#[test]
fn the_exported_fused_multiply_add_rounds_as_vivaes() {
    // The portable C `vivae_fmaf` against vivae's `fma_f32` where a double
    // sum's rounding to float needs the tie-break: products that land the
    // sum on a float midpoint, and random bit patterns (overflow, NaN).
    let dir = scratch("export-fmaf");
    let harness = format!(
        "#include <stdint.h>\n#include <stdio.h>\n#include <string.h>\n{}\n\
         static float f(uint32_t b) {{ float v; memcpy(&v, &b, sizeof v); return v; }}\n\
         int main(void) {{\n    unsigned x, y, z;\n    \
         while (scanf(\"%x %x %x\", &x, &y, &z) == 3) {{\n        \
         float r = vivae_fmaf(f(x), f(y), f(z));\n        uint32_t b;\n        \
         memcpy(&b, &r, sizeof b);\n        printf(\"%08x\\n\", (unsigned)b);\n    }}\n    \
         return 0;\n}}\n",
        vivae_lab::export::c::fmaf_function()
    );
    std::fs::write(dir.join("fmaf.c"), harness).unwrap();
    let exe = dir.join("fmaf");
    assert!(
        cc(&exe, &[], &[dir.join("fmaf.c")], &[]),
        "the harness compiles"
    );
    let mut cases: Vec<[f32; 3]> = Vec::new();
    for k in 12..=23 {
        let small = 2f32.powi(-k);
        for bits in (0x3f80_0000u32..0x3f80_0000 + 64).chain(0x3fff_ffc0..0x4000_0000) {
            for e in [-30, 0, 60] {
                let z = f32::from_bits(bits) * 2f32.powi(e);
                let unit = 2f32.powi(e - 24);
                for (a, b) in [(1.0 + small, 1.0 - small), (1.0 + small, 1.0 + small)] {
                    for sign in [1.0f32, -1.0] {
                        cases.push([a * unit * sign, b, z]);
                        cases.push([a * unit * sign, b, -z]);
                    }
                }
            }
        }
    }
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    for _ in 0..20_000 {
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            f32::from_bits(state as u32)
        };
        cases.push([next(), next(), next()]);
    }
    cases.push([f32::MAX, 2.0, -f32::MAX]);
    cases.push([f32::MAX, 1.5, 0.0]);
    let input: String = (cases.iter())
        .map(|c| {
            format!(
                "{:x} {:x} {:x}\n",
                c[0].to_bits(),
                c[1].to_bits(),
                c[2].to_bits()
            )
        })
        .collect();
    // From a file: writing more than a pipe holds while the harness's
    // answers fill the other pipe would block both.
    std::fs::write(dir.join("cases.txt"), input).unwrap();
    let out = Command::new(&exe)
        .stdin(std::fs::File::open(dir.join("cases.txt")).unwrap())
        .output()
        .unwrap();
    assert!(out.status.success());
    let got: Vec<u32> = (String::from_utf8(out.stdout).unwrap().lines())
        .map(|l| u32::from_str_radix(l, 16).unwrap())
        .collect();
    assert_eq!(got.len(), cases.len());
    let mut midpoints = 0;
    for (c, &g) in cases.iter().zip(&got) {
        let want = vivae_neat::precision::fma_f32(c[0], c[1], c[2]);
        let g = f32::from_bits(g);
        assert!(
            g.to_bits() == want.to_bits() || (g.is_nan() && want.is_nan()),
            "vivae_fmaf({:e}, {:e}, {:e}) = {g:e}, vivae's {want:e}",
            c[0],
            c[1],
            c[2]
        );
        let naive = (f64::from(c[0]) * f64::from(c[1]) + f64::from(c[2])) as f32;
        midpoints += usize::from(naive.to_bits() != want.to_bits() && !want.is_nan());
    }
    // The tie-break path ran, and mattered.
    assert!(midpoints > 100, "{midpoints} double roundings");
}

#[test]
fn an_es_hyperneat_champion_exports_to_c_bit_for_bit() {
    let dir = scratch("export-es");
    let run = run_of(&dir, "es", "\n[substrate]\nkind = \"es-hyperneat\"\n");
    c_matches(&dir, &run, None, None);
    c_matches(&dir, &run, Some("3x8"), None);
    // Fast precision is the dense sheet's: refused in one line naming the run.
    let out = crate::common::run(
        vivae()
            .arg("export")
            .arg(&run)
            .args(["--precision", "fast", "--format", "c", "-o"])
            .arg(dir.join("fast.c")),
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains(&*run.to_string_lossy()) && err.contains("dense polar"),
        "{err}"
    );
    assert!(!dir.join("fast.c").exists());
}

#[test]
fn a_360_degree_run_evolves_resamples_and_exports() {
    let dir = scratch("export-360");
    let run = run_of(
        &dir,
        "omni",
        "\n[surface_sensors]\nfov = 360.0\nangles = 8\n",
    );
    let json = dir.join("omni.json");
    ok(vivae()
        .arg("export")
        .arg(&run)
        .args(["--format", "json", "--sensors", "4x24", "-o"])
        .arg(&json));
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let sheet = &doc["sheets"][0];
    assert_eq!(sheet["fov_deg"], 360.0);
    assert_eq!(sheet["places"].as_array().unwrap().len(), 4 * 24);
    assert_eq!(sheet["places"][0]["angle_deg"], -180.0);
    assert_eq!(sheet["places"][23]["angle_deg"], 180.0);
    c_matches(&dir, &run, Some("4x24"), Some("5x5"));
    // Re-sampled and drawn: the replay figure of the 360° sheet.
    let out = ok(vivae()
        .arg("replay")
        .arg(&run)
        .args(["--sensors", "4x24", "--steps", "100"]));
    assert!(out.contains("fitness="), "{out}");
    assert!(std::fs::read_dir(run.join("replay")).unwrap().count() > 0);
}
