//! The maze task's config: its `[maze]` section (which robot model, which
//! walls), its defaults and the keys a maze run cannot honour.

use vivae_neat::NeatParams;

pub use super::section::{Collision, MazeConfig, MazeRobot, MazeWalls};
use crate::config::{Config, DistanceConfig, SubstrateConfig, TaskName};
use crate::search::StrategyConfig;
use crate::search::TaskFacts;

impl Config {
    /// The config of a maze run with the example's settings: the hard maze,
    /// 400 steps, the paper's robot, plain NEAT with Lehman's parameters
    /// ([`lehman_neat`]) and a population of 250,
    /// the strategies fitted to its px and metrics (novelty search's ρ_min =
    /// 6 px, 10 px MAP-Elites cells, NSGA-II on fitness alone).
    pub fn maze() -> Config {
        let mut c = Config::default();
        c.experiment.task = TaskName(super::NAME.into());
        c.experiment.scenario = "hard-maze".into();
        c.experiment.steps = crate::tasks::maze::STEPS;
        c.experiment.robots = 1;
        // 50,000 evaluations.
        c.experiment.generations = 200;
        c.physics = crate::tasks::maze::MazeTask::physics();
        c.neat = lehman_neat();
        StrategyConfig::fit(
            &mut c,
            &TaskFacts {
                metrics: Some(&super::METRICS),
                // The behaviour is in px: behaviours 6 px apart are distinct
                // (Lehman's maze code, via goNEAT_NS), adapting down to 0.05 px
                // (the library's floor).
                distinct: Some(6.0),
                distinct_floor: Some(0.05),
                // Cells of 10 px over the hard maze (205 × 205); `vivae evolve
                // --task maze` fits them to its maze.
                cell: Some(super::CELL),
                extent: &[205.0],
            },
        );
        c
    }
}

/// Plain NEAT with the parameters of Lehman's released maze code
/// (github:jal278/novelty-search-cpp at 9f53ede: `maze.ne`, `genome.cpp`,
/// `population.cpp`, `noveltyexp.cpp`) wherever `NeatParams` has the knob.
///
/// Why not our `plain_neat` (tuned on XOR): its weight mutations are about
/// five times larger (σ 2.5, ±8) than his (uniform ±0.8, within ±3), which
/// makes fitness-based search far less greedy, so it solved the hard maze
/// in 15 of 40 runs where the paper reports 3 (docs/results.md, "The
/// maze"). His start network routes every input through one hidden node
/// (`mazestartgenes`; `start_hidden = 1`), which slows novelty search on
/// the hard maze to the paper's pace. His steady-state replacement has no
/// knob here; the 16 target species stand in for his re-targeting.
pub fn lehman_neat() -> NeatParams {
    NeatParams {
        population_size: 250,
        // maze.ne's weight_mut_power 0.8 is a uniform ±0.8 draw in
        // genome.cpp: σ = 0.8/√3.
        weight_perturb_power: 0.46,
        // genome.cpp caps weights at ±3; population.cpp starts them within ±1.
        weight_amplitude: 3.0,
        initial_weight_range: 1.0,
        weight_link_probability: 0.95,
        weight_replace_probability: 0.1,
        weight_mutation_probability: 0.6,
        compatibility_threshold: 4.0,
        c_excess: 1.0,
        c_disjoint: 1.0,
        c_weight: 3.0,
        // noveltyexp.cpp aims at 16 species, moving the threshold by 0.1
        // every 12 births (up to 2.1 a generation); here by 1.0 a generation.
        target_species: Some(16),
        threshold_step: 1.0,
        // maze.ne: survival_thresh 0.4.
        survival_threshold: 0.4,
        // rtNEAT never culls a stagnant species.
        stagnation_limit: 1_000_000,
        add_node_probability: 0.005,
        add_link_probability: 0.1,
        add_link_attempts: 40,
        mating_probability: 0.7,
        toggle_enable_probability: 0.1,
        // mazestartgenes: the 11 inputs feed one hidden node, which feeds
        // both outputs.
        start_hidden: 1,
        ..NeatParams::plain_neat()
    }
}

