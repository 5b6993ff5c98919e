//! A hostile round on the newest commands (tournament, drive-image,
//! reproduce, resume across tasks): genomes of the wrong shape, another
//! run's checkpoint, sizes and counts past their bounds. Each is refused
//! with exit code 2 and one line naming what is wrong, before anything
//! changes: no panic, abort, runaway allocation or destroyed run.

use std::path::Path;
use std::process::Command;

use crate::common::*;
use crate::every_task_keeps_the_interrupt_promise::snapshot;
use vivae::cli::drive_image::crc32;

/// A small finished predator–prey run of `generations` with `seed` in `out`.
fn pp_run(out: &Path, generations: u32, seed: u32) {
    ok(vivae()
        .args(["evolve", "-q", "--task", "predator-prey", "--threads", "1"])
        .args(["--population", "8", "--steps", "60"])
        .args(["--seed", &seed.to_string()])
        .args(["--generations", &generations.to_string()])
        .arg("--out")
        .arg(out));
}

/// Exit code 2 and one line holding every one of `needles`.
fn refused(cmd: &mut std::process::Command, needles: &[&str]) -> String {
    let out = run(cmd);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{needles:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    for n in needles {
        assert!(err.contains(n), "{n}: {err}");
    }
    err
}

/// A valid genome of one input and two outputs: no predator–prey side's shape.
const MISFIT: &str = r#"{"nodes":[{"id":0,"kind":"input","activation":"linear"},{"id":1,"kind":"output","activation":"linear"},{"id":2,"kind":"output","activation":"linear"}],"links":[{"innovation":0,"from":0,"to":1,"weight":0.5,"enabled":true}]}"#;

/// `text` with line `k` (0-based) of JSON changed by `edit`.
fn edit_line(text: &str, k: usize, edit: impl Fn(&mut serde_json::Value)) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut v: serde_json::Value = serde_json::from_str(&lines[k]).unwrap();
    edit(&mut v);
    lines[k] = v.to_string();
    lines.join("\n") + "\n"
}

#[test]
fn tournaments_refuse_genomes_of_the_wrong_shape_and_damaged_halls() {
    let dir = scratch("hostile-tournament");
    let a = dir.join("a");
    pp_run(&a, 2, 1);
    let hall = String::from_utf8(read(&a, "hall-of-fame.jsonl")).unwrap();
    let misfit: serde_json::Value = serde_json::from_str(MISFIT).unwrap();
    let copy = |name: &str, file: &str, text: &str| {
        let b = dir.join(name);
        let status = std::process::Command::new("cp")
            .arg("-a")
            .arg(&a)
            .arg(&b)
            .status();
        assert!(status.unwrap().success());
        std::fs::write(b.join(file), text).unwrap();
        b
    };
    let tournament = |b: &Path| {
        let mut cmd = vivae();
        cmd.args(["tournament", "--threads", "1"]).arg(&a).arg(b);
        cmd
    };
    let b = copy(
        "misfit",
        "hall-of-fame.jsonl",
        &edit_line(&hall, 1, |v| v["genome"] = misfit.clone()),
    );
    refused(
        &mut tournament(&b),
        &[
            "hall-of-fame.jsonl",
            "line 2",
            "its prey is not a genome of",
        ],
    );
    let b = copy(
        "alien",
        "hall-of-fame.jsonl",
        &edit_line(&hall, 0, |v| v["side"] = "alien".into()),
    );
    refused(
        &mut tournament(&b),
        &["hall-of-fame.jsonl", "line 1", "\"alien\""],
    );
    let b = copy("empty", "hall-of-fame.jsonl", "");
    refused(
        &mut tournament(&b),
        &["hall-of-fame.jsonl", "holds no hunter"],
    );
    let champions = String::from_utf8(read(&a, "champions.json")).unwrap();
    let mut c: serde_json::Value = serde_json::from_str(&champions).unwrap();
    c["prey"]["genome"] = misfit.clone();
    let b = copy("champion", "champions.json", &c.to_string());
    refused(&mut tournament(&b), &["champions.json", "champion prey"]);
    // Thread counts past the bound are refused before any thread starts
    // (a usage error, in clap's words: its first line says what is wrong).
    let out = run(vivae()
        .args(["tournament", "--threads", "100000"])
        .arg(&a)
        .arg(&a));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    let first = err.lines().next().unwrap();
    assert!(
        first.contains("'100000'") && first.contains("--threads") && first.contains("at most 1024"),
        "{err}"
    );
}

