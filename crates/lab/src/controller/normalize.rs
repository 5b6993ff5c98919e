//! How a re-sampled substrate keeps its drive: the scale of each link's
//! weight by its source node (`substrate.normalize`, `normalize_by`,
//! `normalize_self_loops`).
//!
//! A CPPN paints a weight on every link; with more nodes in a sheet, a neuron
//! sums more inputs. The rules rescale the weights leaving each source node:
//!
//! * `count` (the default, the paper's setting): every node of a sheet gets
//!   `reference / count` — the sheet's node count in the paper (15 surface
//!   sensors, 9 neurons, 5 rays) over its count here. Exactly 1 at the paper's
//!   resolution.
//! * `area`: each node gets `reference × (its share of the sheet's area)`. On
//!   the substrate's polar grid ring k of R sits at radius ρ = (k+1)/R and its
//!   annulus, bounded half-way to the neighbouring rings, has area ∝ ρ; so a
//!   node's share is ρ / Σρ over the sheet. Inner nodes, packed closer, count
//!   less; a dense sheet is weighted like an integral over the sheet rather
//!   than a sum. Not 1 at the paper's resolution (outer nodes weigh more).
//! * `normalize_self_loops = false` leaves each neuron's self-loop at the
//!   CPPN's weight: a neuron has one self-loop at any resolution, while the
//!   count rule shrinks it with the neuron sheet (by 9/81 at 9×9), taking away
//!   the memory the controller evolved with.
//!
//! `substrate.recurrence` then removes neuron→neuron links: `self` keeps only
//! each neuron's self-loop (no lateral links), `none` every recurrent link.
//! Without lateral links a wheel neuron's drive does not depend on the other
//! neurons, so re-sampling the neuron sheet leaves it unchanged wherever the
//! wheel neurons keep their positions (3×3 → 9×9 does): the experiment that
//! tells the lateral field's share of a re-sampling loss (docs/results.md).

use vivae_neat::hyperneat::SubstrateController;

use crate::config::{NormalizeBy, Recurrence, SubstrateConfig};
use crate::controller::sensors::SensorSheet;
use crate::controller::substrate::PolarNode;

/// The paper's neuron count (3×3): the neuron sheet's reference size.
pub const PAPER_NEURONS: usize = 9;

/// The factor of every source node and whether self-loops are exempt.
#[derive(Debug, Clone, PartialEq)]
pub struct SourceScale {
    /// One factor per controller source: inputs (sheet after sheet), then neurons.
    per_source: Vec<f64>,
    /// Whether each neuron's self-loop keeps the CPPN's weight.
    keep_self_loops: bool,
    /// Number of input nodes (the first neuron's source index).
    inputs: usize,
    /// Which neuron→neuron links are kept.
    recurrence: Recurrence,
}

impl SourceScale {
    /// The scale of `config`'s rule for `sheets` and `neurons`.
    pub fn new(config: &SubstrateConfig, sheets: &[SensorSheet], neurons: &[PolarNode]) -> Self {
        let inputs: usize = sheets.iter().map(SensorSheet::len).sum();
        let mut per_source = Vec::with_capacity(inputs + neurons.len());
        let mut sheet = |nodes: &[PolarNode], reference: usize| {
            let count = nodes.len() as f64;
            let total_rho: f64 = nodes.iter().map(|n| n.rho).sum();
            per_source.extend(nodes.iter().map(|n| {
                match (config.normalize, config.normalize_by) {
                    (false, _) => 1.0,
                    (true, NormalizeBy::Count) => reference as f64 / count,
                    (true, NormalizeBy::Area) => reference as f64 * n.rho / total_rho,
                }
            }));
        };
        for s in sheets {
            sheet(&s.nodes(), s.reference_len);
        }
        sheet(neurons, PAPER_NEURONS);
        SourceScale {
            per_source,
            keep_self_loops: config.normalize && !config.normalize_self_loops,
            inputs,
            recurrence: config.recurrence,
        }
    }

    /// The factor of each source (inputs, then neurons).
    pub fn factors(&self) -> &[f64] {
        &self.per_source
    }

    /// Rescales `controller`'s weights (a factor of 1 leaves a weight's bits untouched).
    pub fn apply(&self, controller: &mut SubstrateController) {
        for (source, &factor) in self.per_source.iter().enumerate() {
            if factor != 1.0 {
                controller.scale_source(source, factor);
            }
        }
        if self.keep_self_loops {
            for (i, &factor) in self.per_source[self.inputs..].iter().enumerate() {
                if factor != 1.0 {
                    controller.scale_recurrent(i, i, 1.0 / factor);
                }
            }
        }
        if !self.recurrence.is_full() {
            let n = self.per_source.len() - self.inputs;
            for source in 0..n {
                for target in 0..n {
                    if source != target || self.recurrence == Recurrence::None {
                        // w × 0 is ±0: the cut link adds nothing to any sum.
                        controller.scale_recurrent(source, target, 0.0);
                    }
                }
            }
        }
    }
}
