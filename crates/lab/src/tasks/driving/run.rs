//! The driving experiment as a run's task (`experiment.task = "driving"`,
//! the default): its registration and what a run asks of it.

use vivae_neat::{Genome, GenomeSpec};

use crate::config::{Config, TaskName};
use crate::error::Result;
use crate::search::BehaviourSpace;
use crate::tasks::driving::combined::DrivingTask;
use crate::tasks::driving::section::FitnessConfig;
use crate::tasks::driving::training::Training;
use crate::tasks::maps::TrainingMap;
use crate::tasks::{HeaderContext, RunTask, TaskEntry};

/// The driving task's registration.
pub static TASK: TaskEntry = TaskEntry {
    name: TaskName::DRIVING,
    default_config: Config::default,
    validate: |c| {
        FitnessConfig::of(c)
            .check()
            .and_then(|()| super::descriptors::check(c))
    },
    metric_names: &crate::tasks::driving::descriptors::METRICS,
    generation_columns: "",
    behaviours: &super::descriptors::BEHAVIOURS,
    build,
    own_driver: None,
    refuse_when_other: refuse_for_other_tasks,
    set_robot: None,
    sections: &[super::section::SECTION],
    reads: &crate::config::SharedSection::ALL,
    scenarios: &crate::tasks::driving::scenarios::SCENARIOS,
    maps: true,
    check_map: crate::tasks::any_map,
    substrate: true,
    substrate_episode: Some(super::substrate::episode),
    stepped: None,
    reward_threshold: None,
    host: None,
};

/// With another task than driving: refuses `experiment.placements` (and its
/// aggregate) off their defaults: only a driving episode places obstacles
/// and traffic per evaluation; and `experiment.precision = "fast"`: only the
/// driving task's dense controller has a fast step (its `[fitness]` section
/// the registry refuses, as every section a task does not read).
fn refuse_for_other_tasks(c: &Config) -> std::result::Result<(), String> {
    let e = &c.experiment;
    if !e.precision.is_exact() {
        return Err(format!(
            "experiment.precision = \"{}\": only a driving run has a fast controller step \
             (experiment.task = \"{}\"): drop it",
            e.precision, e.task
        ));
    }
    if e.placements != 1 || !e.placements_aggregate.is_mean() {
        return Err(format!(
            "experiment.placements = {}: only a driving run places obstacles or traffic per evaluation \
             (experiment.task = \"{}\"): drop it",
            e.placements, e.task
        ));
    }
    Ok(())
}

/// The driving experiment `task` is, when it is one: what the program's
/// figures, replays and viewer of a driving run read.
pub fn training_of(task: &dyn RunTask) -> Option<&Training> {
    task.as_any().downcast_ref::<Training>()
}

/// The training of `config` on `maps`.
fn build(config: &Config, maps: &[TrainingMap]) -> Result<Box<dyn RunTask>> {
    Ok(Box::new(Training::new(config, maps)?))
}

impl RunTask for Training {
    fn entry(&self) -> &'static TaskEntry {
        &TASK
    }

    fn genome_spec(&self) -> GenomeSpec {
        self.primary().cppn_spec()
    }

    fn behaviour_space(&self, config: &Config) -> BehaviourSpace {
        super::descriptors::space(config, self.primary().robots())
    }

    fn robot_steps(&self) -> u64 {
        DrivingTask::robot_steps(self)
    }

    fn check_genome(&self, genome: &Genome) -> std::result::Result<(), String> {
        (self.primary().robot_controller(genome).map(drop)).map_err(|e| e.to_string())
    }

    fn links(&self, genome: &Genome) -> Result<(usize, usize)> {
        let controller = self.primary().robot_controller(genome)?;
        Ok((controller.expressed_links(), controller.possible_links()))
    }

    fn describe(&self, maps: &[TrainingMap]) -> String {
        Training::describe(self, maps)
    }

    fn header(&self, config: &Config, ctx: &HeaderContext<'_>) -> String {
        header(self, config, ctx)
    }
}

/// The header of a driving run: robots, substrate, training maps and
/// resolutions, and how fitness is measured.
fn header(t: &Training, c: &Config, ctx: &HeaderContext<'_>) -> String {
    let s = &c.surface_sensors;
    let n = c.substrate.neurons;
    let distance = match c.distance_sensors.rays {
        0 => String::new(),
        r => format!(" + {r} distance rays"),
    };
    let map_labels: Vec<&str> = t.map_labels().collect();
    let maps = if map_labels.is_empty() {
        String::new()
    } else {
        format!(
            "\n  training maps: {} (fitness = mean over maps; robots, figures and replay: the first)",
            map_labels.join(", ")
        )
    };
    let training = if t.resolution_labels().is_empty() {
        String::new()
    } else {
        format!(
            "\n  training: every genome at {} ({:?} of their fitnesses)",
            t.resolution_labels().join(", "),
            t.aggregate()
        )
    };
    let HeaderContext {
        command,
        scenario,
        start,
        threads,
        strategy,
        output,
    } = *ctx;
    format!(
        "vivae {command}: {scenario}\n\
         \x20 robots {}, {} steps per evaluation, population {}, {} generations{start}\n\
         \x20 substrate: {}x{} surface sensors{distance}, {}x{} neurons; threads {threads}, seed {}{training}{maps}{strategy}\n\
         \x20 output: {output}\n\
         \x20 fitness = average speed in px/step over all robots and steps (full throttle on road tends to 5)",
        t.primary().robots(),
        c.experiment.steps,
        c.neat.population_size,
        c.experiment.generations,
        s.rings,
        s.angles,
        n.rings,
        n.angles,
        c.experiment.seed,
    )
}
