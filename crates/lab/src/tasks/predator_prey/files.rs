//! The files of a predator–prey run directory.

/// Each generation of the hunter population.
pub const HUNTERS: &str = "hunters.csv";
/// Each generation of the prey population.
pub const PREY: &str = "prey.csv";
/// The CIAO matrix.
pub const CIAO: &str = "ciao.csv";
/// Each generation's champions' genomes.
pub const HALL: &str = "hall-of-fame.jsonl";
/// The run's state after its last generation.
pub const CHECKPOINT: &str = "checkpoint.json";
/// The master tournament's winners.
pub const CHAMPIONS: &str = "champions.json";
/// With opponents = "fixed": the prey every hunter meets.
pub const FIXED_PREY: &str = "fixed-prey.json";
