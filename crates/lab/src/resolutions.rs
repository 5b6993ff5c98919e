//! Multi-resolution evolution: every genome is evaluated at several substrate
//! resolutions and its fitness aggregates them (the paper's first item of
//! future work: re-sampling during evolution, so that the CPPN generalises).
//!
//! The resolutions are `substrate.train_neurons × substrate.train_sensors`
//! ([`Config::training_configs`]); the experiment's own resolution stays the
//! one reported, drawn and replayed. Each evaluation is deterministic, so the
//! aggregate does not depend on thread or process count.

use vivae_neat::Genome;
use vivae_sim::Scenario;

use crate::config::{Aggregate, Config};
use crate::experiment::{Experiment, ExperimentError};

/// The experiments of every training resolution and how their fitnesses combine.
#[derive(Debug, Clone)]
pub struct Training {
    /// (label such as `s3x5-n9x9`, experiment), in config order.
    resolutions: Vec<(String, Experiment)>,
    aggregate: Aggregate,
}

impl Training {
    /// The training set of `config` on `scenario`; `None` when the config
    /// trains at its own resolution only.
    pub fn new(config: &Config, scenario: &Scenario) -> Result<Option<Training>, ExperimentError> {
        let configs = config.training_configs();
        if configs.is_empty() {
            return Ok(None);
        }
        let mut resolutions = Vec::with_capacity(configs.len());
        for c in &configs {
            let s = &c.surface_sensors;
            let n = c.substrate.neurons;
            let label = format!("s{}x{}-n{}x{}", s.rings, s.angles, n.rings, n.angles);
            let experiment = Experiment::new(c, scenario).map_err(|e| {
                ExperimentError::Config(format!("training resolution {label}: {e}"))
            })?;
            resolutions.push((label, experiment));
        }
        Ok(Some(Training {
            resolutions,
            aggregate: config.substrate.train_aggregate,
        }))
    }

    /// Labels of the resolutions (`sRxA-nRxA`), in evaluation order.
    pub fn labels(&self) -> impl Iterator<Item = &str> {
        self.resolutions.iter().map(|(l, _)| l.as_str())
    }

    /// The experiment of each resolution, in evaluation order.
    pub fn experiments(&self) -> impl Iterator<Item = &Experiment> {
        self.resolutions.iter().map(|(_, e)| e)
    }

    /// How the fitnesses combine.
    pub fn aggregate(&self) -> Aggregate {
        self.aggregate
    }

    /// Fitness of `genome` at every resolution, in evaluation order.
    pub fn fitnesses(&self, genome: &Genome) -> Vec<f64> {
        self.resolutions
            .iter()
            .map(|(_, e)| e.fitness(genome))
            .collect()
    }

    /// The aggregated fitness of `genome`.
    pub fn fitness(&self, genome: &Genome) -> f64 {
        self.aggregate.combine(&self.fitnesses(genome))
    }

    /// Robot-steps one evaluation simulates over all resolutions.
    pub fn robot_steps(&self) -> u64 {
        self.resolutions
            .iter()
            .map(|(_, e)| e.robots() as u64 * u64::from(e.steps()))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::load_scenario;
    use crate::substrate::PolarGrid;
    use vivae_neat::driver::Task;
    use vivae_neat::{EvalContext, Population};

    fn grid(rings: usize, angles: usize) -> PolarGrid {
        PolarGrid { rings, angles }
    }

    #[test]
    fn a_genome_is_evaluated_at_every_listed_resolution() {
        let scenario = load_scenario(None).unwrap().scenario;
        let mut config = Config::default();
        config.experiment.steps = 120;
        config.substrate.train_neurons = vec![grid(3, 3), grid(5, 5)];
        config.substrate.train_sensors = vec![grid(3, 5), grid(3, 6)];
        let experiment = Experiment::new(&config, &scenario).unwrap();
        let training = experiment.training().expect("a training set");
        let labels: Vec<&str> = training.labels().collect();
        assert_eq!(labels, ["s3x5-n3x3", "s3x6-n3x3", "s3x5-n5x5", "s3x6-n5x5"]);
        let pop = Population::new(config.neat.clone(), experiment.cppn_spec(), 4).unwrap();
        let genome = &pop.genomes()[0];
        // Each resolution on its own, as `replay --neurons/--sensors` would run it.
        let single: Vec<f64> = training.experiments().map(|e| e.fitness(genome)).collect();
        for (i, (n, s)) in [
            (grid(3, 3), grid(3, 5)),
            (grid(3, 3), grid(3, 6)),
            (grid(5, 5), grid(3, 5)),
            (grid(5, 5), grid(3, 6)),
        ]
        .into_iter()
        .enumerate()
        {
            let mut c = Config::default();
            c.experiment.steps = 120;
            c.substrate.neurons = n;
            c.surface_sensors.rings = s.rings;
            c.surface_sensors.angles = s.angles;
            let alone = Experiment::new(&c, &scenario).unwrap().fitness(genome);
            assert_eq!(alone.to_bits(), single[i].to_bits(), "resolution {i}");
        }
        let mean = single.iter().sum::<f64>() / 4.0;
        let ctx = EvalContext {
            generation: 1,
            index: 0,
            seed: 0,
        };
        assert_eq!(
            experiment.evaluate(genome, &ctx).fitness.to_bits(),
            mean.to_bits()
        );
        config.substrate.train_aggregate = Aggregate::Min;
        let min = Experiment::new(&config, &scenario).unwrap();
        let lowest = single.iter().copied().fold(f64::INFINITY, f64::min);
        assert_eq!(
            min.evaluate(genome, &ctx).fitness.to_bits(),
            lowest.to_bits()
        );
        // The experiment itself still runs (and reports) its own resolution.
        assert_eq!(experiment.fitness(genome).to_bits(), single[0].to_bits());
    }

    #[test]
    fn no_lists_means_no_training_set() {
        let scenario = load_scenario(None).unwrap().scenario;
        let experiment = Experiment::new(&Config::default(), &scenario).unwrap();
        assert!(experiment.training().is_none());
    }
}
