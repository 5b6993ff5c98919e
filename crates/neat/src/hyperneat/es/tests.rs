//! ES-HyperNEAT: the reference and the fast decode agree bit for bit, and
//! every decoded network keeps the method's invariants.

use super::*;
use crate::hyperneat::test_util::{FnCppn, random_genomes};
use crate::hyperneat::{HyperParams, express_link};
use proptest::prelude::*;

fn layout(inputs: usize, outputs: usize) -> EsLayout {
    let row = |n: usize, y: f64| -> Vec<[f64; 2]> {
        (0..n)
            .map(|i| {
                [
                    if n == 1 {
                        0.0
                    } else {
                        -1.0 + 2.0 * i as f64 / (n - 1) as f64
                    },
                    y,
                ]
            })
            .collect()
    };
    EsLayout {
        inputs: row(inputs, -1.0),
        outputs: row(outputs, 1.0),
        weight_output: 0,
        bias_output: Some(1),
        leo_output: None,
    }
}

fn variants() -> Vec<(EsLayout, EsParams)> {
    let base = EsParams::default();
    let deep = EsParams {
        initial_depth: 2,
        max_depth: 5,
        division_threshold: 0.01,
        ..base
    };
    vec![
        (layout(3, 1), base),
        (layout(5, 2), deep),
        (
            layout(4, 2),
            EsParams {
                recurrent: true,
                ..deep
            },
        ),
        (
            layout(3, 2),
            EsParams {
                iteration_level: 3,
                band_threshold: 0.1,
                ..deep
            },
        ),
        (
            EsLayout {
                leo_output: Some(2),
                ..layout(4, 2)
            },
            deep,
        ),
        (
            upside_down(layout(4, 2)),
            EsParams {
                flow: Flow::Downward,
                ..deep
            },
        ),
    ]
}

/// `l` mirrored along y: the inputs on top, the outputs at the bottom.
fn upside_down(l: EsLayout) -> EsLayout {
    let flip = |v: Vec<[f64; 2]>| v.into_iter().map(|[x, y]| [x, -y]).collect();
    EsLayout {
        inputs: flip(l.inputs),
        outputs: flip(l.outputs),
        ..l
    }
}

#[test]
fn outputs_below_the_inputs_are_reached_by_a_downward_feed_forward_net_only() {
    let l = upside_down(layout(5, 2));
    let deep = EsParams {
        initial_depth: 2,
        max_depth: 5,
        division_threshold: 0.01,
        ..EsParams::default()
    };
    let down = EsParams {
        flow: Flow::Downward,
        ..deep
    };
    let (mut upward_links, mut downward_links, mut downward_hidden) = (0, 0, 0);
    for g in random_genomes(24, 13) {
        // Upward, no link can leave an input at y = 1 for an output at y = −1.
        upward_links += decode_es_genome(&g, &l, &deep).unwrap().links().len();
        let net = decode_es_genome(&g, &l, &down).unwrap();
        check_invariants(&g, &l, &down, &net);
        downward_links += net.links().len();
        downward_hidden += net.num_hidden();
    }
    assert_eq!(upward_links, 0);
    assert!(
        downward_links > 50 && downward_hidden > 20,
        "links {downward_links}, hidden {downward_hidden}"
    );
}

#[test]
fn fast_decode_equals_reference_decode() {
    let mut hidden = 0;
    let mut links = 0;
    for (l, p) in variants() {
        for g in random_genomes(24, 13) {
            let fast = decode_es_genome(&g, &l, &p).unwrap();
            let reference = decode_es(&mut FeedForwardNetwork::from_genome(&g), &l, &p).unwrap();
            assert_eq!(fast, reference);
            hidden += fast.num_hidden();
            links += fast.links().len();
        }
    }
    // The comparison is only worth something if networks have content.
    assert!(hidden > 50 && links > 100, "hidden {hidden}, links {links}");
}

/// Input (0, −1) paints a bump at (0.25, 0.25) and a decoy at (−0.75, −0.25);
/// only the bump paints a link to the output (0, 1).
fn bump(q: &[f64]) -> [f64; 3] {
    let near = |x: f64, y: f64, cx: f64, cy: f64| (x - cx).abs() < 0.2 && (y - cy).abs() < 0.2;
    let (target, source) = ([q[0], q[1]], [q[2], q[3]]);
    let from_input = source == [0.0, -1.0]
        && (near(target[0], target[1], 0.25, 0.25) || near(target[0], target[1], -0.75, -0.25));
    let to_output = target == [0.0, 1.0] && near(source[0], source[1], 0.25, 0.25);
    [if from_input || to_output { 0.9 } else { 0.0 }, 0.0, 0.0]
}

