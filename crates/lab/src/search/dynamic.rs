//! The search a run holds: [`Search`], any registered strategy as a trait
//! object ([`DynStrategy`]), stored in a checkpoint as `{"Name": state}`.

use std::any::Any;

use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use vivae_neat::driver::{Batch, Evaluation, Strategy};
use vivae_neat::{BestEver, GenerationStats, Genome, GenomeSpec, NeatError, Population};

use crate::config::Config;
use crate::error::Result;
use crate::search::{BehaviourSpace, RunStrategy, Start, entries, entry_of, refuse_init};

/// A run's search strategy: the one of
/// [`STRATEGIES`](crate::search::STRATEGIES) the config's `[strategy]`
/// section names, held as a trait object. In a checkpoint it is
/// `{"Name": state}` (its entry's `variant`), as when it was an enum.
pub struct Search(Box<dyn DynStrategy>);

impl Search {
    /// Generation 0 of the strategy of `config` over genomes of shape `spec`
    /// whose behaviour descriptors are those of `space` (the task's),
    /// seeded with `experiment.seed`; NEAT and novelty search may start from
    /// `init`'s genomes instead; the task's evaluations carry the metrics
    /// `metrics`.
    pub fn new(
        config: &Config,
        spec: GenomeSpec,
        space: &BehaviourSpace,
        init: Option<&Population>,
        metrics: &[&str],
    ) -> Result<Search> {
        let entry = entry_of(config)?;
        if !entry.takes_population {
            refuse_init(config, init)?;
        }
        let init = init.filter(|_| entry.takes_population);
        (entry.build)(Start {
            config,
            spec,
            space,
            init,
            metrics,
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
