//! The search a run holds: one [`Search`] value, whichever strategy the
//! config's `[strategy]` section names, that the driver runs and the
//! checkpoint stores. It is a [`Strategy`] by delegation to the one inside.
//!
//! Each strategy is one file here: its [`StrategyEntry`] (registered in
//! [`STRATEGIES`]: the columns it adds to `generations.csv`, how it is built
//! from the config, its header line) and its [`RunStrategy`] (its fields of
//! each row and of the summary line, the files it writes with each
//! checkpoint, its figure). [`Search`] holds any of them as a trait object
//! and stores it in a checkpoint as `{"Name": state}`, read back by the entry
//! whose `variant` is `Name`: a new strategy is its file and its line in
//! [`STRATEGIES`].

pub mod files;
mod map_elites;
mod neat;
mod novelty;
mod nsga2;

pub use nsga2::front_objective_names;

use std::any::Any;
use std::path::Path;

use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use vivae_neat::driver::{Batch, Evaluation, Strategy};
use vivae_neat::hyperneat::{CPPN_INPUTS, leo_seeded_genomes};
use vivae_neat::{
    BestEver, GenerationStats, Genome, GenomeSpec, NeatError, NeatParams, Population,
};

use crate::config::Config;
use crate::config::es::ES_LEO_OUTPUT;
use crate::config::strategy::BehaviourKind;
use crate::error::Result;
use crate::io::bad_input;

/// The generator stream of LEO's seeded generation 0, apart from the
/// population's own (which is seeded with the run seed itself).
const LEO_SEED_STREAM: u64 = 0x1e05_eed0;

/// Generation 0 of `substrate.es.leo_seed`: `params.population_size`
/// genomes of LEO's Gaussian locality seed along x feeding CPPN output
/// [`ES_LEO_OUTPUT`], one innovation history for all, drawn from the run
/// seed `seed` (the population built from them takes `seed` itself).
pub fn leo_seeded(spec: &GenomeSpec, params: &NeatParams, seed: u64) -> Result<Vec<Genome>> {
    if spec.inputs != CPPN_INPUTS || spec.outputs <= ES_LEO_OUTPUT {
        return Err(bad_input(format!(
            "substrate.es.leo_seed = true: the seed needs a substrate CPPN ({CPPN_INPUTS} inputs, output {ES_LEO_OUTPUT}), not {} inputs and {} outputs",
            spec.inputs, spec.outputs
        )));
    }
    Ok(leo_seeded_genomes(
        spec,
        params,
        params.population_size,
        seed ^ LEO_SEED_STREAM,
        ES_LEO_OUTPUT,
    ))
}

/// Generation 0 of a NEAT population for `config`'s substrate: LEO's
/// seeded genomes with `substrate.es.leo_seed`, minimal genomes otherwise.
pub fn initial_population(
    config: &Config,
    params: NeatParams,
    spec: GenomeSpec,
    seed: u64,
) -> Result<Population> {
    if config.substrate.es.leo_seed {
        let genomes = leo_seeded(&spec, &params, seed)?;
        Population::from_genomes(params, spec, genomes, seed)
            .map_err(|e| bad_input(format!("substrate.es.leo_seed: {e}")))
    } else {
        Population::new(params, spec, seed).map_err(|e| bad_input(format!("neat: {e}")))
    }
}

/// A run's search strategy: the one of [`STRATEGIES`] the config's
/// `[strategy]` section names, held as a trait object. In a checkpoint it is
/// `{"Name": state}` (its entry's `variant`), as when it was an enum.
pub struct Search(Box<dyn DynStrategy>);

/// The strategies built in; `strategy.kind` names one of them or one
/// [`register`]ed by a program.
pub static STRATEGIES: [&StrategyEntry; 4] = [
    &neat::STRATEGY,
    &novelty::STRATEGY,
    &map_elites::STRATEGY,
    &nsga2::STRATEGY,
];

