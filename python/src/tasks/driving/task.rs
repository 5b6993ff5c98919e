//! The driving experiment's task from Python: genomes (CPPNs) evaluated,
//! decoded onto the substrate and turned into controllers, episodes measured.

use std::path::{Path, PathBuf};

use numpy::IntoPyArray;
use numpy::ndarray::{Array1, Array2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use vivae_lab::config::Config;
use vivae_lab::controller::es::RobotController;
use vivae_lab::rundir;
use vivae_lab::tasks::driving::{episode::Episode, training::Training};
use vivae_neat::hyperneat::SubstrateController;
use vivae_neat::{EvalContext, Network as _};

use super::controller::Controller;
use crate::evo::{Genome, Population, merge_params};
use crate::{args, errors, settings};

/// The training maps and task of `config`, as `vivae evolve` sets them up.
fn training(
    config: &Config,
) -> vivae_lab::Result<(Vec<vivae_lab::tasks::maps::TrainingMap>, Training)> {
    let maps = vivae_lab::tasks::maps::load(config)?;
    let training = Training::new(config, &maps)?;
    Ok((maps, training))
}

/// The driving task of a config: genomes (CPPNs) evaluated, decoded onto
/// the substrate and turned into controllers, as in `vivae evolve`.
#[pyclass(module = "vivae._vivae", frozen)]
pub struct DriveTask {
    config: Config,
    training: Training,
    pool: crate::pool::ForkSafePool,
}

impl DriveTask {
    fn from_config(py: Python<'_>, config: Config) -> PyResult<DriveTask> {
        let (maps, training) = training(&config).map_err(errors::lab)?;
        for m in &maps {
            errors::warn_scenario(py, &m.loaded.scenario)?;
        }
        let pool = crate::pool::ForkSafePool::new(config.run.threads)?;
        Ok(DriveTask {
            config,
            training,
            pool,
        })
    }

    fn setup(&self) -> &Episode {
        self.training.primary()
    }

    /// Refuses a genome whose links form a cycle where this task's CPPNs are
    /// feed-forward: decoded, the links closing the cycle would be dropped
    /// without a word (the genome is recurrent, the CPPN is not).
    fn check_acyclic(&self, genome: &Genome) -> PyResult<()> {
        if self.training.task().cppn_spec().allow_recurrent || !crate::evo::has_cycle(&genome.inner)
        {
            return Ok(());
        }
        Err(PyValueError::new_err(
            "genome: its links form a cycle (a recurrent network), but this task's CPPNs are \
             feed-forward and decoding would drop the links that close it; \
             give a genome of a population made with recurrent=False",
        ))
    }

    fn controller_of(&self, genome: &Genome) -> PyResult<SubstrateController> {
        self.check_acyclic(genome)?;
        self.setup()
            .controller(&genome.inner)
            .map_err(|e| errors::value(format!("the genome's {e}")))
    }

    /// The controller of either substrate kind (dense sheet or ES-HyperNEAT).
    fn robot_controller_of(&self, genome: &Genome) -> PyResult<RobotController> {
        self.check_acyclic(genome)?;
        self.setup()
            .robot_controller(&genome.inner)
            .map_err(|e| errors::value(format!("the genome's {e}")))
    }
}

#[pymethods]
impl DriveTask {
    /// The task `config` (a TOML file, default the paper's) with `overrides`
    /// (the CLI's flags by name: `scenario`, `sensors="3x5"`, `steps`, …).
    #[new]
    #[pyo3(signature = (config=None, **overrides))]
    fn new(
        py: Python<'_>,
        config: Option<PathBuf>,
        overrides: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<DriveTask> {
        let config = settings::build(config.as_deref(), overrides)?;
        DriveTask::from_config(py, config)
    }

    /// A task from its resolved config's TOML ([`DriveTask::config_toml`]):
    /// how a pickled task is rebuilt in another process.
    #[staticmethod]
    fn from_config_toml(py: Python<'_>, text: &str) -> PyResult<DriveTask> {
        DriveTask::from_config(py, crate::tasks::config_of_toml(text)?)
    }

    /// Pickles by its resolved config (its scenario paths as resolved here).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        crate::tasks::reduce_to_config(slf, &slf.get().config)
    }

    /// The resolved config as TOML (what `config.toml` of a run holds).
    fn config_toml(&self) -> String {
        self.config.to_toml()
    }

    /// (inputs, outputs) of the CPPNs this task evolves.
    #[getter]
    fn cppn_shape(&self) -> (usize, usize) {
        let s = self.setup().cppn_spec();
        (s.inputs, s.outputs)
    }

    /// Robots per episode.
    #[getter]
    fn robots(&self) -> usize {
        self.setup().robots()
    }

    /// Steps per episode.
    #[getter]
    fn steps(&self) -> u32 {
        self.setup().steps()
    }

    /// A generation-0 population of CPPNs with the config's NEAT parameters
    /// (`params` overrides them by name); `seed` defaults to the config's:
    /// the population `vivae evolve` starts from.
    #[pyo3(signature = (seed=None, size=None, params=None))]
    fn population(
        &self,
        #[pyo3(from_py_with = args::opt_seed)] seed: Option<u64>,
        #[pyo3(from_py_with = args::size)] size: Option<usize>,
        params: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Population> {
        let mut params = merge_params(self.config.neat.clone(), params)?;
        if let Some(n) = size {
            params.population_size = n;
        }
        let spec = self.training.task().cppn_spec();
        let seed = seed.unwrap_or(self.config.experiment.seed);
        // With `substrate.es.leo_seed`, LEO's seeded genomes, as a run starts.
        let inner = vivae_lab::search::initial_population(&self.config, params, spec, seed)
            .map_err(errors::lab)?;
        Ok(Population::of(inner))
    }

    /// The fitness of each genome (an episode on every training map and
    /// resolution, as in a run), evaluated in Rust threads without the GIL.
    fn evaluate(&self, py: Python<'_>, genomes: Vec<PyRef<'_, Genome>>) -> PyResult<Vec<f64>> {
        let want = self.training.task().cppn_spec();
        for g in &genomes {
            if g.inner.num_inputs() != want.inputs || g.inner.num_outputs() != want.outputs {
                return Err(PyValueError::new_err(format!(
                    "a CPPN with {} inputs and {} outputs; this task needs {} and {}",
                    g.inner.num_inputs(),
                    g.inner.num_outputs(),
                    want.inputs,
                    want.outputs
                )));
            }
            self.check_acyclic(g)?;
        }
        let genomes: Vec<&vivae_neat::Genome> = genomes.iter().map(|g| &g.inner).collect();
        let task = self.training.task();
        let pool = self.pool.get()?;
        // In chunks of a few genomes per thread, so that Ctrl-C is noticed
        // between them rather than only at the end (each genome keeps its index).
        let chunk = 4 * pool.current_num_threads().max(1);
        let mut fitnesses = Vec::with_capacity(genomes.len());
        for (c, part) in genomes.chunks(chunk).enumerate() {
            let done: Vec<f64> = py.detach(|| {
                pool.install(|| {
                    (part.par_iter().enumerate())
                        .map(|(i, g)| {
                            let index = c * chunk + i;
                            let seed = vivae_neat::eval_seed(self.config.experiment.seed, 0, index);
                            let ctx = EvalContext {
                                generation: 0,
                                index,
                                seed,
                            };
                            task.evaluate(g, &ctx).fitness
                        })
                        .collect()
                })
            });
            fitnesses.extend(done);
            py.check_signals()?;
        }
        Ok(fitnesses)
    }

    /// The substrate `genome` paints, as numpy arrays: `input_weights`
    /// (neurons × inputs), `recurrent_weights` (neurons × neurons, target
    /// by source), `biases` (neurons) and the wheel neurons' indices.
    fn decode<'py>(&self, py: Python<'py>, genome: &Genome) -> PyResult<Bound<'py, PyDict>> {
        let c = self.controller_of(genome)?;
        let (ni, n) = (c.num_inputs(), c.num_neurons());
        let inputs = Array2::from_shape_fn((n, ni), |(t, i)| c.input_weight(i, t));
        let recurrent = Array2::from_shape_fn((n, n), |(t, s)| c.recurrent_weight(s, t));
        let d = PyDict::new(py);
        d.set_item("input_weights", inputs.into_pyarray(py))?;
        d.set_item("recurrent_weights", recurrent.into_pyarray(py))?;
        d.set_item("biases", Array1::from(c.biases().to_vec()).into_pyarray(py))?;
        let w = self.setup().wheels();
        d.set_item("wheels", (w.left, w.right))?;
        d.set_item("sheet_sizes", c.sheet_sizes().to_vec())?;
        Ok(d)
    }

    /// A controller for `robots` robots driven by `genome`'s substrate.
    #[pyo3(signature = (genome, robots=1))]
    fn controller(
        &self,
        genome: &Genome,
        #[pyo3(from_py_with = args::robots)] robots: usize,
    ) -> PyResult<Controller> {
        let c = self.controller_of(genome)?;
        Ok(Controller {
            state: c.batch_state(robots),
            inputs: vec![0.0; robots * c.num_inputs()],
            outputs: vec![0.0; robots * c.num_neurons()],
            wheels: self.setup().wheels(),
            robots,
            controller: c,
        })
    }

    /// Writes `genome` as a `champion.json` (the CLI's format, with this
    /// task's config) that `vivae replay FILE` and `vivae.replay` run; a
    /// shipped scenario is copied beside it (`<stem>-<name>.svg`).
    #[pyo3(signature = (genome, path, fitness, generation=1))]
    fn save_champion(
        &self,
        genome: &Genome,
        path: PathBuf,
        fitness: f64,
        #[pyo3(from_py_with = args::generation)] generation: u32,
    ) -> PyResult<()> {
        self.robot_controller_of(genome)?;
        let mut config = rundir::Champion::recorded_config(&self.config);
        // The file may go anywhere: a scenario file it names is named absolutely.
        let absolute = |name: &mut String| {
            if let Ok(p) = std::fs::canonicalize(name.as_str())
                && p.is_file()
            {
                *name = p.to_string_lossy().into_owned();
            }
        };
        let scenario = &mut config.experiment.scenario;
        if let Some(shipped) = vivae_lab::tasks::scenarios::find(scenario)
            .filter(|_| !Path::new(scenario.as_str()).exists())
        {
            // A shipped scenario's name would be read as a file beside the
            // champion: its copy goes there instead.
            let stem = path
                .file_stem()
                .map_or_else(|| "champion".into(), |s| s.to_string_lossy());
            let name = format!("{stem}-{}.svg", shipped.name);
            let copy = path.parent().unwrap_or(Path::new("")).join(&name);
            vivae_lab::io::write_atomic(&copy, shipped.svg.as_bytes()).map_err(errors::lab)?;
            *scenario = name;
        } else if !scenario.is_empty() {
            absolute(scenario);
        }
        config.experiment.scenarios.iter_mut().for_each(absolute);
        let champion = rundir::Champion {
            format: "vivae-champion".into(),
            generation,
            fitness,
            config: Some(config),
            genome: genome.inner.clone(),
        };
        let text = serde_json::to_string_pretty(&champion).map_err(errors::value)? + "\n";
        vivae_lab::io::write_atomic(&path, text.as_bytes()).map_err(errors::lab)
    }

    /// `genome`'s episode with every measure: fitness, time on road and the
    /// behaviour measures (collisions, turns, loops, side of the road).
    fn episode<'py>(&self, py: Python<'py>, genome: &Genome) -> PyResult<Bound<'py, PyDict>> {
        let c = self.robot_controller_of(genome)?;
        let exp = self.setup();
        let episode = py.detach(|| exp.run(&c, true));
        episode_dict(py, &episode)
    }
}

/// An episode's measures as a dict (fitness, time on road, speed, behaviour).
pub(super) fn episode_dict<'py>(
    py: Python<'py>,
    e: &vivae_lab::tasks::driving::episode::EpisodeRecord,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("fitness", e.fitness)?;
    d.set_item("on_road", e.on_road)?;
    d.set_item("speed", e.speed)?;
    if let Some(b) = &e.behaviour {
        d.set_item("collisions", b.collisions)?;
        d.set_item("left_turns", b.left_turns)?;
        d.set_item("right_turns", b.right_turns)?;
        d.set_item("loops", b.loops)?;
        d.set_item("side", b.side)?;
        for (key, rate) in b.contacts.named() {
            d.set_item(key, rate)?;
        }
    }
    Ok(d)
}
