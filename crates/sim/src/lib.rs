//! The ViVAE robot simulator: SVG scenarios, physics, sensors, snapshots and drawing.