/// The box (lower, upper) the behaviour descriptors lie in.
pub type Bounds = (Vec<f64>, Vec<f64>);

/// A strategy's registration: what a run needs of it before it exists.
pub struct StrategyEntry {
    /// Its `strategy.kind`.
    pub kind: &'static str,
    /// What it selects on beside fitness, which the task then measures.
    pub needs: Needs,
    /// Whether it can start from given genomes (`experiment.init_population`,
    /// LEO's seeded generation 0) rather than minimal ones.
    pub takes_population: bool,
    /// Its name in a checkpoint's `search` field (`{"Name": state}`).
    pub variant: &'static str,
    /// The strategy of a checkpoint's state (its JSON text).
    pub from_state: fn(&str) -> serde_json::Result<Search>,
    /// The columns it adds to `generations.csv` (after NEAT's), each with its
    /// leading comma.
    pub extra_columns: &'static str,
    /// Its generation 0.
    pub build: fn(Start<'_>) -> Result<Search>,
    /// The line the run's header says of it (with its leading line break), or empty.
    pub header_line: fn(&Config) -> String,
    /// What the report of the run in a directory shows of it, read from the
    /// files it wrote (`None`: nothing, as for NEAT); the task's robots given.
    pub report: ReportOf,
}

/// What a strategy's generation 0 is built from.
pub struct Start<'a> {
    /// The run's config.
    pub config: &'a Config,
    /// The shape of the genomes.
    pub spec: GenomeSpec,
    /// The box the behaviour descriptors lie in.
    pub bounds: Bounds,
    /// The genomes to start from, if given (only to an entry that
    /// [`StrategyEntry::takes_population`]).
    pub init: Option<&'a Population>,
}

/// What a strategy selects on beside fitness: the task measures it only then.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Needs {
    /// A behaviour descriptor (`strategy.behaviour`).
    pub behaviour: bool,
    /// The task's metrics (contacts, on-road share, …).
    pub metrics: bool,
}

/// [`StrategyEntry::from_state`] of a strategy whose checkpointed state is
/// its serde form.
pub fn state_of<T>(state: &str) -> serde_json::Result<Search>
where
    T: DynStrategy + serde::de::DeserializeOwned + 'static,
{
    Ok(Search::of(serde_json::from_str::<T>(state)?))
}

/// How a strategy's part of a run's report is read from the run directory.
pub type ReportOf = fn(&Path, &Config, usize) -> Result<Option<StrategyReport>>;

/// A strategy's part of a run's report: its archive or front as saved with
/// the last checkpoint (the program adds its columns of `generations.csv`).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct StrategyReport {
    /// The strategy's name (its `strategy.kind`).
    pub kind: &'static str,
    /// A map-elites archive on a 2-D grid, drawn as a heat map.
    pub grid: Option<GridReport>,
    /// Why a map-elites archive is not drawn as a heat map, if it is not.
    pub grid_note: String,
    /// Names of the behaviour coordinates.
    pub behaviour_names: Vec<String>,
    /// The archive's elites: `[cell, fitness, generation, behaviour]`.
    pub elites: Vec<(usize, f64, u32, Vec<f64>)>,
    /// An nsga2 run's objectives, as configs write them (the program names
    /// their axes).
    pub objectives: Vec<String>,
    /// Its Pareto front: `[member, fitness, objectives]`, fittest first.
    pub front: Vec<(usize, f64, Vec<f64>)>,
}

/// A 2-D grid of MAP-Elites cells (cell = x bin × `bins[1]` + y bin).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GridReport {
    /// Lower bound of each coordinate.
    pub lower: [f64; 2],
    /// Upper bound of each coordinate.
    pub upper: [f64; 2],
    /// Cells along each coordinate.
    pub bins: [usize; 2],
}

/// A strategy's report with nothing of its own but its name (novelty search).
pub(crate) fn named_report(_: &Path, config: &Config, _: usize) -> Result<Option<StrategyReport>> {
    Ok(Some(StrategyReport {
        kind: entry_of(config)?.kind,
        ..StrategyReport::default()
    }))
}

