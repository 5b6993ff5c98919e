//! NEAT from Python: populations driven ask/tell, genomes, networks.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_neat::{FeedForwardNetwork, GenomeSpec, NeatParams, RecurrentNetwork};

use crate::errors;

/// A genome: a NEAT network's genes (for HyperNEAT, a CPPN).
#[pyclass(module = "vivae._vivae", frozen)]
#[derive(Clone)]
pub struct Genome {
    pub inner: vivae_neat::Genome,
    /// Whether its network may have cycles (the population's spec allows recurrent links).
    pub recurrent: bool,
}

#[pymethods]
impl Genome {
    /// The genome's network, ready to activate.
    fn network(&self) -> Network {
        let net = if self.recurrent {
            Net::Recurrent(Box::new(RecurrentNetwork::from_genome(&self.inner)))
        } else {
            Net::FeedForward(Box::new(FeedForwardNetwork::from_genome(&self.inner)))
        };
        Network { net }
    }

    /// The genome as JSON, the format of the `genome` field of the CLI's `champion.json`.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.inner).map_err(errors::value)
    }

    /// A genome from [`Genome::to_json`]'s JSON (checked: a malformed one is a `ValueError`).
    #[staticmethod]
    #[pyo3(signature = (text, recurrent=false))]
    fn from_json(text: &str, recurrent: bool) -> PyResult<Genome> {
        let inner: vivae_neat::Genome =
            serde_json::from_str(text).map_err(|e| errors::value(format!("genome JSON: {e}")))?;
        Ok(Genome { inner, recurrent })
    }

    /// Number of input nodes.
    #[getter]
    fn num_inputs(&self) -> usize {
        self.inner.num_inputs()
    }

    /// Number of output nodes.
    #[getter]
    fn num_outputs(&self) -> usize {
        self.inner.num_outputs()
    }

    /// Number of hidden nodes.
    #[getter]
    fn num_hidden(&self) -> usize {
        self.inner.num_hidden()
    }

    /// Number of enabled links.
    #[getter]
    fn num_links(&self) -> usize {
        self.inner.num_enabled_links()
    }

    fn __repr__(&self) -> String {
        format!(
            "Genome(inputs={}, outputs={}, hidden={}, links={})",
            self.inner.num_inputs(),
            self.inner.num_outputs(),
            self.inner.num_hidden(),
            self.inner.num_enabled_links()
        )
    }
}

enum Net {
    FeedForward(Box<FeedForwardNetwork>),
    Recurrent(Box<RecurrentNetwork>),
}

/// A genome's network (feed-forward, or recurrent with state between calls).
#[pyclass(module = "vivae._vivae")]
pub struct Network {
    net: Net,
}

impl Network {
    fn dyn_net(&mut self) -> &mut dyn vivae_neat::Network {
        match &mut self.net {
            Net::FeedForward(n) => n.as_mut(),
            Net::Recurrent(n) => n.as_mut(),
        }
    }
}

#[pymethods]
impl Network {
    /// The outputs for `inputs` (one value per input node, bias included).
    fn activate(&mut self, inputs: Vec<f64>) -> PyResult<Vec<f64>> {
        let net = self.dyn_net();
        if inputs.len() != net.num_inputs() {
            return Err(PyValueError::new_err(format!(
                "got {} inputs, the network has {}",
                inputs.len(),
                net.num_inputs()
            )));
        }
        let mut out = vec![0.0; net.num_outputs()];
        net.activate(&inputs, &mut out);
        Ok(out)
    }

    /// Clears recurrent state (nothing for a feed-forward network).
    fn reset(&mut self) {
        self.dyn_net().reset();
    }

    /// Number of inputs.
    #[getter]
    fn num_inputs(&mut self) -> usize {
        self.dyn_net().num_inputs()
    }

    /// Number of outputs.
    #[getter]
    fn num_outputs(&mut self) -> usize {
        self.dyn_net().num_outputs()
    }
}

