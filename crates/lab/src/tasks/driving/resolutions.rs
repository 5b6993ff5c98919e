//! Multi-resolution evolution: every genome is evaluated at several substrate
//! resolutions and its fitness aggregates them (the paper's first item of
//! future work: re-sampling during evolution, so that the CPPN generalises).
//!
//! The resolutions are `substrate.train_neurons × substrate.train_sensors`
//! ([`Config::training_configs`]); the experiment's own resolution stays the
//! one reported, drawn and replayed. Each evaluation is deterministic, so the
//! aggregate does not depend on thread or process count.

use vivae_sim::Scenario;

use crate::config::Config;
use crate::tasks::driving::combined::{Combined, DrivingTask};
use crate::tasks::driving::episode::{Episode, EpisodeError};

/// Label of a resolution, such as `s3x5-n9x9`.
pub fn label(config: &Config) -> String {
    let s = &config.surface_sensors;
    let n = config.substrate.neurons;
    format!("s{}x{}-n{}x{}", s.rings, s.angles, n.rings, n.angles)
}

/// The task of `config` on `scenario` at every training resolution, their
/// fitnesses combined by `substrate.train_aggregate`; `None` when the config
/// trains at its own resolution only.
pub fn at_resolutions(
    config: &Config,
    scenario: &Scenario,
) -> Result<Option<Combined>, EpisodeError> {
    let configs = config.training_configs();
    if configs.is_empty() {
        return Ok(None);
    }
    let mut parts: Vec<(String, Box<dyn DrivingTask>)> = Vec::with_capacity(configs.len());
    for c in &configs {
        let label = label(c);
        let experiment = Episode::new(c, scenario)
            .map_err(|e| EpisodeError::Config(format!("training resolution {label}: {e}")))?;
        parts.push((label, Box::new(experiment)));
    }
    Ok(Some(Combined::new(parts, config.substrate.train_aggregate)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Aggregate;
    use crate::controller::substrate::PolarGrid;
    use crate::tasks::scenarios::load_scenario;
    use vivae_neat::driver::Task;
    use vivae_neat::{EvalContext, Population};

    fn grid(rings: usize, angles: usize) -> PolarGrid {
        PolarGrid { rings, angles }
    }

    const CTX: EvalContext = EvalContext {
        generation: 1,
        index: 0,
        seed: 0,
    };

    #[test]
    fn a_genome_is_evaluated_at_every_listed_resolution() {
        let scenario = load_scenario(None).unwrap().scenario;
        let mut config = Config::default();
        config.experiment.steps = 120;
        config.substrate.train_neurons = vec![grid(3, 3), grid(5, 5)];
        config.substrate.train_sensors = vec![grid(3, 5), grid(3, 6)];
        let experiment = Episode::new(&config, &scenario).unwrap();
        let training = at_resolutions(&config, &scenario)
            .unwrap()
            .expect("a training set");
        let labels: Vec<&str> = training.labels().collect();
        assert_eq!(labels, ["s3x5-n3x3", "s3x6-n3x3", "s3x5-n5x5", "s3x6-n5x5"]);
        let pop = Population::new(config.neat.clone(), experiment.cppn_spec(), 4).unwrap();
        let genome = &pop.genomes()[0];
        let single = training.fitnesses(genome, &CTX);
        // Each resolution on its own, as `replay --neurons/--sensors` would run it.
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
            let alone = Episode::new(&c, &scenario).unwrap().fitness(genome);
            assert_eq!(alone.to_bits(), single[i].to_bits(), "resolution {i}");
        }
        let mean = single.iter().sum::<f64>() / 4.0;
        assert_eq!(
            training.evaluate(genome, &CTX).fitness.to_bits(),
            mean.to_bits()
        );
        config.substrate.train_aggregate = Aggregate::Min;
        let min = at_resolutions(&config, &scenario).unwrap().unwrap();
        let lowest = single.iter().copied().fold(f64::INFINITY, f64::min);
        assert_eq!(
            min.evaluate(genome, &CTX).fitness.to_bits(),
            lowest.to_bits()
        );
        // The experiment itself still runs (and reports) its own resolution.
        assert_eq!(experiment.fitness(genome).to_bits(), single[0].to_bits());
    }

    #[test]
    fn no_lists_means_no_training_set() {
        let scenario = load_scenario(None).unwrap().scenario;
        assert!(
            at_resolutions(&Config::default(), &scenario)
                .unwrap()
                .is_none()
        );
    }
}
