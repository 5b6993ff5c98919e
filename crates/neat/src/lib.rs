//! NEAT, CPPNs, neural networks and HyperNEAT substrate decoding.

pub mod activation;
pub mod hyperneat;
pub mod network;

pub use activation::{Activation, bipolar_sigmoid};
pub use network::Network;
