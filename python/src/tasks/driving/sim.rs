//! The simulator stepped for the Python environments: N worlds of one
//! scenario, robots driven by wheel commands from numpy arrays, their
//! sensors written to numpy arrays, the worlds stepped in Rust threads.

use numpy::{PyArray3, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use vivae_lab::controller::sensors::read_sheets;
use vivae_lab::tasks::driving::episode::Episode;
use vivae_sim::World;

use crate::settings;
use crate::{args, errors};

/// Most worlds one `DriveCore` steps.
pub use crate::args::MAX_WORLDS;

/// One world and its robots' buffers.
#[derive(Clone)]
struct Slot {
    world: World,
    controls: Vec<[f64; 2]>,
    readings: Vec<f64>,
    /// Odometers after the last step (a step's reward is their increase).
    odometers: Vec<f64>,
    /// Steps since the last reset.
    steps: u32,
    /// Whether the episode ended in the last step (autoreset: the next step resets).
    done: bool,
}

/// The shapes every call checks its arrays against.
#[derive(Clone, Copy)]
struct Shape {
    robots: usize,
    obs: usize,
    limit: u32,
}

impl Slot {
    fn reset(&mut self, start: &World) {
        self.world.clone_from(start);
        self.odometers.fill(0.0);
        self.steps = 0;
        self.done = false;
    }

    fn observe(&mut self, exp: &Episode, obs: &mut [f32]) {
        let n = self.readings.len();
        for (i, out) in obs
            .chunks_exact_mut(n)
            .enumerate()
            .take(self.odometers.len())
        {
            read_sheets(exp.sensors(), &self.world, i, &mut self.readings);
            for (o, r) in out.iter_mut().zip(&self.readings) {
                *o = *r as f32;
            }
        }
    }

    /// One step of this world: wheels from `actions`, rewards = distance driven.
    fn step(
        &mut self,
        ctx: &Ctx<'_>,
        actions: &[f32],
        obs: &mut [f32],
        rewards: &mut [f64],
    ) -> bool {
        if ctx.autoreset && self.done {
            self.reset(ctx.experiment.world());
            rewards.fill(0.0);
            self.observe(ctx.experiment, obs);
            return false;
        }
        for (c, a) in self.controls.iter_mut().zip(actions.chunks_exact(2)) {
            *c = [f64::from(a[0]), f64::from(a[1])];
        }
        self.world.step(&self.controls);
        for ((r, odo), robot) in rewards
            .iter_mut()
            .zip(&mut self.odometers)
            .zip(self.world.robots())
        {
            *r = robot.odometer - *odo;
            *odo = robot.odometer;
        }
        self.steps += 1;
        self.done = self.steps >= ctx.shape.limit;
        self.observe(ctx.experiment, obs);
        self.done
    }
}

/// What every world's step reads.
struct Ctx<'a> {
    experiment: &'a Episode,
    shape: Shape,
    autoreset: bool,
}

/// The arrays of one call, every world's part one after another.
struct Buffers<'a> {
    actions: &'a [f32],
    obs: &'a mut [f32],
    rewards: &'a mut [f64],
    truncated: &'a mut [bool],
}

/// A numpy array's data, checked for [`DriveCore::step`].
struct Raw<T> {
    ptr: *mut T,
    len: usize,
}

impl<T: numpy::Element> Raw<T> {
    /// `a`'s data if `a` has `shape`, is C-contiguous and aligned and, when `write`, writeable.
    fn of<D: numpy::ndarray::Dimension>(
        a: &Bound<'_, numpy::PyArray<T, D>>,
        what: &str,
        shape: &[usize],
        write: bool,
    ) -> PyResult<Raw<T>> {
        if a.shape() != shape {
            return Err(PyValueError::new_err(format!(
                "{what} has shape {:?}, expected {shape:?}",
                a.shape()
            )));
        }
        // SAFETY: `a` is a live numpy array: its object fields may be read.
        let flags =
            unsafe { (*numpy::npyffi::objects::_PyArray_GET_ITEM_DATA(a.as_array_ptr())).flags };
        let aligned = flags & numpy::npyffi::NPY_ARRAY_ALIGNED != 0;
        let writeable = flags & numpy::npyffi::NPY_ARRAY_WRITEABLE != 0;
        if !a.is_c_contiguous() || !aligned || (write && !writeable) {
            return Err(PyValueError::new_err(format!(
                "{what} must be a C-contiguous, aligned{} array",
                if write { ", writeable" } else { "" }
            )));
        }
        Ok(Raw {
            ptr: a.data(),
            len: a.len(),
        })
    }

