//! The predator–prey task from Python: its episode stepped for the
//! PettingZoo environment (`PredatorPreyCore`), and meetings of genomes
//! played by the task's rules for two ask/tell populations
//! (`PredatorPreyTask`). vivae-lab owns the rules (the arena, the inputs,
//! the catch, the fitness); this module only binds them.

mod tournament;

use std::path::PathBuf;

use numpy::ndarray::Array1;
use numpy::{IntoPyArray, PyArray1, PyArray3};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use vivae_lab::config::Config;
use vivae_lab::tasks::predator_prey::coevo::Coevolution;
use vivae_lab::tasks::predator_prey::meeting::Meeting;
use vivae_lab::tasks::predator_prey::{Arena, INPUTS, NAME, OUTPUTS, Outcome, Side};

use crate::errors;
use crate::evo::{Genome, Population, merge_params};
use crate::settings;

/// `config` + `overrides` for the predator–prey task (`task` may be given,
/// but only as `"predator-prey"`) and its arena.
fn arena_of(
    py: Python<'_>,
    config: Option<PathBuf>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<(Config, Arena)> {
    let given = PyDict::new(py);
    if let Some(o) = overrides {
        given.update(o.as_mapping())?;
    }
    match given.get_item("task")? {
        Some(t) if !t.is_none() => {
            let t: String = t.extract()?;
            if t != NAME {
                return Err(PyValueError::new_err(format!(
                    "task={t:?}: this is the predator-prey task; leave task out or give \"{NAME}\""
                )));
            }
        }
        _ => given.set_item("task", NAME)?,
    }
    let config = settings::build(config.as_deref(), Some(&given))?;
    if config.experiment.task.0 != NAME {
        return Err(PyValueError::new_err(format!(
            "config: experiment.task = {:?}; this is the predator-prey task",
            config.experiment.task.0
        )));
    }
    let arena = config_arena(py, &config)?;
    Ok((config, arena))
}

/// The arena of a resolved predator–prey `config`: its scenario loaded (a
/// warning for each of the scenario's), its physics, steps and controllers.
fn config_arena(py: Python<'_>, config: &Config) -> PyResult<Arena> {
    let path = settings::scenario_path(config);
    let loaded =
        vivae_lab::tasks::scenarios::load_scenario(path.as_deref()).map_err(errors::lab)?;
    errors::warn_scenario(py, &loaded.scenario)?;
    Arena::of_config(&loaded.scenario, config).map_err(errors::value)
}

/// `side` by its name.
fn side_of(name: &str) -> PyResult<Side> {
    match name {
        "hunter" => Ok(Side::Hunter),
        "prey" => Ok(Side::Prey),
        other => Err(PyValueError::new_err(format!(
            "side={other:?}: expected \"hunter\" or \"prey\""
        ))),
    }
}

/// An action (turn, forward) for the task: NaN refused, the rest clamped to [0, 1].
fn action(what: &str, a: (f64, f64)) -> PyResult<[f64; 2]> {
    if a.0.is_nan() || a.1.is_nan() {
        return Err(PyValueError::new_err(format!(
            "{what}'s action ({}, {}): NaN is not a command (turn and forward are in [0, 1])",
            a.0, a.1
        )));
    }
    Ok([a.0.clamp(0.0, 1.0), a.1.clamp(0.0, 1.0)])
}

/// An outcome as a dict: `hunter_fitness`, `prey_fitness`, `caught`, `steps`, `mean_distance`.
fn outcome_dict<'py>(py: Python<'py>, o: &Outcome) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("hunter_fitness", o.hunter_fitness())?;
    d.set_item("prey_fitness", o.prey_fitness())?;
    d.set_item("caught", o.caught)?;
    d.set_item("steps", o.steps)?;
    d.set_item("mean_distance", o.mean_distance)?;
    Ok(d)
}

