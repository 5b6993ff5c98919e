//! An evolved driving controller stepped from Python: a decoded substrate
//! driving robots from readings the caller gives.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use vivae_lab::controller::substrate::WheelNeurons;
use vivae_neat::Network as _;
use vivae_neat::hyperneat::{BatchState, SubstrateController};

/// A decoded substrate driving robots from their readings (the evolved
/// controller, outside the simulator's own rollout).
#[pyclass(module = "vivae._vivae")]
pub struct Controller {
    pub(super) controller: SubstrateController,
    pub(super) state: BatchState,
    pub(super) inputs: Vec<f64>,
    pub(super) outputs: Vec<f64>,
    pub(super) wheels: WheelNeurons,
    pub(super) robots: usize,
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
