//! NSGA-II (Deb, Pratap, Agarwal & Meyarivan 2002) over NEAT genomes.
//!
//! Each generation, the parents P and their children Q (evaluated) are
//! sorted into non-dominated fronts (the paper's fast non-dominated sort);
//! the next parents are the best fronts in full and, from the front that no
//! longer fits, the members of largest crowding distance. Children are bred
//! from parents picked by binary tournaments on the crowded comparison
//! (lower rank, then larger crowding distance) with NEAT's crossover
//! ([`Nsga2Params::crossover_probability`]) and mutation. Generation 0 is a
//! batch of minimal genomes, which become the first parents.
//!
//! The objectives are read from each [`Evaluation`]: its fitness or one of
//! its metrics, each maximised or minimised ([`Objective`]). The fitness the
//! task reports stays what the driver sees (champion, best ever, target).

use rand::RngExt;
use rand_pcg::Pcg64;
use serde::{Deserialize, Serialize};

pub use super::archive::pareto::{
    crowding_distances, dominates, fast_non_dominated_sort, non_dominated_fronts,
};
use super::told::{self, own_batch_state, own_batch_strategy, told_batch_accessors};
use super::{Breeding, check_count, check_neat, first_batch, invalid};
use crate::driver::{Evaluation, Strategy};
use crate::error::NeatError;
use crate::genome::{Genome, GenomeSpec};
use crate::innovation::InnovationTracker;
use crate::params::NeatParams;
use crate::population::BestEver;

/// Which measurement of an [`Evaluation`] an objective is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Measure {
    /// [`Evaluation::fitness`].
    Fitness,
    /// `Evaluation::metrics[i]`.
    Metric(usize),
}

/// One objective: a measurement and its direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Objective {
    /// What is measured.
    pub measure: Measure,
    /// Larger is better (else smaller is).
    pub maximise: bool,
}

impl Objective {
    /// The value to maximise for this objective: the measurement, negated
    /// when minimised; a missing metric is `None`, a non-finite one the worst.
    fn of(&self, e: &Evaluation) -> Option<f64> {
        let v = match self.measure {
            Measure::Fitness => e.fitness,
            Measure::Metric(i) => *e.metrics.get(i)?,
        };
        let v = if self.maximise { v } else { -v };
        Some(if v.is_finite() { v } else { f64::MIN })
    }
}

/// NSGA-II's own settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Nsga2Params {
    /// Parents N, and children per generation.
    pub population_size: usize,
    /// The objectives (at least one).
    pub objectives: Vec<Objective>,
    /// Probability that a child is a crossover of two tournament winners
    /// rather than a mutant of one.
    pub crossover_probability: f64,
}

impl Nsga2Params {
    /// Checks every setting's range.
    pub fn validate(&self) -> Result<(), NeatError> {
        if self.population_size == 0 {
            return Err(invalid("population_size", 0, "must be at least 1"));
        }
        if self.objectives.is_empty() {
            return Err(invalid("objectives", 0, "need at least one objective"));
        }
        if !(0.0..=1.0).contains(&self.crossover_probability) {
            let value = self.crossover_probability;
            return Err(invalid("crossover_probability", value, "must be in [0, 1]"));
        }
        Ok(())
    }
}

/// A parent: its genome and what it scored.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Member {
    genome: Genome,
    /// One value per objective, to maximise.
    objectives: Vec<f64>,
    fitness: f64,
}

/// The batch just told: its objectives (to maximise) and fitness.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Told {
    objectives: Vec<Vec<f64>>,
    fitness: Vec<f64>,
}

/// The serialised state of [`Nsga2`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct State {
    spec: GenomeSpec,
    params: NeatParams,
    nsga: Nsga2Params,
    seed: u64,
    generation: u32,
    rng: Pcg64,
    tracker: InnovationTracker,
    parents: Vec<Member>,
    batch: Vec<Genome>,
    told: Option<Told>,
    best: Option<BestEver>,
}

own_batch_state!(State, Told);

