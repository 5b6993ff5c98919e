//! Decoding a CPPN over a layout into a [`SubstrateController`].

use super::batch::{BatchCppn, CppnElement};
use super::controller::SubstrateController;
use super::error::HyperError;
use super::layout::SubstrateLayout;
use super::params::HyperParams;
use crate::feedforward::FeedForwardNetwork;
use crate::genome::Genome;
use crate::network::Network;
use crate::precision::Precision;

/// Decodes `cppn` over `layout` into a controller.
///
/// Makes `layout.num_queries()` CPPN activations; never allocates per query.
/// Query order (which matters only for stateful CPPNs) is: every neuron's
/// bias, then for each source (input sheets in order, then neurons) every
/// target neuron.
pub fn decode(
    cppn: &mut impl Network,
    layout: &SubstrateLayout,
    params: &HyperParams,
) -> Result<SubstrateController, HyperError> {
    params.validate()?;
    let num_outputs = cppn.num_outputs();
    layout.check(cppn.num_inputs(), num_outputs)?;
    let n = layout.neurons.len();
    let num_inputs = layout.num_inputs();
    let mut bias = vec![0.0; n];
    let mut out = vec![0.0; num_outputs];
    let mut query = [0.0, 0.0, 0.0, 0.0, 1.0];
    for (target, &[x1, y1]) in layout.neurons.iter().enumerate() {
        query[0] = x1;
        query[1] = y1;
        cppn.activate(&query, &mut out);
        bias[target] = params.weight_or_zero(out[layout.bias_output]);
    }
    // Source by source, so that each source's column is written contiguously.
    let sources = layout.sources();
    debug_assert_eq!(sources.len(), num_inputs + n);
    Ok(SubstrateController::build(
        layout,
        &bias,
        Precision::Exact,
        |j, column| {
            let ([x2, y2], output) = sources[j];
            query[2] = x2;
            query[3] = y2;
            for (&[x1, y1], w) in layout.neurons.iter().zip(column.iter_mut()) {
                query[0] = x1;
                query[1] = y1;
                cppn.activate(&query, &mut out);
                *w = params.weight_or_zero(out[output]);
            }
        },
    ))
}

/// Decodes a CPPN genome over `layout`: the batched path ([`BatchCppn`]) for
/// acyclic genomes, [`decode`] with a [`FeedForwardNetwork`] otherwise. The
/// result equals `decode(&mut FeedForwardNetwork::from_genome(genome), ..)`.
pub fn decode_genome(
    genome: &Genome,
    layout: &SubstrateLayout,
    params: &HyperParams,
) -> Result<SubstrateController, HyperError> {
    match BatchCppn::<f64>::new(genome) {
        Some(mut cppn) => decode_batched(&mut cppn, layout, params, Precision::Exact),
        None => decode(&mut FeedForwardNetwork::from_genome(genome), layout, params),
    }
}

/// Decodes a CPPN genome over `layout` for a controller stepping in
/// `precision`: [`Precision::Exact`] is [`decode_genome`]; [`Precision::Fast`]
/// queries an acyclic CPPN in f32 ([`BatchCppn<f32>`]: other bits than the
/// exact decode, the same on every CPU) and returns the controller already
/// in fast precision. A cyclic CPPN is decoded in f64 either way.
pub fn decode_genome_at(
    genome: &Genome,
    layout: &SubstrateLayout,
    params: &HyperParams,
    precision: Precision,
) -> Result<SubstrateController, HyperError> {
    let fast = match precision {
        Precision::Fast => BatchCppn::<f32>::new(genome),
        Precision::Exact => None,
    };
    match fast {
        Some(mut cppn) => decode_batched(&mut cppn, layout, params, precision),
        None => {
            let mut controller = decode_genome(genome, layout, params)?;
            controller.set_precision(precision);
            Ok(controller)
        }
    }
}