#[test]
fn a_refused_resume_leaves_the_run_exactly_as_it_was() {
    let dir = scratch("hostile-resume");
    let a = dir.join("a");
    let other = dir.join("other");
    pp_run(&a, 3, 1);
    pp_run(&other, 2, 2);
    let own = read(&a, "checkpoint.json");
    // Another run's checkpoint copied in: refused, nothing cut or rewritten.
    std::fs::copy(other.join("checkpoint.json"), a.join("checkpoint.json")).unwrap();
    let before = snapshot(&a);
    refused(
        vivae().args(["resume", "-q", "--generations", "5"]).arg(&a),
        &["checkpoint.json", "another run's checkpoint"],
    );
    assert!(snapshot(&a) == before, "a refused resume changed the run");
    // Genomes of the wrong shape in the checkpoint: refused by name, no panic.
    // (Spliced into the text: the checkpoint's own key order is kept.)
    let text = String::from_utf8(own.clone()).unwrap();
    let start = text.find("\"hall_hunters\":[").unwrap() + "\"hall_hunters\":[".len();
    let mut first =
        serde_json::Deserializer::from_str(&text[start..]).into_iter::<serde_json::Value>();
    first.next().unwrap().unwrap();
    let end = start + first.byte_offset();
    let forged = format!("{}{MISFIT}{}", &text[..start], &text[end..]);
    std::fs::write(a.join("checkpoint.json"), forged).unwrap();
    let before = snapshot(&a);
    refused(
        vivae().args(["resume", "-q", "--generations", "5"]).arg(&a),
        &["checkpoint.json", "hunter hall of fame", "generation 0"],
    );
    assert!(snapshot(&a) == before, "a refused resume changed the run");
    // A precision the run has no choice of is refused, not ignored.
    std::fs::write(a.join("checkpoint.json"), &own).unwrap();
    refused(
        vivae().args(["resume", "--precision", "fast"]).arg(&a),
        &["--precision fast", "predator-prey"],
    );
    // With its own checkpoint back, the run resumes.
    let line = ok(vivae().args(["resume", "-q", "--generations", "4"]).arg(&a));
    assert!(line.contains("generations=4"), "{line}");
}

/// A PNG of a header saying `width` × `height` RGB pixels, one IDAT chunk
/// holding `zlib` (the compressed rows), and an end.
fn png_of(width: u32, height: u32, zlib: &[u8]) -> Vec<u8> {
    let chunk = |kind: &[u8], data: &[u8]| {
        let mut c = (data.len() as u32).to_be_bytes().to_vec();
        let body = [kind, data].concat();
        c.extend_from_slice(&body);
        c.extend_from_slice(&crc32(&body).to_be_bytes());
        c
    };
    let ihdr = [
        &width.to_be_bytes()[..],
        &height.to_be_bytes(),
        &[8, 2, 0, 0, 0],
    ]
    .concat();
    [
        &b"\x89PNG\r\n\x1a\n"[..],
        &chunk(b"IHDR", &ihdr),
        &chunk(b"IDAT", zlib),
        &chunk(b"IEND", &[]),
    ]
    .concat()
}

/// A PNG of just a header claiming `width` × `height` RGB pixels (and an end).
fn png_header(width: u32, height: u32) -> Vec<u8> {
    png_of(
        width,
        height,
        &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01],
    )
}

/// A zlib stream that inflates to `bytes` zero bytes (`bytes` − 1 a multiple
/// of 258), about 160 times smaller: one fixed-Huffman block of a literal 0
/// and then copies of 258 bytes at distance 1, each 13 bits.
fn zeros_zlib(bytes: u64) -> Vec<u8> {
    assert_eq!((bytes - 1) % 258, 0);
    let mut out = vec![0x78, 0x01];
    let (mut acc, mut held) = (0u64, 0u32);
    // Deflate packs bits from each byte's lowest; Huffman codes go in
    // from their highest bit, other fields from their lowest.
    let mut put = |value: u64, len: u32, huffman: bool, out: &mut Vec<u8>| {
        for i in 0..len {
            let bit = if huffman { len - 1 - i } else { i };
            acc |= ((value >> bit) & 1) << held;
            held += 1;
            if held == 8 {
                out.push(acc as u8);
                (acc, held) = (0, 0);
            }
        }
    };
    put(1, 1, false, &mut out); // the last block
    put(1, 2, false, &mut out); // fixed Huffman codes
    put(0x30, 8, true, &mut out); // literal 0
    for _ in 0..(bytes - 1) / 258 {
        put(0b1100_0101, 8, true, &mut out); // length 258 (code 285)
        put(0, 5, true, &mut out); // distance 1 (code 0)
    }
    put(0, 7, true, &mut out); // end of block (code 256)
    put(0, 7, false, &mut out); // to the byte's end
    out.extend_from_slice(&((bytes % 65521) << 16 | 1).to_be_bytes()[4..]); // Adler-32
    out
}

/// Most data memory (`ulimit -d`, KiB) `drive-image` may use while it
/// reads the decompression bomb: far less than the bomb inflates to.
const BOMB_DATA_KIB: u64 = 256 * 1024;

