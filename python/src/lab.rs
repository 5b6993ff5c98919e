//! The driving experiment from Python: evaluating and decoding genomes,
//! whole runs written as `vivae evolve` writes them, replays.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use vivae_lab::config::Config;
use vivae_lab::controller::es::RobotController;
use vivae_lab::controller::substrate::WheelNeurons;
use vivae_lab::run::{Outcome, Run};
use vivae_lab::rundir::{self, GenerationRecord};
use vivae_lab::tasks::driving::{episode::Episode, training::Training};
use vivae_neat::hyperneat::{BatchState, SubstrateController};
use vivae_neat::{EvalContext, Network as _};

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
        let config = Config::from_toml(text).map_err(|e| errors::value(format!("config: {e}")))?;
        DriveTask::from_config(py, config)
    }

    /// Pickles by its resolved config (its scenario paths as resolved here).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        let text = slf.get().config.to_toml();
        Ok((slf.get_type().getattr("from_config_toml")?, (text,)))
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
        if let Some(shipped) =
            vivae_lab::tasks::scenarios::find(scenario).filter(|_| !Path::new(scenario.as_str()).exists())
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

fn episode_dict<'py>(
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

/// A decoded substrate driving robots from their readings (the evolved
/// controller, outside the simulator's own rollout).
#[pyclass(module = "vivae._vivae")]
pub struct Controller {
    controller: SubstrateController,
    state: BatchState,
    inputs: Vec<f64>,
    outputs: Vec<f64>,
    wheels: WheelNeurons,
    robots: usize,
}

#[pymethods]
impl Controller {
    /// One update from `obs` (robots × readings, any real dtype: the
    /// environments' float32 included; each reading clamped to [0, 1], NaN
    /// read as 0): the wheel commands (robots × 2).
    fn act<'py>(
        &mut self,
        py: Python<'py>,
        obs: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let obs = real_array(py, obs, "obs")?;
        let obs: PyReadonlyArray2<'_, f64> = obs.extract().map_err(|_| {
            PyValueError::new_err(format!(
                "obs has {} dimensions, expected 2 (robots × readings)",
                obs.getattr("ndim")
                    .and_then(|d| d.extract::<usize>())
                    .unwrap_or(0)
            ))
        })?;
        let ni = self.controller.num_inputs();
        if obs.shape() != [self.robots, ni] {
            return Err(PyValueError::new_err(format!(
                "obs has shape {:?}, expected [{}, {ni}]",
                obs.shape(),
                self.robots
            )));
        }
        // Read as every exported controller reads them: clamped to [0, 1], NaN as 0.
        for (dst, src) in self.inputs.iter_mut().zip(obs.as_array().iter()) {
            *dst = vivae_lab::export::reading(*src);
        }
        self.controller
            .activate_batch(&mut self.state, &self.inputs, &mut self.outputs);
        let n = self.controller.num_neurons();
        let w = self.wheels;
        let out = Array2::from_shape_fn((self.robots, 2), |(r, k)| {
            self.outputs[r * n + if k == 0 { w.left } else { w.right }]
        });
        Ok(out.into_pyarray(py))
    }

    /// Back to the start: every neuron state zero.
    fn reset(&mut self) {
        self.state.reset();
    }
}

/// `value` as a float64 numpy array: ints and floats of any width; strings,
/// objects, complex numbers and bools are a `TypeError` naming `what`.
fn real_array<'py>(
    py: Python<'py>,
    value: &Bound<'py, PyAny>,
    what: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let np = py.import("numpy")?;
    let given = np.call_method1("asarray", (value,))?;
    let kind: String = given.getattr("dtype")?.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "i" | "u" | "f") {
        let dtype = given.getattr("dtype")?.str()?;
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "{what}: expected real numbers (float or int), got dtype {dtype}"
        )));
    }
    given.call_method1("astype", ("float64",))
}

