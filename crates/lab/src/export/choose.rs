//! Which genome of a run to export or drive, decoded at the resolution asked
//! for: the one place the CLI (`vivae export`, `vivae drive-image`) and
//! Python (`vivae.export`, `vivae.drive_image`) find it.

use std::path::{Path, PathBuf};

use vivae_neat::{Genome, Precision};

use crate::config::Config;
use crate::controller::es::RobotController;
use crate::controller::substrate::PolarGrid;
use crate::error::{Error, Result};
use crate::io::bad_input;
use crate::rundir::{self, files};
use crate::search::files::{Member, read_member};
use crate::tasks::substrate::SubstrateEpisode;

/// Which genome of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Pick {
    /// The run's champion (`champion.json`).
    #[default]
    Champion,
    /// The best genome of this generation (`best-genomes.jsonl`).
    Generation(u32),
    /// A MAP-Elites elite or an NSGA-II front member.
    Member(Member),
}

/// A run's genome, decoded.
#[derive(Debug)]
pub struct Chosen {
    /// The config (the run's, with the resolution asked for).
    pub config: Config,
    /// The episode setup of the run's (first) map at that resolution, as
    /// its task declares it ([`crate::tasks::TaskEntry::substrate_episode`]).
    pub episode: Box<dyn SubstrateEpisode>,
    /// The genome.
    pub genome: Genome,
    /// Its decoded controller.
    pub controller: RobotController,
    /// What was chosen, for the artifact: run, member, resolution, substrate.
    pub description: String,
}

/// Decodes `pick` of the run (or champion file) `source` with surface
/// sensors `sensors`, neurons `neurons` and in precision `precision`
/// (default: the run's).
pub fn choose(
    source: &Path,
    pick: Pick,
    sensors: Option<PolarGrid>,
    neurons: Option<PolarGrid>,
    precision: Option<Precision>,
) -> Result<Chosen> {
    let (champion, mut config, _) = crate::tasks::load_genome_source(source)?;
    let entry = crate::tasks::entry_of(&config).map_err(|e| bad_input(e.to_string()))?;
    let Some(episode_of) = entry.substrate_episode else {
        return Err(bad_input(format!(
            "{}: {} run has no substrate network to decode: runs of {} have one",
            source.display(),
            crate::error::a(entry.name),
            crate::tasks::names_with(|t| t.substrate_episode.is_some())
        )));
    };
    let (genome, what) = genome_of(source, pick, champion)?;
    // A multi-map run's controller reads its sensors the same on every map.
    if crate::tasks::maps::is_multi_map(&config) {
        let maps = std::mem::take(&mut config.experiment.scenarios);
        config.experiment.scenario = maps[0].clone();
    }
    let overrides = crate::run::prepare::Overrides {
        sensors,
        neurons,
        precision,
        ..Default::default()
    };
    let refused = |e: String| bad_input(format!("{}: {e}", source.display()));
    overrides.apply(&mut config).map_err(refused)?;
    crate::tasks::check(&config).map_err(|e| refused(e.to_string()))?;
    let path = (!config.experiment.scenario.is_empty())
        .then(|| PathBuf::from(&config.experiment.scenario))
        .filter(|p| p.exists());
    // The run's map only gives the robots' starts; the embedded map stands in when it is gone.
    let scenario = crate::tasks::scenarios::load_scenario(path.as_deref())?;
    let episode = episode_of(&config, &scenario.scenario).map_err(|e| refused(e.to_string()))?;
    let controller = episode
        .robot_controller(&genome)
        .map_err(|e| Error::Genome {
            path: source.to_path_buf(),
            reason: format!("the genome's {e}"),
        })?;
    let s = &config.surface_sensors;
    let description = format!(
        "{what} of {}; substrate {}; surface sensors {}x{} over {} deg; neurons {}; precision {}",
        source.display(),
        match config.substrate.kind {
            crate::controller::es::SubstrateKind::Polar => "polar",
            crate::controller::es::SubstrateKind::EsHyperneat => "es-hyperneat",
        },
        s.rings,
        s.angles,
        s.fov,
        config.substrate.neurons,
        config.experiment.precision,
    );
    Ok(Chosen {
        config,
        episode,
        genome,
        controller,
        description,
    })
}

/// The controller `pick` of the run (or champion file) `source`, ready to
/// write: a driving run's decoded substrate ([`choose`], with `sensors`,
/// `neurons`, `precision`), or the network of a task whose genome is its
/// controller (a plain task: [`crate::tasks::RunTask::network_outputs`]);
/// a task that declares neither is refused by name.
pub fn exported(
    source: &Path,
    pick: Pick,
    sensors: Option<PolarGrid>,
    neurons: Option<PolarGrid>,
    precision: Option<Precision>,
) -> Result<super::Exported> {
    let (champion, config, _) = crate::tasks::load_genome_source(source)?;
    if crate::tasks::entry_of(&config).is_ok_and(|t| t.substrate_episode.is_some()) {
        let c = choose(source, pick, sensors, neurons, precision)?;
        return Ok(super::Exported::new(
            c.episode.as_ref(),
            &c.controller,
            &c.description,
        ));
    }
    let name = config.experiment.task.name();
    let refused = |why: String| bad_input(format!("{}: {why}", source.display()));
    if sensors.is_some() || neurons.is_some() || precision.is_some() {
        return Err(refused(format!(
            "{} run has no substrate to re-sample: drop the sensors, neurons and precision",
            crate::error::a(name)
        )));
    }
    let task = crate::tasks::describe::build(&config, &crate::tasks::maps::load(&config)?)?;
    let outputs = task.network_outputs().ok_or_else(|| {
        refused(format!(
            "task {name} does not export a controller: export needs a substrate network (runs of {}) or a task whose genome is its network (a plain task)",
            crate::tasks::names_with(|t| t.substrate_episode.is_some())
        ))
    })?;
    let (genome, what) = genome_of(source, pick, champion)?;
    task.check_genome(&genome).map_err(|reason| Error::Genome {
        path: source.to_path_buf(),
        reason,
    })?;
    let description = format!(
        "{what} of {}; a plain NEAT network of task {name}",
        source.display()
    );
    let recurrent = task.genome_spec().allow_recurrent;
    let readings = task.network_readings();
    super::Exported::plain(&genome, recurrent, readings, outputs, &description).map_err(refused)
}

/// The genome `pick` names, and how to call it.
fn genome_of(source: &Path, pick: Pick, champion: rundir::Champion) -> Result<(Genome, String)> {
    match pick {
        Pick::Champion => Ok((
            champion.genome,
            format!("champion (generation {})", champion.generation),
        )),
        Pick::Generation(g) => {
            let best = rundir::read_best_genomes(&source.join(files::BEST_GENOMES))?;
            let n = best.len();
            let b = (best.into_iter().find(|b| b.generation == g)).ok_or_else(|| {
                bad_input(format!(
                    "{}: generation {g} has no recorded best genome ({n} generations recorded)",
                    source.join(files::BEST_GENOMES).display()
                ))
            })?;
            Ok((b.genome, format!("best of generation {g}")))
        }
        Pick::Member(m) => {
            let (genome, _, generation) = read_member(source, m)?;
            let what = match m {
                Member::Elite(c) => format!("elite of cell {c} (generation {generation})"),
                Member::Front(k) => format!("front member {k}"),
            };
            Ok((genome, what))
        }
    }
}
