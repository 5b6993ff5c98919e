//! The vivae experiments: HyperNEAT-controlled robots learning to drive in ViVAE.

pub mod figures;
pub mod substrate;