/// Evolves as `vivae evolve` does and writes the same run directory (all
/// but `figures/`, `report.html` and the wall times of `timing.csv`).
#[pyfunction]
#[pyo3(signature = (out=None, config=None, force=false, on_generation=None, **overrides))]
pub fn evolve<'py>(
    py: Python<'py>,
    out: Option<PathBuf>,
    config: Option<PathBuf>,
    force: bool,
    on_generation: Option<Py<PyAny>>,
    overrides: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let resolved = settings::resolved(config.as_deref(), overrides)?;
    let config = resolved.config.clone();
    let dir = out.clone().unwrap_or_else(vivae_lab::io::default_run_dir);
    if let Some(driver) = vivae_lab::tasks::entry_of(&config)
        .ok()
        .and_then(|e| e.own_driver)
    {
        return own_driver_run(py, &dir, |session| {
            (driver.evolve)(&dir, config, force, session)
        });
    }
    // Without a config file a task starts from its own defaults, which it
    // may fit to its scenario (e.g. a grid archive fitted to its arena).
    let prepared = resolved.prepare().map_err(errors::lab)?;
    for m in &prepared.maps {
        errors::warn_scenario(py, &m.loaded.scenario)?;
    }
    let run = py
        .detach(|| prepared.create(&dir, force))
        .map_err(errors::lab)?;
    drive(py, run, on_generation)
}

/// Runs a task on its own driver (the predator–prey task's two
/// populations): the dict holds `out`, `finished` and the summary line's
/// `key=value` fields (numbers as numbers).
fn own_driver_run<'py>(
    py: Python<'py>,
    dir: &Path,
    run: impl FnOnce(&vivae_lab::tasks::Session<'_>) -> vivae_lab::Result<vivae_lab::tasks::Stopped>
    + Send,
) -> PyResult<Bound<'py, PyDict>> {
    let stop = AtomicBool::new(false);
    let quiet = |_: &str| {};
    let line = py
        .detach(|| {
            let stopped = run(&vivae_lab::tasks::Session {
                interrupted: &stop,
                say: &quiet,
                players: None,
            })?;
            // Nothing sets `stop`: a run here stops only at its end.
            let line = stopped.line().unwrap_or_default().to_string();
            // Its figures and report.html, as the CLI draws them when a run stops.
            if let Some(tools) = vivae::tasks::of_run(dir) {
                (tools.report)(dir)?;
            }
            Ok::<_, vivae_lab::Error>(line)
        })
        .map_err(errors::lab)?;
    let d = PyDict::new(py);
    d.set_item("out", dir.to_path_buf())?;
    for (key, value) in line.split_whitespace().filter_map(|w| w.split_once('=')) {
        if key == "out" {
            continue;
        }
        match (value.parse::<u64>(), value.parse::<f64>()) {
            (Ok(n), _) => d.set_item(key, n)?,
            (_, Ok(x)) => d.set_item(key, x)?,
            _ => d.set_item(key, value)?,
        }
    }
    let done = d
        .get_item("generations")?
        .map(|g| g.extract::<u32>())
        .transpose()?;
    let config = vivae_lab::tasks::read_config(&dir.join("config.toml")).map_err(errors::lab)?;
    d.set_item("finished", done == Some(config.experiment.generations))?;
    Ok(d)
}

/// Continues the interrupted run in `out` (or extends a finished one to
/// `generations`) as `vivae resume` does: the same files, byte for byte.
/// `precision` ("exact" or "fast"), when given, must be the run's own.
#[pyfunction]
#[pyo3(signature = (out, generations=None, threads=None, on_generation=None, precision=None))]
pub fn resume<'py>(
    py: Python<'py>,
    out: PathBuf,
    #[pyo3(from_py_with = args::generations)] generations: Option<u32>,
    #[pyo3(from_py_with = args::opt_threads)] threads: Option<usize>,
    on_generation: Option<Py<PyAny>>,
    precision: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let precision = precision
        .map(|p| p.parse::<vivae_neat::Precision>())
        .transpose()
        .map_err(|e| errors::value(format!("precision: {e}")))?;
    if let Some(driver) = vivae_lab::tasks::own_driver_of_run(&out) {
        return own_driver_run(py, &out, |session| {
            (driver.resume)(&out, generations, session)
        });
    }
    let run = py
        .detach(|| Run::resume_in(&out, generations, threads, precision))
        .map_err(errors::lab)?;
    drive(py, run, on_generation)
}

