//! NEAT from Python: populations driven ask/tell, genomes, networks.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_neat::{FeedForwardNetwork, GenomeSpec, NeatParams, RecurrentNetwork};

use crate::{args, errors};

/// A genome: a NEAT network's genes (for HyperNEAT, a CPPN).
#[pyclass(module = "vivae._vivae", frozen)]
#[derive(Clone)]
pub struct Genome {
    pub inner: vivae_neat::Genome,
    /// Whether its network may have cycles (the population's spec allows recurrent links).
    pub recurrent: bool,
}

impl Genome {
    /// `inner` for Python: recurrent when `recurrent` says so or when its
    /// enabled links form a cycle (a cyclic genome activated as a
    /// feed-forward network would silently compute something else).
    pub fn new(inner: vivae_neat::Genome, recurrent: bool) -> Genome {
        let recurrent = recurrent || has_cycle(&inner);
        Genome { inner, recurrent }
    }
}

/// Whether the enabled links of `genome` form a cycle (a self-loop included):
/// Kahn's algorithm leaves a node unordered exactly when it lies on or after one.
pub fn has_cycle(genome: &vivae_neat::Genome) -> bool {
    let ids: std::collections::HashMap<u32, usize> = (genome.nodes().iter().enumerate())
        .map(|(i, n)| (n.id, i))
        .collect();
    let mut indegree = vec![0usize; ids.len()];
    let mut next: Vec<Vec<usize>> = vec![Vec::new(); ids.len()];
    for l in genome.links().iter().filter(|l| l.enabled) {
        let (Some(&a), Some(&b)) = (ids.get(&l.from), ids.get(&l.to)) else {
            continue;
        };
        next[a].push(b);
        indegree[b] += 1;
    }
    let mut ready: Vec<usize> = (0..ids.len()).filter(|&i| indegree[i] == 0).collect();
    let mut ordered = 0;
    while let Some(i) = ready.pop() {
        ordered += 1;
        for &j in &next[i] {
            indegree[j] -= 1;
            if indegree[j] == 0 {
                ready.push(j);
            }
        }
    }
    ordered != ids.len()
}

#[pymethods]
impl Genome {
    /// Pickles by JSON: `Genome.from_json(to_json(), recurrent)`.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String, bool))> {
        let this = slf.get();
        let json = serde_json::to_string(&this.inner).map_err(errors::value)?;
        Ok((slf.get_type().getattr("from_json")?, (json, this.recurrent)))
    }

    /// Whether its network keeps state between activations (it may have cycles).
    #[getter]
    fn recurrent(&self) -> bool {
        self.recurrent
    }

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

    /// A genome from [`Genome::to_json`]'s JSON (checked: a malformed one is a
    /// `ValueError`); a genome whose links form a cycle is recurrent whatever
    /// `recurrent` says.
    #[staticmethod]
    #[pyo3(signature = (text, recurrent=false))]
    fn from_json(text: &str, recurrent: bool) -> PyResult<Genome> {
        let inner: vivae_neat::Genome =
            serde_json::from_str(text).map_err(|e| errors::value(format!("genome JSON: {e}")))?;
        Ok(Genome::new(inner, recurrent))
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
    let given = json_dict(given, what)?;
    let base = serde_json::to_value(&base).map_err(errors::value)?;
    let with = |keys: &mut dyn Iterator<Item = (&String, &serde_json::Value)>| {
        let mut value = base.clone();
        if let Some(v) = value.as_object_mut() {
            for (k, x) in keys {
                v.insert(k.clone(), x.clone());
            }
        }
        serde_json::from_value::<T>(value)
    };
    let g = &given;
    with(&mut g.iter()).map_err(|e| {
        // serde names no field for a value of the wrong type: find the key.
        let bad = g.iter().find_map(|(k, x)| {
            with(&mut std::iter::once((k, x)))
                .err()
                .map(|e| format!("{what}[{k:?}] = {x}: {e}"))
        });
        errors::value(bad.unwrap_or_else(|| format!("{what}: {e}")))
    })
}

/// The Python dict `given` as JSON, key by key, so that a value JSON cannot
/// hold (NaN, an infinity, a set, an object) is an error naming its key
/// (`what[key]`) and what was expected.
fn json_dict(
    given: &Bound<'_, PyDict>,
    what: &str,
) -> PyResult<serde_json::Map<String, serde_json::Value>> {
    let json = given.py().import("json")?;
    let strict = PyDict::new(given.py());
    strict.set_item("allow_nan", false)?;
    let mut out = serde_json::Map::new();
    for (k, x) in given.iter() {
        let Ok(key) = k.extract::<String>() else {
            let ty = k.get_type().name()?;
            return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "{what}: keys are parameter names (str), got a key of type {ty}"
            )));
        };
        let shown = x.repr()?;
        let text: String = match json.call_method("dumps", (&x,), Some(&strict)) {
            Ok(t) => t.extract()?,
            Err(e) if e.is_instance_of::<PyValueError>(given.py()) => {
                return Err(errors::value(format!(
                    "{what}[{key:?}] = {shown}: expected a finite number"
                )));
            }
            Err(_) => {
                let ty = x.get_type().name()?;
                return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                    "{what}[{key:?}] = {shown}: expected a number, bool, string, list or dict, got {ty}"
                )));
            }
        };
        let value: serde_json::Value = serde_json::from_str(&text).map_err(errors::value)?;
        out.insert(key, value);
    }
    Ok(out)
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
        #[pyo3(from_py_with = args::inputs)] inputs: usize,
        #[pyo3(from_py_with = args::outputs)] outputs: usize,
        #[pyo3(from_py_with = args::seed)] seed: u64,
        #[pyo3(from_py_with = args::size)] size: Option<usize>,
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
    // The parameters' own bounds (population_size among them) are named first.
    params.validate().map_err(errors::value)?;
    check_sizes(inputs, outputs, params.population_size)?;
    let spec = GenomeSpec {
        allow_recurrent: recurrent,
        ..spec
    };
    Ok((params, spec))
}

/// Most genes (nodes and links of every minimal genome) a generation 0 may
/// hold: checked before anything is allocated, so that a huge request is a
/// `MemoryError` rather than an abort of the interpreter.
pub const MAX_GENES: u128 = 50_000_000;

/// Refuses `inputs`, `outputs` and a population `size` whose generation 0
/// would not fit in [`MAX_GENES`] (a minimal genome links every input to every output).
fn check_sizes(inputs: usize, outputs: usize, size: usize) -> PyResult<()> {
    let (i, o, n) = (inputs as u128, outputs as u128, size as u128);
    let genes = (i * o + i + o) * n;
    if genes > MAX_GENES {
        return Err(pyo3::exceptions::PyMemoryError::new_err(format!(
            "inputs={inputs}, outputs={outputs}, size={size}: generation 0 would hold {genes} genes \
             ((inputs × outputs + inputs + outputs) × size), more than the {MAX_GENES} allowed; \
             use fewer inputs, outputs or genomes"
        )));
    }
    Ok(())
}
