//! Deserialising a genome or a population checks it: each class of
//! inconsistent JSON is refused with the typed error naming what is wrong,
//! never a panic, and whatever is accepted can evolve on.

use proptest::prelude::*;
use serde_json::{Value, json};
use vivae_neat::{
    Genome, GenomeAt, GenomeError, GenomeSpec, NeatError, NeatParams, Population, PopulationError,
    RawGenome,
};

fn fitness(g: &Genome, seed: u64) -> f64 {
    g.links().iter().map(|l| l.weight.abs()).sum::<f64>() + (seed % 5) as f64
}

/// An evaluated population a few generations in: hidden nodes, several
/// species, a best-ever record.
fn evolved() -> Population {
    let params = NeatParams {
        population_size: 40,
        add_node_probability: 0.3,
        target_species: Some(4),
        ..NeatParams::default()
    };
    let mut p = Population::new(params, GenomeSpec::cppn(), 17).unwrap();
    for _ in 0..5 {
        p.evaluate(|g, ctx| fitness(g, ctx.seed));
        p.next_generation();
    }
    p.evaluate(|g, ctx| fitness(g, ctx.seed));
    assert!(p.species().len() >= 2, "the cases need two species");
    assert!(p.genomes().iter().any(|g| g.num_hidden() > 0));
    p
}

/// Stands in for the RNG state in editable values: `Value` cannot hold its
/// 128-bit integers exactly.
const RNG: &str = "\"exact rng state\"";

/// The RNG state of `evolved()` as JSON text.
fn rng_text() -> &'static str {
    static TEXT: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    TEXT.get_or_init(|| {
        let text = evolved().to_json().unwrap();
        let start = text.find("\"rng\":").unwrap() + "\"rng\":".len();
        let end = start + text[start..].find('}').unwrap() + 1;
        text[start..end].to_string()
    })
}

/// `evolved()` as an editable JSON value (RNG state held aside).
fn as_value(p: &Population) -> Value {
    let mut v: Value = serde_json::from_str(&p.to_json().unwrap()).unwrap();
    v["rng"] = serde_json::from_str(RNG).unwrap();
    v
}

/// The JSON text of an edited value, exact RNG state restored.
fn text(v: &Value) -> String {
    v.to_string().replace(RNG, rng_text())
}

/// The error restoring `v` gives (it must give one).
fn refused(v: &Value) -> NeatError {
    Population::from_json(&text(v)).expect_err("an inconsistent population was accepted")
}

/// The population error restoring `v` gives.
fn population_error(v: &Value) -> PopulationError {
    match refused(v) {
        NeatError::InvalidPopulation(e) => e,
        other => panic!("expected an invalid-population error, got {other:?}"),
    }
}

/// The genome error `genome` (JSON) gives, through the typed path and through serde.
fn genome_error(genome: &Value) -> GenomeError {
    let raw: RawGenome = serde_json::from_value(genome.clone()).unwrap();
    let typed = Genome::try_from(raw).expect_err("an invalid genome was accepted");
    let via_serde = serde_json::from_value::<Genome>(genome.clone()).unwrap_err();
    assert!(
        via_serde.to_string().contains(&typed.to_string()),
        "{via_serde} vs {typed}"
    );
    typed
}

#[test]
fn the_untouched_population_and_its_genomes_are_accepted() {
    let p = evolved();
    let v = as_value(&p);
    assert_eq!(Population::from_json(&text(&v)).unwrap(), p);
    for g in p.genomes() {
        let back: Genome = serde_json::from_value(serde_json::to_value(g).unwrap()).unwrap();
        assert_eq!(&back, g);
    }
}

