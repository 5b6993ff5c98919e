//! Double pole balancing on a cart (Stanley & Miikkulainen 2002, "Evolving
//! neural networks through augmenting topologies", Evolutionary Computation
//! 10(2), Sec. 4.3; Gomez, Schmidhuber & Miikkulainen 2008, JMLR 9, Sec. 5),
//! the task of `cargo run -p vivae-neat --example pole` and of `vivae
//! reproduce pole-markov | pole-nonmarkov`. docs/neat-benchmarks.md gives the
//! setup, its sources and the measured results.
//!
//! Wieland's equations for two poles (1.0 m and 0.1 m, masses 0.1 and 0.01 kg) on a
//! 1 kg cart, integrated with 4th-order Runge–Kutta in 0.01 s steps; as in Stanley's and
//! Gomez's code, the controller acts every two integration steps (0.02 s). Force
//! `(out − 0.5)·20` N; failure when |x| > 2.4 m or a pole leaves ±36°. Sines and
//! cosines are the portable ones ([`crate::math`]), so a run is the same bits on
//! every machine.
//!
//! * Markov: inputs x, ẋ, θ1, θ̇1, θ2, θ̇2 (scaled as in Stanley's code) and a
//!   bias; feed-forward networks; fitness = steps balanced; solved = 100,000 steps.
//! * Non-Markov: inputs x, θ1, θ2 and a bias; recurrent networks (synchronous update);
//!   Gruau's damping fitness over 1,000 steps. As in Stanley's code, each generation one
//!   species champion is tested for 100,000 steps and, if it passes, on the 625
//!   generalisation starts (≥ 200 balanced for 1,000 steps = solved): the champion of
//!   the best species not yet tested since its best fitness last rose, else of the best.
//!
//! Evaluations are counted up to and including the solving genome (non-Markov: the
//! whole generation in which it was found, as Stanley counted).
//!
//! For Gomez et al. (2008)'s damping-fitness comparison, [`Criterion::Gomez`] tests
//! the generation's best genome for 100,000 steps only, [`Setup::start`] can start
//! the long pole at their 4.0°, and [`Setup::restart_after`] restarts a population
//! stuck for G generations, counting every attempt's evaluations.

use std::collections::BTreeMap;

use super::cart_pole::balance;
pub use super::cart_pole::{SUCCESS_STEPS, State, score, start_state};
use crate::{
    Activation, FeedForwardNetwork, Genome, GenomeSpec, NeatError, NeatParams, Population,
    RecurrentNetwork,
};

/// The 625 generalisation starts: x, ẋ, θ1, θ̇1 each at 0.05, 0.25, 0.5, 0.75, 0.95 of
/// their ranges (±2.16 m, ±1.35 m/s, ±3.6°, ±8.6°/s).
pub fn generalisation(g: &Genome) -> usize {
    let levels = [0.05, 0.25, 0.5, 0.75, 0.95];
    let span = |r: f64, l: f64| (l * 2.0 - 1.0) * r;
    let mut net = RecurrentNetwork::from_genome(g);
    let mut ok = 0;
    for &a in &levels {
        for &b in &levels {
            for &c in &levels {
                for &d in &levels {
                    let s = [
                        span(2.16, a),
                        span(1.35, b),
                        span(3.6f64.to_radians(), c),
                        span(8.6f64.to_radians(), d),
                        0.0,
                        0.0,
                    ];
                    if balance(&mut net, false, s, 1000).0 == 1000 {
                        ok += 1;
                    }
                }
            }
        }
    }
    ok
}

/// The genome shape: 7 inputs feed-forward with velocities, 4 recurrent without.
pub fn spec(markov: bool) -> GenomeSpec {
    GenomeSpec {
        inputs: if markov { 7 } else { 4 },
        outputs: 1,
        output_activation: Activation::Sigmoid,
        hidden_activations: vec![Activation::Sigmoid],
        allow_recurrent: !markov,
    }
}

/// Parameters used for double pole balancing (Stanley's where ours match his).
///
/// Without velocities the weights start wider (±2.5, as in `plain_neat`) and are
/// perturbed more finely (σ = 1.0): a controller that must infer velocities from
/// recurrence needs large weights tuned precisely (docs/neat-benchmarks.md measures
/// each change). The Markov settings are unchanged.
pub fn pole_params(markov: bool) -> NeatParams {
    NeatParams {
        population_size: if markov { 150 } else { 1000 },
        initial_weight_range: if markov { 1.0 } else { 2.5 },
        add_link_probability: 0.05,
        // NEAT's default replacement rate (10 %), not plain NEAT's 20 %.
        weight_replace_probability: NeatParams::default().weight_replace_probability,
        weight_perturb_power: if markov { 2.5 } else { 1.0 },
        // Population 1000 at threshold 3.0 splits into ~170 tiny species; steer to 20.
        target_species: if markov { None } else { Some(20) },
        ..NeatParams::plain_neat()
    }
}

