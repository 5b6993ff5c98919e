//! Two NEAT populations co-evolved: hunters and prey, each genome evaluated
//! against opponents from the other population, and the records of
//! co-evolutionary progress (the hall of fame and the CIAO matrix).
//!
//! A generation: each population's opponents are picked from the other's
//! hall of fame *before* the generation (so both sides are evaluated
//! against the past, in either order, and the result does not depend on
//! which goes first); every genome plays one episode against each opponent
//! and its fitness is the mean; each side's best joins its hall of fame;
//! the new hunter champion plays every prey champion so far and the new
//! prey champion every earlier hunter champion (the CIAO matrix's new row
//! and column, Cliff & Miller 1995).

use serde::{Deserialize, Serialize};
use vivae_neat::driver::Strategy;
use vivae_neat::{GenerationStats, Genome, NeatError, Population, eval_seed};

use crate::config::Config;
use crate::error::{Error, Result};
use crate::tasks::predator_prey::meetings::{Meetings, Pair};
use crate::tasks::predator_prey::section::{CoevolutionConfig, Opponents};
use crate::tasks::predator_prey::{Arena, Outcome, Side};

/// One cell of the CIAO matrix: the best hunter of one generation against
/// the best prey of another.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CiaoCell {
    /// The hunter's generation.
    pub hunter: u32,
    /// The prey's generation.
    pub prey: u32,
    /// The hunter's fitness in the episode (the prey's is 2 minus it).
    pub hunter_fitness: f64,
    /// Whether the hunter caught the prey.
    pub caught: bool,
}

/// What one generation of one side gave.
#[derive(Debug, Clone, PartialEq)]
pub struct SideRecord {
    /// Its statistics (best and mean fitness, species, sizes).
    pub stats: GenerationStats,
    /// The generations of the opponents it met (the other side's hall of fame).
    pub opponents: Vec<u32>,
    /// Share of its episodes that ended in a catch.
    pub catch_rate: f64,
}

/// What one generation gave.
#[derive(Debug, Clone, PartialEq)]
pub struct GenerationRecord {
    /// Its number (0 = the first).
    pub generation: u32,
    /// The hunters'.
    pub hunters: SideRecord,
    /// The prey's.
    pub prey: SideRecord,
    /// The CIAO matrix's new cells.
    pub ciao: Vec<CiaoCell>,
}

/// The complete state of a co-evolution: serialisable, so that a restored
/// one continues bit-identically.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Coevolution {
    /// The hunter population.
    pub hunters: Population,
    /// The prey population.
    pub prey: Population,
    /// The best hunter of every generation done (the hunters' hall of fame).
    pub hall_hunters: Vec<Genome>,
    /// The best prey of every generation done.
    pub hall_prey: Vec<Genome>,
    /// The run's seed (the hall-of-fame samples are drawn from it).
    pub seed: u64,
    /// With opponents = "fixed": the prey every hunter meets (the prey
    /// population then does not evolve).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fixed_prey: Option<Genome>,
}

impl Coevolution {
    /// Two fresh populations of `config`'s NEAT settings, of the genomes of
    /// their sides' kinds (`[coevolution] hunter`, `prey`): the hunters from
    /// the run's seed, the prey from a seed derived from it.
    pub fn new(config: &Config) -> Result<Coevolution, NeatError> {
        let seed = config.experiment.seed;
        let c = &CoevolutionConfig::of(config);
        let (hunters, prey) = (Arena::spec_of(c.hunter), Arena::spec_of(c.prey));
        Ok(Coevolution {
            hunters: Population::new(config.neat.clone(), hunters, seed)?,
            prey: Population::new(config.neat.clone(), prey, eval_seed(seed, u32::MAX, 1))?,
            hall_hunters: Vec::new(),
            hall_prey: Vec::new(),
            seed,
            fixed_prey: None,
        })
    }

    /// Generations done.
    pub fn done(&self) -> u32 {
        self.hall_hunters.len() as u32
    }