own_batch_strategy! {
    /// NSGA-II over NEAT genomes (see the module docs).
    pub struct Nsga2(State);
}

impl State {
    /// Checks a restored state's settings, parents and what was told.
    fn check_own(&self) -> Result<(), NeatError> {
        let s = self;
        s.nsga.validate()?;
        let m = s.nsga.objectives.len();
        let ok = |o: &[f64]| o.len() == m && o.iter().all(|v| v.is_finite());
        if !s
            .parents
            .iter()
            .all(|p| ok(&p.objectives) && p.fitness.is_finite())
        {
            return Err(invalid("parents", "a parent", "objectives not matching"));
        }
        if let Some(t) = &s.told
            && (t.objectives.len() != s.batch.len() || !t.objectives.iter().all(|o| ok(o)))
        {
            return Err(invalid("told", t.fitness.len(), "does not match the batch"));
        }
        if s.batch.is_empty() || s.parents.len() > s.nsga.population_size {
            return Err(invalid(
                "batch",
                s.batch.len(),
                "empty, or too many parents",
            ));
        }
        Ok(())
    }
}

impl Nsga2 {
    /// Generation 0: `nsga.population_size` minimal genomes drawn from a
    /// `Pcg64` seeded with `seed` (also the run seed of every evaluation).
    pub fn new(
        params: NeatParams,
        spec: GenomeSpec,
        nsga: Nsga2Params,
        seed: u64,
    ) -> Result<Nsga2, NeatError> {
        check_neat(&params, &spec)?;
        nsga.validate()?;
        let (rng, tracker, batch) = first_batch(&spec, &params, seed, nsga.population_size);
        Ok(Nsga2(State {
            spec,
            params,
            nsga,
            seed,
            generation: 0,
            rng,
            tracker,
            parents: Vec::new(),
            batch,
            told: None,
            best: None,
        }))
    }

    /// The settings.
    pub fn params(&self) -> &Nsga2Params {
        &self.0.nsga
    }

    /// The non-dominated members of the parents and the batch just told:
    /// each genome with its objective values as the task measured them and
    /// its fitness, in order (parents first).
    pub fn pareto_front(&self) -> Vec<(&Genome, Vec<f64>, f64)> {
        let s = &self.0;
        let mut pool: Vec<(&Genome, &[f64], f64)> = (s.parents.iter())
            .map(|p| (&p.genome, &p.objectives[..], p.fitness))
            .collect();
        if let Some(t) = &s.told {
            let told = s.batch.iter().zip(&t.objectives).zip(&t.fitness);
            pool.extend(told.map(|((g, o), &f)| (g, &o[..], f)));
        }
        let objectives: Vec<&[f64]> = pool.iter().map(|p| p.1).collect();
        let fronts = non_dominated_fronts(&objectives);
        let first = fronts.into_iter().next().unwrap_or_default();
        let sense = |o: &Objective, v: f64| if o.maximise { v } else { -v };
        first
            .into_iter()
            .map(|i| {
                let (g, o, f) = pool[i];
                let raw = s
                    .nsga
                    .objectives
                    .iter()
                    .zip(o)
                    .map(|(obj, &v)| sense(obj, v));
                (g, raw.collect(), f)
            })
            .collect()
    }

    /// The objective values, as the task measured them, of every member of
    /// the parents and the batch just told (the pool [`Nsga2::pareto_front`]
    /// picks from), parents first.
    pub fn scored_objectives(&self) -> Vec<Vec<f64>> {
        let s = &self.0;
        let told = s.told.iter().flat_map(|t| &t.objectives);
        let measured = |o: &Vec<f64>| -> Vec<f64> {
            let senses = s.nsga.objectives.iter().zip(o);
            senses
                .map(|(obj, &v)| if obj.maximise { v } else { -v })
                .collect()
        };
        (s.parents.iter().map(|p| &p.objectives))
            .chain(told)
            .map(measured)
            .collect()
    }

