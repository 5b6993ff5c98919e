//! The exported C keeps vivae's bits under any optimisation short of
//! fast-math: the dense controller (exact and fast) and an ES-HyperNEAT
//! one, compiled by gcc at `-O0`, `-O2` and `-O3 -march=native` (GNU C, no
//! `-ffp-contract` flag: GCC contracts multiply-adds there unless the file
//! stops it), and by clang at `-O3 -march=native` where it is installed,
//! give vivae's wheel commands to the bit at every step of recorded
//! episodes and of random and extreme readings (NaN, ±∞, out of range,
//! subnormal) with the state carried; and `-ffast-math` is a compile error
//! that says why.

use std::path::{Path, PathBuf};
use std::process::Command;

use vivae_lab::controller::es::RobotController;
use vivae_lab::export::choose::{Chosen, Pick, choose};
use vivae_lab::export::frames::record;
use vivae_lab::export::{Exported, Format, reading, write};
use vivae_lab::tasks::driving::rollout::Drive;
use vivae_neat::Precision;

use crate::common::*;

/// A small run of `extra` config keys in `dir/name`.
fn run(dir: &Path, name: &str, extra: &str) -> PathBuf {
    let config = dir.join(format!("{name}.toml"));
    std::fs::write(&config, format!("{}{extra}", small_config(3))).unwrap();
    let out = dir.join(name);
    evolve(&config, &out, &[]);
    out
}

/// A harness around the exported step: readings in as hex bit patterns
/// (`double`s, or `float`s for a fast controller), a line a step; every
/// output's bits out (a robot's two: its wheel commands).
const HARNESS: &str = r#"#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include "controller.h"

static void put(vivae_real v) {
#if VIVAE_FAST
    uint32_t b;
#else
    uint64_t b;
#endif
    memcpy(&b, &v, sizeof b);
    printf(" %llx", (unsigned long long)b);
}

int main(void) {
    vivae_real in[VIVAE_INPUTS], state[VIVAE_STATE], out[VIVAE_OUTPUTS];
    memset(state, 0, sizeof state);
    for (;;) {
        for (int i = 0; i < VIVAE_INPUTS; i++) {
            unsigned long long b;
            if (scanf("%llx", &b) != 1)
                return 0;
#if VIVAE_FAST
            uint32_t w = (uint32_t)b;
#else
            uint64_t w = (uint64_t)b;
#endif
            memcpy(&in[i], &w, sizeof w);
        }
        vivae_step(in, state, out);
        for (int o = 0; o < VIVAE_OUTPUTS; o++)
            put(out[o]);
        printf("\n");
    }
}
"#;

/// Readings for `steps` steps of `ni` inputs: mostly in the sensors' range,
/// with every kind of extreme mixed in (a reading's kind persists for a
/// while, as a broken sensor's would).
fn hostile_readings(ni: usize, steps: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut state = seed | 1;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let mut kinds = vec![0u64; ni];
    (0..steps)
        .map(|_| {
            (0..ni)
                .map(|i| {
                    if next() % 16 == 0 {
                        kinds[i] = next() % 20;
                    }
                    let u = (next() >> 11) as f64 / (1u64 << 53) as f64;
                    match kinds[i] {
                        0..=7 => u,
                        8 => f64::NAN,
                        9 => f64::from_bits(0xfff8_0000_0000_0001), // negative NaN with a payload
                        10 => f64::INFINITY,
                        11 => f64::NEG_INFINITY,
                        12 => -u * 1e300,
                        13 => 1.0 + u * 1e300,
                        14 => [0.0, -0.0, 1.0, 1.0 - f64::EPSILON / 2.0][next() as usize % 4],
                        15 => f64::from_bits(next() % (1 << 52)), // subnormal
                        16 => f64::from_bits(next()),             // any bits
                        17 => -u,
                        _ => 1.0 + u,
                    }
                })
                .collect()
        })
        .collect()
}