    /// The hall of fame of `side`.
    pub fn hall(&self, side: Side) -> &[Genome] {
        match side {
            Side::Hunter => &self.hall_hunters,
            Side::Prey => &self.hall_prey,
        }
    }

    /// The generations of the opponents `side` meets in generation `g`:
    /// indices into the other side's hall of fame (empty in generation 0,
    /// when it meets the other population's first genome).
    pub fn opponents(&self, side: Side, g: u32, how: Opponents, sample: usize) -> Vec<u32> {
        let n = self.hall(side.other()).len() as u64;
        if n == 0 {
            return Vec::new();
        }
        match how {
            // Fixed: the hunters meet the fixed prey, not a hall of fame.
            Opponents::Best | Opponents::Fixed => vec![(n - 1) as u32],
            Opponents::HallOfFame => {
                let stream = match side {
                    Side::Hunter => 0,
                    Side::Prey => 1 << 20,
                };
                (0..sample.max(1))
                    .map(|k| (eval_seed(self.seed, g, stream + k) % n) as u32)
                    .collect()
            }
        }
    }

    /// Plays generation `done()`: breeds both populations (after the first),
    /// has `meetings` play every genome against its side's opponents (both
    /// sides in one batch), and adds both champions to the halls of fame.
    pub fn generation(
        &mut self,
        arena: &Arena,
        config: &Config,
        meetings: &dyn Meetings,
    ) -> Result<GenerationRecord> {
        if let Some(prey) = self.fixed_prey.clone() {
            return self.generation_fixed(arena, &prey, meetings);
        }
        let g = self.done();
        let how = CoevolutionConfig::of(config).opponents;
        let sample = CoevolutionConfig::of(config).sample;
        self.hunters.prepare();
        self.prey.prepare();
        let picks = [Side::Hunter, Side::Prey].map(|s| self.opponents(s, g, how, sample));
        let against = [
            self.opponent_genomes(Side::Hunter, &picks[0]),
            self.opponent_genomes(Side::Prey, &picks[1]),
        ];
        let [hunters, prey] = {
            let (hs, ps) = (self.hunters.genomes(), self.prey.genomes());
            let hunter_pairs = hs
                .iter()
                .flat_map(|h| against[0].iter().map(move |o| (h, o)));
            let prey_pairs = ps
                .iter()
                .flat_map(|p| against[1].iter().map(move |o| (o, p)));
            let pairs: Vec<Pair<'_>> = hunter_pairs.chain(prey_pairs).collect();
            let outcomes = meetings.play(arena, &pairs).map_err(evolution)?;
            let (ho, po) = outcomes.split_at(hs.len() * against[0].len());
            [
                scores(Side::Hunter, ho, against[0].len()),
                scores(Side::Prey, po, against[1].len()),
            ]
        };
        let catches = [hunters.1, prey.1];
        self.hunters.set_fitnesses(hunters.0).map_err(evolution)?;
        self.prey.set_fitnesses(prey.0).map_err(evolution)?;
        let champion = |pop: &Population| pop.champion().map(|(g, _)| g.clone());
        let (h, p) = (champion(&self.hunters), champion(&self.prey));
        let (Some(h), Some(p)) = (h, p) else {
            return Err(evolution("an empty population"));
        };
        self.hall_hunters.push(h);
        self.hall_prey.push(p);
        let record = |pop: &Population, picks: &[u32], caught: usize, games: usize| SideRecord {
            stats: pop.stats(),
            opponents: picks.to_vec(),
            catch_rate: caught as f64 / games.max(1) as f64,
        };
        let games = |k: usize, pop: &Population| against[k].len() * pop.genomes().len();
        Ok(GenerationRecord {
            generation: g,
            hunters: record(
                &self.hunters,
                &picks[0],
                catches[0],
                games(0, &self.hunters),
            ),
            prey: record(&self.prey, &picks[1], catches[1], games(1, &self.prey)),
            ciao: self.ciao_of(arena, g, meetings)?,
        })
    }