#[test]
fn each_kind_of_bad_genome_is_named() {
    let p = evolved();
    let g = p
        .genomes()
        .iter()
        .max_by_key(|g| g.links().len())
        .unwrap()
        .clone();
    let base = serde_json::to_value(&g).unwrap();
    let first = &g.links()[0];

    let mut v = base.clone();
    let node = v["nodes"][0].clone();
    v["nodes"].as_array_mut().unwrap().push(node);
    assert_eq!(genome_error(&v), GenomeError::DuplicateNode(0));

    let mut v = base.clone();
    v["links"][1]["innovation"] = json!(first.innovation);
    assert_eq!(
        genome_error(&v),
        GenomeError::DuplicateInnovation(first.innovation)
    );

    let mut v = base.clone();
    v["links"][1]["from"] = json!(first.from);
    v["links"][1]["to"] = json!(first.to);
    assert!(matches!(
        genome_error(&v),
        GenomeError::DuplicateLink { from, to } if (from, to) == (first.from, first.to)
    ));

    let mut v = base.clone();
    v["links"][0]["to"] = json!(9999);
    assert!(matches!(
        genome_error(&v),
        GenomeError::MissingNode { to: 9999, .. }
    ));

    let mut v = base.clone();
    v["links"][0]["to"] = json!(1);
    assert!(matches!(
        genome_error(&v),
        GenomeError::LinkIntoInput { to: 1, .. }
    ));

    // JSON cannot hold a NaN; an unchecked genome built in code can.
    let mut raw: RawGenome = serde_json::from_value(base.clone()).unwrap();
    raw.links[0].weight = f64::NAN;
    assert!(matches!(
        Genome::try_from(raw),
        Err(GenomeError::NonFiniteWeight { .. })
    ));
    let mut v = base.clone();
    v["links"][0]["weight"] = json!("NaN");
    assert!(serde_json::from_value::<Genome>(v).is_err());

    // The typed error also comes out of `Genome::from_parts`.
    let raw: RawGenome = serde_json::from_value(base).unwrap();
    let mut links = raw.links.clone();
    links[0].to = 9999;
    assert!(matches!(
        Genome::from_parts(raw.nodes, links),
        Err(NeatError::InvalidGenome(GenomeError::MissingNode { .. }))
    ));
}

#[test]
fn bad_genomes_inside_a_population_are_located() {
    let p = evolved();
    let base = as_value(&p);

    let mut v = base.clone();
    v["genomes"][3]["links"][0]["to"] = json!(9999);
    assert!(matches!(
        population_error(&v),
        PopulationError::Genome {
            at: GenomeAt::Member(3),
            error: GenomeError::MissingNode { .. }
        }
    ));

    let mut v = base.clone();
    let id = v["species"][1]["id"].as_u64().unwrap() as u32;
    v["species"][1]["representative"]["links"][0]["to"] = json!(9999);
    let e = population_error(&v);
    assert!(
        matches!(e, PopulationError::Genome { at: GenomeAt::Representative(s), .. } if s == id),
        "{e}"
    );

    let mut v = base.clone();
    v["best_ever"]["genome"]["links"][0]["to"] = json!(9999);
    assert!(matches!(
        population_error(&v),
        PopulationError::Genome {
            at: GenomeAt::BestEver,
            ..
        }
    ));

    // Inputs and outputs must agree with the spec: make an output a hidden node.
    let mut v = base.clone();
    let nodes = v["genomes"][2]["nodes"].as_array_mut().unwrap();
    let output = nodes.iter_mut().find(|n| n["kind"] == "output").unwrap();
    output["kind"] = json!("hidden");
    assert!(matches!(
        population_error(&v),
        PopulationError::Shape {
            at: GenomeAt::Member(2),
            outputs: 2,
            spec_outputs: 3,
            ..
        }
    ));
}

