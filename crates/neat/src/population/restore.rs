//! Restoring a checkpoint: the population as read, checked as a whole
//! before it becomes a [`Population`].

use std::collections::BTreeSet;

use serde::Deserialize;

use crate::error::{GenomeAt, NeatError, PopulationError};
use crate::genome::{Genome, GenomeSpec, NodeKind, RawGenome};
use crate::innovation::InnovationTracker;
use crate::species::Species;

use super::{BestEver, Population, population_fields};

population_fields! {
    /// A population as read, not yet checked (the serialised form of [`Population`]).
    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    pub(super) struct RawPopulation of (RawGenome, RawSpecies, RawBestEver);
}

/// A [`Species`] as read, its representative not yet checked.
#[derive(Deserialize)]
struct RawSpecies {
    id: u32,
    representative: RawGenome,
    members: Vec<usize>,
    created: u32,
    best_fitness: Option<f64>,
    last_improved: u32,
}

/// A [`BestEver`] as read, its genome not yet checked.
#[derive(Deserialize)]
struct RawBestEver {
    genome: RawGenome,
    fitness: f64,
    generation: u32,
}

/// Checks a raw genome's invariants and its shape against `spec`.
fn checked_genome(at: GenomeAt, raw: RawGenome, spec: &GenomeSpec) -> Result<Genome, NeatError> {
    let genome = Genome::try_from(raw).map_err(|error| PopulationError::Genome { at, error })?;
    check_genome(at, &genome, spec)?;
    Ok(genome)
}

/// Checks a genome's invariants and that its inputs and outputs match `spec`.
pub(super) fn check_genome(
    at: GenomeAt,
    genome: &Genome,
    spec: &GenomeSpec,
) -> Result<(), PopulationError> {
    genome
        .check()
        .map_err(|error| PopulationError::Genome { at, error })?;
    let (inputs, outputs) = (genome.num_inputs(), genome.num_outputs());
    if inputs != spec.inputs || outputs != spec.outputs {
        return Err(PopulationError::Shape {
            at,
            inputs,
            outputs,
            spec_inputs: spec.inputs,
            spec_outputs: spec.outputs,
        });
    }
    // Ids say what a node is in every genome of the run; crossover relies on it.
    for n in genome.nodes() {
        let expected = NodeKind::of_id(n.id, spec);
        if n.kind != expected {
            return Err(PopulationError::NodeKind {
                at,
                id: n.id,
                kind: n.kind.name(),
                expected: expected.name(),
            });
        }
    }
    Ok(())
}

/// Checks the innovation history against itself and the genomes: one number
/// per link and one link per number, every genome link numbered as the
/// history says, split nodes hidden and unique, counters above every id in
/// use. Together these keep later mutations from ever duplicating a number.
pub(super) fn check_history<'a>(
    tracker: &InnovationTracker,
    spec: &GenomeSpec,
    genomes: impl Iterator<Item = (GenomeAt, &'a Genome)>,
) -> Result<(), PopulationError> {
    use PopulationError as E;
    let mut numbers = BTreeSet::new();
    let mut innovation = None;
    for (_, _, i) in tracker.recorded_links() {
        if !numbers.insert(i) {
            return Err(E::SharedInnovation(i));
        }
        innovation = innovation.max(Some(i));
    }
    let first_hidden = (spec.inputs + spec.outputs) as u64;
    let mut splits = BTreeSet::new();
    let mut node = None;
    for id in tracker.split_ids() {
        if u64::from(id) < first_hidden || !splits.insert(id) {
            return Err(E::SplitNode(id));
        }
        node = node.max(Some(id));
    }
    for (at, g) in genomes {
        for l in g.links() {
            let recorded = tracker.innovation_of(l.from, l.to);
            if recorded != Some(l.innovation) {
                return Err(E::InnovationMismatch {
                    at,
                    from: l.from,
                    to: l.to,
                    innovation: l.innovation,
                    recorded,
                });
            }
        }
        node = node.max(g.nodes().last().map(|n| n.id));
    }
    let counters = [
        (
            "the innovation counter",
            tracker.innovations(),
            "innovation number",
            innovation,
        ),
        ("the node counter", tracker.next_node_id(), "node id", node),
    ];
    for (counter, value, what, used) in counters {
        if let Some(used) = used
            && used >= value
        {
            return Err(E::Counter {
                counter,
                value,
                what,
                used,
            });
        }
    }
    Ok(())
}

impl TryFrom<RawPopulation> for Population {
    type Error = NeatError;