impl std::fmt::Debug for StrategyEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StrategyEntry")
            .field("kind", &self.kind)
            .finish()
    }
}

/// The strategies programs added with [`register`].
static REGISTERED: std::sync::RwLock<Vec<&'static StrategyEntry>> =
    std::sync::RwLock::new(Vec::new());

/// Adds a strategy to those a config can name (`strategy.kind = "its kind"`),
/// beside the built-in [`STRATEGIES`]; the error says why not (a name taken).
pub fn register(entry: &'static StrategyEntry) -> std::result::Result<(), String> {
    let mut added = REGISTERED.write().unwrap_or_else(|e| e.into_inner());
    let taken = |e: &&StrategyEntry| e.kind == entry.kind || e.variant == entry.variant;
    if STRATEGIES.iter().chain(added.iter()).any(taken) {
        // Registering the same entry twice is harmless (tests, re-imports).
        if STRATEGIES
            .iter()
            .chain(added.iter())
            .any(|e| std::ptr::eq(*e, entry))
        {
            return Ok(());
        }
        return Err(format!(
            "a strategy called '{}' ({}) is registered already",
            entry.kind, entry.variant
        ));
    }
    added.push(entry);
    Ok(())
}

/// Every strategy a config can name: the built-in ones, then the registered.
pub fn entries() -> Vec<&'static StrategyEntry> {
    let added = REGISTERED.read().unwrap_or_else(|e| e.into_inner());
    STRATEGIES.iter().chain(added.iter()).copied().collect()
}

/// The strategy called `kind`; the error lists the ones there are.
pub fn entry(kind: &str) -> std::result::Result<&'static StrategyEntry, String> {
    let all = entries();
    all.iter().copied().find(|e| e.kind == kind).ok_or_else(|| {
        let names: Vec<_> = all.iter().map(|e| e.kind).collect();
        format!("'{kind}': expected {}", names.join(", "))
    })
}

/// The strategy `config` names (checked by [`check`]).
pub fn entry_of(config: &Config) -> Result<&'static StrategyEntry> {
    entry(config.strategy.kind.name()).map_err(|why| bad_input(format!("strategy.kind = {why}")))
}

/// Checks `config`'s `[strategy]` section for a task measuring `metrics`:
/// the strategy is registered, what it needs fits the run, its settings are
/// valid; the error names the key.
pub fn check(config: &Config, metrics: &[&str]) -> std::result::Result<(), String> {
    let s = &config.strategy;
    let e = entry(s.kind.name()).map_err(|why| format!("strategy.kind = {why}"))?;
    let multi_map = !config.experiment.scenarios.is_empty();
    if e.needs.behaviour && s.behaviour == BehaviourKind::EndPositions && multi_map {
        return Err(format!(
            "strategy.behaviour = {:?}: one map only (maps have their own robots): use end-position on several maps",
            s.behaviour.name()
        ));
    }
    if config.substrate.es.leo_seed && !e.takes_population {
        return Err(format!(
            "substrate.es.leo_seed = true: a {} run starts from minimal genomes (only {} runs start from the seed)",
            e.kind,
            takers().join(" and ")
        ));
    }
    crate::config::strategy::validate(s, metrics)
}

/// The strategies that can start from given genomes.
fn takers() -> Vec<&'static str> {
    entries()
        .into_iter()
        .filter(|e| e.takes_population)
        .map(|e| e.kind)
        .collect()
}

/// What a run needs of its search strategy beside ask and tell.
pub trait RunStrategy {
    /// Its registration.
    fn entry(&self) -> &'static StrategyEntry;

    /// The NEAT population inside, for strategies that breed one.
    fn population(&self) -> Option<&Population> {
        None
    }

    /// The genomes of the batch to evaluate next.
    fn batch(&self) -> Vec<Genome>;

