//! Hidden-node discovery (the paper's Algorithm 3), shared by the reference
//! and the fast decode: explore from the inputs, iterate from the hidden
//! nodes found, connect to the outputs, keep what lies on input→output paths.

use std::cmp::Ordering;
use std::collections::{BTreeMap, BTreeSet};

use super::EsLayout;
use super::params::EsParams;
use super::query::{Fixed, Found, Query};
use crate::hyperneat::error::HyperError;
use crate::hyperneat::leo::express_link;
use crate::hyperneat::sparse::{SparseLink, SparseNetwork};

/// A substrate point, ordered by y then x (so hidden nodes come out bottom to top).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pt([f64; 2]);

impl Pt {
    /// The point, with −0 made +0 so that equal positions compare equal.
    fn new([x, y]: [f64; 2]) -> Pt {
        Pt([x + 0.0, y + 0.0])
    }
}

impl PartialEq for Pt {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Pt {}
impl PartialOrd for Pt {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Pt {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0[1]
            .total_cmp(&other.0[1])
            .then(self.0[0].total_cmp(&other.0[0]))
    }
}

/// The links found so far, keyed (source, target), and the hidden nodes.
struct Substrate<'a> {
    layout: &'a EsLayout,
    params: &'a EsParams,
    inputs: BTreeMap<Pt, usize>,
    outputs: BTreeMap<Pt, usize>,
    hidden: BTreeSet<Pt>,
    links: BTreeMap<(Pt, Pt), f64>,
    found: Vec<Found>,
    points: Vec<[f64; 2]>,
    leo: Vec<f64>,
}

impl Substrate<'_> {
    /// Explores from (`outgoing`) or to `node` and returns the expressed
    /// (point, weight) pairs in the order found.
    fn explore<Q: Query>(
        &mut self,
        q: &mut Q,
        node: Pt,
        outgoing: bool,
        explore: &mut impl FnMut(&mut Q, Fixed, &mut Vec<Found>),
    ) -> Vec<(Pt, f64)> {
        let fixed = Fixed {
            node: node.0,
            outgoing,
        };
        self.found.clear();
        explore(q, fixed, &mut self.found);
        self.points.clear();
        self.points.extend(self.found.iter().map(|f| f.point));
        if let Some(leo) = self.layout.leo_output {
            self.leo.resize(self.points.len(), 0.0);
            q.query(leo, fixed, &self.points, &mut self.leo);
        }
        let expression = &self.params.expression;
        self.found
            .iter()
            .enumerate()
            .filter_map(|(k, f)| {
                let leo = self.layout.leo_output.map(|_| self.leo[k]);
                express_link(expression, f.o, leo).map(|w| (Pt::new(f.point), w))
            })
            .collect()
    }

    /// Adds link `source → target` if the substrate allows it; true if it is new.
    fn add(&mut self, source: Pt, target: Pt, weight: f64) -> bool {
        if self.inputs.contains_key(&target) {
            return false;
        }
        let allowed = if self.params.recurrent {
            source != target
        } else {
            self.params.flow.allows(source.0, target.0)
        };
        if !allowed || self.links.contains_key(&(source, target)) {
            return false;
        }
        self.links.insert((source, target), weight);
        true
    }

    fn is_io(&self, p: &Pt) -> bool {
        self.inputs.contains_key(p) || self.outputs.contains_key(p)
    }
}

