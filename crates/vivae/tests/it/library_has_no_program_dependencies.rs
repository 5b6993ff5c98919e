//! The experiment library (`vivae-lab`) and the two libraries it joins build
//! without any of the program's dependencies, so that other programs (the
//! Python package) can bind them: read from `Cargo.lock`, no web server,
//! async runtime, command-line parser, plotting, progress bars, signal
//! handling or MPI is reachable from them.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Crates only the `vivae` program may depend on.
const PROGRAM_ONLY: &[&str] = &[
    "axum",
    "tokio",
    "clap",
    "plotters",
    "indicatif",
    "ctrlc",
    "mpi",
    "anyhow",
];

/// Every package of `Cargo.lock` with the names of its dependencies.
fn lock_graph(text: &str) -> BTreeMap<String, Vec<String>> {
    let mut graph = BTreeMap::new();
    for block in text.split("[[package]]").skip(1) {
        let name = block
            .lines()
            .find_map(|l| l.strip_prefix("name = "))
            .map(|n| n.trim_matches('"').to_string())
            .expect("a package has a name");
        let deps = block
            .split_once("dependencies = [")
            .map(|(_, rest)| rest.split(']').next().unwrap_or(""))
            .unwrap_or("")
            .split(',')
            .filter_map(|d| d.trim().trim_matches('"').split(' ').next())
            .filter(|d| !d.is_empty())
            .map(String::from)
            .collect();
        graph
            .entry(name)
            .or_insert_with(Vec::new)
            .extend::<Vec<String>>(deps);
    }
    graph
}

/// Names of the entries of section `[section]` of a Cargo.toml.
fn section_names(toml: &str, section: &str) -> BTreeSet<String> {
    let header = format!("[{section}]");
    toml.lines()
        .skip_while(|l| l.trim() != header)
        .skip(1)
        .take_while(|l| !l.trim_start().starts_with('['))
        .filter_map(|l| l.split(['=', '.']).next())
        .map(|n| n.trim().to_string())
        .filter(|n| !n.is_empty() && !n.starts_with('#'))
        .collect()
}

/// `Cargo.lock` does not tell dev-dependencies apart: drop the edges of the
/// workspace crate in `dir` to what only its tests and benches use.
fn drop_dev_edges(graph: &mut BTreeMap<String, Vec<String>>, name: &str, dir: &Path) {
    let toml = std::fs::read_to_string(dir.join("Cargo.toml")).expect("Cargo.toml");
    let normal = section_names(&toml, "dependencies");
    let dev_only: BTreeSet<String> = section_names(&toml, "dev-dependencies")
        .difference(&normal)
        .cloned()
        .collect();
    if let Some(deps) = graph.get_mut(name) {
        deps.retain(|d| !dev_only.contains(d));
    }
}

/// Everything `root` depends on, directly or not (itself included).
fn reachable(graph: &BTreeMap<String, Vec<String>>, root: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut todo = vec![root.to_string()];
    while let Some(p) = todo.pop() {
        if seen.insert(p.clone()) {
            todo.extend(graph.get(&p).into_iter().flatten().cloned());
        }
    }
    seen
}

#[test]
fn the_libraries_reach_none_of_the_programs_dependencies() {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let lock = crates.join("../Cargo.lock");
    let mut graph = lock_graph(&std::fs::read_to_string(lock).expect("Cargo.lock"));
    for (name, dir) in [
        ("vivae-lab", "lab"),
        ("vivae-neat", "neat"),
        ("vivae-sim", "sim"),
    ] {
        drop_dev_edges(&mut graph, name, &crates.join(dir));
    }
    // The check itself must see the program's dependencies where they are.
    let program = reachable(&graph, "vivae");
    for name in ["axum", "tokio", "clap", "plotters"] {
        assert!(program.contains(name), "the lock file reader missed {name}");
    }
    for library in ["vivae-lab", "vivae-neat", "vivae-sim"] {
        let deps = reachable(&graph, library);
        assert!(deps.len() > 5, "{library}: {deps:?}");
        let bad: Vec<&&str> = PROGRAM_ONLY.iter().filter(|p| deps.contains(**p)).collect();
        assert!(bad.is_empty(), "{library} depends on {bad:?}");
    }
}
