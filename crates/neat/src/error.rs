//! Typed errors of the NEAT library.

use thiserror::Error;

/// Everything that can go wrong when configuring or restoring NEAT.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum NeatError {
    /// A parameter has a value outside its valid range.
    #[error("invalid NEAT parameter `{field}` = {value}: {reason}")]
    InvalidParam {
        /// Name of the offending field.
        field: &'static str,
        /// The offending value, formatted.
        value: String,
        /// What the value must satisfy.
        reason: &'static str,
    },
    /// A genome specification is unusable (e.g. no inputs).
    #[error("invalid genome spec: {0}")]
    InvalidSpec(String),
    /// A genome violates a structural invariant.
    #[error("invalid genome: {0}")]
    InvalidGenome(String),
    /// A checkpoint could not be written or read.
    #[error("checkpoint: {0}")]
    Checkpoint(String),
}
