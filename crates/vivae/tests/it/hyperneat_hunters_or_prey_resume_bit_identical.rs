//! `[coevolution] hunter`/`prey = "hyperneat"`: that side evolves CPPNs
//! decoded onto the sensors' substrate, the run resumes bit-identically and
//! at any thread count, a tournament plays it against a plain NEAT run, and
//! a HyperNEAT run's prey can be a fixed prey only for HyperNEAT prey.

use std::path::Path;

use crate::common::*;

/// `vivae evolve -q` of the small predator–prey `toml` into `out`; its stdout.
fn evolve_pp(dir: &Path, toml: &str, out: &str, args: &[&str]) -> String {
    let path = dir.join(format!("{out}.toml"));
    std::fs::write(
        &path,
        format!("[experiment]\ntask = \"predator-prey\"\nsteps = 150\nseed = 5\n[neat]\npopulation_size = 16\n{toml}"),
    )
    .unwrap();
    ok(vivae()
        .args(["evolve", "-q", "--config"])
        .arg(&path)
        .args(args)
        .arg("--out")
        .arg(dir.join(out)))
}

/// The number of inputs of each side's genomes in a run's hall of fame.
fn inputs(dir: &Path, side: &str) -> Vec<usize> {
    let text = String::from_utf8(read(dir, "hall-of-fame.jsonl")).unwrap();
    text.lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .filter(|v| v["side"] == side)
        .map(|v| {
            let nodes = v["genome"]["nodes"].as_array().unwrap();
            nodes.iter().filter(|n| n["kind"] == "input").count()
        })
        .collect()
}

#[test]
fn hyperneat_sides_evolve_resume_and_play_plain_neat_runs() {
    let dir = scratch("pp-hyperneat");
    for (name, toml) in [
        ("hunter", "[coevolution]\nhunter = \"hyperneat\"\n"),
        (
            "both",
            "[coevolution]\nopponents = \"hall-of-fame\"\nsample = 2\nhunter = \"hyperneat\"\nprey = \"hyperneat\"\n[hyperneat]\nthreshold = 0.1\n",
        ),
    ] {
        let whole = format!("{name}-whole");
        let line = evolve_pp(&dir, toml, &whole, &["--generations", "5"]);
        assert!(line.contains("generations=5"), "{line}");
        let whole = dir.join(whole);
        // CPPNs: x1, y1, x2, y2 and a bias; a plain NEAT side has 11 inputs.
        assert_eq!(inputs(&whole, "hunter"), [5; 5], "{name}");
        let prey = if name == "both" { 5 } else { 11 };
        assert_eq!(inputs(&whole, "prey"), [prey; 5], "{name}");
        let config = std::fs::read_to_string(whole.join("config.toml")).unwrap();
        assert!(config.contains("hunter = \"hyperneat\""), "{config}");

        let part = format!("{name}-part");
        evolve_pp(&dir, toml, &part, &["--generations", "2"]);
        let part = dir.join(part);
        ok(vivae()
            .args(["resume", "-q", "--generations", "5"])
            .arg(&part));
        let one = format!("{name}-one");
        evolve_pp(&dir, toml, &one, &["--generations", "5", "--threads", "1"]);
        let one = dir.join(one);
        for file in [
            "hunters.csv",
            "prey.csv",
            "ciao.csv",
            "hall-of-fame.jsonl",
            "champions.json",
        ] {
            assert!(read(&whole, file) == read(&part, file), "{name}: {file}");
            assert!(read(&whole, file) == read(&one, file), "{name}: {file}");
        }
        assert!(read(&whole, "checkpoint.json") == read(&part, "checkpoint.json"));
    }
    // The HyperNEAT hunters against plain NEAT prey of another run, and back.
    let neat = "neat";
    evolve_pp(&dir, "", neat, &["--generations", "3"]);
    let table = ok(vivae()
        .arg("tournament")
        .arg(dir.join("both-whole"))
        .arg(dir.join(neat)));
    assert_eq!(table.lines().count(), 9, "{table}");
    // A plain NEAT run's prey is no fixed prey for HyperNEAT prey.
    let path = dir.join("fixed.toml");
    std::fs::write(
        &path,
        format!(
            "[experiment]\ntask = \"predator-prey\"\n[coevolution]\nopponents = \"fixed\"\nprey = \"hyperneat\"\nfixed_prey = {:?}\n",
            dir.join(neat).to_string_lossy()
        ),
    )
    .unwrap();
    let out = run(vivae()
        .args(["evolve", "-q", "--generations", "1", "--config"])
        .arg(&path)
        .arg("--out")
        .arg(dir.join("refused")));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("coevolution.prey = \"hyperneat\""), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