    /// The batch's task fitnesses once told, in batch order.
    fn fitnesses(&self, evaluations: &[Evaluation]) -> Vec<f64> {
        evaluations.iter().map(Evaluation::finite_fitness).collect()
    }

    /// Its values of [`StrategyEntry::extra_columns`] for the generation just
    /// told, each with its leading comma.
    fn extra_fields(&self) -> String {
        String::new()
    }

    /// Its `key=value` fields of the summary line, each with a leading space.
    fn summary_fields(&self) -> String {
        String::new()
    }

    /// Writes its own files into the run directory `dir` (with each checkpoint).
    fn write_outputs(&self, _dir: &Path, _config: &Config) -> Result<()> {
        Ok(())
    }

    /// What its end-of-run figure shows after `generation`, if it has one
    /// (the program draws it).
    fn figure(&self, _config: &Config, _generation: u32) -> Option<StrategyFigure> {
        None
    }
}

/// A strategy's end-of-run figure, as data: the program draws each kind.
#[derive(Debug, Clone, PartialEq)]
pub enum StrategyFigure {
    /// An archive on a 2-D grid of cells, as a heat map of its elites' fitness.
    Grid(GridFigure),
    /// A population scored on two objectives, and its Pareto front.
    Front(FrontFigure),
}

/// A 2-D grid archive to draw as a heat map.
#[derive(Debug, Clone, PartialEq)]
pub struct GridFigure {
    /// The figure's title.
    pub title: String,
    /// Names of the two behaviour coordinates (x, then y).
    pub axes: [String; 2],
    /// Lower bound of each coordinate.
    pub lower: [f64; 2],
    /// Upper bound of each coordinate.
    pub upper: [f64; 2],
    /// Cells along each coordinate.
    pub bins: [usize; 2],
    /// `(cell, fitness)` of every elite; cell = x bin × `bins[1]` + y bin.
    pub elites: Vec<(usize, f64)>,
}

/// A population scored on two objectives and its Pareto front, to draw.
#[derive(Debug, Clone, PartialEq)]
pub struct FrontFigure {
    /// The figure's title.
    pub title: String,
    /// The two objectives as configs write them (`fitness`, `-contacts`).
    pub objectives: [String; 2],
    /// Every scored member's two objective values.
    pub population: Vec<[f64; 2]>,
    /// The front's members' values, fittest first (as `front.csv` numbers them).
    pub front: Vec<[f64; 2]>,
}

/// The header line of the strategies that search on a behaviour descriptor.
pub(crate) fn behaviour_line(c: &Config) -> String {
    let s = &c.strategy;
    format!(
        "\n  strategy: {}, behaviour {}",
        s.kind.name(),
        s.behaviour.name()
    )
}

/// Generation 0 of a NEAT population for `config`: `init`'s genomes (only
/// they carry over: fitness, species and the champion were measured on
/// another substrate and mean nothing here), or [`initial_population`].
pub(crate) fn starting_population(start: Start<'_>) -> Result<Population> {
    let Start {
        config, spec, init, ..
    } = start;
    let (neat, seed) = (config.neat.clone(), config.experiment.seed);
    match init {
        Some(p) => Population::from_genomes(neat, spec, p.genomes().to_vec(), seed)
            .map_err(|e| bad_input(format!("initial population: {e}"))),
        None => initial_population(config, neat, spec, seed),
    }
}

/// Refuses a starting population for a strategy that starts from minimal genomes.
fn refuse_init(config: &Config, init: Option<&Population>) -> Result<()> {
    match init {
        None => Ok(()),
        Some(_) => Err(bad_input(format!(
            "experiment.init_population: a {} run starts from minimal genomes (only {} runs start from a population)",
            config.strategy.kind.name(),
            takers().join(" and ")
        ))),
    }
}

