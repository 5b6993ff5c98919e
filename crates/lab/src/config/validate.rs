//! Checking a config: every value on its own, then sizes that validate one by one but cannot run.

use super::*;

impl Config {
    /// Checks every value the tasks share; the error names the key and the reason.
    /// [`crate::tasks::check`] adds the rules of the config's task.
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.validate_experiment()?;
        self.validate_parameters()?;
        self.validate_sizes()?;
        self.validate_run()
    }

    /// Checks the `experiment` section.
    fn validate_experiment(&self) -> Result<(), ConfigError> {
        let e = &self.experiment;
        if e.generations == 0 {
            return Err(ConfigError::new(
                "experiment.generations = 0: must be at least 1",
            ));
        }
        if e.steps == 0 {
            return Err(ConfigError::new("experiment.steps = 0: must be at least 1"));
        }
        if !e.scenario.is_empty() && !e.scenarios.is_empty() {
            return Err(ConfigError::new(format!(
                "experiment.scenarios = [...] and experiment.scenario = \"{}\" are both set: train on one map with `scenario` or on several with `scenarios`, not both",
                e.scenario
            )));
        }
        if e.scenarios.len() > MAX_MAPS {
            return Err(ConfigError::new(format!(
                "experiment.scenarios = {} maps: must be at most {MAX_MAPS}",
                e.scenarios.len()
            )));
        }
        if e.placements == 0 || e.placements > MAX_PLACEMENTS {
            return Err(ConfigError::new(format!(
                "experiment.placements = {}: must be from 1 to {MAX_PLACEMENTS}",
                e.placements
            )));
        }
        if e.scenarios.iter().any(String::is_empty) {
            return Err(ConfigError::new(
                "experiment.scenarios = [.., \"\", ..]: a map name is empty",
            ));
        }
        Ok(())
    }

    /// Checks the NEAT, HyperNEAT, physics and sensor parameters.
    fn validate_parameters(&self) -> Result<(), ConfigError> {
        if self.neat.population_size < 2 {
            return Err(ConfigError::new(format!(
                "neat.population_size = {}: must be at least 2 (NEAT breeds from pairs)",
                self.neat.population_size
            )));
        }
        self.neat.validate().map_err(|err| match err {
            vivae_neat::NeatError::InvalidParam {
                field,
                value,
                reason,
            } => ConfigError::new(format!("neat.{field} = {value}: {reason}")),
            other => ConfigError::new(format!("neat: {other}")),
        })?;
        self.hyperneat.validate().map_err(|err| match err {
            vivae_neat::hyperneat::HyperError::InvalidParam {
                field,
                value,
                reason,
            } => ConfigError::new(format!("hyperneat.{field} = {value}: {reason}")),
            other => ConfigError::new(format!("hyperneat: {other}")),
        })?;
        self.physics
            .validate()
            .map_err(|err| ConfigError::new(format!("physics.{}", param_message(&err))))?;
        self.surface_sensors
            .validate()
            .map_err(|err| ConfigError::new(format!("surface_sensors.{}", param_message(&err))))?;
        if let Some(d) = self.distance_sensors.layout() {
            d.validate().map_err(|err| {
                ConfigError::new(format!("distance_sensors.{}", param_message(&err)))
            })?;
        }
        if self.opponent_sensors.slices > 0 {
            let o = &self.opponent_sensors;
            vivae_sim::OpponentRadar::new(o.slices, o.range).map_err(|err| {
                ConfigError::new(format!("opponent_sensors.{}", param_message(&err)))
            })?;
        }
        self.substrate.es.validate().map_err(ConfigError::new)?;
        if !self.substrate.kind.is_polar() {
            super::es::check_feed_forward(self.substrate.es.recurrent, self.substrate.coordinates)
                .map_err(ConfigError::new)?;
        }
        self.validate_leo()
    }

    /// Checks `substrate.es.leo` and `leo_seed` against the substrate kind,
    /// the strategy and `experiment.init_population`.
    fn validate_leo(&self) -> Result<(), ConfigError> {
        let es = &self.substrate.es;
        let key = if es.leo_seed { "leo_seed" } else { "leo" };
        if (es.leo || es.leo_seed) && self.substrate.kind.is_polar() {
            return Err(ConfigError::new(format!(
                "substrate.es.{key} = true applies to substrate.kind = \"es-hyperneat\" only (the dense sheet expresses links by the threshold)"
            )));
        }
        if !es.leo_seed {
            return Ok(());
        }
        // Which strategies can start from the seed is the strategy's to say
        // (`search::check`).
        if !self.experiment.init_population.is_empty() {
            return Err(ConfigError::new(
                "substrate.es.leo_seed = true: experiment.init_population already gives generation 0, remove one of them",
            ));
        }
        Ok(())
    }

    /// Checks the sizes of the run's substrates at every training resolution.
    fn validate_sizes(&self) -> Result<(), ConfigError> {
        self.check_sizes()?;
        let training =
            self.substrate.train_neurons.len().max(1) * self.substrate.train_sensors.len().max(1);
        if training > MAX_TRAINING_RESOLUTIONS {
            return Err(ConfigError::new(format!(
                "substrate.train_neurons x train_sensors = {training} resolutions: must be at most {MAX_TRAINING_RESOLUTIONS}"
            )));
        }
        for c in self.training_configs() {
            c.check_sizes().map_err(|e| {
                ConfigError::new(format!("substrate.train_neurons/train_sensors: {e}"))
            })?;
        }
        Ok(())
    }

    /// Checks the `run` section.
    fn validate_run(&self) -> Result<(), ConfigError> {
        let r = &self.run;
        if r.checkpoint_interval == 0 {
            return Err(ConfigError::new(
                "run.checkpoint_interval = 0: must be at least 1",
            ));
        }
        if r.checkpoint_keep == 0 {
            return Err(ConfigError::new(
                "run.checkpoint_keep = 0: must be at least 1",
            ));
        }
        if r.threads > super::MAX_THREADS {
            return Err(ConfigError::new(format!(
                "run.threads = {}: must be at most {}",
                r.threads,
                super::MAX_THREADS
            )));
        }
        Ok(())
    }

    /// Refuses sizes that validate one by one but cannot run: a substrate whose
    /// weight matrix would not fit in memory, absurd step counts.
    fn check_sizes(&self) -> Result<(), ConfigError> {
        let e = &self.experiment;
        if e.steps > MAX_STEPS {
            return Err(ConfigError::new(format!(
                "experiment.steps = {}: must be at most {MAX_STEPS}",
                e.steps
            )));
        }
        let n = &self.substrate.neurons;
        let neurons = n.rings.saturating_mul(n.angles);
        let s = &self.surface_sensors;
        let sensors = s.rings.saturating_mul(s.angles);
        let rays = self.distance_sensors.rays;
        for (key, value, max) in [
            ("substrate.neurons", neurons, MAX_NEURONS),
            ("surface_sensors (rings x angles)", sensors, MAX_SENSORS),
            ("distance_sensors.rays", rays, MAX_RAYS),
        ] {
            if value > max {
                return Err(ConfigError::new(format!(
                    "{key} = {value} nodes: must be at most {max}"
                )));
            }
        }
        // Every sensor and neuron may link to every neuron: one f64 weight each,
        // held per evaluation thread.
        let links = (sensors + rays + neurons) as u64 * neurons as u64;
        let bytes = links * 8;
        if bytes > MAX_SUBSTRATE_BYTES {
            return Err(ConfigError::new(format!(
                "substrate of {sensors} sensors, {rays} rays and {neurons} neurons: its {links} possible links need about {} MiB per thread, more than the limit of {} MiB",
                bytes >> 20,
                MAX_SUBSTRATE_BYTES >> 20
            )));
        }
        Ok(())
    }
}

pub(super) fn param_message(err: &vivae_sim::ParamError) -> String {
    format!("{} = {}: {}", err.field, err.value, err.reason)
}
