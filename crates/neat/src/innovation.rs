//! Historical markings: innovation numbers and hidden-node ids.
//!
//! The tracker remembers every structural innovation for the whole run (a superset
//! of Stanley's "within a generation"), so the same link `(from, to)` always carries
//! the same innovation number and the same split yields the same node id in every
//! genome. That keeps alignment exact and makes duplicate links impossible.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// Hands out innovation numbers and node ids; part of the population state.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(from = "TrackerRepr", into = "TrackerRepr")]
pub struct InnovationTracker {
    next_innovation: u32,
    next_node: u32,
    links: BTreeMap<(u32, u32), u32>,
    /// Split link innovation → node ids created by splitting it (in order).
    splits: BTreeMap<u32, Vec<u32>>,
}

impl InnovationTracker {
    /// A tracker whose first hidden node id is `first_hidden` (inputs + outputs).
    pub fn new(first_hidden: u32) -> InnovationTracker {
        InnovationTracker {
            next_innovation: 0,
            next_node: first_hidden,
            links: BTreeMap::new(),
            splits: BTreeMap::new(),
        }
    }

    /// The innovation number of link `from → to`, allocating one if it is new.
    pub fn link_innovation(&mut self, from: u32, to: u32) -> u32 {
        if let Some(&i) = self.links.get(&(from, to)) {
            return i;
        }
        let i = self.next_innovation;
        self.next_innovation += 1;
        self.links.insert((from, to), i);
        i
    }

    /// The id of the node created by splitting link `innovation` in a genome:
    /// the first id already used for that split that the genome does not
    /// contain (`has_node(id)` is false), else a new one.
    ///
    /// Takes the genome's membership test rather than the genome so that the
    /// tracker stays below the genome in the module graph.
    pub fn split_node(&mut self, innovation: u32, has_node: impl Fn(u32) -> bool) -> u32 {
        let ids = self.splits.entry(innovation).or_default();
        if let Some(&id) = ids.iter().find(|&&id| !has_node(id)) {
            return id;
        }
        let id = self.next_node;
        self.next_node += 1;
        ids.push(id);
        id
    }

    /// Number of innovation numbers handed out so far.
    pub fn innovations(&self) -> u32 {
        self.next_innovation
    }

    /// The next hidden-node id that would be allocated.
    pub fn next_node_id(&self) -> u32 {
        self.next_node
    }

    /// Makes sure the tracker knows a genome's link `from → to` with its
    /// `innovation` (used when a population is built from existing genomes)
    /// so that later innovations never collide.
    pub(crate) fn absorb_link(&mut self, from: u32, to: u32, innovation: u32) {
        self.links.entry((from, to)).or_insert(innovation);
        self.next_innovation = self.next_innovation.max(innovation + 1);
    }

    /// Makes sure later hidden-node ids never collide with node `id`.
    pub(crate) fn absorb_node(&mut self, id: u32) {
        self.next_node = self.next_node.max(id + 1);
    }

    /// The innovation number recorded for link `from → to`, if any.
    pub fn innovation_of(&self, from: u32, to: u32) -> Option<u32> {
        self.links.get(&(from, to)).copied()
    }

    /// Every recorded link as `(from, to, innovation)` (for consistency checks on restore).
    pub(crate) fn recorded_links(&self) -> impl Iterator<Item = (u32, u32, u32)> + '_ {
        self.links.iter().map(|(&(f, t), &i)| (f, t, i))
    }

    /// Every node id recorded for a split (for consistency checks on restore).
    pub(crate) fn split_ids(&self) -> impl Iterator<Item = u32> + '_ {
        self.splits.values().flatten().copied()
    }
}

/// JSON-friendly form: maps with tuple keys become lists.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct TrackerRepr {
    next_innovation: u32,
    next_node: u32,
    links: Vec<(u32, u32, u32)>,
    splits: Vec<(u32, Vec<u32>)>,
}

impl From<TrackerRepr> for InnovationTracker {
    fn from(r: TrackerRepr) -> Self {
        InnovationTracker {
            next_innovation: r.next_innovation,
            next_node: r.next_node,
            links: r.links.into_iter().map(|(f, t, i)| ((f, t), i)).collect(),
            splits: r.splits.into_iter().collect(),
        }
    }
}

impl From<InnovationTracker> for TrackerRepr {
    fn from(t: InnovationTracker) -> Self {
        TrackerRepr {
            next_innovation: t.next_innovation,
            next_node: t.next_node,
            links: t.links.into_iter().map(|((f, t), i)| (f, t, i)).collect(),
            splits: t.splits.into_iter().collect(),
        }
    }
}