impl Search {
    /// Generation 0 of the strategy of `config` over genomes of shape `spec`
    /// whose behaviour descriptors lie in the box `bounds` (lower, upper),
    /// seeded with `experiment.seed`; NEAT and novelty search may start from
    /// `init`'s genomes instead.
    pub fn new(
        config: &Config,
        spec: GenomeSpec,
        bounds: Bounds,
        init: Option<&Population>,
    ) -> Result<Search> {
        let entry = entry_of(config)?;
        if !entry.takes_population {
            refuse_init(config, init)?;
        }
        let init = init.filter(|_| entry.takes_population);
        (entry.build)(Start {
            config,
            spec,
            bounds,
            init,
        })
    }

    /// `strategy` as a run's search.
    pub fn of<T: DynStrategy + 'static>(strategy: T) -> Search {
        Search(Box::new(strategy))
    }

    /// The strategy inside, as a run uses it.
    pub fn strategy(&self) -> &dyn DynStrategy {
        self.0.as_ref()
    }

    /// The strategy inside as its own type, if it is a `T`.
    pub fn downcast_ref<T: 'static>(&self) -> Option<&T> {
        self.0.as_any().downcast_ref()
    }

    /// Which strategy this is (its `strategy.kind`).
    pub fn kind(&self) -> &'static str {
        self.strategy().entry().kind
    }

    /// The NEAT population, for NEAT and novelty search.
    pub fn population(&self) -> Option<&Population> {
        self.strategy().population()
    }

    /// The genomes of the batch to evaluate next.
    pub fn batch(&self) -> Vec<Genome> {
        self.strategy().batch()
    }

    /// The batch's task fitnesses once told, in batch order (NEAT's as its
    /// population holds them; novelty search's population holds novelty).
    pub fn fitnesses(&self, evaluations: &[Evaluation]) -> Vec<f64> {
        self.strategy().fitnesses(evaluations)
    }

    /// `[species id, members]` of each species (none without species).
    pub fn species(&self) -> Vec<(u32, usize)> {
        self.population().map_or_else(Vec::new, |p| {
            p.species()
                .iter()
                .map(|s| (s.id, s.members.len()))
                .collect()
        })
    }
}

/// A strategy a run can hold: any [`Strategy`] that is also a
/// [`RunStrategy`], behind a trait object (the blanket impl below).
pub trait DynStrategy: RunStrategy + std::fmt::Debug + Send + Sync {
    /// [`Strategy::ask`].
    fn ask_dyn(&mut self) -> Batch<'_>;
    /// [`Strategy::tell`].
    fn tell_dyn(&mut self, evaluations: &[Evaluation]) -> std::result::Result<(), NeatError>;
    /// [`Strategy::prepare`].
    fn prepare_dyn(&mut self);
    /// [`Strategy::generation`].
    fn generation_dyn(&self) -> u32;
    /// [`Strategy::champion`].
    fn champion_dyn(&self) -> Option<(&Genome, f64)>;
    /// [`Strategy::best_ever`].
    fn best_ever_dyn(&self) -> Option<&BestEver>;
    /// [`Strategy::stats`].
    fn stats_dyn(&self) -> GenerationStats;
    /// Its state as a checkpoint stores it.
    fn state(&self) -> serde_json::Result<Box<RawValue>>;
    /// A boxed copy.
    fn clone_box(&self) -> Box<dyn DynStrategy>;
    /// Itself as [`Any`], to compare and downcast.
    fn as_any(&self) -> &dyn Any;
    /// Whether `other` is the same strategy in the same state.
    fn eq_dyn(&self, other: &dyn Any) -> bool;
}