#[test]
fn each_kind_of_bad_population_is_named() {
    let p = evolved();
    let base = as_value(&p);
    let n = p.genomes().len();
    let edit = |f: &dyn Fn(&mut Value)| {
        let mut v = base.clone();
        f(&mut v);
        population_error(&v)
    };

    assert_eq!(edit(&|v| v["genomes"] = json!([])), PopulationError::Empty);
    assert_eq!(
        edit(&|v| {
            v["fitness"].as_array_mut().unwrap().pop();
        }),
        PopulationError::FitnessCount {
            given: n - 1,
            genomes: n
        }
    );
    let s0 = p.species()[0].id;
    assert_eq!(
        edit(&|v| v["species"][0]["members"] = json!([])),
        PopulationError::EmptySpecies(s0)
    );
    assert!(matches!(
        edit(&|v| v["species"][0]["members"].as_array_mut().unwrap().push(json!(n + 5))),
        PopulationError::MissingMember { member, .. } if member == n + 5
    ));
    // A genome listed twice, and a genome listed by no species.
    let m = p.species()[0].members[0];
    assert_eq!(
        edit(&|v| v["species"][1]["members"]
            .as_array_mut()
            .unwrap()
            .push(json!(m))),
        PopulationError::Membership {
            member: m,
            count: 2
        }
    );
    assert_eq!(
        edit(&|v| {
            v["species"][0]["members"].as_array_mut().unwrap().remove(0);
        }),
        if p.species()[0].members.len() > 1 {
            PopulationError::Membership {
                member: m,
                count: 0,
            }
        } else {
            PopulationError::EmptySpecies(s0)
        }
    );
    assert_eq!(
        edit(&|v| {
            let first = v["species"][0].clone();
            v["species"].as_array_mut().unwrap().push(first);
        }),
        PopulationError::DuplicateSpecies(s0)
    );
    for (field, counter) in [
        (
            &["tracker", "next_innovation"][..],
            "the innovation counter",
        ),
        (&["tracker", "next_node"][..], "the node counter"),
        (&["next_species_id"][..], "next_species_id"),
    ] {
        let e = edit(&|v| {
            let mut at = &mut *v;
            for key in field {
                at = &mut at[*key];
            }
            *at = json!(0);
        });
        assert!(
            matches!(e, PopulationError::Counter { counter: c, value: 0, .. } if c == counter),
            "{field:?}: {e}"
        );
    }
    assert!(matches!(
        edit(&|v| v["best_ever"]["generation"] = json!(1000)),
        PopulationError::FutureGeneration {
            generation: 1000,
            ..
        }
    ));
    assert_eq!(
        edit(&|v| v["threshold"] = json!(-1.0)),
        PopulationError::Threshold(-1.0)
    );
}

#[test]
fn a_history_that_could_duplicate_innovations_is_refused() {
    let p = evolved();
    let base = as_value(&p);
    let edit = |f: &dyn Fn(&mut Value)| {
        let mut v = base.clone();
        f(&mut v);
        population_error(&v)
    };
    let links = p.genomes()[0].links();
    let fresh = p.tracker().innovations() + 5;
    assert_eq!(
        edit(&|v| v["genomes"][0]["links"][0]["innovation"] = json!(fresh)),
        PopulationError::InnovationMismatch {
            at: GenomeAt::Member(0),
            from: links[0].from,
            to: links[0].to,
            innovation: fresh,
            recorded: Some(links[0].innovation),
        }
    );
    let first = base["tracker"]["links"][0][2].clone();
    assert!(matches!(
        edit(&|v| v["tracker"]["links"][1][2] = first.clone()),
        PopulationError::SharedInnovation(_)
    ));
    assert!(
        !base["tracker"]["splits"].as_array().unwrap().is_empty(),
        "the case needs a split"
    );
    assert_eq!(
        edit(&|v| v["tracker"]["splits"][0][1][0] = json!(0)),
        PopulationError::SplitNode(0)
    );
    // Swap the kinds of an output and a hidden node: counts stay right, ids do not.
    let (i, g) = p
        .genomes()
        .iter()
        .enumerate()
        .find(|(_, g)| g.num_hidden() > 0)
        .unwrap();
    let e = edit(&|v| {
        for n in v["genomes"][i]["nodes"].as_array_mut().unwrap() {
            let id = n["id"].as_u64().unwrap();
            if id == 5 {
                n["kind"] = json!("hidden");
            } else if n["kind"] == "hidden" && id == u64::from(g.nodes().last().unwrap().id) {
                n["kind"] = json!("output");
            }
        }
    });
    assert_eq!(
        e,
        PopulationError::NodeKind {
            at: GenomeAt::Member(i),
            id: 5,
            kind: "hidden",
            expected: "output",
        }
    );
}