    /// The genomes `side` meets at the hall-of-fame indices `picks` (the
    /// other population's first genome when there are none: generation 0).
    fn opponent_genomes(&self, side: Side, picks: &[u32]) -> Vec<Genome> {
        if picks.is_empty() {
            let first = match side {
                Side::Hunter => &self.prey.genomes()[0],
                Side::Prey => &self.hunters.genomes()[0],
            };
            vec![first.clone()]
        } else {
            let hall = self.hall(side.other());
            picks.iter().map(|&i| hall[i as usize].clone()).collect()
        }
    }

    /// Generation `done()` against the fixed prey `prey`: breeds and
    /// evaluates the hunters only; the prey's record is that one genome's
    /// (its fitness the mean over its games, `2 −` the hunters' mean) and
    /// it fills the prey's hall of fame, so the CIAO matrix's columns are
    /// all the fixed prey.
    fn generation_fixed(
        &mut self,
        arena: &Arena,
        prey: &Genome,
        meetings: &dyn Meetings,
    ) -> Result<GenerationRecord> {
        let g = self.done();
        self.hunters.prepare();
        let opponents = std::slice::from_ref(prey);
        let pairs: Vec<Pair<'_>> = self.hunters.genomes().iter().map(|h| (h, prey)).collect();
        let outcomes = meetings.play(arena, &pairs).map_err(evolution)?;
        let (fitness, caught) = scores(Side::Hunter, &outcomes, 1);
        let games = outcomes.len();
        let mean = fitness.iter().sum::<f64>() / fitness.len().max(1) as f64;
        self.hunters.set_fitnesses(fitness).map_err(evolution)?;
        let Some((h, _)) = self.hunters.champion() else {
            return Err(evolution("an empty population"));
        };
        self.hall_hunters.push(h.clone());
        self.hall_prey.push(prey.clone());
        let catch_rate = caught as f64 / games.max(1) as f64;
        // Every column is the same prey: one game per hunter champion.
        let pairs: Vec<Pair<'_>> = self.hall_hunters.iter().map(|h| (h, prey)).collect();
        let outcomes = meetings.play(arena, &pairs).map_err(evolution)?;
        let row: Vec<CiaoCell> = (0..=g)
            .zip(&outcomes)
            .map(|(h, out)| CiaoCell {
                hunter: h,
                prey: g,
                hunter_fitness: out.hunter_fitness(),
                caught: out.caught,
            })
            .collect();
        let last = row[g as usize];
        let ciao = (0..=g)
            .map(|p| CiaoCell { prey: p, ..last })
            .chain(row[..g as usize].iter().copied())
            .collect();
        Ok(GenerationRecord {
            generation: g,
            hunters: SideRecord {
                stats: self.hunters.stats(),
                opponents: Vec::new(),
                catch_rate,
            },
            prey: SideRecord {
                stats: GenerationStats::of_batch(g, opponents, &[2.0 - mean]),
                opponents: Vec::new(),
                catch_rate,
            },
            ciao,
        })
    }

    /// The CIAO matrix's cells new in generation `g`: its hunter champion
    /// against every prey champion up to `g`, and every earlier hunter
    /// champion against its prey champion (played by `meetings`).
    pub fn ciao_of(&self, arena: &Arena, g: u32, meetings: &dyn Meetings) -> Result<Vec<CiaoCell>> {
        let cells: Vec<(u32, u32)> = (0..=g)
            .map(|i| (g, i))
            .chain((0..g).map(|i| (i, g)))
            .collect();
        let pairs: Vec<Pair<'_>> = (cells.iter())
            .map(|&(h, p)| (&self.hall_hunters[h as usize], &self.hall_prey[p as usize]))
            .collect();
        let outcomes = meetings.play(arena, &pairs).map_err(evolution)?;
        Ok(cells
            .iter()
            .zip(&outcomes)
            .map(|(&(h, p), out)| CiaoCell {
                hunter: h,
                prey: p,
                hunter_fitness: out.hunter_fitness(),
                caught: out.caught,
            })
            .collect())
    }
}

