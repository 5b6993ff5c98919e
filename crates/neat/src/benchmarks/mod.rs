//! The field's benchmark tasks as library code, so that the examples, the
//! divan benchmarks and the lab's replication packs (`vivae reproduce`) run
//! the same work. Pure tasks: no file I/O.

pub mod boxes;
mod cart_pole;
pub mod pole;
pub mod pole_lanes;
pub mod retina;
pub mod xor;
