//! NEAT, CPPNs, neural networks and HyperNEAT substrate decoding.
//!
//! A pure library: genomes evolve through [`Population`], phenotypes are built with
//! [`FeedForwardNetwork::from_genome`] (the CPPN) or [`RecurrentNetwork::from_genome`],
//! and everything the rest of the project needs from a network is the [`Network`]
//! trait. All randomness comes from seeded `rand_pcg` generators, and every
//! transcendental function from [`math`], so a run gives the same bits on
//! every machine and at any thread count.
//!
//! [`driver::Evolution`] runs generations of a population on a [`driver::Task`]
//! until a [`driver::StopCriteria`] holds and says why it stopped. The
//! population is one [`driver::Strategy`], the ask/tell seam behind the
//! driver: any other search over genomes (see [`driver::strategy`] for a
//! (1+1) evolution strategy) runs, is observed and is checkpointed the same
//! way; [`strategies`] has novelty search, MAP-Elites and NSGA-II, all
//! breeding with NEAT's operators. XOR, the classic NEAT benchmark, in full:
//!
//! ```
//! use vivae_neat::driver::{Evolution, NoCheckpoints, ParallelEvaluator, StopCriteria, StopReason};
//! use vivae_neat::{EvalContext, FeedForwardNetwork, Genome, GenomeSpec, NeatParams, Network, Population};
//!
//! // Fitness (4 − Σ|error|)²: 16 is perfect.
//! let xor = |genome: &Genome, _: &EvalContext| {
//!     let mut net = FeedForwardNetwork::from_genome(genome);
//!     let mut error = 0.0;
//!     for (a, b) in [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0), (1.0, 1.0)] {
//!         let mut out = [0.0];
//!         net.activate(&[a, b, 1.0], &mut out); // the third input is a bias
//!         error += (out[0] - if a != b { 1.0 } else { 0.0 }).abs();
//!     }
//!     (4.0 - error).powi(2)
//! };
//! let population = Population::new(NeatParams::plain_neat(), GenomeSpec::plain(3, 1), 1)?;
//! let mut evolution = Evolution::new(population, ParallelEvaluator::new(xor));
//! let stop = StopCriteria::generations(300).or_target(15.0);
//! let reason = evolution.run(&stop, &mut (), &mut NoCheckpoints)?;
//! assert!(matches!(reason, StopReason::TargetFitness { .. }), "{reason:?}");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Which parameter preset when
//!
//! * [`NeatParams::paper_cppn`] (= [`NeatParams::default`], the paper's
//!   Table II) for CPPNs and HyperNEAT: a genome that paints a substrate, with
//!   [`GenomeSpec::cppn`] and a large population.
//! * [`NeatParams::plain_neat`] for direct encodings, where the genome *is* the
//!   network (XOR, parity, pole balancing), with [`GenomeSpec::plain`]
//!   (Stanley's XOR settings). Do not use the default there: its high
//!   compatibility threshold and small weight steps make such tasks stall.
//!
//! Restored state is checked: deserialising a [`Genome`] or a [`Population`]
//! validates it (typed [`GenomeError`] / [`PopulationError`]), and
//! [`stats`] holds the mean and median every summary uses.

pub mod activation;
pub mod benchmarks;
mod compile;
pub mod crossover;
pub mod distance;
pub mod driver;
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
pub mod precision;
pub mod recurrent;
pub mod recurrent_lanes;
pub mod simd;
pub mod species;
pub mod stats;
pub mod strategies;
#[cfg(test)]
mod test_genes;

pub use activation::{Activation, bipolar_sigmoid};
pub use crossover::crossover;
pub use distance::distance;
pub use error::{GenomeAt, GenomeError, NeatError, PopulationError};
pub use eval::{EvalContext, eval_seed};
pub use feedforward::FeedForwardNetwork;
pub use genome::{Genome, GenomeSpec, LinkGene, NodeGene, NodeKind, RawGenome};
pub use innovation::InnovationTracker;
pub use network::Network;
pub use params::NeatParams;
pub use population::{BestEver, GenerationStats, Population, allocate_offspring};
pub use precision::Precision;
pub use recurrent::RecurrentNetwork;
pub use recurrent_lanes::RecurrentLanes;
pub use species::Species;
pub use strategies::{MapElites, NoveltySearch, Nsga2};