/// An error of the co-evolution (a population's, or the meetings').
fn evolution(e: impl std::fmt::Display) -> Error {
    Error::Evolution(e.to_string())
}

/// What `champions.json` holds: each side's master-tournament winner.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Champions {
    /// Generations done.
    pub generations: u32,
    /// The hunter champion.
    pub hunter: ChampionEntry,
    /// The prey champion.
    pub prey: ChampionEntry,
}

/// One side's champion: the generation whose best has the highest mean
/// fitness against every champion of the other side (Floreano & Nolfi's
/// master tournament).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ChampionEntry {
    /// Its generation.
    pub generation: u32,
    /// Its mean fitness in the master tournament.
    pub master_fitness: f64,
    /// The genome.
    pub genome: Genome,
}

/// The mean fitness for `side` and the catches of each genome whose
/// meetings are `outcomes`, `per` consecutive ones per genome (its
/// opponents in order).
fn scores(side: Side, outcomes: &[Outcome], per: usize) -> (Vec<f64>, usize) {
    let fitness = (outcomes.chunks(per.max(1)))
        .map(|games| {
            let mut sum = 0.0;
            for out in games {
                sum += out.fitness(side);
            }
            sum / per.max(1) as f64
        })
        .collect();
    let caught = outcomes.iter().filter(|o| o.caught).count();
    (fitness, caught)
}

