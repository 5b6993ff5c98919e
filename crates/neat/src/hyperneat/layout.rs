//! Substrate geometry: input sheets and the neuron sheet in CPPN space.

use serde::{Deserialize, Serialize};

use super::error::HyperError;

/// Number of CPPN inputs a substrate query feeds: `(x1, y1, x2, y2, 1)`.
pub const CPPN_INPUTS: usize = 5;

/// One input sheet: node coordinates and which CPPN output paints its links.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InputSheet {
    /// CPPN-space coordinates of the sheet's nodes, in controller-input order.
    pub coords: Vec<[f64; 2]>,
    /// Index of the CPPN output giving the weight sheet node → neuron.
    pub cppn_output: usize,
}

/// The geometry of a substrate: input sheets and the neuron sheet.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubstrateLayout {
    /// Input sheets; the controller's inputs are their nodes concatenated in order.
    pub inputs: Vec<InputSheet>,
    /// CPPN-space coordinates of the neurons (the controller's outputs, in order).
    pub neurons: Vec<[f64; 2]>,
    /// CPPN output giving each neuron's bias (queried with `x2 = y2 = 0`).
    pub bias_output: usize,
    /// CPPN output giving the weight neuron → neuron.
    pub recurrent_output: usize,
}

impl SubstrateLayout {
    /// Total number of input nodes over all sheets.
    pub fn num_inputs(&self) -> usize {
        self.inputs.iter().map(|s| s.coords.len()).sum()
    }

    /// Every source of links, in the controller's source order (the input
    /// sheets' nodes, then the neurons), each with the CPPN output that
    /// paints its links.
    pub(crate) fn sources(&self) -> Vec<([f64; 2], usize)> {
        let inputs = self.inputs.iter();
        inputs
            .flat_map(|s| s.coords.iter().map(move |&c| (c, s.cppn_output)))
            .chain(self.neurons.iter().map(|&c| (c, self.recurrent_output)))
            .collect()
    }

    /// Number of CPPN queries a decode makes: one per possible link plus one per bias.
    pub fn num_queries(&self) -> usize {
        let n = self.neurons.len();
        n * (self.num_inputs() + n + 1)
    }

    /// Checks the layout against a CPPN's input and output counts.
    pub fn check(&self, cppn_inputs: usize, cppn_outputs: usize) -> Result<(), HyperError> {
        if cppn_inputs != CPPN_INPUTS {
            return Err(HyperError::CppnInputs(cppn_inputs));
        }
        if self.neurons.is_empty() {
            return Err(HyperError::NoNeurons);
        }
        let out = |role, output| check_cppn_output(role, output, cppn_outputs);
        out("the neuron bias", self.bias_output)?;
        out("neuron -> neuron weights", self.recurrent_output)?;
        for sheet in &self.inputs {
            out("input -> neuron weights", sheet.cppn_output)?;
        }
        check_finite(self.neurons.iter().map(|c| ("neuron", c)))?;
        for sheet in &self.inputs {
            check_finite(sheet.coords.iter().map(|c| ("input", c)))?;
        }
        Ok(())
    }
}

/// Every position finite, else [`HyperError::BadCoordinate`] naming its
/// sheet and its index (counted over all of `positions`).
pub(crate) fn check_finite<'c>(
    positions: impl Iterator<Item = (&'static str, &'c [f64; 2])>,
) -> Result<(), HyperError> {
    for (index, (sheet, c)) in positions.enumerate() {
        if !(c[0].is_finite() && c[1].is_finite()) {
            let coord = *c;
            return Err(HyperError::BadCoordinate {
                sheet,
                index,
                coord,
            });
        }
    }
    Ok(())
}

/// `output` must be one of the CPPN's `available` outputs; `role` names its use.
pub(crate) fn check_cppn_output(
    role: &'static str,
    output: usize,
    available: usize,
) -> Result<(), HyperError> {
    if output < available {
        Ok(())
    } else {
        Err(HyperError::CppnOutput {
            role,
            output,
            available,
        })
    }
}

/// The link-weight, optional bias and optional LEO outputs of a layout whose
/// links are queried one by one, each checked against the CPPN's outputs.
pub(crate) fn check_link_outputs(
    (weight, bias, leo): (usize, Option<usize>, Option<usize>),
    available: usize,
) -> Result<(), HyperError> {
    check_cppn_output("link weights", weight, available)?;
    if let Some(b) = bias {
        check_cppn_output("biases", b, available)?;
    }
    if let Some(l) = leo {
        check_cppn_output("link expression (LEO)", l, available)?;
    }
    Ok(())
}
