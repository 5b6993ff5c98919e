//! The robot's controller: polar sheets, the sensors that feed them, the
//! substrate decoded from a CPPN (fixed sheets or ES-HyperNEAT) and the
//! weight normalisation applied to it.

pub mod blind;
pub mod drive;
pub mod es;
pub mod normalize;
pub mod readings;
// The sheets' geometry is below the config, which names grids in its keys.
pub use crate::polar;
pub mod sensors;
pub mod substrate;
