//! A population's controllers activated together: one call per environment
//! step for every genome's network, without the GIL.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use vivae_neat::{FeedForwardNetwork, Network, RecurrentNetwork};

use crate::evo::Genome;

/// The networks of many genomes (one per row of the observations), each
/// fed its row and a bias input of 1: `act` steps them all at once, with
/// the same bits as each genome's `network().activate`.
#[pyclass(module = "vivae._vivae")]
pub struct Controllers {
    nets: Vec<Box<dyn Network + Send + Sync>>,
    inputs: usize,
    outputs: usize,
}

#[pymethods]
impl Controllers {
    /// One network per genome of `genomes` (all of the same shape; a
    /// recurrent genome keeps its state between calls until `reset`).
    #[new]
    fn new(genomes: Vec<PyRef<'_, Genome>>) -> PyResult<Controllers> {
        let Some(first) = genomes.first() else {
            return Err(PyValueError::new_err("genomes: give at least one"));
        };
        let (inputs, outputs) = (first.inner.num_inputs(), first.inner.num_outputs());
        if inputs < 1 {
            return Err(PyValueError::new_err(
                "genomes: a network needs its bias input",
            ));
        }
        let mut nets: Vec<Box<dyn Network + Send + Sync>> = Vec::with_capacity(genomes.len());
        for (i, g) in genomes.iter().enumerate() {
            let shape = (g.inner.num_inputs(), g.inner.num_outputs());
            if shape != (inputs, outputs) {
                return Err(PyValueError::new_err(format!(
                    "genomes[{i}] has {} inputs and {} outputs, genomes[0] {inputs} and {outputs}",
                    shape.0, shape.1
                )));
            }
            nets.push(if g.recurrent {
                Box::new(RecurrentNetwork::from_genome(&g.inner))
            } else {
                Box::new(FeedForwardNetwork::from_genome(&g.inner))
            });
        }
        Ok(Controllers {
            nets,
            inputs,
            outputs,
        })
    }

    /// Number of networks.
    fn __len__(&self) -> usize {
        self.nets.len()
    }

    /// Observation values per row (the networks' inputs but the bias).
    #[getter]
    fn obs_size(&self) -> usize {
        self.inputs - 1
    }

    /// Outputs per network.
    #[getter]
    fn outputs(&self) -> usize {
        self.outputs
    }

    /// The outputs (rows × outputs, float64) for `obs` (rows × obs_size,
    /// float64, read in place): row `r` is fed to network `rows[r]`, or to
    /// network `r` without `rows` (then one row per network).
    #[pyo3(signature = (obs, rows=None))]
    fn act<'py>(
        &mut self,
        py: Python<'py>,
        obs: PyReadonlyArray2<'py, f64>,
        rows: Option<PyReadonlyArray1<'py, i64>>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (n, d) = (obs.shape()[0], obs.shape()[1]);
        if d != self.inputs - 1 {
            return Err(PyValueError::new_err(format!(
                "obs has {d} values a row, the networks read {} (and a bias)",
                self.inputs - 1
            )));
        }
        let which: Vec<usize> = match &rows {
            None if n == self.nets.len() => (0..n).collect(),
            None => {
                return Err(PyValueError::new_err(format!(
                    "obs has {n} rows for {} networks; say which with rows=",
                    self.nets.len()
                )));
            }
            Some(r) => {
                let r = r.as_array();
                if r.len() != n {
                    return Err(PyValueError::new_err(format!(
                        "rows has {} entries for {n} rows of obs",
                        r.len()
                    )));
                }
                let mut which = Vec::with_capacity(n);
                for &k in r.iter() {
                    match usize::try_from(k).ok().filter(|&k| k < self.nets.len()) {
                        Some(k) => which.push(k),
                        None => {
                            return Err(PyValueError::new_err(format!(
                                "rows: {k} is not a network (0 to {})",
                                self.nets.len() - 1
                            )));
                        }
                    }
                }
                which
            }
        };
        let view = obs.as_array();
        let mut out = Array2::<f64>::zeros((n, self.outputs));
        let (nets, ni) = (&mut self.nets, self.inputs);
        py.detach(|| {
            let mut input = vec![0.0; ni];
            for (r, &k) in which.iter().enumerate() {
                for (dst, src) in input.iter_mut().zip(view.row(r).iter()) {
                    *dst = *src;
                }
                input[ni - 1] = 1.0;
                let row = out.row_mut(r);
                let slice = row
                    .into_slice()
                    .expect("a row of a standard array is contiguous");
                nets[k].activate(&input, slice);
            }
        });
        Ok(out.into_pyarray(py))
    }

    /// Clears the state of the networks `rows` (all without it).
    #[pyo3(signature = (rows=None))]
    fn reset(&mut self, rows: Option<Vec<usize>>) -> PyResult<()> {
        match rows {
            None => self.nets.iter_mut().for_each(|n| n.reset()),
            Some(rows) => {
                for k in rows {
                    let Some(net) = self.nets.get_mut(k) else {
                        return Err(PyValueError::new_err(format!(
                            "rows: {k} is not a network (0 to {})",
                            self.nets.len() - 1
                        )));
                    };
                    net.reset();
                }
            }
        }
        Ok(())
    }
}