/// Runs the discovery with `explore` (the reference or the fast quadtree)
/// and assembles the network.
pub(crate) fn discover<Q: Query>(
    q: &mut Q,
    layout: &EsLayout,
    params: &EsParams,
    mut explore: impl FnMut(&mut Q, Fixed, &mut Vec<Found>),
) -> Result<SparseNetwork, HyperError> {
    params.validate()?;
    layout.check(q.num_outputs())?;
    let mut s = Substrate {
        layout,
        params,
        inputs: layout
            .inputs
            .iter()
            .enumerate()
            .map(|(i, &p)| (Pt::new(p), i))
            .collect(),
        outputs: layout
            .outputs
            .iter()
            .enumerate()
            .map(|(i, &p)| (Pt::new(p), i))
            .collect(),
        hidden: BTreeSet::new(),
        links: BTreeMap::new(),
        found: Vec::new(),
        points: Vec::new(),
        leo: Vec::new(),
    };
    // From the inputs, then `iteration_level` rounds from the new hidden nodes.
    let mut unexplored: Vec<Pt> = layout.inputs.iter().map(|&p| Pt::new(p)).collect();
    for round in 0..=params.iteration_level {
        let mut new = Vec::new();
        for &source in &unexplored {
            for (target, w) in s.explore(q, source, true, &mut explore) {
                if s.add(source, target, w) && !s.is_io(&target) && s.hidden.insert(target) {
                    new.push(target);
                }
            }
        }
        unexplored = new;
        if round == params.iteration_level || unexplored.is_empty() {
            break;
        }
    }
    // To the outputs, only from nodes already there.
    for &target in &layout.outputs {
        let target = Pt::new(target);
        for (source, w) in s.explore(q, target, false, &mut explore) {
            if s.inputs.contains_key(&source) || s.hidden.contains(&source) {
                s.add(source, target, w);
            }
        }
    }
    assemble(
        q, layout, &s.inputs, &s.outputs, &s.hidden, &s.links, params,
    )
}

/// Keeps the hidden nodes on input→output paths and the links between
/// kept nodes, queries the biases and builds the network.
fn assemble<Q: Query>(
    q: &mut Q,
    layout: &EsLayout,
    inputs: &BTreeMap<Pt, usize>,
    outputs: &BTreeMap<Pt, usize>,
    hidden: &BTreeSet<Pt>,
    links: &BTreeMap<(Pt, Pt), f64>,
    params: &EsParams,
) -> Result<SparseNetwork, HyperError> {
    let (ni, no) = (layout.inputs.len(), layout.outputs.len());
    let hidden: Vec<Pt> = hidden.iter().copied().collect();
    let index = |p: &Pt| -> usize {
        inputs
            .get(p)
            .copied()
            .or_else(|| outputs.get(p).map(|&o| ni + o))
            .unwrap_or_else(|| ni + no + hidden.binary_search(p).expect("a known node"))
    };
    let all: Vec<(usize, usize, f64)> = links
        .iter()
        .map(|((a, b), &w)| (index(a), index(b), w))
        .collect();
    let n = ni + no + hidden.len();
    let forward = reach(n, 0..ni, &all, |&(a, b, _)| (a, b));
    let backward = reach(n, ni..ni + no, &all, |&(a, b, _)| (b, a));
    // New index of each kept node: inputs and outputs always, hidden nodes on a path.
    let mut renumber = vec![usize::MAX; n];
    let mut kept_hidden = Vec::new();
    for i in 0..n {
        if i < ni + no {
            renumber[i] = i;
        } else if forward[i] && backward[i] {
            renumber[i] = ni + no + kept_hidden.len();
            kept_hidden.push(hidden[i - ni - no].0);
        }
    }
    let kept_links: Vec<SparseLink> = all
        .iter()
        .filter(|&&(a, b, _)| forward[a] && backward[b])
        .map(|&(a, b, weight)| SparseLink {
            source: renumber[a],
            target: renumber[b],
            weight,
        })
        .collect();
    let mut bias = vec![0.0; no + kept_hidden.len()];
    if let Some(output) = layout.bias_output {
        let nodes: Vec<[f64; 2]> = layout.outputs.iter().chain(&kept_hidden).copied().collect();
        let origin = Fixed {
            node: [0.0, 0.0],
            outgoing: true,
        };
        q.query(output, origin, &nodes, &mut bias);
        for b in bias.iter_mut() {
            *b = params.expression.express(*b).unwrap_or(0.0);
        }
    }
    SparseNetwork::new(ni, no, kept_hidden, bias, kept_links)
}

/// Which of `n` nodes are reachable from `start` along `edge(link)` = (from, to).
fn reach<L>(
    n: usize,
    start: std::ops::Range<usize>,
    links: &[L],
    edge: impl Fn(&L) -> (usize, usize),
) -> Vec<bool> {
    let mut next: Vec<Vec<usize>> = vec![Vec::new(); n];
    for l in links {
        let (a, b) = edge(l);
        next[a].push(b);
    }
    let mut seen = vec![false; n];
    let mut todo: Vec<usize> = start.collect();
    for &i in &todo {
        seen[i] = true;
    }
    while let Some(i) = todo.pop() {
        for &j in &next[i] {
            if !seen[j] {
                seen[j] = true;
                todo.push(j);
            }
        }
    }
    seen
}