    /// Environmental selection on parents ∪ the batch told: the next
    /// parents, with their ranks and crowding distances.
    fn select(&mut self, told: Told) -> (Vec<usize>, Vec<f64>) {
        let s = &mut self.0;
        let children = s.batch.drain(..).zip(told.objectives).zip(told.fitness);
        s.parents
            .extend(children.map(|((genome, objectives), fitness)| Member {
                genome,
                objectives,
                fitness,
            }));
        let objectives: Vec<&[f64]> = s.parents.iter().map(|p| &p.objectives[..]).collect();
        let n = s.nsga.population_size;
        let mut crowd = vec![0.0; objectives.len()];
        let (mut keep, mut ranks) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for (rank, front) in non_dominated_fronts(&objectives).into_iter().enumerate() {
            if keep.len() == n {
                break;
            }
            crowding_distances(&front, &objectives, &mut crowd);
            let mut front = front;
            if keep.len() + front.len() > n {
                front.sort_by(|&a, &b| crowd[b].total_cmp(&crowd[a]).then(a.cmp(&b)));
                front.truncate(n - keep.len());
            }
            ranks.extend(std::iter::repeat_n(rank, front.len()));
            keep.extend(front);
        }
        let crowding = keep.iter().map(|&i| crowd[i]).collect();
        let mut pool: Vec<Option<Member>> = s.parents.drain(..).map(Some).collect();
        s.parents = keep.iter().filter_map(|&i| pool[i].take()).collect();
        (ranks, crowding)
    }
}

impl Strategy for Nsga2 {
    told_batch_accessors!();

    fn tell(&mut self, evaluations: &[Evaluation]) -> Result<(), NeatError> {
        let s = &mut self.0;
        check_count(evaluations.len(), s.batch.len())?;
        let mut objectives = Vec::with_capacity(evaluations.len());
        for e in evaluations {
            let o: Option<Vec<f64>> = s.nsga.objectives.iter().map(|o| o.of(e)).collect();
            let reason = "an objective names a metric the evaluation does not have";
            objectives.push(o.ok_or_else(|| invalid("objectives", e.metrics.len(), reason))?);
        }
        let fitness: Vec<f64> = evaluations.iter().map(Evaluation::finite_fitness).collect();
        let told = Told {
            objectives,
            fitness,
        };
        told::record(&mut s.told, &mut s.best, &s.batch, s.generation, told);
        Ok(())
    }

