//! A checkpoint is an output: the JSON of NEAT's population and of every
//! strategy keeps its field names in their order (top level and what the
//! strategy was told), whatever the in-memory layout behind it.

use vivae_neat::driver::{Evaluation, Strategy};
use vivae_neat::strategies::{
    Cells, MapElites, MapElitesParams, Measure, NoveltyParams, NoveltySearch, Nsga2, Nsga2Params,
    Objective,
};
use vivae_neat::{GenomeSpec, NeatParams, Population};

/// The keys of the JSON object `json`, in order, each with its value's text.
fn fields(json: &str) -> Vec<(String, &str)> {
    let b = json.as_bytes();
    assert_eq!(b.first(), Some(&b'{'), "not an object: {json:.40}");
    let (mut out, mut depth, mut in_string) = (Vec::new(), 0usize, false);
    let (mut key_start, mut value_start, mut key) = (0, 0, String::new());
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'\\' if in_string => i += 1,
            b'"' => {
                in_string = !in_string;
                if depth == 1 && in_string && value_start == 0 {
                    key_start = i + 1;
                } else if depth == 1 && !in_string && value_start == 0 {
                    key = json[key_start..i].to_string();
                }
            }
            _ if in_string => {}
            b':' if depth == 1 && value_start == 0 => value_start = i + 1,
            b'{' | b'[' => depth += 1,
            b'}' | b']' | b',' => {
                if depth == 1 && value_start > 0 {
                    out.push((std::mem::take(&mut key), &json[value_start..i]));
                    value_start = 0;
                }
                if b[i] != b',' {
                    depth -= 1;
                }
            }
            _ => {}
        }
        i += 1;
    }
    out
}

fn names(fields: &[(String, &str)]) -> Vec<String> {
    fields.iter().map(|(k, _)| k.clone()).collect()
}

/// Runs `s` for two generations (asked, told) and checks the key order of
/// its JSON, and of its `told` record when given.
fn keeps_its_fields<S: Strategy>(mut s: S, top: &[&str], told: Option<&[&str]>) {
    for _ in 0..2 {
        let n = s.ask().genomes.len();
        let evaluation = |i: usize| Evaluation {
            metrics: vec![i as f64 * 0.3, 1.0 - i as f64],
            behaviour: vec![(i as f64 * 0.37).sin(), (i as f64 * 0.11).cos() - 0.5],
            ..Evaluation::fitness(i as f64 % 5.0)
        };
        s.tell(&(0..n).map(evaluation).collect::<Vec<_>>()).unwrap();
    }
    let json = serde_json::to_string(&s).unwrap();
    let fields = fields(&json);
    assert_eq!(names(&fields), top);
    if let Some(told) = told {
        let (_, value) = fields.iter().find(|(k, _)| k == "told").unwrap();
        assert_eq!(names(&self::fields(value)), told);
    }
}

fn neat(population_size: usize) -> NeatParams {
    NeatParams {
        population_size,
        ..NeatParams::plain_neat()
    }
}

#[test]
fn population_json_keeps_its_fields_in_order() {
    let population = Population::new(neat(12), GenomeSpec::plain(3, 2), 5).unwrap();
    let top = [
        "params",
        "spec",
        "seed",
        "generation",
        "rng",
        "tracker",
        "genomes",
        "fitness",
        "species",
        "next_species_id",
        "threshold",
        "best_ever",
    ];
    keeps_its_fields(population, &top, None);
}

#[test]
fn novelty_search_json_keeps_its_fields_in_order() {
    let population = Population::new(neat(12), GenomeSpec::plain(3, 2), 5).unwrap();
    let novelty = NoveltySearch::new(population, NoveltyParams::default()).unwrap();
    let top = [
        "population",
        "novelty",
        "dims",
        "archive",
        "threshold",
        "idle",
        "told",
        "best",
    ];
    keeps_its_fields(novelty, &top, Some(&["fitness", "novelty", "added"]));
}

#[test]
fn map_elites_json_keeps_its_fields_in_order() {
    let cells = Cells::grid(vec![-1.0, -1.0], vec![1.0, 1.0], vec![4, 4]).unwrap();
    let map = MapElitesParams::default();
    let me = MapElites::new(neat(1), GenomeSpec::plain(3, 2), map, cells, 5).unwrap();
    let top = [
        "spec",
        "params",
        "map",
        "cells",
        "archive",
        "seed",
        "generation",
        "rng",
        "tracker",
        "batch",
        "told",
        "best",
    ];
    keeps_its_fields(me, &top, Some(&["fitness", "inserted"]));
}

#[test]
fn nsga2_json_keeps_its_fields_in_order() {
    let objective = |measure, maximise| Objective { measure, maximise };
    let nsga = Nsga2Params {
        population_size: 8,
        objectives: vec![
            objective(Measure::Fitness, true),
            objective(Measure::Metric(1), false),
        ],
        crossover_probability: 0.5,
    };
    let es = Nsga2::new(neat(1), GenomeSpec::plain(3, 2), nsga, 5).unwrap();
    let top = [
        "spec",
        "params",
        "nsga",
        "seed",
        "generation",
        "rng",
        "tracker",
        "parents",
        "batch",
        "told",
        "best",
    ];
    keeps_its_fields(es, &top, Some(&["objectives", "fitness"]));
}