/// `--small`: the task without velocities with a population of 150 steered
/// to 10 species, and Stanley's survival threshold (0.4) against the early
/// convergence a small population brings (docs/neat-benchmarks.md measures
/// each part).
pub fn small_params() -> NeatParams {
    NeatParams {
        population_size: 150,
        target_species: Some(10),
        survival_threshold: 0.4,
        ..pole_params(false)
    }
}

/// Which species champion to test each generation, as in Stanley's `pole2_epoch`: the
/// champion of the best species not yet tested since its best fitness last rose, else
/// that of the best species. Re-testing the population champion instead would test
/// the same elite, generation after generation, once it fails.
#[derive(Default)]
pub struct ChampionRotation {
    /// Per species id: the best fitness seen, and whether its champion was tested since.
    seen: BTreeMap<u32, (f64, bool)>,
}

impl ChampionRotation {
    /// The index of the genome to test in the evaluated population.
    pub fn pick(&mut self, pop: &Population) -> Option<usize> {
        let f = pop.fitnesses();
        // (species best fitness, species id, champion index), best species first.
        let mut ranked: Vec<(f64, u32, usize)> = pop
            .species()
            .iter()
            .filter_map(|s| {
                let champ = s.members.iter().copied().max_by(|&a, &b| {
                    f[a].total_cmp(&f[b]).then(b.cmp(&a)) // lowest index among ties
                })?;
                Some((f[champ], s.id, champ))
            })
            .collect();
        ranked.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        for &(best, id, _) in &ranked {
            let entry = self.seen.entry(id).or_insert((f64::NEG_INFINITY, false));
            if best > entry.0 {
                *entry = (best, false);
            }
        }
        let &(_, id, champ) = ranked
            .iter()
            .find(|r| !self.seen[&r.1].1)
            .or(ranked.first())?;
        self.seen.get_mut(&id)?.1 = true;
        Some(champ)
    }
}

/// The generalisation score of `g` if it balances 100,000 steps from `start`.
fn long_run_then_generalisation(g: &Genome, start: State) -> Option<usize> {
    let mut net = RecurrentNetwork::from_genome(g);
    (balance(&mut net, false, start, SUCCESS_STEPS).0 == SUCCESS_STEPS).then(|| generalisation(g))
}

/// When a run without velocities counts as solved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Criterion {
    /// Stanley's: a species champion (by [`ChampionRotation`]) balances
    /// 100,000 steps and then ≥ 200 of the 625 generalisation starts.
    Stanley,
    /// Gomez et al. (2008), Section 5.4: "the best controller from each
    /// generation" balances 100,000 steps; no generalisation test (its score
    /// is still measured and reported).
    Gomez,
}

impl Criterion {
    /// `stanley` or `gomez`; the error is one line naming the value.
    pub fn parse(s: &str) -> Result<Self, String> {
        match s {
            "stanley" => Ok(Criterion::Stanley),
            "gomez" => Ok(Criterion::Gomez),
            _ => Err(format!("--criterion takes stanley or gomez, got `{s}`")),
        }
    }
}

/// The solution found this generation by `criterion`, if any: the genome and
/// its generalisation score.
fn solution(
    pop: &Population,
    criterion: Criterion,
    rotation: &mut ChampionRotation,
    start: State,
) -> Option<(usize, usize)> {
    match criterion {
        Criterion::Stanley => {
            let i = rotation.pick(pop)?;
            let score = long_run_then_generalisation(&pop.genomes()[i], start)?;
            (score >= 200).then_some((i, score))
        }
        Criterion::Gomez => {
            let f = pop.fitnesses();
            // The best genome, lowest index among ties.
            let i = (0..f.len()).max_by(|&a, &b| f[a].total_cmp(&f[b]).then(b.cmp(&a)))?;
            long_run_then_generalisation(&pop.genomes()[i], start).map(|score| (i, score))
        }
    }
}

/// The outcome of one run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PoleRun {
    /// Evaluations until the solution (see the module's counting), `None` when unsolved.
    pub evals: Option<usize>,
    /// Hidden nodes of the solution.
    pub hidden: usize,
    /// Generalisation score (of 625) of the solution, without velocities.
    pub generalisation: Option<usize>,
}