/// One predator–prey episode stepped a call at a time (the engine behind
/// `vivae.PredatorPreyParallelEnv`), with per-step rewards whose sums are
/// the task's fitnesses.
/// Adds the task's classes and `tournament` to the module `m`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PredatorPreyCore>()?;
    m.add_class::<PredatorPreyTask>()?;
    m.add_function(wrap_pyfunction!(tournament::tournament, m)?)
}

#[pyclass(module = "vivae._vivae")]
pub struct PredatorPreyCore {
    arena: Arena,
    meeting: Meeting,
    /// Rewards given so far this episode: hunter, prey.
    given: [f64; 2],
}

impl PredatorPreyCore {
    fn observe<'py>(&self, py: Python<'py>, side: Side) -> Bound<'py, PyArray1<f64>> {
        let mut i = [0.0; INPUTS];
        self.arena.inputs(self.meeting.world(), side, &mut i);
        Array1::from(i.to_vec()).into_pyarray(py)
    }
}

#[pymethods]
impl PredatorPreyCore {
    /// The task's episode in the arena `config` + `overrides` describe
    /// (`scenario`, `steps`, … as `vivae evolve --task predator-prey`).
    #[new]
    #[pyo3(signature = (config=None, **overrides))]
    fn new(
        py: Python<'_>,
        config: Option<PathBuf>,
        overrides: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PredatorPreyCore> {
        let (_, arena) = arena_of(py, config, overrides)?;
        let meeting = arena.start();
        Ok(PredatorPreyCore {
            arena,
            meeting,
            given: [0.0; 2],
        })
    }

    /// Readings per robot (the networks' inputs: 4 radar slices, 6 rangefinders, a bias).
    #[getter]
    fn obs_size(&self) -> usize {
        INPUTS
    }

    /// Steps per episode (`experiment.steps`).
    #[getter]
    fn max_steps(&self) -> u32 {
        self.arena.steps()
    }

    /// Steps played since the reset.
    #[getter]
    fn elapsed(&self) -> u32 {
        self.meeting.steps()
    }

    /// Back to the scenario's start: (hunter's observation, prey's observation).
    #[allow(clippy::type_complexity)]
    fn reset<'py>(
        &mut self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>) {
        self.meeting = self.arena.start();
        self.given = [0.0; 2];
        (self.observe(py, Side::Hunter), self.observe(py, Side::Prey))
    }

    /// One step: each side's (turn, forward) in [0, 1] (clamped; NaN is a
    /// `ValueError`). Returns (hunter obs, prey obs, hunter reward, prey
    /// reward, caught, over). A non-final step rewards the hunter
    /// (1 − d)/T and the prey (1 + d)/T (d: the distance after the step as
    /// a share of the arena's diagonal); the final one gives each side its
    /// fitness minus its rewards so far, so that an episode's rewards add up
    /// to the task's fitnesses.
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        hunter: (f64, f64),
        prey: (f64, f64),
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
        f64,
        f64,
        bool,
        bool,
    )> {
        if self.arena.over(&self.meeting) {
            return Err(PyRuntimeError::new_err(
                "step: the episode is over; reset() first",
            ));
        }
        let (h, p) = (action("hunter", hunter)?, action("prey", prey)?);
        self.arena.advance(&mut self.meeting, h, p);
        let over = self.arena.over(&self.meeting);
        let rewards = if over {
            let o = self.arena.outcome(&self.meeting);
            [
                o.hunter_fitness() - self.given[0],
                o.prey_fitness() - self.given[1],
            ]
        } else {
            let d = self.arena.distance(&self.meeting);
            let t = f64::from(self.arena.steps());
            [(1.0 - d) / t, (1.0 + d) / t]
        };
        self.given[0] += rewards[0];
        self.given[1] += rewards[1];
        Ok((
            self.observe(py, Side::Hunter),
            self.observe(py, Side::Prey),
            rewards[0],
            rewards[1],
            self.meeting.caught(),
            over,
        ))
    }

    /// The hunter–prey distance now, as a share of the arena's diagonal.
    fn distance(&self) -> f64 {
        self.arena.distance(&self.meeting)
    }

    /// The episode's outcome so far as a dict: `hunter_fitness`,
    /// `prey_fitness`, `caught`, `steps`, `mean_distance` (the task's
    /// fitnesses once the episode is over).
    fn outcome<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        outcome_dict(py, &self.arena.outcome(&self.meeting))
    }

    /// The world as an RGB image (height × width × 3, uint8), `scale` pixels per px.
    #[pyo3(signature = (scale=1.0))]
    fn render<'py>(&self, py: Python<'py>, scale: f64) -> PyResult<Bound<'py, PyArray3<u8>>> {
        let opts = vivae_sim::DrawOptions {
            trajectories: false,
            surface_sensors: None,
            distance_sensors: None,
            scale,
            legend: false,
            title: None,
        };
        crate::render::render_rgb(py, self.meeting.world(), &opts)
    }
}