/// vivae's wheel commands for `readings`, each read as [`reading`] of it,
/// the state carried: the controller stepped as the simulator steps it.
fn vivae_steps(chosen: &Chosen, readings: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let c: &RobotController = &chosen.controller;
    let no = c.num_outputs();
    let wheels = c.wheel_outputs().unwrap_or(chosen.episode.wheels());
    let mut states = c.robot_states(1);
    let (mut outputs, mut wide) = (vec![0.0; no], vec![0.0; c.num_inputs()]);
    readings
        .iter()
        .map(|x| {
            let x: Vec<f64> = x.iter().map(|&v| reading(v)).collect();
            if c.single_inputs() {
                let single: Vec<f32> = x.iter().map(|&v| v as f32).collect();
                c.step_robots_single(&mut states, &single, &mut wide, &mut outputs);
            } else {
                c.step_robots(&mut states, &x, &mut outputs);
            }
            let out = states.outputs(&outputs, no, 0);
            vec![out[wheels.left], out[wheels.right]]
        })
        .collect()
}

/// `readings` as the harness reads them: each value's bits (a fast
/// controller's rounded to f32 first).
fn harness_input(readings: &[Vec<f64>], fast: bool) -> String {
    let mut s = String::new();
    for x in readings {
        let line: Vec<String> = (x.iter())
            .map(|&v| {
                if fast {
                    format!("{:x}", (v as f32).to_bits())
                } else {
                    format!("{:x}", v.to_bits())
                }
            })
            .collect();
        s.push_str(&line.join(" "));
        s.push('\n');
    }
    s
}

/// The outputs `exe` gives for `input` (from [`harness_input`]), widened to f64.
fn harness_outputs(exe: &Path, input: &Path, fast: bool) -> Vec<Vec<f64>> {
    let out = Command::new(exe)
        .stdin(std::fs::File::open(input).unwrap())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let value = |t: &str| {
        let b = u64::from_str_radix(t, 16).unwrap();
        if fast {
            f64::from(f32::from_bits(b as u32))
        } else {
            f64::from_bits(b)
        }
    };
    (String::from_utf8(out.stdout).unwrap().lines())
        .map(|l| l.split_whitespace().map(value).collect())
        .collect()
}

/// Steps whose outputs all have vivae's bits (a NaN is never vivae's).
fn equal_steps(got: &[Vec<f64>], want: &[Vec<f64>]) -> usize {
    assert_eq!(got.len(), want.len());
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    (got.iter().zip(want))
        .filter(|(g, w)| bits(g) == bits(w))
        .count()
}

/// The compilers and flags to check: gcc always, clang where it is installed
/// (required with `VIVAE_REQUIRE_CLANG=1`, as `.ci/run` sets after installing it).
fn compilers() -> Vec<(&'static str, Vec<&'static str>)> {
    let mut out = vec![
        ("gcc", vec!["-O0"]),
        ("gcc", vec!["-O2"]),
        ("gcc", vec!["-O3", "-march=native"]),
    ];
    let clang = Command::new("clang").arg("--version").output();
    if clang.is_ok_and(|o| o.status.success()) {
        out.push(("clang", vec!["-O3", "-march=native"]));
    } else if std::env::var_os("VIVAE_REQUIRE_CLANG").is_some_and(|v| v == "1") {
        panic!("VIVAE_REQUIRE_CLANG=1 but clang is not on PATH");
    } else {
        println!("clang is not on PATH: the exported C is checked with gcc only");
    }
    out
}