/// Everything a run needs besides its seed.
#[derive(Clone, Debug)]
pub struct Setup {
    /// The NEAT parameters.
    pub params: NeatParams,
    /// Velocities given (feed-forward networks, solved = 100,000 steps).
    pub markov: bool,
    /// When a run without velocities counts as solved.
    pub criterion: Criterion,
    /// Start a fresh population after this many generations without a solution.
    pub restart_after: Option<u32>,
    /// Generations of all attempts together before the run counts as unsolved.
    pub max_generations: u32,
    /// The state every trial but the generalisation starts begins from.
    pub start: State,
}

impl Setup {
    /// The task with velocities, Stanley's settings: population 150, at
    /// most 200 generations.
    pub fn markov() -> Setup {
        Setup {
            params: pole_params(true),
            markov: true,
            criterion: Criterion::Stanley,
            restart_after: None,
            max_generations: 200,
            start: start_state(true, 4.5),
        }
    }

    /// The task without velocities on Stanley's 2002 terms, population 1,000
    /// (`--small`: population 150, 10 species, survival 0.4, the settings
    /// that meet his row), at most 150,000 evaluations.
    pub fn nonmarkov(small: bool) -> Setup {
        Setup {
            params: if small {
                small_params()
            } else {
                pole_params(false)
            },
            markov: false,
            criterion: Criterion::Stanley,
            restart_after: None,
            max_generations: if small { 1000 } else { 150 },
            start: start_state(false, 4.5),
        }
    }

    /// The task without velocities on Gomez et al. 2008's terms (their rule,
    /// the long pole at 4.0°), population 16 in 2 species, σ 0.5, restarted
    /// after 250 generations, at most 150,000 evaluations: the best setting
    /// docs/neat-benchmarks.md measured.
    pub fn gomez() -> Setup {
        Setup {
            params: NeatParams {
                population_size: 16,
                target_species: Some(2),
                weight_perturb_power: 0.5,
                ..small_params()
            },
            markov: false,
            criterion: Criterion::Gomez,
            restart_after: Some(250),
            max_generations: 9375,
            start: start_state(false, 4.0),
        }
    }
}

/// The task's fitness of every genome, their trials side by side
/// ([`super::pole_lanes`]: the bits of [`score`] of each one's network), a share of the
/// genomes per rayon thread.
fn lane_fitnesses(genomes: &[Genome], markov: bool, start: State) -> Vec<f64> {
    use super::pole_lanes::score_lanes;
    use rayon::prelude::*;
    let share = genomes.len().div_ceil(rayon::current_num_threads()).max(1);
    genomes
        .par_chunks(share)
        .flat_map_iter(|gs| {
            let mut out = Vec::with_capacity(gs.len());
            if markov {
                let mut nets: Vec<_> = gs.iter().map(FeedForwardNetwork::from_genome).collect();
                score_lanes(&mut nets, true, start, &mut out);
            } else {
                let mut nets: Vec<_> = gs.iter().map(RecurrentNetwork::from_genome).collect();
                score_lanes(&mut nets, false, start, &mut out);
            }
            out.into_iter().map(|(f, _)| f)
        })
        .collect()
}

/// One population evolved for at most `generations`: the result if solved, else
/// the evaluations spent.
fn attempt(
    setup: &Setup,
    seed: u64,
    generations: u32,
    observe: &mut dyn FnMut(&Population),
) -> Result<Result<PoleRun, usize>, NeatError> {
    let markov = setup.markov;
    let mut pop = Population::new(setup.params.clone(), spec(markov), seed)?;
    let mut rotation = ChampionRotation::default();
    let mut spent = 0;
    for _ in 0..generations {
        let fitness = lane_fitnesses(pop.genomes(), markov, setup.start);
        pop.set_fitnesses(fitness)?;
        let done = spent;
        spent += pop.genomes().len();
        if markov {
            let f = pop.fitnesses();
            if let Some(i) = f.iter().position(|&x| x >= SUCCESS_STEPS as f64) {
                return Ok(Ok(PoleRun {
                    evals: Some(done + i + 1),
                    hidden: pop.genomes()[i].num_hidden(),
                    generalisation: None,
                }));
            }
        } else if let Some((i, score)) = solution(&pop, setup.criterion, &mut rotation, setup.start)
        {
            return Ok(Ok(PoleRun {
                evals: Some(spent),
                hidden: pop.genomes()[i].num_hidden(),
                generalisation: Some(score),
            }));
        }
        observe(&pop);
        pop.next_generation();
    }
    Ok(Err(spent))
}

/// A run: attempts of at most `restart_after` generations each (the first with
/// `seed`, attempt k with `seed ^ k << 32`) until one solves or
/// `max_generations` are spent; every attempt's evaluations count.
pub fn run(setup: &Setup, seed: u64) -> Result<PoleRun, NeatError> {
    run_observed(setup, seed, &mut |_| {})
}