    /// The byte range the data spans.
    fn bytes(&self) -> (usize, usize) {
        let start = self.ptr as usize;
        (start, start + self.len * std::mem::size_of::<T>())
    }
}

/// `v` as a numpy array of `T` with `D`'s dimensions (`dtype` names `T`):
/// a `TypeError` naming `what`, the array expected and the value given otherwise.
fn typed<'py, T: numpy::Element, D: numpy::ndarray::Dimension>(
    v: &Bound<'py, PyAny>,
    what: &str,
    dtype: &str,
) -> PyResult<Bound<'py, numpy::PyArray<T, D>>> {
    if let Ok(a) = v.cast::<numpy::PyArray<T, D>>() {
        return Ok(a.clone());
    }
    let dims = D::NDIM.map_or_else(|| "any number of".to_string(), |n| n.to_string());
    let given = match (v.getattr("dtype"), v.getattr("ndim")) {
        (Ok(dtype), Ok(ndim)) => {
            format!("an array of dtype {} with {ndim} dimensions", dtype.str()?)
        }
        _ => vivae_lab::error::a(&v.get_type().name()?.to_string()),
    };
    Err(pyo3::exceptions::PyTypeError::new_err(format!(
        "{what}: expected a numpy array of dtype {dtype} with {dims} dimensions, got {given}"
    )))
}

/// An error when two of the byte `ranges` overlap.
fn disjoint(ranges: &[(usize, usize)]) -> PyResult<()> {
    for (i, a) in ranges.iter().enumerate() {
        for b in &ranges[i + 1..] {
            if a.0 < b.1 && b.0 < a.1 {
                return Err(PyValueError::new_err(
                    "actions, obs, rewards and truncated must not share memory",
                ));
            }
        }
    }
    Ok(())
}

/// Steps every world once, on `pool`: one contiguous run of worlds per
/// thread (a world's step is too little work to share out finer).
fn step_all(pool: &rayon::ThreadPool, ctx: &Ctx<'_>, slots: &mut [Slot], b: Buffers<'_>) {
    let s = ctx.shape;
    let (ra, ro) = (s.robots * 2, s.robots * s.obs);
    let threads = pool.current_num_threads();
    if threads <= 1 || slots.len() == 1 {
        let worlds = slots.iter_mut().zip(b.actions.chunks_exact(ra));
        let outputs = b
            .obs
            .chunks_exact_mut(ro)
            .zip(b.rewards.chunks_exact_mut(s.robots));
        for (((slot, a), (o, r)), t) in worlds.zip(outputs).zip(b.truncated.iter_mut()) {
            *t = slot.step(ctx, a, o, r);
        }
        return;
    }
    let per = slots.len().div_ceil(threads);
    pool.install(|| {
        let worlds = slots.par_iter_mut().zip(b.actions.par_chunks_exact(ra));
        let outputs = b
            .obs
            .par_chunks_exact_mut(ro)
            .zip(b.rewards.par_chunks_exact_mut(s.robots));
        worlds
            .zip(outputs)
            .zip(b.truncated.par_iter_mut())
            .with_min_len(per)
            .for_each(|(((slot, a), (o, r)), t)| *t = slot.step(ctx, a, o, r));
    });
}

/// N copies of one driving world, stepped together (the engine behind
/// `vivae.DriveEnv`, `vivae.DriveVectorEnv` and `vivae.DriveParallelEnv`).
#[pyclass(module = "vivae._vivae")]
pub struct DriveCore {
    experiment: Episode,
    slots: Vec<Slot>,
    shape: Shape,
    pool: crate::pool::ForkSafePool,
    sensors: vivae_sim::SurfaceSensors,
    distance: Option<vivae_sim::DistanceSensors>,
}

impl DriveCore {
    fn check(&self, what: &str, got: &[usize], want: &[usize]) -> PyResult<()> {
        if got == want {
            Ok(())
        } else {
            Err(PyValueError::new_err(format!(
                "{what} has shape {got:?}, expected {want:?}"
            )))
        }
    }

    fn n(&self) -> usize {
        self.slots.len()
    }
}

