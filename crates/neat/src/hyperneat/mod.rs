//! HyperNEAT: decoding a CPPN into a substrate controller.
//!
//! The module knows nothing about robots or polar grids: a [`SubstrateLayout`]
//! is a list of input sheets and one sheet of neurons, each node a point in
//! the plane. A CPPN with inputs `(x1, y1, x2, y2, 1)` — `(x1, y1)` the target
//! neuron, `(x2, y2)` the source node — paints every possible connection:
//!
//! * input sheet `s` → neuron: CPPN output `inputs[s].cppn_output`;
//! * neuron bias: output `bias_output`, queried with `x2 = y2 = 0`;
//! * neuron → neuron (all ordered pairs, self-loops included): `recurrent_output`.
//!
//! An output `o` is expressed as a connection only when `|o| > t`, with weight
//! `w = sign(o)·(|o| − t)/(1 − t)·amplitude` ([`HyperParams`]). The same rule
//! decides whether a bias is present. The result is a one-layer, fully
//! recurrent [`SubstrateController`].
//!
//! One concern per file: [`HyperParams`] (expression rule), [`SubstrateLayout`]
//! (geometry), [`BatchCppn`] (the CPPN compiled for batched queries),
//! [`decode`] / [`decode_genome`] / [`decode_genome_at`] (CPPN → controller) and
//! [`SubstrateController`] (the decoded network); [`HyperError`] for all of them.

mod batch;
mod controller;
mod decode;
mod error;
pub mod es;
mod layered;
mod layout;
mod leo;
mod params;
mod sparse;
#[cfg(test)]
mod test_util;

pub use batch::{BatchCppn, CppnElement};
pub use controller::{BatchState, Link, LinkSource, SubstrateController};
pub use decode::{decode, decode_genome, decode_genome_at};
pub use error::HyperError;
pub use layered::{LayeredLayout, decode_layered};
pub use layout::{CPPN_INPUTS, InputSheet, SubstrateLayout};
pub use leo::{express_link, leo_seeded_genome, leo_seeded_genomes};
pub use params::HyperParams;
pub use sparse::{SparseLink, SparseNetwork};