/// The predator–prey task for two ask/tell populations: their starting
/// populations, and meetings of a hunter and a prey genome played by the
/// task's rules (as `vivae evolve --task predator-prey` plays them).
#[pyclass(module = "vivae._vivae", frozen)]
pub struct PredatorPreyTask {
    config: Config,
    arena: Arena,
    pool: crate::pool::ForkSafePool,
}

impl PredatorPreyTask {
    fn from_config(
        py: Python<'_>,
        config: Option<PathBuf>,
        overrides: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PredatorPreyTask> {
        let (config, arena) = arena_of(py, config, overrides)?;
        let pool = crate::pool::ForkSafePool::new(config.run.threads)?;
        Ok(PredatorPreyTask {
            config,
            arena,
            pool,
        })
    }
}

/// `genomes` checked to be the task's networks (11 inputs, 2 outputs).
fn check_genomes(what: &str, genomes: &[PyRef<'_, Genome>]) -> PyResult<()> {
    for (k, g) in genomes.iter().enumerate() {
        let (i, o) = (g.inner.num_inputs(), g.inner.num_outputs());
        if (i, o) != (INPUTS, OUTPUTS) {
            return Err(PyValueError::new_err(format!(
                "{what}[{k}]: a genome with {i} inputs and {o} outputs; the predator-prey task's networks have {INPUTS} and {OUTPUTS}"
            )));
        }
    }
    Ok(())
}

#[pymethods]
impl PredatorPreyTask {
    /// The task in the arena `config` (a TOML file) + `overrides` describe
    /// (`scenario`, `steps`, `population`, `seed`, `threads`, … as
    /// `vivae evolve --task predator-prey`).
    #[new]
    #[pyo3(signature = (config=None, **overrides))]
    fn new(
        py: Python<'_>,
        config: Option<PathBuf>,
        overrides: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PredatorPreyTask> {
        PredatorPreyTask::from_config(py, config, overrides)
    }

    /// A task from its resolved config's TOML ([`PredatorPreyTask::config_toml`]).
    #[staticmethod]
    fn from_config_toml(py: Python<'_>, text: &str) -> PyResult<PredatorPreyTask> {
        let config = crate::tasks::config_of_toml(text)?;
        let arena = config_arena(py, &config)?;
        let pool = crate::pool::ForkSafePool::new(config.run.threads)?;
        Ok(PredatorPreyTask {
            config,
            arena,
            pool,
        })
    }

    /// Pickles by its resolved config.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        crate::tasks::reduce_to_config(slf, &slf.get().config)
    }

    /// The resolved config as TOML.
    fn config_toml(&self) -> String {
        self.config.to_toml()
    }

    /// (inputs, outputs) of both sides' networks: (11, 2).
    #[getter]
    fn shape(&self) -> (usize, usize) {
        (INPUTS, OUTPUTS)
    }

    /// Steps per episode.
    #[getter]
    fn steps(&self) -> u32 {
        self.arena.steps()
    }

    /// The generation-0 population of `side` (`"hunter"` or `"prey"`) that
    /// `vivae evolve --task predator-prey` starts from: the config's NEAT
    /// settings (`params` overrides them by name, `size` the population
    /// size), the hunters seeded with `seed` (default the config's), the
    /// prey with a seed derived from it.
    #[pyo3(signature = (side, seed=None, size=None, params=None))]
    fn population(
        &self,
        side: &str,
        #[pyo3(from_py_with = crate::args::opt_seed)] seed: Option<u64>,
        #[pyo3(from_py_with = crate::args::size)] size: Option<usize>,
        params: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Population> {
        let side = side_of(side)?;
        let mut config = self.config.clone();
        config.neat = merge_params(config.neat, params)?;
        if let Some(n) = size {
            config.neat.population_size = n;
        }
        config.neat.validate().map_err(errors::value)?;
        if let Some(s) = seed {
            config.experiment.seed = s;
        }
        let co = Coevolution::new(&config).map_err(errors::value)?;
        Ok(Population::of(match side {
            Side::Hunter => co.hunters,
            Side::Prey => co.prey,
        }))
    }

    /// One episode of `hunter`'s network against `prey`'s, by the task's
    /// rules (both activated as recurrent networks, as in a run): a dict of
    /// `hunter_fitness`, `prey_fitness`, `caught`, `steps`, `mean_distance`.
    fn meet<'py>(
        &self,
        py: Python<'py>,
        hunter: PyRef<'py, Genome>,
        prey: PyRef<'py, Genome>,
    ) -> PyResult<Bound<'py, PyDict>> {
        check_genomes("hunter", std::slice::from_ref(&hunter))?;
        check_genomes("prey", std::slice::from_ref(&prey))?;
        let (h, p) = (&hunter.inner, &prey.inner);
        let arena = &self.arena;
        let out = py.detach(|| arena.play_genomes(h, p));
        outcome_dict(py, &out)
    }

    /// The fitness of each of `genomes`, playing `side` (`"hunter"` or
    /// `"prey"`), against `opponents` of the other side: its mean fitness
    /// over one episode with each, as a run scores a generation (in Rust
    /// threads, the GIL released). What `tell` takes.
    fn evaluate(
        &self,
        py: Python<'_>,
        side: &str,
        genomes: Vec<PyRef<'_, Genome>>,
        opponents: Vec<PyRef<'_, Genome>>,
    ) -> PyResult<Vec<f64>> {
        let side = side_of(side)?;
        check_genomes("genomes", &genomes)?;
        check_genomes("opponents", &opponents)?;
        if opponents.is_empty() {
            return Err(PyValueError::new_err(
                "opponents: give at least one genome of the other side",
            ));
        }
        let genomes: Vec<&vivae_neat::Genome> = genomes.iter().map(|g| &g.inner).collect();
        let opponents: Vec<&vivae_neat::Genome> = opponents.iter().map(|g| &g.inner).collect();
        let arena = &self.arena;
        let pool = self.pool.get()?;
        let score = |genome: &vivae_neat::Genome| {
            let mut sum = 0.0;
            for o in &opponents {
                let out = match side {
                    Side::Hunter => arena.play_genomes(genome, o),
                    Side::Prey => arena.play_genomes(o, genome),
                };
                sum += out.fitness(side);
            }
            sum / opponents.len() as f64
        };
        // In chunks of a few genomes per thread, so that Ctrl-C is noticed
        // between them rather than only at the end.
        let chunk = 4 * pool.current_num_threads().max(1);
        let mut fitnesses = Vec::with_capacity(genomes.len());
        for part in genomes.chunks(chunk) {
            let done: Vec<f64> =
                py.detach(|| pool.install(|| part.par_iter().map(|g| score(g)).collect()));
            fitnesses.extend(done);
            py.check_signals()?;
        }
        Ok(fitnesses)
    }
}