/// Exports `chosen` as C into `dir`, compiles it with every compiler and
/// flag set, and returns (what, steps equal, steps) for recorded episodes
/// and hostile readings; vivae's bits are `recorded` and [`vivae_steps`].
fn check(
    dir: &Path,
    name: &str,
    chosen: &Chosen,
    recorded: &[Recording],
) -> Vec<(String, usize, usize)> {
    let dir = dir.join(name);
    std::fs::create_dir_all(&dir).unwrap();
    let exported = Exported::new(&chosen.episode, &chosen.controller, name);
    let fast = exported.net.precision == Precision::Fast;
    write(&exported, Format::C, &dir.join("controller.c")).unwrap();
    std::fs::write(dir.join("harness.c"), HARNESS).unwrap();
    let ni = exported.net.inputs;
    // Hostile readings: several sequences, each from a zero state.
    let hostile: Vec<Vec<Vec<f64>>> = (1..=3).map(|s| hostile_readings(ni, 1500, s)).collect();
    let mut cases: Vec<(String, PathBuf, Vec<Vec<f64>>)> = Vec::new();
    for (k, (readings, wheels)) in recorded.iter().enumerate() {
        let input = dir.join(format!("recorded{k}.txt"));
        std::fs::write(&input, harness_input(readings, fast)).unwrap();
        // The recorded readings are the simulator's: already in [0, 1].
        assert!(
            readings
                .iter()
                .flatten()
                .all(|&v| reading(v).to_bits() == v.to_bits())
        );
        cases.push(("recorded".into(), input, wheels.clone()));
    }
    for (k, readings) in hostile.iter().enumerate() {
        let input = dir.join(format!("hostile{k}.txt"));
        std::fs::write(&input, harness_input(readings, fast)).unwrap();
        cases.push(("hostile".into(), input, vivae_steps(chosen, readings)));
    }
    let mut results = Vec::new();
    without_the_pragma_gcc_contracts(&dir, fast, &cases);
    for (cc, flags) in compilers() {
        let exe = dir.join(format!("drive-{cc}{}", flags.join("")));
        let status = Command::new(cc)
            .args(["-Wall", "-Wextra", "-Werror", "-o"])
            .arg(&exe)
            .args(&flags)
            .arg(dir.join("harness.c"))
            .arg(dir.join("controller.c"))
            .status()
            .expect("the C compiler runs");
        assert!(status.success(), "{cc} {flags:?} compiles {name}");
        for what in ["recorded", "hostile"] {
            let (mut equal, mut steps) = (0, 0);
            for (_, input, want) in cases.iter().filter(|c| c.0 == what) {
                let got = harness_outputs(&exe, input, fast);
                assert!(
                    got.iter().flatten().all(|v| v.is_finite()),
                    "a NaN or infinite reading made the wheels non-finite"
                );
                equal += equal_steps(&got, want);
                steps += want.len();
            }
            let label = format!("{name}, {cc} {}, {what}", flags.join(" "));
            println!("{label}: {equal} of {steps} steps bit-equal to vivae");
            results.push((label, equal, steps));
        }
    }
    results
}

/// The file with GCC's pragma taken out, at `gcc -O3 -march=native`: where
/// the CPU has FMA, GCC contracts multiply-adds and some steps lose vivae's
/// bits (so the comparison above would see it if the pragma stopped working).
fn without_the_pragma_gcc_contracts(
    dir: &Path,
    fast: bool,
    cases: &[(String, PathBuf, Vec<Vec<f64>>)],
) {
    let source = std::fs::read_to_string(dir.join("controller.c")).unwrap();
    let pragma = "#pragma GCC optimize(\"fp-contract=off\")";
    assert!(source.contains(pragma));
    std::fs::write(dir.join("bare.c"), source.replace(pragma, "")).unwrap();
    let flags = ["-O3", "-march=native"];
    let asm = Command::new("gcc")
        .args(flags)
        .args(["-S", "-o", "-"])
        .arg(dir.join("bare.c"))
        .output()
        .expect("gcc runs");
    let fused = String::from_utf8_lossy(&asm.stdout)
        .matches("vfmadd")
        .count();
    if fused == 0 {
        println!(
            "gcc -O3 -march=native fuses nothing on this CPU: the pragma is not put to the test"
        );
        return;
    }
    let exe = dir.join("bare");
    let status = Command::new("gcc")
        .args(flags)
        .arg("-o")
        .arg(&exe)
        .arg(dir.join("harness.c"))
        .arg(dir.join("bare.c"))
        .status()
        .unwrap();
    assert!(status.success());
    let (mut equal, mut steps) = (0, 0);
    for (_, input, want) in cases {
        equal += equal_steps(&harness_outputs(&exe, input, fast), want);
        steps += want.len();
    }
    println!(
        "without the pragma, gcc -O3 -march=native: {fused} fused multiply-adds, \
         {equal} of {steps} steps bit-equal to vivae"
    );
    // The exact step's f64 sums and exp certainly change when fused; the
    // fast one's might by chance not (its sums are fused already).
    assert!(
        fast || equal < steps,
        "the contracted build should lose vivae's bits somewhere"
    );
}

/// One recorded episode: its readings and its outputs (a robot's: its
/// wheel commands), a step each.
type Recording = (Vec<Vec<f64>>, Vec<Vec<f64>>);