#[test]
fn a_decompression_bomb_is_read_by_its_header_within_a_memory_bound() {
    let run_dir = small_run("hostile-bomb", 1);
    let dir = run_dir.parent().unwrap().to_path_buf();
    // 100 × 100 RGB pixels by the header (30,100 bytes of rows), behind
    // 1 GB of zeros in 6 MB: a reader that inflated the whole stream
    // would need more than three times the bound.
    let inflated = 1 + 258 * 4_000_000;
    let bomb = dir.join("bomb.png");
    std::fs::write(&bomb, png_of(100, 100, &zeros_zlib(inflated))).unwrap();
    assert!(std::fs::metadata(&bomb).unwrap().len() < inflated / 100);
    assert!(inflated > 3 * 1024 * BOMB_DATA_KIB);
    // Every image vivae reads goes through the one PNG reader: as a frame
    // and as the map of --poses.
    let poses = dir.join("poses.csv");
    std::fs::write(&poses, "x,y,heading\n50,50,0\n").unwrap();
    for extra in [
        vec![bomb.clone()],
        vec![bomb.clone(), "--poses".into(), poses],
    ] {
        let out = run(Command::new("sh")
            .arg("-c")
            .arg(format!("ulimit -d {BOMB_DATA_KIB} && exec \"$0\" \"$@\""))
            .arg(env!("CARGO_BIN_EXE_vivae"))
            .arg("drive-image")
            .arg(&*run_dir)
            .args(&extra));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{extra:?}: {:?} {err}", out.status);
        // A black frame: one CSV line of wheel commands after the header.
        let csv = String::from_utf8_lossy(&out.stdout);
        assert_eq!(csv.lines().count(), 2, "{csv}");
        assert!(csv.starts_with("frame,left,right\n0,"), "{csv}");
    }
    // The header's cap, from the same reader: a few bytes claiming
    // 100000 × 100000 pixels are refused by name before any allocation.
    let huge = dir.join("huge.png");
    std::fs::write(&huge, png_header(100_000, 100_000)).unwrap();
    refused(
        Command::new("sh")
            .arg("-c")
            .arg(format!("ulimit -d {BOMB_DATA_KIB} && exec \"$0\" \"$@\""))
            .arg(env!("CARGO_BIN_EXE_vivae"))
            .arg("drive-image")
            .arg(&*run_dir)
            .arg(&huge),
        &["huge.png", "100000 x 100000 pixels", "100000000"],
    );
}

#[test]
fn sizes_counts_and_seeds_past_their_bounds_are_refused_before_any_work() {
    let run_dir = small_run("hostile-bounds", 1);
    let dir = run_dir.parent().unwrap().to_path_buf();
    let huge = dir.join("huge.png");
    std::fs::write(&huge, png_header(100_000, 100_000)).unwrap();
    refused(
        vivae().arg("drive-image").arg(&*run_dir).arg(&huge),
        &["huge.png", "100000 x 100000 pixels", "100000000"],
    );
    refused(
        vivae()
            .arg("drive-image")
            .arg(&*run_dir)
            .arg(&huge)
            .args(["--heading", "inf"]),
        &["--heading inf"],
    );
    // A map too large to draw is refused with the scales that can be drawn.
    let map = dir.join("map.png");
    refused(
        vivae()
            .arg("drive-image")
            .arg(&*run_dir)
            .arg("--draw-map")
            .arg(&map)
            .args(["--scale", "1000"]),
        &[
            "--scale 1000",
            "100000000 pixels",
            "use a scale from 0 to 14.43",
        ],
    );
    assert!(!map.exists());
    // Roads place nothing at random: a placement seed is refused by name.
    refused(
        vivae()
            .arg("replay")
            .arg(&*run_dir)
            .args(["--placement-seed", "5"]),
        &[
            "--placement-seed 5",
            "places no obstacles or traffic at random",
        ],
    );
    refused(
        vivae().current_dir(&dir).args([
            "reproduce",
            "xor",
            "--no-journal",
            "--runs",
            "1000000000",
        ]),
        &["--runs 1000000000", "at most 10000"],
    );
    refused(
        vivae().current_dir(&dir).args([
            "reproduce",
            "xor",
            "--no-journal",
            "--seed",
            "18446744073709551615",
        ]),
        &["--seed 18446744073709551615", "2^64 - 1"],
    );
    let config = dir.join("sample.toml");
    std::fs::write(
        &config,
        "[experiment]\ntask = \"predator-prey\"\n[coevolution]\nsample = 1000000000\n",
    )
    .unwrap();
    refused(
        vivae().args(["config", "check"]).arg(&config),
        &[
            "sample.toml",
            "coevolution.sample = 1000000000",
            "at most 1000",
        ],
    );
    // Nothing was left behind.
    assert!(!dir.join("reproduce-xor.md").exists());
}