#[test]
fn a_band_becomes_a_hidden_node_and_dead_ends_are_dropped() {
    let l = EsLayout {
        inputs: vec![[0.0, -1.0]],
        outputs: vec![[0.0, 1.0]],
        weight_output: 0,
        bias_output: None,
        leo_output: None,
    };
    let p = EsParams::default();
    let net = decode_es(&mut FnCppn(bump), &l, &p).unwrap();
    assert_eq!(net.hidden(), &[[0.25, 0.25]]);
    let w = HyperParams::default().express(0.9).unwrap();
    let links: Vec<(usize, usize, f64)> = net
        .links()
        .iter()
        .map(|l| (l.source, l.target, l.weight))
        .collect();
    // Node 0 the input, 1 the output, 2 the hidden node.
    assert_eq!(links, vec![(2, 1, w), (0, 2, w)]);
    // With no route to the output, nothing survives.
    let mut no_exit = FnCppn(|q: &[f64]| if q[1] == 1.0 { [0.0; 3] } else { bump(q) });
    let net = decode_es(&mut no_exit, &l, &p).unwrap();
    assert_eq!(net.num_hidden(), 0);
    assert!(net.links().is_empty());
}

#[test]
fn a_uniform_pattern_expresses_nothing() {
    let l = layout(3, 2);
    let mut flat = FnCppn(|_: &[f64]| [0.8, 0.0, 0.0]);
    let net = decode_es(&mut flat, &l, &EsParams::default()).unwrap();
    assert_eq!(net.num_hidden(), 0);
    assert!(net.links().is_empty());
}

#[test]
fn bad_layouts_and_params_are_errors() {
    let g = &random_genomes(1, 1)[0];
    let mut l = layout(2, 1);
    l.leo_output = Some(3);
    assert!(matches!(
        decode_es_genome(g, &l, &EsParams::default()),
        Err(HyperError::CppnOutput { output: 3, .. })
    ));
    let mut l = layout(2, 1);
    l.outputs.push(l.inputs[0]);
    assert!(decode_es_genome(g, &l, &EsParams::default()).is_err());
    let p = EsParams {
        initial_depth: 5,
        max_depth: 4,
        ..Default::default()
    };
    assert!(decode_es_genome(g, &layout(2, 1), &p).is_err());
}

/// Whether `v` is a quadtree centre coordinate at some level `2..=max_depth + 1`.
fn on_quadtree_grid(v: f64, max_depth: u32) -> bool {
    (2..=max_depth + 1).any(|level| {
        let k = (v + 1.0) * f64::from(1u32 << (level - 1));
        k.fract() == 0.0 && (k as i64) % 2 == 1
    })
}

/// Checks the invariants every decoded network keeps.
fn check_invariants(g: &Genome, l: &EsLayout, p: &EsParams, net: &SparseNetwork) {
    let (ni, no) = (l.inputs.len(), l.outputs.len());
    let pos = |i: usize| -> [f64; 2] {
        if i < ni {
            l.inputs[i]
        } else if i < ni + no {
            l.outputs[i - ni]
        } else {
            net.hidden()[i - ni - no]
        }
    };
    let n = ni + no + net.num_hidden();
    let edges: Vec<(usize, usize)> = net.links().iter().map(|k| (k.source, k.target)).collect();
    let forward = discover_reach(n, 0..ni, &edges, false);
    let backward = discover_reach(n, ni..ni + no, &edges, true);
    for h in ni + no..n {
        assert!(
            forward[h] && backward[h],
            "hidden node {h} is not on an input→output path"
        );
        assert!(
            pos(h).iter().all(|&v| on_quadtree_grid(v, p.max_depth)),
            "{:?}",
            pos(h)
        );
    }
    let mut cppn = FeedForwardNetwork::from_genome(g);
    let mut out = vec![0.0; cppn.num_outputs()];
    for k in net.links() {
        assert!(forward[k.source] && backward[k.target]);
        let ([x1, y1], [x2, y2]) = (pos(k.target), pos(k.source));
        if !p.recurrent {
            assert!(
                p.flow.allows([x2, y2], [x1, y1]),
                "a feed-forward link goes {:?}",
                p.flow
            );
        }
        cppn.activate(&[x1, y1, x2, y2, 1.0], &mut out);
        let leo = l.leo_output.map(|o| out[o]);
        assert_eq!(
            Some(k.weight),
            express_link(&p.expression, out[l.weight_output], leo)
        );
        assert!(k.weight != 0.0 && k.weight.abs() <= p.expression.amplitude);
    }
    assert!(p.recurrent || !net.is_recurrent());
}

fn discover_reach(
    n: usize,
    start: std::ops::Range<usize>,
    edges: &[(usize, usize)],
    back: bool,
) -> Vec<bool> {
    let mut seen = vec![false; n];
    let mut todo: Vec<usize> = start.collect();
    todo.iter().for_each(|&i| seen[i] = true);
    while let Some(i) = todo.pop() {
        for &(a, b) in edges {
            let (from, to) = if back { (b, a) } else { (a, b) };
            if from == i && !seen[to] {
                seen[to] = true;
                todo.push(to);
            }
        }
    }
    seen
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn decoded_networks_keep_the_invariants(
        seed in 0u64..1000,
        which in 0usize..6,
        depth in 2u32..6,
        band in 0.05f64..0.5,
    ) {
        let (l, p) = variants().swap_remove(which);
        let p = EsParams { max_depth: depth, initial_depth: p.initial_depth.min(depth), band_threshold: band, ..p };
        for g in random_genomes(3, seed) {
            let net = decode_es_genome(&g, &l, &p).unwrap();
            check_invariants(&g, &l, &p, &net);
        }
    }
}