    fn prepare(&mut self) {
        let Some(told) = self.0.told.take() else {
            return;
        };
        let (ranks, crowding) = self.select(told);
        let s = &mut self.0;
        let parents = &s.parents;
        // Binary tournament on the crowded comparison; a tie goes to the first drawn.
        let tournament = |rng: &mut Pcg64| {
            let (a, b) = (
                rng.random_range(0..parents.len()),
                rng.random_range(0..parents.len()),
            );
            let a_wins =
                ranks[a] < ranks[b] || (ranks[a] == ranks[b] && crowding[a] >= crowding[b]);
            if a_wins { a } else { b }
        };
        // The better ranked parent counts as the fitter in crossover.
        let pick = |rng: &mut Pcg64| {
            let i = tournament(rng);
            (&parents[i].genome, -(ranks[i] as f64))
        };
        let next = (&mut s.batch, &mut s.generation);
        let size = (s.nsga.population_size, s.nsga.crossover_probability);
        Breeding::new(&s.spec, &s.params, &mut s.tracker, &mut s.rng).next_batch(next, size, pick);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn objectives_read_fitness_and_metrics_in_their_sense() {
        let e = Evaluation {
            fitness: 2.0,
            metrics: vec![5.0, f64::NAN],
            behaviour: vec![],
        };
        let of = |measure, maximise| Objective { measure, maximise }.of(&e);
        assert_eq!(of(Measure::Fitness, true), Some(2.0));
        assert_eq!(of(Measure::Metric(0), false), Some(-5.0));
        assert_eq!(
            of(Measure::Metric(1), true),
            Some(f64::MIN),
            "non-finite is the worst"
        );
        assert_eq!(of(Measure::Metric(2), true), None);
    }

    #[test]
    fn selection_keeps_whole_fronts_then_the_least_crowded() {
        let spec = GenomeSpec::plain(2, 1);
        let nsga = Nsga2Params {
            population_size: 4,
            objectives: vec![
                Objective {
                    measure: Measure::Fitness,
                    maximise: true
                };
                2
            ],
            crossover_probability: 0.5,
        };
        let mut es = Nsga2::new(NeatParams::plain_neat(), spec, nsga, 9).unwrap();
        // Generation 0 told by hand: four genomes, fronts {0, 1, 3} and {2}.
        let objectives = vec![
            vec![0.0, 4.0],
            vec![2.0, 2.0],
            vec![1.0, 1.0],
            vec![4.0, 0.0],
        ];
        let told = Told {
            objectives,
            fitness: vec![0.0; 4],
        };
        let genomes = es.0.batch.clone();
        let (ranks, crowding) = es.select(told);
        assert_eq!(ranks, [0, 0, 0, 1]);
        assert_eq!(crowding, [f64::INFINITY, 2.0, f64::INFINITY, f64::INFINITY]);
        let kept: Vec<&Genome> = es.0.parents.iter().map(|p| &p.genome).collect();
        assert_eq!(kept, [&genomes[0], &genomes[1], &genomes[3], &genomes[2]]);

        // Now 8 compete for 4: front 0 has five members and loses its most crowded.
        es.0.batch = genomes;
        let objectives = vec![
            vec![1.0, 3.0],
            vec![3.5, 0.5],
            vec![0.0, 0.0],
            vec![0.0, 0.0],
        ];
        let (ranks, crowding) = es.select(Told {
            objectives,
            fitness: vec![0.0; 4],
        });
        // Pool: parents (0,4) (2,2) (4,0) (1,1), children (1,3) (3.5,0.5) (0,0) (0,0).
        // Front 0 = (0,4) (2,2) (4,0) (1,3) (3.5,0.5); crowding ∞, 1.25, ∞, 1, 1.
        assert_eq!(ranks, [0; 4]);
        assert_eq!(crowding, [f64::INFINITY, f64::INFINITY, 1.25, 1.0]);
        let kept: Vec<&[f64]> = es.0.parents.iter().map(|p| &p.objectives[..]).collect();
        assert_eq!(
            kept,
            [&[0.0, 4.0][..], &[4.0, 0.0], &[2.0, 2.0], &[1.0, 3.0]]
        );
    }

    #[test]
    fn checkpoints_that_contradict_themselves_are_refused() {
        let nsga = Nsga2Params {
            population_size: 6,
            objectives: vec![
                Objective {
                    measure: Measure::Metric(0),
                    maximise: false
                };
                2
            ],
            crossover_probability: 0.5,
        };
        let spec = GenomeSpec::plain(2, 1);
        let mut es = Nsga2::new(NeatParams::plain_neat(), spec, nsga, 4).unwrap();
        for _ in 0..2 {
            let n = es.ask().genomes.len();
            let told = |i: usize| Evaluation {
                metrics: vec![i as f64],
                ..Evaluation::fitness(1.0)
            };
            es.tell(&(0..n).map(told).collect::<Vec<_>>()).unwrap();
        }
        let reread = |edit: &dyn Fn(&mut State)| {
            let mut state = es.0.clone();
            edit(&mut state);
            serde_json::from_str::<Nsga2>(&serde_json::to_string(&state).unwrap())
        };
        assert_eq!(reread(&|_| ()).unwrap(), es);
        assert!(
            reread(&|s| {
                s.parents[0].objectives.pop();
            })
            .is_err()
        );
        let fewer = |s: &mut State| drop(s.told.as_mut().unwrap().objectives.pop());
        assert!(reread(&fewer).is_err(), "objectives for fewer children");
        assert!(reread(&|s| s.nsga.objectives.clear()).is_err());
        let crowded = |s: &mut State| s.parents.extend(s.parents.clone());
        assert!(
            reread(&crowded).is_err(),
            "more parents than the population size"
        );
    }
}