/// The master tournament (Floreano & Nolfi 1997) from a full CIAO matrix
/// of `n` generations: each generation's champion's mean fitness against
/// every champion of the other side, for `side`.
pub fn master_tournament(cells: &[CiaoCell], n: u32, side: Side) -> Vec<f64> {
    let mut sum = vec![0.0; n as usize];
    for c in cells {
        let (g, f) = match side {
            Side::Hunter => (c.hunter, c.hunter_fitness),
            Side::Prey => (c.prey, 2.0 - c.hunter_fitness),
        };
        if let Some(s) = sum.get_mut(g as usize) {
            *s += f;
        }
    }
    sum.iter().map(|s| s / f64::from(n.max(1))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::predator_prey::meetings::{MeetingsError, OnThreads};
    use vivae_sim::{LoadOptions, Scenario};

    fn setup(how: Opponents) -> (Arena, Config) {
        let mut config = Config::predator_prey();
        config.neat.population_size = 12;
        config.experiment.steps = 60;
        config.owned.update(|c: &mut CoevolutionConfig| {
            c.opponents = how;
            c.sample = 4;
        });
        let svg = crate::tasks::scenarios::find("predator-prey").unwrap().svg;
        let sc = Scenario::from_svg(svg, "pp.svg", &LoadOptions::default()).unwrap();
        let arena = Arena::new(&sc, &config.physics, config.experiment.steps).unwrap();
        (arena, config)
    }

    #[test]
    fn opponents_are_the_last_champion_or_a_sample_of_the_hall() {
        for how in [Opponents::Best, Opponents::HallOfFame] {
            let (arena, config) = setup(how);
            let mut co = Coevolution::new(&config).unwrap();
            for g in 0..4 {
                let r = co.generation(&arena, &config, &OnThreads).unwrap();
                assert_eq!(r.generation, g);
                let want = match (g, how) {
                    (0, _) => 0,
                    (_, Opponents::Best | Opponents::Fixed) => 1,
                    (_, Opponents::HallOfFame) => 4,
                };
                assert_eq!(r.hunters.opponents.len(), want, "{how:?} {g}");
                assert!(r.prey.opponents.iter().all(|&o| o < g));
                if how == Opponents::Best && g > 0 {
                    assert_eq!(r.hunters.opponents, [g - 1]);
                }
                // The CIAO matrix grows by a row and a column.
                assert_eq!(r.ciao.len() as u32, 2 * g + 1);
            }
            assert_eq!((co.done(), co.hall_prey.len()), (4, 4));
            // The two sides' samples are drawn from different streams.
            if how == Opponents::HallOfFame {
                let h = co.opponents(Side::Hunter, 9, how, 8);
                let p = co.opponents(Side::Prey, 9, how, 8);
                assert_ne!(h, p);
            }
        }
    }

    #[test]
    fn against_a_fixed_prey_only_the_hunters_evolve() {
        let (arena, config) = setup(Opponents::Fixed);
        let mut co = Coevolution::new(&config).unwrap();
        let prey = co.prey.genomes()[3].clone();
        co.fixed_prey = Some(prey.clone());
        let before = co.prey.clone();
        for g in 0..3 {
            let r = co.generation(&arena, &config, &OnThreads).unwrap();
            // The same CIAO cells as a co-evolution's: a row and a column.
            assert_eq!(r.ciao.len() as u32, 2 * g + 1);
            for c in &r.ciao {
                let out = arena.play_genomes(&co.hall_hunters[c.hunter as usize], &prey);
                assert_eq!(
                    (c.hunter_fitness, c.caught),
                    (out.hunter_fitness(), out.caught)
                );
            }
            let (h, p) = (r.hunters.stats.mean_fitness, r.prey.stats.best_fitness);
            assert!((h.unwrap() + p.unwrap() - 2.0).abs() < 1e-12);
        }
        assert!(co.hall_prey.iter().all(|g| *g == prey));
        assert_eq!(co.prey, before, "the prey population does not evolve");
    }

    /// Plays each batch backwards, one meeting at a time, as another
    /// player (the program's over MPI) may; or refuses every batch.
    struct Backwards {
        fail: bool,
        batches: std::sync::atomic::AtomicUsize,
    }

    impl Meetings for Backwards {
        fn play(&self, arena: &Arena, pairs: &[Pair<'_>]) -> Result<Vec<Outcome>, MeetingsError> {
            self.batches
                .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            if self.fail {
                return Err(MeetingsError("rank 1 is gone".into()));
            }
            let mut out: Vec<Outcome> = (pairs.iter().rev())
                .map(|&(h, p)| arena.play_genomes(h, p))
                .collect();
            out.reverse();
            Ok(out)
        }
    }

    #[test]
    fn any_player_of_the_meetings_gives_the_same_coevolution() {
        for how in [Opponents::Best, Opponents::HallOfFame, Opponents::Fixed] {
            let (arena, config) = setup(how);
            let mut a = Coevolution::new(&config).unwrap();
            if how == Opponents::Fixed {
                a.fixed_prey = Some(a.prey.genomes()[2].clone());
            }
            let mut b = a.clone();
            let player = Backwards {
                fail: false,
                batches: Default::default(),
            };
            for _ in 0..3 {
                let ra = a.generation(&arena, &config, &OnThreads).unwrap();
                let rb = b.generation(&arena, &config, &player).unwrap();
                assert_eq!(ra, rb, "{how:?}");
            }
            assert_eq!(a, b, "{how:?}");
            // Two batches a generation: its games, then its CIAO cells.
            assert_eq!(player.batches.into_inner(), 6);
        }
        let (arena, config) = setup(Opponents::Best);
        let mut co = Coevolution::new(&config).unwrap();
        let failing = Backwards {
            fail: true,
            batches: Default::default(),
        };
        let err = co.generation(&arena, &config, &failing).unwrap_err();
        assert!(err.to_string().contains("rank 1 is gone"), "{err}");
        assert_eq!(co.done(), 0, "a failed generation adds no champions");
    }

    #[test]
    fn master_tournament_averages_each_champion_over_the_other_side() {
        let cell = |hunter, prey, f| CiaoCell {
            hunter,
            prey,
            hunter_fitness: f,
            caught: f > 1.0,
        };
        let cells = [
            cell(0, 0, 0.5),
            cell(0, 1, 0.25),
            cell(1, 0, 1.5),
            cell(1, 1, 1.0),
        ];
        assert_eq!(master_tournament(&cells, 2, Side::Hunter), [0.375, 1.25]);
        assert_eq!(master_tournament(&cells, 2, Side::Prey), [1.0, 1.375]);
    }
}
