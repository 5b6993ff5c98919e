//! Plain HyperNEAT over a layered, feed-forward substrate (e.g. the retina
//! and boxes benchmarks), with the weight threshold or LEO.

use serde::{Deserialize, Serialize};

use super::error::HyperError;
use super::layout::{CPPN_INPUTS, check_finite, check_link_outputs};
use super::leo::express_link;
use super::params::HyperParams;
use super::sparse::{SparseLink, SparseNetwork};
use crate::network::Network;

/// Layers of node positions; each layer is fully connected to the next.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LayeredLayout {
    /// Layers from inputs (first) to outputs (last); at least two.
    pub layers: Vec<Vec<[f64; 2]>>,
    /// CPPN output giving link weights (queried target first, then source).
    pub weight_output: usize,
    /// CPPN output giving biases (queried with source (0, 0)); none if `None` (or absent:
    /// a missing `Option` field reads as `None`).
    pub bias_output: Option<usize>,
    /// CPPN output for LEO: a link exists iff it is > 0; `None` (or absent): the weight
    /// threshold decides.
    pub leo_output: Option<usize>,
}

impl LayeredLayout {
    /// Checks that there are two or more non-empty layers of finite
    /// positions and that the CPPN has the outputs named.
    pub fn check(&self, cppn_inputs: usize, cppn_outputs: usize) -> Result<(), HyperError> {
        if cppn_inputs != CPPN_INPUTS {
            return Err(HyperError::CppnInputs(cppn_inputs));
        }
        if self.layers.len() < 2 || self.layers.iter().any(Vec::is_empty) {
            return Err(HyperError::Inconsistent(
                "need two or more non-empty layers",
            ));
        }
        let outputs = (self.weight_output, self.bias_output, self.leo_output);
        check_link_outputs(outputs, cppn_outputs)?;
        check_finite(self.layers.iter().flatten().map(|c| ("layer", c)))
    }
}

/// Decodes `cppn` over a layered substrate into a feed-forward network:
/// inputs are the first layer, outputs the last, hidden nodes the others in
/// order; one query per possible link and per bias.
pub fn decode_layered(
    cppn: &mut impl Network,
    layout: &LayeredLayout,
    params: &HyperParams,
) -> Result<SparseNetwork, HyperError> {
    params.validate()?;
    layout.check(cppn.num_inputs(), cppn.num_outputs())?;
    let layers = &layout.layers;
    let (ni, no) = (layers[0].len(), layers[layers.len() - 1].len());
    // Index of the first node of each layer: inputs, outputs, then hidden layers.
    let mut first = vec![0; layers.len()];
    let mut next = ni + no;
    for (k, layer) in layers.iter().enumerate().skip(1) {
        if k == layers.len() - 1 {
            first[k] = ni;
        } else {
            first[k] = next;
            next += layer.len();
        }
    }
    let mut out = vec![0.0; cppn.num_outputs()];
    let mut links = Vec::new();
    for k in 1..layers.len() {
        for (t, &[x1, y1]) in layers[k].iter().enumerate() {
            for (s, &[x2, y2]) in layers[k - 1].iter().enumerate() {
                cppn.activate(&[x1, y1, x2, y2, 1.0], &mut out);
                let leo = layout.leo_output.map(|l| out[l]);
                if let Some(weight) = express_link(params, out[layout.weight_output], leo) {
                    links.push(SparseLink {
                        source: first[k - 1] + s,
                        target: first[k] + t,
                        weight,
                    });
                }
            }
        }
    }
    let hidden: Vec<[f64; 2]> = layers[1..layers.len() - 1]
        .iter()
        .flatten()
        .copied()
        .collect();
    let mut bias = vec![0.0; no + hidden.len()];
    if let Some(b) = layout.bias_output {
        let nodes = layers[layers.len() - 1].iter().chain(&hidden);
        for (v, &[x, y]) in bias.iter_mut().zip(nodes) {
            cppn.activate(&[x, y, 0.0, 0.0, 1.0], &mut out);
            *v = params.express(out[b]).unwrap_or(0.0);
        }
    }
    SparseNetwork::new(ni, no, hidden, bias, links)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hyperneat::test_util::{FnCppn, known};

    #[test]
    fn every_adjacent_pair_is_queried_and_expressed_by_the_rule() {
        let layout = LayeredLayout {
            layers: vec![
                vec![[-1.0, -1.0], [1.0, -1.0]],
                vec![[-0.5, 0.0], [0.0, 0.0], [0.5, 0.0]],
                vec![[0.0, 1.0]],
            ],
            weight_output: 0,
            bias_output: Some(1),
            leo_output: None,
        };
        let p = HyperParams::default();
        let net = decode_layered(&mut FnCppn(known), &layout, &p).unwrap();
        assert!(!net.is_recurrent());
        assert_eq!(net.hidden(), &layout.layers[1][..]);
        let mut expected = 0;
        for l in net.links() {
            // Inputs 0–1, output 2, hidden 3–5.
            let pos = |i: usize| match i {
                0 | 1 => layout.layers[0][i],
                2 => layout.layers[2][0],
                _ => layout.layers[1][i - 3],
            };
            let [x1, y1] = pos(l.target);
            let [x2, y2] = pos(l.source);
            assert_eq!(Some(l.weight), p.express(known(&[x1, y1, x2, y2, 1.0])[0]));
            assert!(l.source < 2 && l.target >= 3 || l.source >= 3 && l.target == 2);
            expected += 1;
        }
        assert!(expected > 0);
        // With LEO always on, all 2·3 + 3·1 links exist but the one of
        // weight output tanh(0) = 0 (hidden (0, 0) → output (0, 1)).
        let mut always = FnCppn(|q: &[f64]| [known(q)[0], 0.0, 1.0]);
        let leo = LayeredLayout {
            leo_output: Some(2),
            bias_output: None,
            ..layout.clone()
        };
        let net = decode_layered(&mut always, &leo, &p).unwrap();
        assert_eq!(net.links().len(), 8);
        assert!(net.biases().iter().all(|&b| b == 0.0));
    }

    #[test]
    fn layouts_read_without_bias_or_leo_outputs_have_none() {
        let json = r#"{"layers": [[[0.0, 0.0]], [[0.0, 1.0]]], "weight_output": 1}"#;
        let layered: LayeredLayout = serde_json::from_str(json).unwrap();
        assert_eq!((layered.bias_output, layered.leo_output), (None, None));
        let json = r#"{"inputs": [], "outputs": [[0.0, 1.0]], "weight_output": 1}"#;
        let es: crate::hyperneat::es::EsLayout = serde_json::from_str(json).unwrap();
        assert_eq!((es.bias_output, es.leo_output), (None, None));
        let json = r#"{"inputs": [], "outputs": [], "weight_output": 1, "bias": 0}"#;
        assert!(serde_json::from_str::<crate::hyperneat::es::EsLayout>(json).is_err());
    }
}
