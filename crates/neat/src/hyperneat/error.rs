//! Errors of substrate layout checks, decoding and controller loading.

/// Errors of substrate decoding.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HyperError {
    /// A hyper-parameter is out of its valid range.
    #[error("invalid HyperNEAT parameter {field} = {value}: {reason}")]
    InvalidParam {
        /// Name of the offending field.
        field: &'static str,
        /// The rejected value.
        value: f64,
        /// What the valid range is.
        reason: &'static str,
    },
    /// The CPPN does not take the 5 substrate-query inputs.
    #[error("the CPPN has {0} inputs; substrate queries need 5 (x1, y1, x2, y2, bias)")]
    CppnInputs(usize),
    /// The layout refers to a CPPN output the CPPN does not have.
    #[error(
        "the layout uses CPPN output {output} for {role}, but the CPPN has only {available} outputs"
    )]
    CppnOutput {
        /// Which query uses the output.
        role: &'static str,
        /// The requested output index.
        output: usize,
        /// How many outputs the CPPN has.
        available: usize,
    },
    /// The layout has no neurons.
    #[error("the substrate has no neurons")]
    NoNeurons,
    /// A node coordinate is not finite.
    #[error("{sheet} node {index} has a non-finite coordinate {coord:?}")]
    BadCoordinate {
        /// Which sheet.
        sheet: &'static str,
        /// Node index within the sheet.
        index: usize,
        /// The coordinate.
        coord: [f64; 2],
    },
    /// Serialised controller data are inconsistent.
    #[error("inconsistent controller data: {0}")]
    Inconsistent(&'static str),
}
