//! The black-box network boundary used by the rest of the project.

/// A network mapping an input vector to an output vector, possibly with state.
pub trait Network {
    /// Number of inputs `activate` expects.
    fn num_inputs(&self) -> usize;
    /// Number of outputs `activate` writes.
    fn num_outputs(&self) -> usize;
    /// Feeds `inputs` and writes `outputs`; never allocates.
    fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]);
    /// Clears recurrent state (a no-op for acyclic networks).
    fn reset(&mut self);
}