impl<T> DynStrategy for T
where
    T: Strategy + RunStrategy + Clone + PartialEq + std::fmt::Debug + Send + Sync + 'static,
{
    fn ask_dyn(&mut self) -> Batch<'_> {
        Strategy::ask(self)
    }
    fn tell_dyn(&mut self, evaluations: &[Evaluation]) -> std::result::Result<(), NeatError> {
        Strategy::tell(self, evaluations)
    }
    fn prepare_dyn(&mut self) {
        Strategy::prepare(self)
    }
    fn generation_dyn(&self) -> u32 {
        Strategy::generation(self)
    }
    fn champion_dyn(&self) -> Option<(&Genome, f64)> {
        Strategy::champion(self)
    }
    fn best_ever_dyn(&self) -> Option<&BestEver> {
        Strategy::best_ever(self)
    }
    fn stats_dyn(&self) -> GenerationStats {
        Strategy::stats(self)
    }
    fn state(&self) -> serde_json::Result<Box<RawValue>> {
        serde_json::value::to_raw_value(self)
    }
    fn clone_box(&self) -> Box<dyn DynStrategy> {
        Box::new(self.clone())
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn eq_dyn(&self, other: &dyn Any) -> bool {
        other.downcast_ref::<T>() == Some(self)
    }
}

impl Clone for Search {
    fn clone(&self) -> Self {
        Search(self.0.clone_box())
    }
}

impl PartialEq for Search {
    fn eq(&self, other: &Self) -> bool {
        self.0.eq_dyn(other.0.as_any())
    }
}

impl std::fmt::Debug for Search {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_tuple("Search").field(&self.0).finish()
    }
}

/// `{"Name": state}`: the bytes of the enum this type once was.
impl Serialize for Search {
    fn serialize<S: serde::Serializer>(
        &self,
        serializer: S,
    ) -> std::result::Result<S::Ok, S::Error> {
        let entry = self.0.entry();
        let index = (entries().iter())
            .position(|e| e.kind == entry.kind)
            .unwrap_or(0);
        let state = self.0.state().map_err(serde::ser::Error::custom)?;
        serializer.serialize_newtype_variant("Search", index as u32, entry.variant, &state)
    }
}

impl<'de> Deserialize<'de> for Search {
    fn deserialize<D: serde::Deserializer<'de>>(
        deserializer: D,
    ) -> std::result::Result<Search, D::Error> {
        deserializer.deserialize_map(SearchVisitor)
    }
}

/// Reads `{"Name": state}` by the registered strategy called `Name`.
struct SearchVisitor;

impl<'de> serde::de::Visitor<'de> for SearchVisitor {
    type Value = Search;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a search strategy, {\"Name\": state}")
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(
        self,
        mut map: A,
    ) -> std::result::Result<Search, A::Error> {
        use serde::de::Error as _;
        let name: String = map
            .next_key()?
            .ok_or_else(|| A::Error::custom("no strategy"))?;
        let entry = (entries().into_iter())
            .find(|e| e.variant == name)
            .ok_or_else(|| A::Error::custom(unknown_variant(&name)))?;
        let state: Box<RawValue> = map.next_value()?;
        if map.next_key::<String>()?.is_some() {
            return Err(A::Error::custom("a search holds one strategy"));
        }
        (entry.from_state)(state.get()).map_err(A::Error::custom)
    }
}

/// What serde says of an unknown variant, over the strategies' checkpoint
/// names (registered ones included, so not a `'static` list).
fn unknown_variant(name: &str) -> String {
    let names: Vec<_> = entries()
        .iter()
        .map(|e| format!("`{}`", e.variant))
        .collect();
    format!(
        "unknown variant `{name}`, expected one of {}",
        names.join(", ")
    )
}

impl Strategy for Search {
    fn ask(&mut self) -> Batch<'_> {
        self.0.ask_dyn()
    }

    fn tell(&mut self, evaluations: &[Evaluation]) -> std::result::Result<(), NeatError> {
        self.0.tell_dyn(evaluations)
    }

    fn prepare(&mut self) {
        self.0.prepare_dyn()
    }

    fn generation(&self) -> u32 {
        self.0.generation_dyn()
    }

    fn champion(&self) -> Option<(&Genome, f64)> {
        self.0.champion_dyn()
    }

    fn best_ever(&self) -> Option<&BestEver> {
        self.0.best_ever_dyn()
    }

    fn stats(&self) -> GenerationStats {
        self.0.stats_dyn()
    }
}