/// Draws the figures (`figures/`) and `report.html` of the finished or
/// interrupted run in `out`, as the program does at a run's end (and
/// `vivae resume` does for a run whose figures are missing or stale);
/// changes no result file. Returns the report's path.
#[pyfunction]
pub fn report(py: Python<'_>, out: PathBuf) -> PyResult<PathBuf> {
    py.detach(|| {
        if let Some(tools) = vivae::tasks::of_run(&out) {
            return (tools.report)(&out);
        }
        // Opened as `vivae resume` opens it (locked; truncated to its newest
        // checkpoint, which a finished run's files already end at).
        let run = Run::resume(&out, None, None)?;
        if run.task().report_curves() {
            // A task without figures of its own: its curves alone.
            return vivae::report_html::write(run.dir());
        }
        if run.episode().is_none() {
            let task = &run.config().experiment.task;
            return Err(vivae_lab::io::bad_input(format!(
                "{}: a {task} run draws no figures; its curves are in generations.csv",
                out.display()
            )));
        }
        vivae::report::finish_run(&run)?;
        Ok(run.dir().join(vivae_lab::rundir::files::REPORT))
    })
    .map_err(errors::lab)
}

/// Runs `run` to its end (or to Ctrl-C, or an exception of `on_generation`,
/// each after a checkpoint) and sums it up as a dict.
fn drive<'py>(
    py: Python<'py>,
    mut run: Run,
    on_generation: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let stop = AtomicBool::new(false);
    let failure: Mutex<Option<PyErr>> = Mutex::new(None);
    let started = std::time::Instant::now();
    let mut reused = 0u64;
    let outcome = py.detach(|| {
        run.run(&stop, |r: &GenerationRecord| {
            reused += r.reused as u64;
            Python::attach(|py| {
                let result = match &on_generation {
                    Some(cb) => record_dict(py, r).and_then(|d| cb.call1(py, (d,)).map(|_| ())),
                    None => Ok(()),
                };
                let result = result.and_then(|()| py.check_signals());
                if let Err(e) = result {
                    *failure.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
                    stop.store(true, Ordering::SeqCst);
                }
            });
        })
    });
    let outcome = outcome.map_err(errors::lab)?;
    let wall = started.elapsed().as_secs_f64();
    if let Some(e) = failure.into_inner().unwrap_or_else(|p| p.into_inner()) {
        if e.is_instance_of::<PyKeyboardInterrupt>(py) {
            return Err(PyKeyboardInterrupt::new_err(format!(
                "interrupted after generation {}; checkpoint written. Resume with: vivae.resume({:?})",
                run.done(),
                run.dir().display().to_string()
            )));
        }
        return Err(e);
    }
    let d = PyDict::new(py);
    d.set_item("out", run.dir().to_path_buf())?;
    d.set_item("generations", run.done())?;
    d.set_item("finished", outcome == Outcome::Finished)?;
    d.set_item("wall_s", wall)?;
    d.set_item("evaluations_reused", reused)?;
    if let Some(m) = run.target_progress() {
        // A task with a goal: as the CLI's `solved=` and `evals_to_solve=`.
        d.set_item("solved", m.solved_at.is_some())?;
        d.set_item("evals_to_solve", m.solved_at)?;
        d.set_item("evaluations", m.evaluations)?;
    }
    if let Some(c) = run.champion() {
        d.set_item("best", c.fitness)?;
        d.set_item("champion_generation", c.generation)?;
        d.set_item("champion", Genome::new(c.genome, false))?;
    }
    Ok(d)
}