/// `robots` recorded episodes of `chosen`, `steps` long: (readings, wheels).
fn recordings(chosen: &Chosen, steps: u32) -> Vec<Recording> {
    (0..chosen.episode.robots())
        .map(|robot| {
            let rec = record(&chosen.episode, &chosen.controller, robot, steps).unwrap();
            let readings = rec.sensors.chunks_exact(rec.inputs).map(<[f64]>::to_vec);
            (
                readings.collect(),
                rec.wheels.iter().map(|w| w.to_vec()).collect(),
            )
        })
        .collect()
}

#[test]
fn exported_c_gives_vivaes_bits_at_every_optimisation_level() {
    let dir = scratch("export-flags");
    let dense = run(&dir, "dense", "");
    let es = run(&dir, "es", "\n[substrate]\nkind = \"es-hyperneat\"\n");
    let pick = |run: &Path, p| choose(run, Pick::Champion, None, None, p).unwrap();
    let mut results = Vec::new();
    for (name, chosen) in [
        ("dense exact", pick(&dense, None)),
        ("dense fast", pick(&dense, Some(Precision::Fast))),
        ("es", pick(&es, None)),
    ] {
        let recorded = recordings(&chosen, 1000);
        results.extend(check(&dir, name, &chosen, &recorded));
    }
    let total: usize = results.iter().map(|r| r.2).sum();
    assert!(total >= 3 * 3 * 4500, "{total} steps compared");
    for (label, equal, steps) in &results {
        assert_eq!(equal, steps, "{label}: {equal} of {steps} steps bit-equal");
    }
}