/// With `experiment.task = "maze"`: refuses the keys a maze run cannot
/// honour; the message names the key.
pub(super) fn validate(c: &Config) -> Result<(), String> {
    let e = &c.experiment;
    let s = &c.substrate;
    let refuse = |key: &str, why: &str| Err(format!("{key}: {why} (experiment.task = \"maze\")"));
    if !e.scenarios.is_empty() {
        return refuse(
            "experiment.scenarios",
            "a maze run has one maze: name it with experiment.scenario",
        );
    }
    if e.scenario.is_empty() {
        return refuse(
            "experiment.scenario",
            "name the maze: hard-maze, medium-maze or an SVG file with one robot and a `goal` mark",
        );
    }
    if e.robots != 1 {
        return refuse(
            &format!("experiment.robots = {}", e.robots),
            "a maze has one robot: use 1",
        );
    }
    if !e.init_population.is_empty() {
        return refuse(
            "experiment.init_population",
            "a maze run starts from minimal networks (retrain re-samples a substrate, which a maze network has not)",
        );
    }
    if !s.train_neurons.is_empty() || !s.train_sensors.is_empty() {
        return refuse(
            "substrate.train_neurons/train_sensors",
            "a maze network has no substrate to train at several resolutions",
        );
    }
    if !s.kind.is_polar() {
        return refuse(
            "substrate.kind",
            "a maze network is evolved directly, not decoded into an ES-HyperNEAT substrate",
        );
    }
    validate_robot(c)?;
    let unused = [
        ("substrate", *s == SubstrateConfig::default()),
        (
            "surface_sensors",
            c.surface_sensors == vivae_sim::SurfaceSensors::default(),
        ),
        (
            "distance_sensors",
            c.distance_sensors == DistanceConfig::default(),
        ),
        (
            "hyperneat",
            c.hyperneat == vivae_neat::hyperneat::HyperParams::default(),
        ),
    ];
    match unused.iter().find(|(_, default)| !default) {
        Some((section, _)) => refuse(
            &format!("[{section}]"),
            "a maze robot has the paper's 6 rangefinders and 4 radar slices and a plain network: leave this section at its defaults",
        ),
        None => Ok(()),
    }
}

/// The `[maze]` keys and `[physics]` as the chosen robot reads them: Lehman's
/// robot has its own constants, ours has none of Lehman's options.
fn validate_robot(c: &Config) -> Result<(), String> {
    let m = &MazeConfig::of(c);
    match m.robot {
        MazeRobot::Lehman if c.physics != super::MazeTask::physics() => Err(
            "[physics]: Lehman's maze robot has its own constants (docs/howto/maze.md): leave [physics] at the maze's defaults or use maze.robot = \"vivae\"".into(),
        ),
        MazeRobot::Vivae
            if (m.quirks, m.walls, m.collision)
                != (true, MazeWalls::Lehman, Collision::Stop) =>
        {
            Err("[maze] quirks/walls/collision: these are options of Lehman's robot (maze.robot = \"lehman\"); our robot reads [physics] and the scenario's walls".into())
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use crate::config::Config;
    use crate::tasks::config_from_toml;

    #[test]
    fn the_maze_fits_the_strategies_to_its_px_and_metrics() {
        let s = crate::search::StrategyConfig::of(&Config::maze());
        let library = vivae_neat::strategies::NoveltyParams::default();
        assert_eq!(
            (s.novelty.threshold, s.novelty.threshold_floor),
            (6.0, library.threshold_floor)
        );
        assert_eq!(s.map_elites.bins, [21]);
        assert_eq!(s.nsga2.objectives, ["fitness"]);
    }

    #[test]
    fn a_maze_section_in_a_driving_config_names_the_key_that_fixes_it() {
        let e = config_from_toml("[maze]\nrobot = \"vivae\"\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("[maze]") && e.contains("task = \"maze\"") && e.contains("[experiment]"),
            "{e}"
        );
        let fixed = "[experiment]\ntask = \"maze\"\n[maze]\nrobot = \"vivae\"\n";
        assert!(config_from_toml(fixed).is_ok());
    }
}