/// [`run`], telling `observe` each unsolved generation's population once its
/// fitnesses are set (the example's `POLE_TRACE`).
pub fn run_observed(
    setup: &Setup,
    seed: u64,
    observe: &mut dyn FnMut(&Population),
) -> Result<PoleRun, NeatError> {
    let mut left = setup.max_generations;
    let mut spent = 0;
    for k in 0u64.. {
        let generations = setup.restart_after.unwrap_or(left).min(left);
        if generations == 0 {
            break;
        }
        match attempt(setup, seed ^ (k << 32), generations, observe)? {
            Ok(result) => {
                return Ok(PoleRun {
                    evals: result.evals.map(|e| e + spent),
                    ..result
                });
            }
            Err(evals) => spent += evals,
        }
        left -= generations;
    }
    Ok(PoleRun::default())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::benchmarks::pole_lanes::score_lanes;
    use crate::simd;
    use crate::test_genes::grown;
    use crate::{InnovationTracker, RecurrentNetwork};
    use rand::SeedableRng;

    #[test]
    fn the_markov_task_is_solved_and_counts_evaluations_up_to_the_solver() {
        let setup = Setup::markov();
        let r = run(&setup, 1).unwrap();
        let evals = r.evals.expect("seed 1 solves the Markov task");
        assert!(evals > 1 && r.generalisation.is_none(), "{r:?}");
        assert_eq!(run(&setup, 1).unwrap(), r, "deterministic");
        let mut generations = 0;
        run_observed(&setup, 1, &mut |_| generations += 1).unwrap();
        assert_eq!(
            evals.div_ceil(150),
            generations + 1,
            "observed: the unsolved generations"
        );
        let one = Setup {
            max_generations: 1,
            ..Setup::markov()
        };
        let first = run(&one, 1).unwrap();
        assert!(first.evals.is_none() || first.evals == r.evals);
    }

    #[test]
    fn a_failing_controller_balances_no_generalisation_start() {
        let g = Population::new(pole_params(false), spec(false), 1)
            .unwrap()
            .genomes()[0]
            .clone();
        assert!(generalisation(&g) < 625);
        assert!(Criterion::parse("gomez").is_ok() && Criterion::parse("x").is_err());
        assert_eq!(Setup::gomez().params.population_size, 16);
    }

    #[test]
    fn episodes_side_by_side_score_each_genome_as_alone() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        for markov in [true, false] {
            let (spec, params) = (spec(markov), pole_params(markov));
            let mut tracker = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
            // Grown genomes and a first generation: trials of every length
            // (some past 100 steps, where the damping term counts), more
            // than the lanes, so lanes are refilled and then compacted.
            let mut genomes: Vec<_> = (0..21)
                .map(|i| grown(&spec, &params, &mut tracker, &mut rng, i % 5))
                .collect();
            // A few generations of evolution, so that some trials balance long.
            let mut pop = crate::Population::new(params.clone(), spec.clone(), 1).unwrap();
            let start = start_state(markov, 4.5);
            for _ in 0..8 {
                pop.evaluate(|g, _| {
                    if markov {
                        score(&mut FeedForwardNetwork::from_genome(g), true, start).0
                    } else {
                        score(&mut RecurrentNetwork::from_genome(g), false, start).0
                    }
                });
                pop.next_generation();
            }
            genomes.extend_from_slice(&pop.genomes()[..150]);
            let alone: Vec<(f64, u32)> = genomes
                .iter()
                .map(|g| {
                    if markov {
                        score(&mut FeedForwardNetwork::from_genome(g), markov, start)
                    } else {
                        score(&mut RecurrentNetwork::from_genome(g), markov, start)
                    }
                })
                .collect();
            let lengths: std::collections::BTreeSet<u32> = alone.iter().map(|a| a.1).collect();
            assert!(lengths.len() > 5, "trials of several lengths: {lengths:?}");
            assert!(
                lengths.last() > Some(&100),
                "a trial past 100 steps: {lengths:?}"
            );
            for level in simd::available() {
                let before = simd::set_level(level);
                let mut out = Vec::new();
                if markov {
                    let mut nets: Vec<_> = genomes
                        .iter()
                        .map(FeedForwardNetwork::from_genome)
                        .collect();
                    score_lanes(&mut nets, markov, start, &mut out);
                } else {
                    let mut nets: Vec<_> =
                        genomes.iter().map(RecurrentNetwork::from_genome).collect();
                    score_lanes(&mut nets, markov, start, &mut out);
                }
                simd::set_level(before);
                let bits =
                    |v: &[(f64, u32)]| v.iter().map(|(f, t)| (f.to_bits(), *t)).collect::<Vec<_>>();
                assert_eq!(bits(&out), bits(&alone), "markov {markov}, {level:?}");
            }
        }
    }
}