#[test]
fn fast_math_is_a_compile_error_that_says_why() {
    let dir = scratch("export-fast-math");
    let dense = run(&dir, "dense", "");
    let c = dir.join("controller.c");
    for precision in ["exact", "fast"] {
        ok(vivae()
            .arg("export")
            .arg(&dense)
            .args(["--format", "c", "--precision", precision, "-o"])
            .arg(&c));
        for (flag, says) in [
            ("-ffast-math", "-ffast-math"),
            ("-Ofast", "-ffast-math"),
            ("-ffinite-math-only", "NaN"),
            ("-fassociative-math", "reorders"),
        ] {
            let out = Command::new("gcc")
                .args(["-c", "-O2", "-fno-signed-zeros", "-fno-trapping-math", flag])
                .arg(&c)
                .arg("-o")
                .arg(dir.join("controller.o"))
                .output()
                .expect("gcc runs");
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success(), "{precision}, {flag}: compiled");
            assert!(
                err.contains("#error") && err.contains(says) && err.contains("vivae's bits"),
                "{precision}, {flag}: {err}"
            );
        }
        // Without them it compiles, warning-free.
        let out = Command::new("gcc")
            .args(["-c", "-O2", "-Wall", "-Wextra", "-Werror"])
            .arg(&c)
            .arg("-o")
            .arg(dir.join("controller.o"))
            .output()
            .expect("gcc runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// A replay's `episode.csv` of a plain task: each step's inputs and the
/// network's outputs (`outputs` of them), as vivae's own network computed them.
fn plain_episode(csv: &str, outputs: usize) -> Recording {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let ins: Vec<usize> = (0..header.len())
        .filter(|&i| header[i].starts_with("in"))
        .collect();
    let outs: Vec<usize> = (0..header.len())
        .filter(|&i| header[i].starts_with("out"))
        .collect();
    assert_eq!(outs.len(), outputs, "{header:?}");
    let (mut readings, mut want) = (Vec::new(), Vec::new());
    for line in lines {
        // Rust writes each f64 in the shortest text that reads back to its bits.
        let v: Vec<f64> = line.split(',').map(|t| t.parse().unwrap()).collect();
        readings.push(ins.iter().map(|&i| v[i]).collect());
        want.push(outs.iter().map(|&i| v[i]).collect());
    }
    (readings, want)
}

/// A classic-control network reads raw observations (a position or a
/// velocity leaves [0, 1]): its task declares them unbounded, and the
/// exported step, and the C file under every compiler and flag set above,
/// give vivae's own network's outputs to the bit on the task's recorded
/// episode (the replay's `episode.csv`), whatever their number: CartPole's
/// two, Acrobot's three, Pendulum's one.
#[test]
fn an_exported_classic_control_network_reads_its_observations_unclamped() {
    for (task, generations, outputs) in [("cartpole", 4, 2), ("acrobot", 2, 3), ("pendulum", 2, 1)]
    {
        classic_network_keeps_its_bits(task, generations, outputs);
    }
}

/// [`an_exported_classic_control_network_reads_its_observations_unclamped`] for `task`.
fn classic_network_keeps_its_bits(task: &str, generations: u32, outputs: usize) {
    let dir = scratch(&format!("export-{task}"));
    let out = dir.join("run");
    ok(vivae()
        .args(["evolve", "-q", "--task", task, "--seed", "1"])
        .args(["--generations", &generations.to_string(), "--out"])
        .arg(&out));
    ok(vivae().arg("replay").arg(&out));
    let csv = std::fs::read_to_string(out.join("replay/episode.csv")).unwrap();
    let (readings, want) = plain_episode(&csv, outputs);
    assert!(want.len() >= 20, "{task}: {} steps recorded", want.len());
    // The test can tell: observations leave the sensors' range.
    assert!(readings.iter().flatten().any(|&v| v < 0.0));
    assert!(readings.iter().flatten().any(|&v| reading(v) != v));
    let exported = vivae_lab::export::choose::exported(&out, Pick::Champion, None, None, None)
        .expect("a classic-control champion exports");
    assert_eq!(
        exported.net.readings,
        vivae_lab::export::Readings::UNBOUNDED
    );
    assert_eq!(exported.net.outputs.len(), outputs, "{task}");
    let stepped = steps_of(&exported.net, &readings);
    let equal = equal_steps(&stepped, &want);
    println!(
        "{task}, vivae's exported step: {equal} of {} steps bit-equal to vivae",
        want.len()
    );
    assert_eq!(equal, want.len(), "{task}: vivae's exported step");
    let c = dir.join("controller.c");
    ok(vivae()
        .arg("export")
        .arg(&out)
        .args(["--format", "c", "-o"])
        .arg(&c));
    let header = std::fs::read_to_string(dir.join("controller.h")).unwrap();
    assert!(
        header.contains(&format!("#define VIVAE_OUTPUTS {outputs}\n")),
        "{header}"
    );
    std::fs::write(dir.join("harness.c"), HARNESS).unwrap();
    let input = dir.join("recorded.txt");
    std::fs::write(&input, harness_input(&readings, false)).unwrap();
    // Hostile readings (NaN, ±∞, ±1e300, any bits) against the exported step:
    // a sum may overflow there, and a NaN state must then be NaN in C too.
    let hostile = hostile_readings(exported.net.inputs, 1500, 5);
    let hostile_input = dir.join("hostile.txt");
    std::fs::write(&hostile_input, harness_input(&hostile, false)).unwrap();
    let hostile_want = steps_of(&exported.net, &hostile);
    let same = |a: &[Vec<f64>], b: &[Vec<f64>]| {
        a.len() == b.len()
            && (a.iter().flatten().zip(b.iter().flatten()))
                .all(|(x, y)| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()))
    };
    for (cc, flags) in compilers() {
        let exe = dir.join(format!("{task}-{cc}{}", flags.join("")));
        let status = Command::new(cc)
            .args(["-Wall", "-Wextra", "-Werror", "-o"])
            .arg(&exe)
            .args(&flags)
            .arg(dir.join("harness.c"))
            .arg(&c)
            .status()
            .expect("the C compiler runs");
        assert!(
            status.success(),
            "{cc} {flags:?} compiles the {task} network"
        );
        let got = harness_outputs(&exe, &input, false);
        assert!(got.iter().all(|o| o.len() == outputs));
        let equal = equal_steps(&got, &want);
        println!(
            "{task}, {cc} {}: {equal} of {} steps bit-equal to vivae",
            flags.join(" "),
            want.len()
        );
        assert_eq!(equal, want.len(), "{task}, {cc} {flags:?}");
        let got = harness_outputs(&exe, &hostile_input, false);
        assert!(
            same(&got, &hostile_want),
            "{task}, {cc} {flags:?}: hostile readings"
        );
    }
}

/// The exported step's outputs for `readings`, from a zero state, the state carried.
fn steps_of(net: &vivae_lab::export::StepNet, readings: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let (mut state, mut scratch) = (vec![0.0; net.nodes], vec![0.0; net.nodes]);
    (readings.iter())
        .map(|x| {
            let mut o = vec![0.0; net.outputs.len()];
            net.step(x, &mut state, &mut scratch, &mut o);
            o
        })
        .collect()
}