#[test]
fn settings_a_task_does_not_read_are_refused_by_name() {
    let dir = scratch("hostile-unread");
    // A one-generation run of the config at `path`, which must be refused.
    let evolve = |path: &Path| {
        let mut c = vivae();
        (c.args(["evolve", "-q", "--generations", "1", "--config"])
            .arg(path))
        .arg("--out")
        .arg(dir.join("never"));
        c
    };
    let pp = "[experiment]\ntask = \"predator-prey\"\n";
    let zone = |rect: &str| {
        let svg = include_str!("../../../../scenarios/predator-prey.svg");
        svg.replace(
            "</svg>",
            &format!(
                r#"<rect id="zone" inkscape:label="ObstacleRegion" data-count="2" {rect}/></svg>"#
            ),
        )
    };
    let lane = r#"<path id="lane" inkscape:label="Route" d="M 20,20 L 200,20" style="fill:none;stroke:#fff"/>"#;
    let svg_files = [
        (
            "outside.svg",
            zone(r#"x="900" y="10" width="40" height="40""#),
        ),
        ("flat.svg", zone(r#"x="10" y="10" width="0" height="40""#)),
        (
            "inside.svg",
            zone(r#"x="100" y="100" width="40" height="40""#),
        ),
        (
            "lanes.svg",
            include_str!("../../../../scenarios/predator-prey.svg")
                .replace("</svg>", &format!("{lane}{lane}</svg>")),
        ),
    ];
    for (name, text) in &svg_files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let cases: [(&str, String, &[&str]); 8] = [
        (
            "driving.toml",
            "[coevolution]\nopponents = \"hall-of-fame\"\n".into(),
            &[
                "coevolution.opponents",
                "only a predator-prey run reads [coevolution]",
            ],
        ),
        (
            "maze.toml",
            "[experiment]\ntask = \"maze\"\n[coevolution]\nsample = 3\n".into(),
            &["coevolution.sample = 3", "(experiment.task = \"maze\")"],
        ),
        (
            "cost.toml",
            format!("{pp}[fitness]\ncontact_cost = -1e308\n"),
            &[
                "fitness.contact_cost = -1e308",
                "only a driving run reads [fitness]",
            ],
        ),
        (
            "progress.toml",
            format!("{pp}[fitness]\nkind = \"progress\"\n"),
            &["fitness.kind = \"progress\"", "only a driving run"],
        ),
        (
            "outside.toml",
            format!("{pp}scenario = \"outside.svg\"\n"),
            &[
                "outside.svg",
                "obstacle region 'zone'",
                "outside the 300 x 300 arena",
            ],
        ),
        (
            "flat.toml",
            format!("{pp}scenario = \"flat.svg\"\n"),
            &["flat.svg", "obstacle region 'zone' has no area"],
        ),
        // An obstacle region inside a predator-prey arena: no obstacle is placed at random there.
        (
            "inside.toml",
            format!("{pp}scenario = \"inside.svg\"\n"),
            &[
                "inside.svg",
                "obstacle region 'zone'",
                "places no obstacles at random",
            ],
        ),
        (
            "lanes.toml",
            format!("{pp}scenario = \"lanes.svg\"\n"),
            &[
                "lanes.svg",
                "route lane (<path> on line",
                "used by another element too",
            ],
        ),
    ];
    for (name, text, needles) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        refused(vivae().args(["config", "check"]).arg(&path), needles);
        refused(&mut evolve(&path), needles);
    }
    // The scenario files themselves are refused wherever they are read.
    refused(
        vivae()
            .args(["scenario", "info"])
            .arg(dir.join("lanes.svg")),
        &["lanes.svg", "route lane"],
    );
    assert!(!dir.join("never").exists());
}

#[test]
fn a_reproduce_stopped_by_sigterm_leaves_no_scratch_run() {
    let dir = scratch("hostile-reproduce-term");
    let child = vivae()
        .current_dir(&dir)
        .args([
            "reproduce",
            "maze-hard",
            "--runs",
            "1",
            "--threads",
            "1",
            "-q",
        ])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id();
    let tmp = std::env::temp_dir();
    let scratch_run = tmp.join(format!("vivae-reproduce-{pid}-0"));
    wait_for_file(&scratch_run.join("config.toml"), 300);
    let status = std::process::Command::new("kill")
        .args(["-TERM", &pid.to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{err}");
    assert!(err.contains("the same command continues"), "{err}");
    let building = tmp.join(format!(".vivae-reproduce-{pid}-0.tmp-{pid}"));
    for left in [&scratch_run, &building] {
        assert!(!left.exists(), "{} left behind", left.display());
    }
}
