//! NEAT, CPPNs, neural networks and HyperNEAT substrate decoding.
//!
//! A pure library: genomes evolve through [`Population`], phenotypes are built with
//! [`FeedForwardNetwork::from_genome`] (the CPPN) or [`RecurrentNetwork::from_genome`],
//! and everything the rest of the project needs from a network is the [`Network`]
//! trait. All randomness comes from seeded `rand_pcg` generators.

pub mod activation;
pub mod crossover;
pub mod distance;
pub mod error;
pub mod eval;
pub mod feedforward;
pub mod genome;
pub mod hyperneat;
pub mod innovation;
pub mod math;
pub mod mutation;
pub mod network;
pub mod params;
pub mod population;
pub mod recurrent;
pub mod species;

pub use activation::{Activation, bipolar_sigmoid};
pub use crossover::crossover;
pub use distance::distance;
pub use error::NeatError;
pub use eval::{EvalContext, eval_seed};
pub use feedforward::FeedForwardNetwork;
pub use genome::{Genome, GenomeSpec, LinkGene, NodeGene, NodeKind};
pub use innovation::InnovationTracker;
pub use network::Network;
pub use params::NeatParams;
pub use population::{BestEver, GenerationStats, Population, allocate_offspring};
pub use recurrent::RecurrentNetwork;
pub use species::Species;
