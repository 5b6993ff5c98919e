//! Figures of a run: convergence, network drawing, trajectories.
