//! `vivae export --format c` runs as vivae does: the guide's C example,
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

/// The guide's C example (between its `c-example` markers).
fn guide_example() -> String {
    let guide =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/guide.md"))
            .unwrap();
    let start = guide
        .find("<!-- c-example -->\n```c\n")
        .expect("the guide's C example")
        + 24;
    let end = start + guide[start..].find("```\n<!-- /c-example -->").unwrap();
    guide[start..end].to_string()
}

/// A small run of `config_text` (plus the small config's keys) in `dir/name`.
fn run_of(dir: &Path, name: &str, config_text: &str) -> PathBuf {
    let config = dir.join(format!("{name}.toml"));
    std::fs::write(&config, format!("{}{config_text}", small_config(3))).unwrap();
    let out = dir.join(name);
    evolve(&config, &out, &[]);
    out
}

/// Exports `run` as C (with `extra` flags) and builds the guide's example with it.
fn build_c(dir: &Path, run: &Path, extra: &[&str]) -> PathBuf {
    let c = dir.join("controller.c");
    ok(vivae()
        .arg("export")
        .arg(run)
        .args(["--format", "c", "-o"])
        .arg(&c)
        .args(extra));
    std::fs::write(dir.join("drive.c"), guide_example()).unwrap();
    let exe = dir.join("drive");
    let status = Command::new("cc")
        .args([
            "-std=c99",
            "-O2",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-ffp-contract=off",
            "-o",
        ])
        .arg(&exe)
        .arg(dir.join("drive.c"))
        .arg(&c)
        .status()
        .expect("cc (the C compiler Rust links with) runs");
    assert!(
        status.success(),
        "the exported C file and the guide's example compile"
    );
    exe
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
    let grid = |g: Option<&str>| g.map(|g| g.parse::<PolarGrid>().unwrap());
    let chosen = choose(run, Pick::Champion, grid(sensors), grid(neurons)).unwrap();
    let rec = record(&chosen.episode, &chosen.controller, 1, 300).unwrap();
    let mut extra = Vec::new();
    for (flag, v) in [("--sensors", sensors), ("--neurons", neurons)] {
        if let Some(v) = v {
            extra.extend([flag, v]);
        }
    }
    let exe = build_c(dir, run, &extra);
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
fn an_es_hyperneat_champion_exports_to_c_bit_for_bit() {
    let dir = scratch("export-es");
    let run = run_of(&dir, "es", "\n[substrate]\nkind = \"es-hyperneat\"\n");
    c_matches(&dir, &run, None, None);
    c_matches(&dir, &run, Some("3x8"), None);
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