#[pymethods]
impl DriveCore {
    /// `num_worlds` copies of the world `config` + `overrides` describe (as
    /// `vivae evolve` would build it); `threads` steps them (0 = one per core).
    #[new]
    #[pyo3(signature = (num_worlds, config=None, threads=0, **overrides))]
    fn new(
        py: Python<'_>,
        #[pyo3(from_py_with = args::num_worlds)] num_worlds: usize,
        config: Option<std::path::PathBuf>,
        #[pyo3(from_py_with = args::threads)] threads: usize,
        overrides: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<DriveCore> {
        if num_worlds == 0 || num_worlds > MAX_WORLDS {
            return Err(PyValueError::new_err(format!(
                "num_worlds = {num_worlds}: expected 1 to {MAX_WORLDS}"
            )));
        }
        let config = settings::build(config.as_deref(), overrides)?;
        let path = settings::scenario_path(&config);
        let loaded =
            vivae_lab::tasks::scenarios::load_scenario(path.as_deref()).map_err(errors::lab)?;
        errors::warn_scenario(py, &loaded.scenario)?;
        let experiment = Episode::new(&config, &loaded.scenario)
            .map_err(|e| errors::lab(vivae_lab::Error::from(e)))?;
        let robots = experiment.robots();
        let obs: usize = experiment.sensors().iter().map(|s| s.len()).sum();
        let slot = Slot {
            world: experiment.world().clone(),
            controls: vec![[0.0; 2]; robots],
            readings: vec![0.0; obs],
            odometers: vec![0.0; robots],
            steps: 0,
            done: false,
        };
        let pool = crate::pool::ForkSafePool::new(threads.min(num_worlds))?;
        Ok(DriveCore {
            shape: Shape {
                robots,
                obs,
                limit: experiment.steps(),
            },
            slots: vec![slot; num_worlds],
            experiment,
            pool,
            sensors: config.surface_sensors.clone(),
            distance: config.distance_sensors.layout(),
        })
    }

    /// Number of worlds.
    #[getter]
    fn num_worlds(&self) -> usize {
        self.n()
    }

    /// Robots per world.
    #[getter]
    fn robots(&self) -> usize {
        self.shape.robots
    }

    /// Readings per robot: the surface sensors, then the distance rays.
    #[getter]
    fn obs_size(&self) -> usize {
        self.shape.obs
    }

    /// Steps per episode (`experiment.steps`).
    #[getter]
    fn max_steps(&self) -> u32 {
        self.shape.limit
    }

    /// Worker threads stepping the worlds.
    #[getter]
    fn threads(&self) -> PyResult<usize> {
        self.pool.threads()
    }

    /// Puts the worlds where `mask` is true (all when `None`) back at the
    /// start and writes every world's readings to `obs` (num_worlds × robots × obs_size).
    #[pyo3(signature = (obs, mask=None))]
    fn reset(&mut self, obs: &Bound<'_, PyAny>, mask: Option<Vec<bool>>) -> PyResult<()> {
        let obs = typed::<f32, numpy::Ix3>(obs, "obs", "float32")?;
        let mut obs = obs
            .try_readwrite()
            .map_err(|e| PyValueError::new_err(format!("obs: {e}")))?;
        let (n, s) = (self.n(), self.shape);
        self.check("obs", obs.shape(), &[n, s.robots, s.obs])?;
        if let Some(m) = &mask
            && m.len() != n
        {
            return Err(PyValueError::new_err(format!(
                "mask has {} entries, expected {n}",
                m.len()
            )));
        }
        let obs = obs.as_slice_mut().map_err(errors::value)?;
        let (exp, start) = (&self.experiment, self.experiment.world());
        for (k, (slot, o)) in self
            .slots
            .iter_mut()
            .zip(obs.chunks_exact_mut(s.robots * s.obs))
            .enumerate()
        {
            if mask.as_ref().is_none_or(|m| m[k]) {
                slot.reset(start);
            }
            slot.observe(exp, o);
        }
        Ok(())
    }

    /// One step of every world: `actions` (num_worlds × robots × 2, wheel
    /// commands in [-1, 1]; NaN counts as 0) in; readings, rewards (px driven
    /// this step) and whether the step limit was reached out. With
    /// `autoreset`, a world whose episode ended in the previous call is
    /// reset instead (its reward 0). The GIL is released meanwhile.
    #[pyo3(signature = (actions, obs, rewards, truncated, autoreset=true))]
    fn step(
        &mut self,
        py: Python<'_>,
        actions: &Bound<'_, PyAny>,
        obs: &Bound<'_, PyAny>,
        rewards: &Bound<'_, PyAny>,
        truncated: &Bound<'_, PyAny>,
        autoreset: bool,
    ) -> PyResult<()> {
        let actions = typed::<f32, numpy::Ix3>(actions, "actions", "float32")?;
        let obs = typed::<f32, numpy::Ix3>(obs, "obs", "float32")?;
        let rewards = typed::<f64, numpy::Ix2>(rewards, "rewards", "float64")?;
        let truncated = typed::<bool, numpy::Ix1>(truncated, "truncated", "bool")?;
        let (n, s) = (self.n(), self.shape);
        let a = Raw::of(&actions, "actions", &[n, s.robots, 2], false)?;
        let o = Raw::of(&obs, "obs", &[n, s.robots, s.obs], true)?;
        let r = Raw::of(&rewards, "rewards", &[n, s.robots], true)?;
        let t = Raw::of(&truncated, "truncated", &[n], true)?;
        disjoint(&[a.bytes(), o.bytes(), r.bytes(), t.bytes()])?;
        // SAFETY: each array is C-contiguous with exactly these elements (and
        // writeable where written), and no two share a byte, so these are the
        // only references to their data while the call lasts. (Rust's
        // borrows are what numpy's borrow tracking would guard; it is not
        // used because it costs more per call than stepping a small world.)
        let buffers = unsafe {
            Buffers {
                actions: std::slice::from_raw_parts(a.ptr, a.len),
                obs: std::slice::from_raw_parts_mut(o.ptr, o.len),
                rewards: std::slice::from_raw_parts_mut(r.ptr, r.len),
                truncated: std::slice::from_raw_parts_mut(t.ptr, t.len),
            }
        };
        let ctx = Ctx {
            experiment: &self.experiment,
            shape: s,
            autoreset,
        };
        let pool = self.pool.get()?;
        let slots = &mut self.slots;
        py.detach(|| step_all(&pool, &ctx, slots, buffers));
        Ok(())
    }

    /// Steps since world `index` was last reset.
    fn elapsed(&self, #[pyo3(from_py_with = args::index)] index: usize) -> PyResult<u32> {
        self.slots
            .get(index)
            .map(|s| s.steps)
            .ok_or_else(|| PyValueError::new_err(format!("no world {index}")))
    }

    /// Each robot's distance driven since world `index` was reset, px.
    fn odometers(&self, #[pyo3(from_py_with = args::index)] index: usize) -> PyResult<Vec<f64>> {
        self.slots
            .get(index)
            .map(|s| s.odometers.clone())
            .ok_or_else(|| PyValueError::new_err(format!("no world {index}")))
    }

    /// World `index` as an RGB image (height × width × 3, uint8), robots
    /// with their sensors, `scale` pixels per px.
    #[pyo3(signature = (index=0, scale=1.0))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        #[pyo3(from_py_with = args::index)] index: usize,
        scale: f64,
    ) -> PyResult<Bound<'py, PyArray3<u8>>> {
        let slot = self
            .slots
            .get(index)
            .ok_or_else(|| PyValueError::new_err(format!("no world {index}")))?;
        let opts = vivae_sim::DrawOptions {
            trajectories: false,
            surface_sensors: Some(self.sensors.clone()),
            distance_sensors: self.distance.clone(),
            scale,
            legend: false,
            title: None,
        };
        crate::render::render_rgb(py, &slot.world, &opts)
    }

    /// Steps the worlds `steps` times with uniformly random wheel commands
    /// drawn in Rust (seeded): the native baseline the benchmarks compare
    /// the Python vector env with. Returns robot-steps done.
    #[pyo3(signature = (steps, seed=0))]
    fn run_random(
        &mut self,
        py: Python<'_>,
        #[pyo3(from_py_with = args::steps)] steps: u32,
        #[pyo3(from_py_with = args::seed)] seed: u64,
    ) -> PyResult<u64> {
        use rand::{RngExt, SeedableRng};
        let (n, s) = (self.n(), self.shape);
        let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
        let mut actions = vec![0f32; n * s.robots * 2];
        let mut obs = vec![0f32; n * s.robots * s.obs];
        let mut rewards = vec![0f64; n * s.robots];
        let mut truncated = vec![false; n];
        let ctx = Ctx {
            experiment: &self.experiment,
            shape: s,
            autoreset: true,
        };
        let pool = self.pool.get()?;
        let slots = &mut self.slots;
        py.detach(|| {
            for _ in 0..steps {
                for a in &mut actions {
                    *a = rng.random_range(-1.0f32..=1.0);
                }
                let buffers = Buffers {
                    actions: &actions,
                    obs: &mut obs,
                    rewards: &mut rewards,
                    truncated: &mut truncated,
                };
                step_all(&pool, &ctx, slots, buffers);
            }
        });
        Ok(u64::from(steps) * (n * s.robots) as u64)
    }
}