/// A NEAT population driven ask/tell.
#[pyclass(module = "vivae._vivae")]
pub struct Population {
    pub inner: vivae_neat::Population,
    /// Whether its genomes may have cycles.
    pub recurrent: bool,
}

impl Population {
    /// `inner` for Python.
    pub fn of(inner: vivae_neat::Population) -> Population {
        let recurrent = inner.spec().allow_recurrent;
        Population { inner, recurrent }
    }
}

/// `base` with the keys of the Python dict `params` replaced (checked by serde: an unknown key is an error).
pub fn merge_params(base: NeatParams, params: Option<&Bound<'_, PyDict>>) -> PyResult<NeatParams> {
    merged(base, params, "params")
}

/// `base` with the keys of the Python dict `given` replaced, checked by
/// serde (an unknown key is a `ValueError` naming `what`).
pub fn merged<T: serde::Serialize + serde::de::DeserializeOwned>(
    base: T,
    given: Option<&Bound<'_, PyDict>>,
    what: &str,
) -> PyResult<T> {
    let Some(given) = given else {
        return Ok(base);
    };
    let json = given.py().import("json")?;
    let text: String = json.call_method1("dumps", (given,))?.extract()?;
    let given: serde_json::Value = serde_json::from_str(&text).map_err(errors::value)?;
    let mut value = serde_json::to_value(&base).map_err(errors::value)?;
    if let (Some(v), Some(g)) = (value.as_object_mut(), given.as_object()) {
        for (k, x) in g {
            v.insert(k.clone(), x.clone());
        }
    }
    serde_json::from_value(value).map_err(|e| errors::value(format!("{what}: {e}")))
}

ask_tell!(Population, "Population", "population", &["spec"], {
    /// A generation-0 population of minimal genomes with `inputs` (include
    /// a constant bias input if you want one) and `outputs`. `preset`:
    /// `"plain"` (Stanley's settings, sigmoid networks, for direct
    /// encodings like XOR) or `"cppn"` (the paper's Table II). `params`
    /// overrides NEAT parameters by name (`vivae config default`'s `[neat]`).
    #[new]
    #[pyo3(signature = (inputs, outputs, *, seed=1, size=None, preset="plain", recurrent=false, params=None))]
    fn new(
        inputs: usize,
        outputs: usize,
        seed: u64,
        size: Option<usize>,
        preset: &str,
        recurrent: bool,
        params: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Population> {
        let (params, spec) = neat_setup(inputs, outputs, preset, recurrent, params, size)?;
        let inner = vivae_neat::Population::new(params, spec, seed).map_err(errors::value)?;
        Ok(Population::of(inner))
    }

    /// Number of genomes per generation.
    #[getter]
    fn size(&self) -> usize {
        self.inner.genomes().len()
    }
});

/// NEAT parameters and genome shape of a `preset` (`"plain"` or `"cppn"`)
/// with `inputs` and `outputs`, `params` overriding by name and `size` the
/// population size: what every ask/tell class starts from.
pub fn neat_setup(
    inputs: usize,
    outputs: usize,
    preset: &str,
    recurrent: bool,
    params: Option<&Bound<'_, PyDict>>,
    size: Option<usize>,
) -> PyResult<(NeatParams, GenomeSpec)> {
    let (base, spec) = match preset {
        "plain" => (NeatParams::plain_neat(), GenomeSpec::plain(inputs, outputs)),
        "cppn" => (
            NeatParams::paper_cppn(),
            GenomeSpec {
                inputs,
                outputs,
                ..GenomeSpec::cppn()
            },
        ),
        other => {
            return Err(PyValueError::new_err(format!(
                "preset {other:?}: expected \"plain\" or \"cppn\""
            )));
        }
    };
    let mut params = merge_params(base, params)?;
    if let Some(n) = size {
        params.population_size = n;
    }
    let spec = GenomeSpec {
        allow_recurrent: recurrent,
        ..spec
    };
    Ok((params, spec))
}