/// The batched decode into a controller in `precision`: every neuron's bias
/// in one batch, then one batch per source over all targets, expressed
/// straight into the source's column.
fn decode_batched<E: CppnElement>(
    cppn: &mut BatchCppn<E>,
    layout: &SubstrateLayout,
    params: &HyperParams,
    precision: Precision,
) -> Result<SubstrateController, HyperError> {
    params.validate()?;
    layout.check(cppn.num_inputs(), cppn.num_outputs())?;
    let n = layout.neurons.len();
    let mut out = vec![E::default(); n];
    cppn.query_targets(layout.bias_output, &layout.neurons, [0.0, 0.0], &mut out);
    let bias: Vec<f64> = out
        .iter()
        .map(|&o| params.weight_or_zero(o.to_f64()))
        .collect();
    let sources = layout.sources();
    Ok(SubstrateController::build(
        layout,
        &bias,
        precision,
        |j, column| {
            let (source, output) = sources[j];
            cppn.query_targets_with(output, &layout.neurons, source, |start, values| {
                for (w, &o) in column[start..].iter_mut().zip(values) {
                    *w = params.weight_or_zero(o.to_f64());
                }
            });
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hyperneat::test_util::{FnCppn, close, known, layout, random_genomes};
    use crate::hyperneat::{InputSheet, LinkSource};
    use crate::precision::Precision;

    #[test]
    fn bias_is_queried_with_zero_source() {
        let mut seen = Vec::new();
        let mut cppn = FnCppn(|q: &[f64]| {
            seen.push([q[0], q[1], q[2], q[3]]);
            // Bias output encodes (x1 + 2 y1) and is only valid at x2 = y2 = 0.
            let bias = if q[2] == 0.0 && q[3] == 0.0 {
                0.1 * (q[0] + 2.0 * q[1]) + 0.5
            } else {
                f64::NAN
            };
            [0.0, bias, 0.0]
        });
        let l = layout(vec![[0.3, 0.4]], vec![[1.0, 0.0], [0.0, 1.0]]);
        let c = decode(&mut cppn, &l, &HyperParams::default()).unwrap();
        let p = HyperParams::default();
        assert!(close(c.biases()[0], p.express(0.6).unwrap()));
        assert!(close(c.biases()[1], p.express(0.7).unwrap()));
        // 2 biases + 2×(1 input + 2 neurons) links.
        assert_eq!(seen.len(), l.num_queries());
        assert_eq!(seen.len(), 8);
        assert_eq!(
            seen.iter().filter(|q| q[2] == 0.0 && q[3] == 0.0).count(),
            2
        );
        assert_eq!(c.expressed_links(), 0);
        assert_eq!(c.possible_links(), 6);
    }

    #[test]
    fn known_cppn_gives_known_weights() {
        let inputs = vec![[-1.0, 0.0], [0.0, 1.0], [1.0, 0.0]];
        let neurons = vec![[-0.5, 0.0], [0.5, 0.5]];
        let l = layout(inputs.clone(), neurons.clone());
        let p = HyperParams::default();
        let c = decode(&mut FnCppn(known), &l, &p).unwrap();
        let mut expressed = 0;
        for (t, &[x1, y1]) in neurons.iter().enumerate() {
            let b = known(&[x1, y1, 0.0, 0.0, 1.0])[1];
            assert_eq!(c.biases()[t], p.express(b).unwrap_or(0.0));
            for (s, &[x2, y2]) in inputs.iter().enumerate() {
                let o = known(&[x1, y1, x2, y2, 1.0])[0];
                assert_eq!(c.input_weight(s, t), p.express(o).unwrap_or(0.0));
                expressed += usize::from(p.express(o).is_some());
            }
            for (s, &[x2, y2]) in neurons.iter().enumerate() {
                let o = known(&[x1, y1, x2, y2, 1.0])[2];
                assert_eq!(c.recurrent_weight(s, t), p.express(o).unwrap_or(0.0));
                expressed += usize::from(p.express(o).is_some());
            }
        }
        assert_eq!(c.expressed_links(), expressed);
        assert_eq!(c.links().count(), expressed);
        // Spot values: input (1, 0) → neuron (−0.5, 0): o = tanh(−1.5).
        let o = (-1.5f64).tanh();
        assert!(close(c.input_weight(2, 0), -(o.abs() - 0.2) / 0.8 * 3.0));
        // Self-loop of neuron 1 at (0.5, 0.5): o = e^0 · signum(0) = 1 → +3.
        assert!(close(c.recurrent_weight(1, 1), 3.0));
        // Self-loop of neuron 0 at (−0.5, 0): o = −1 → −3.
        assert!(close(c.recurrent_weight(0, 0), -3.0));
    }

    #[test]
    fn resampling_the_same_cppn_at_another_resolution() {
        let grid = |k: usize| -> Vec<[f64; 2]> {
            (0..k)
                .flat_map(|i| {
                    (0..k).map(move |j| [i as f64 / (k - 1) as f64, j as f64 / (k - 1) as f64])
                })
                .collect()
        };
        let p = HyperParams::default();
        let coarse = decode(&mut FnCppn(known), &layout(grid(3), grid(3)), &p).unwrap();
        let fine = decode(&mut FnCppn(known), &layout(grid(5), grid(9)), &p).unwrap();
        assert_eq!(fine.num_neurons(), 81);
        assert_eq!(fine.possible_links(), 81 * (25 + 81));
        // Nodes of the 3-grid sit in the finer grids: index (i, j) ↦ (s·i, s·j).
        let at = |k: usize, s: usize, i: usize, j: usize| (s * i) * k + s * j;
        for ti in 0..3 {
            for tj in 0..3 {
                let t3 = ti * 3 + tj;
                let t9 = at(9, 4, ti, tj);
                assert_eq!(coarse.biases()[t3], fine.biases()[t9]);
                for si in 0..3 {
                    for sj in 0..3 {
                        let s3 = si * 3 + sj;
                        assert_eq!(
                            coarse.input_weight(s3, t3),
                            fine.input_weight(at(5, 2, si, sj), t9)
                        );
                        assert_eq!(
                            coarse.recurrent_weight(s3, t3),
                            fine.recurrent_weight(at(9, 4, si, sj), t9)
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn multiple_input_sheets_use_their_own_output() {
        let mut cppn = FnCppn(|_: &[f64]| [0.5, 0.0, 0.0, -0.9]);
        let l = SubstrateLayout {
            inputs: vec![
                InputSheet {
                    coords: vec![[0.0, 1.0], [1.0, 0.0]],
                    cppn_output: 0,
                },
                InputSheet {
                    coords: vec![[0.0, 0.5]],
                    cppn_output: 3,
                },
            ],
            neurons: vec![[0.0, 0.3]],
            bias_output: 1,
            recurrent_output: 2,
        };
        let p = HyperParams::default();
        let c = decode(&mut cppn, &l, &p).unwrap();
        assert_eq!(c.sheet_sizes(), &[2, 1]);
        assert_eq!(c.input_weight(0, 0), p.express(0.5).unwrap());
        assert_eq!(c.input_weight(2, 0), p.express(-0.9).unwrap());
        let sources: Vec<LinkSource> = c.links().map(|l| l.source).collect();
        assert_eq!(
            sources,
            vec![
                LinkSource::Input { sheet: 0, index: 0 },
                LinkSource::Input { sheet: 0, index: 1 },
                LinkSource::Input { sheet: 1, index: 0 },
            ]
        );
    }

    #[test]
    fn bad_layouts_are_errors() {
        let p = HyperParams::default();
        let mut three = FnCppn(|_: &[f64]| [0.0; 3]);
        let mut l = layout(vec![[0.0, 0.0]], vec![[0.0, 1.0]]);
        l.inputs[0].cppn_output = 3;
        assert!(matches!(
            decode(&mut three, &l, &p),
            Err(HyperError::CppnOutput { output: 3, .. })
        ));
        let l = layout(vec![[0.0, 0.0]], vec![]);
        assert_eq!(
            decode(&mut three, &l, &p).unwrap_err(),
            HyperError::NoNeurons
        );
        let l = layout(vec![[f64::INFINITY, 0.0]], vec![[0.0, 1.0]]);
        assert!(matches!(
            decode(&mut three, &l, &p),
            Err(HyperError::BadCoordinate { .. })
        ));
    }

    #[test]
    fn batched_decode_equals_feed_forward_decode() {
        let grid = |r: usize, a: usize| -> Vec<[f64; 2]> {
            (0..r * a)
                .map(|i| {
                    [
                        (i % a) as f64 / a as f64 - 0.5,
                        (i / a + 1) as f64 / r as f64,
                    ]
                })
                .collect()
        };
        // Sheets longer than one batch exercise the chunking.
        let l = SubstrateLayout {
            inputs: vec![InputSheet {
                coords: grid(3, 100),
                cppn_output: 0,
            }],
            neurons: grid(2, 5),
            bias_output: 1,
            recurrent_output: 2,
        };
        let p = HyperParams::default();
        let mut hidden = 0;
        for g in random_genomes(20, 7) {
            hidden += g.num_hidden();
            let batched = decode_genome(&g, &l, &p).unwrap();
            let plain = decode(&mut FeedForwardNetwork::from_genome(&g), &l, &p).unwrap();
            assert_eq!(batched, plain);
        }
        assert!(hidden > 20, "genomes should have hidden nodes");
    }

    #[test]
    fn fast_decode_stays_close_to_the_exact_one_and_steps_in_f32() {
        let l = layout(
            (0..40).map(|i| [i as f64 / 20.0 - 1.0, 0.3]).collect(),
            (0..20).map(|i| [i as f64 / 10.0 - 1.0, 0.8]).collect(),
        );
        let p = HyperParams::default();
        let mut differ = 0;
        for g in random_genomes(20, 7) {
            let exact = decode_genome(&g, &l, &p).unwrap();
            let same = decode_genome_at(&g, &l, &p, Precision::Exact).unwrap();
            assert_eq!(exact, same);
            let fast = decode_genome_at(&g, &l, &p, Precision::Fast).unwrap();
            assert_eq!(fast.precision(), Precision::Fast);
            for t in 0..20 {
                let pairs = (0..40)
                    .map(|s| (exact.input_weight(s, t), fast.input_weight(s, t)))
                    .chain(
                        (0..20)
                            .map(|s| (exact.recurrent_weight(s, t), fast.recurrent_weight(s, t))),
                    )
                    .chain([(exact.biases()[t], fast.biases()[t])]);
                for (e, f) in pairs {
                    // A CPPN output 2e-5 off moves a weight at most 2e-5 / 0.8 × 3.
                    assert!((e - f).abs() < 1e-4, "exact {e}, fast {f}");
                    differ += usize::from(e != f);
                }
            }
        }
        assert!(
            differ > 1000,
            "only {differ} weights differ: were they decoded in f32?"
        );
    }
}