    fn try_from(raw: RawPopulation) -> Result<Population, NeatError> {
        raw.params.validate()?;
        raw.spec.validate()?;
        let spec = &raw.spec;
        let genomes = checked_genomes(raw.genomes, spec)?;
        check_fitness(raw.fitness.as_deref(), genomes.len())?;
        let species = checked_species(raw.species, genomes.len(), spec)?;
        let best_ever = checked_best_ever(raw.best_ever, raw.generation, spec)?;
        if !(raw.threshold.is_finite() && raw.threshold >= 0.0) {
            return Err(PopulationError::Threshold(raw.threshold).into());
        }
        if let Some(generation) = raw.refocused.filter(|&g| g > raw.generation) {
            return Err(PopulationError::FutureGeneration {
                what: "refocused",
                generation,
                current: raw.generation,
            }
            .into());
        }
        let every_genome = genomes
            .iter()
            .enumerate()
            .map(|(i, g)| (GenomeAt::Member(i), g))
            .chain(
                species
                    .iter()
                    .map(|s| (GenomeAt::Representative(s.id), &s.representative)),
            )
            .chain(best_ever.iter().map(|b| (GenomeAt::BestEver, &b.genome)));
        check_history(&raw.tracker, spec, every_genome)?;
        check_species_counter(&species, raw.next_species_id)?;

        Ok(Population {
            params: raw.params,
            spec: raw.spec,
            seed: raw.seed,
            generation: raw.generation,
            rng: raw.rng,
            tracker: raw.tracker,
            genomes,
            fitness: raw.fitness,
            species,
            next_species_id: raw.next_species_id,
            threshold: raw.threshold,
            best_ever,
            refocused: raw.refocused,
        })
    }
}

/// The members: at least one, each checked against `spec`.
fn checked_genomes(raw: Vec<RawGenome>, spec: &GenomeSpec) -> Result<Vec<Genome>, NeatError> {
    if raw.is_empty() {
        return Err(PopulationError::Empty.into());
    }
    raw.into_iter()
        .enumerate()
        .map(|(i, g)| checked_genome(GenomeAt::Member(i), g, spec))
        .collect()
}

/// Fitness values, if recorded: one per genome, all finite.
fn check_fitness(fitness: Option<&[f64]>, genomes: usize) -> Result<(), PopulationError> {
    if let Some(fitness) = fitness {
        if fitness.len() != genomes {
            return Err(PopulationError::FitnessCount {
                given: fitness.len(),
                genomes,
            });
        }
        if let Some(i) = fitness.iter().position(|f| !f.is_finite()) {
            return Err(PopulationError::NonFiniteFitness(format!("genome {i}")));
        }
    }
    Ok(())
}

/// Species: unique ids, members that partition the `n` genomes, finite
/// records, representatives checked against `spec`.
fn checked_species(
    raw: Vec<RawSpecies>,
    n: usize,
    spec: &GenomeSpec,
) -> Result<Vec<Species>, NeatError> {
    use PopulationError as E;
    let mut ids = BTreeSet::new();
    let mut listed = vec![0usize; n];
    let mut species = Vec::with_capacity(raw.len());
    for s in raw {
        if !ids.insert(s.id) {
            return Err(E::DuplicateSpecies(s.id).into());
        }
        if s.members.is_empty() {
            return Err(E::EmptySpecies(s.id).into());
        }
        for &member in &s.members {
            let count = listed.get_mut(member).ok_or(E::MissingMember {
                species: s.id,
                member,
                genomes: n,
            })?;
            *count += 1;
        }
        if s.best_fitness.is_some_and(|f| !f.is_finite()) {
            return Err(E::NonFiniteFitness(format!("species {}", s.id)).into());
        }
        species.push(Species {
            id: s.id,
            representative: checked_genome(GenomeAt::Representative(s.id), s.representative, spec)?,
            members: s.members,
            created: s.created,
            best_fitness: s.best_fitness,
            last_improved: s.last_improved,
        });
    }
    if let Some(member) = listed.iter().position(|&c| c != 1) {
        return Err(E::Membership {
            member,
            count: listed[member],
        }
        .into());
    }
    Ok(species)
}

/// The best-ever record, if any: finite fitness, not from a generation
/// after `current`, its genome checked against `spec`.
fn checked_best_ever(
    raw: Option<RawBestEver>,
    current: u32,
    spec: &GenomeSpec,
) -> Result<Option<BestEver>, NeatError> {
    let Some(b) = raw else {
        return Ok(None);
    };
    if !b.fitness.is_finite() {
        return Err(PopulationError::NonFiniteFitness("the best-ever genome".into()).into());
    }
    if b.generation > current {
        return Err(PopulationError::FutureGeneration {
            what: "the best-ever record",
            generation: b.generation,
            current,
        }
        .into());
    }
    Ok(Some(BestEver {
        genome: checked_genome(GenomeAt::BestEver, b.genome, spec)?,
        fitness: b.fitness,
        generation: b.generation,
    }))
}

/// The species counter is above every species id in use.
fn check_species_counter(species: &[Species], next_species_id: u32) -> Result<(), PopulationError> {
    if let Some(used) = species.iter().map(|s| s.id).max()
        && used >= next_species_id
    {
        return Err(PopulationError::Counter {
            counter: "next_species_id",
            value: next_species_id,
            what: "species id",
            used,
        });
    }
    Ok(())
}