#[test]
fn genomes_that_number_links_differently_cannot_form_a_population() {
    let p = evolved();
    let a = p.genomes()[0].clone();
    let mut raw: RawGenome = serde_json::from_value(serde_json::to_value(&a).unwrap()).unwrap();
    let (x, y) = (raw.links[0].innovation, raw.links[1].innovation);
    raw.links[0].innovation = y;
    raw.links[1].innovation = x;
    let b = Genome::try_from(raw).unwrap();
    let e = Population::from_genomes(
        p.params().clone(),
        GenomeSpec::cppn(),
        vec![a.clone(), b],
        1,
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            NeatError::InvalidPopulation(PopulationError::InnovationMismatch {
                at: GenomeAt::Member(1),
                ..
            })
        ),
        "{e}"
    );
    // The same genomes, consistently numbered, are fine.
    assert!(
        Population::from_genomes(
            p.params().clone(),
            GenomeSpec::cppn(),
            p.genomes().to_vec(),
            1
        )
        .is_ok()
    );
}

#[test]
fn bad_parameters_specs_and_syntax_keep_their_own_errors() {
    let p = evolved();
    let base = as_value(&p);
    let mut v = base.clone();
    v["params"]["population_size"] = json!(0);
    assert!(matches!(
        refused(&v),
        NeatError::InvalidParam {
            field: "population_size",
            ..
        }
    ));
    let mut v = base.clone();
    v["spec"]["inputs"] = json!(0);
    assert!(matches!(refused(&v), NeatError::InvalidSpec(_)));
    let mut v = base.clone();
    v["surprise"] = json!(1);
    assert!(matches!(refused(&v), NeatError::Checkpoint(_)));
    let whole = text(&base);
    assert!(matches!(
        Population::from_json(&whole[..whole.len() / 2]),
        Err(NeatError::Checkpoint(_))
    ));
    // Nested in another document, the message still names the problem.
    let mut v = base.clone();
    v["genomes"][0]["links"][0]["to"] = json!(9999);
    let e = serde_json::from_str::<Population>(&text(&v))
        .unwrap_err()
        .to_string();
    assert!(e.contains("genome 0") && e.contains("missing node"), "{e}");
}

/// Every numeric leaf of the population's JSON, as a path of keys and indices.
fn numeric_paths(v: &Value, path: &mut Vec<Value>, out: &mut Vec<Vec<Value>>) {
    match v {
        Value::Number(_) => out.push(path.clone()),
        Value::Array(items) => {
            for (i, x) in items.iter().enumerate() {
                path.push(json!(i));
                numeric_paths(x, path, out);
                path.pop();
            }
        }
        Value::Object(fields) => {
            for (k, x) in fields {
                path.push(json!(k));
                numeric_paths(x, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

fn at_path<'a>(v: &'a mut Value, path: &[Value]) -> &'a mut Value {
    path.iter().fold(v, |v, key| match key {
        Value::String(k) => &mut v[k.as_str()],
        Value::Number(i) => &mut v[i.as_u64().unwrap() as usize],
        _ => unreachable!(),
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Overwriting any number of the state with an awkward value is either
    /// refused with an error or gives a population that evolves on.
    #[test]
    fn any_accepted_population_evolves_on(
        which in any::<prop::sample::Index>(),
        value in prop::sample::select(vec![
            json!(0), json!(1), json!(2), json!(7), json!(39), json!(40), json!(1000),
            json!(-1), json!(65_536), json!(0.5), json!(-3.5),
        ]),
    ) {
        let p = evolved();
        let mut v = as_value(&p);
        let mut paths = Vec::new();
        numeric_paths(&v, &mut Vec::new(), &mut paths);
        let path = &paths[which.index(paths.len())];
        *at_path(&mut v, path) = value;
        if let Ok(mut q) = Population::from_json(&text(&v)) {
            q.next_generation();
            q.evaluate(|g, ctx| fitness(g, ctx.seed));
            q.next_generation();
            prop_assert!(q.genomes().iter().all(|g| g.check().is_ok()));
        }
    }
}