fn record_dict<'py>(py: Python<'py>, r: &GenerationRecord) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let row = &r.row;
    d.set_item("generation", row.generation)?;
    d.set_item("total", r.total)?;
    d.set_item("best", row.best)?;
    d.set_item("mean", row.mean)?;
    d.set_item("median", row.median)?;
    d.set_item("worst", row.worst)?;
    d.set_item("species", row.species)?;
    d.set_item("best_ever", r.best_ever)?;
    d.set_item("seconds", r.seconds)?;
    d.set_item("robot_steps_per_second", r.robot_steps_per_second)?;
    d.set_item("reused", r.reused)?;
    Ok(d)
}

/// Replays a champion (a run directory or a `champion.json`) as `vivae
/// replay` does, without the figure: its fitness, time on road and behaviour measures.
#[pyfunction]
#[pyo3(signature = (source, **overrides))]
pub fn replay<'py>(
    py: Python<'py>,
    source: PathBuf,
    overrides: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (champion, mut config, _) = vivae_lab::tasks::load_genome_source(&source).map_err(errors::lab)?;
    let other_scenario = overrides.is_some_and(|o| o.contains("scenario").unwrap_or(false));
    // A multi-map run replays on its first training map unless told otherwise.
    if !other_scenario && vivae_lab::tasks::maps::is_multi_map(&config) {
        let maps = std::mem::take(&mut config.experiment.scenarios);
        config.experiment.scenario = maps[0].clone();
    }
    let extra = PyDict::new(py);
    // Another scenario has its own robot starts: all of them, unless told.
    if other_scenario {
        extra.set_item("robots", 0)?;
    }
    if let Some(o) = overrides {
        extra.update(o.as_mapping())?;
    }
    // Not a config key: which placement of random obstacles and traffic to replay on.
    let placement_seed: u64 = match extra.get_item("placement_seed")? {
        Some(v) => {
            extra.del_item("placement_seed")?;
            args::int("placement_seed", &v)?
        }
        None => 0,
    };
    let config = settings::build_from(config, Some(&extra))?;
    let path = settings::scenario_path(&config);
    if let Some(p) = path.as_deref().filter(|p| !other_scenario && !p.exists()) {
        return Err(errors::lab(vivae_lab::io::bad_input(format!(
            "{}: the champion's scenario {} is not there; name one with scenario=",
            source.display(),
            p.display()
        ))));
    }
    let scenario = vivae_lab::tasks::scenarios::load_scenario(path.as_deref()).map_err(errors::lab)?;
    let experiment = Episode::new(&config, &scenario.scenario)
        .map_err(|e| errors::lab(vivae_lab::Error::from(e)))?
        .with_placement_seed(placement_seed);
    let controller = experiment.robot_controller(&champion.genome).map_err(|e| {
        errors::lab(vivae_lab::Error::Genome {
            path: source.clone(),
            reason: format!("the genome's {e}"),
        })
    })?;
    let episode = py.detach(|| experiment.run(&controller, true));
    episode_dict(py, &episode)
}

/// A champion file's (or run directory's) genome.
#[pyfunction]
pub fn load_genome(source: PathBuf) -> PyResult<(Genome, f64, u32)> {
    let (c, _, _) = vivae_lab::tasks::load_genome_source(&source).map_err(errors::lab)?;
    Ok((Genome::new(c.genome, false), c.fitness, c.generation))
}

/// The shipped scenarios: (name, description).
#[pyfunction]
pub fn scenarios() -> Vec<(String, String)> {
    vivae_lab::tasks::scenarios::all()
        .map(|s| (s.name.to_string(), s.what.to_string()))
        .collect()
}

/// The default config, commented (`vivae config default`).
#[pyfunction]
pub fn default_config() -> String {
    Config::default_commented(&vivae_lab::tasks::sections())
}
