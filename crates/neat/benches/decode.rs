//! HyperNEAT decoding and substrate-controller speed.
//!
//! `cargo bench -p vivae-neat --bench decode`
//!
//! * `decode_8m`: an 8-million-connection substrate (2000 inputs, 2000
//!   neurons: 2000 × (2000 + 2000 + 1) = 8 002 000 CPPN queries, the size of
//!   the HyperNEAT paper's largest), target ≤ 1 s on one core; with
//!   `decode_genome` (batched), `decode_8m_fast` (the fast precision's f32
//!   queries, `decode_genome_at`) and, for comparison, generic `decode`.
//! * `decode_paper`: the paper's 3×5 → 3×3 substrate (done once per genome).
//! * `es_decode_paper` / `es_decode_paper_reference`: ES-HyperNEAT at the
//!   paper's settings (`EsParams::default()`: initial and maximum depth 3,
//!   iteration level 1) from 15 inputs to 9 outputs, the batched decode and
//!   the one-query-at-a-time reference (done once per genome).
//! * `controller_step_paper`: one update of the 3×5 → 3×3 controller (done
//!   ~200 M times in the default run: 100 genomes × 400 generations × 5 robots
//!   × 1000 steps).
//! * `controller_batch_step_paper` / `_camera`: one batched update of 5
//!   robots, 3×5 → 3×3 and 32×96 → 9×9, in exact and in fast precision.

use divan::Bencher;
use vivae_neat::hyperneat::es::{EsLayout, EsParams, decode_es, decode_es_genome};
use vivae_neat::hyperneat::{
    HyperParams, InputSheet, SubstrateController, SubstrateLayout, decode, decode_genome,
    decode_genome_at,
};
use vivae_neat::{
    Activation, FeedForwardNetwork, Genome, LinkGene, Network, NodeGene, NodeKind, Precision,
};

fn main() {
    // `VIVAE_SIMD=scalar|avx2|avx512` benchmarks that level (the program's
    // switch, read here because the library does no environment I/O).
    if let Ok(v) = std::env::var("VIVAE_SIMD") {
        let wanted =
            vivae_neat::simd::SimdLevel::from_name(&v).expect("VIVAE_SIMD: scalar, avx2 or avx512");
        eprintln!("VIVAE_SIMD: {:?}", vivae_neat::simd::set_level(wanted));
    }
    divan::main();
}

/// A representative evolved CPPN: 5 inputs, 3 bipolar-sigmoid outputs, six
/// hidden nodes with the Table I functions, 32 enabled links.
fn genome() -> Genome {
    let node = |id, kind, activation| NodeGene {
        id,
        kind,
        activation,
    };
    let mut nodes: Vec<NodeGene> = (0..5)
        .map(|i| node(i, NodeKind::Input, Activation::Linear))
        .collect();
    nodes.extend((5..8).map(|i| node(i, NodeKind::Output, Activation::BipolarSigmoid)));
    let hidden = [
        Activation::Gaussian,
        Activation::Sine,
        Activation::Abs,
        Activation::BipolarSigmoid,
        Activation::Cosine,
        Activation::Linear,
    ];
    nodes.extend(
        hidden
            .iter()
            .enumerate()
            .map(|(k, &a)| node(8 + k as u32, NodeKind::Hidden, a)),
    );
    let pairs: [(u32, u32); 32] = [
        // Inputs to outputs (the minimal genome).
        (0, 5),
        (1, 5),
        (2, 5),
        (3, 5),
        (4, 5),
        (0, 6),
        (1, 6),
        (4, 6),
        (0, 7),
        (1, 7),
        (2, 7),
        (3, 7),
        (4, 7),
        // Inputs to hidden nodes.
        (0, 8),
        (2, 8),
        (1, 9),
        (3, 9),
        (0, 10),
        (2, 10),
        (4, 11),
        (1, 11),
        (3, 12),
        (1, 12),
        (4, 13),
        // Hidden to hidden and to outputs.
        (8, 11),
        (9, 13),
        (13, 6),
        (8, 5),
        (9, 7),
        (10, 5),
        (11, 6),
        (12, 7),
    ];
    let links = pairs
        .iter()
        .enumerate()
        .map(|(i, &(from, to))| LinkGene {
            innovation: i as u32,
            from,
            to,
            weight: 0.3 + 0.37 * ((i * 7 % 11) as f64 - 5.0),
            enabled: true,
        })
        .collect();
    Genome::from_parts(nodes, links).expect("valid benchmark genome")
}

/// The benchmark genome as a one-query-at-a-time network.
fn cppn() -> FeedForwardNetwork {
    let net = FeedForwardNetwork::from_genome(&genome());
    assert_eq!(net.num_computed(), 3 + 6);
    net
}

/// `n` points spread over the upper half-disc (rings × angles), in CPPN space.
fn half_disc(rings: usize, angles: usize) -> Vec<[f64; 2]> {
    (0..rings)
        .flat_map(|k| {
            let rho = (k + 1) as f64 / rings as f64;
            (0..angles).map(move |j| {
                let phi = if angles == 1 {
                    0.0
                } else {
                    -std::f64::consts::FRAC_PI_2
                        + std::f64::consts::PI * j as f64 / (angles - 1) as f64
                };
                [rho * phi.sin(), rho * phi.cos()]
            })
        })
        .collect()
}

fn layout(sensors: (usize, usize), neurons: (usize, usize)) -> SubstrateLayout {
    SubstrateLayout {
        inputs: vec![InputSheet {
            coords: half_disc(sensors.0, sensors.1),
            cppn_output: 0,
        }],
        neurons: half_disc(neurons.0, neurons.1),
        bias_output: 1,
        recurrent_output: 2,
    }
}

/// The production path: `decode_genome` (batched queries).
#[divan::bench(sample_count = 3, sample_size = 1)]
fn decode_8m(bencher: Bencher) {
    let layout = layout((20, 100), (20, 100));
    assert_eq!(layout.num_queries(), 8_002_000);
    let g = genome();
    bencher.bench_local(|| decode_genome(&g, &layout, &HyperParams::default()).unwrap());
}

/// The fast precision's decode: f32 queries, the controller in fast precision.
#[divan::bench(sample_count = 3, sample_size = 1)]
fn decode_8m_fast(bencher: Bencher) {
    let layout = layout((20, 100), (20, 100));
    let g = genome();
    bencher.bench_local(|| {
        decode_genome_at(&g, &layout, &HyperParams::default(), Precision::Fast).unwrap()
    });
}

/// The generic path: `decode` over any `Network`, one query at a time.
#[divan::bench(sample_count = 3, sample_size = 1)]
fn decode_8m_one_query_at_a_time(bencher: Bencher) {
    let layout = layout((20, 100), (20, 100));
    let mut net = cppn();
    bencher.bench_local(|| decode(&mut net, &layout, &HyperParams::default()).unwrap());
}

#[divan::bench]
fn decode_paper(bencher: Bencher) {
    let layout = layout((3, 5), (3, 3));
    let g = genome();
    bencher.bench_local(|| decode_genome(&g, &layout, &HyperParams::default()).unwrap());
}

/// The ES-HyperNEAT substrate of the benchmarks: as many inputs as the
/// paper's 3×5 sensor sheet along the bottom edge, as many outputs as its
/// 3×3 neuron sheet along the top.
fn es_layout() -> EsLayout {
    let row = |n: usize, y: f64| -> Vec<[f64; 2]> {
        (0..n)
            .map(|i| [-1.0 + 2.0 * i as f64 / (n - 1) as f64, y])
            .collect()
    };
    EsLayout {
        inputs: row(15, -1.0),
        outputs: row(9, 1.0),
        weight_output: 0,
        bias_output: Some(1),
        leo_output: None,
    }
}

#[divan::bench]
fn es_decode_paper(bencher: Bencher) {
    let (g, layout) = (genome(), es_layout());
    bencher.bench_local(|| decode_es_genome(&g, &layout, &EsParams::default()).unwrap());
}

#[divan::bench]
fn es_decode_paper_reference(bencher: Bencher) {
    let layout = es_layout();
    let mut net = cppn();
    bencher.bench_local(|| decode_es(&mut net, &layout, &EsParams::default()).unwrap());
}

/// One CPPN query (the unit of decoding cost).
#[divan::bench]
fn cppn_query(bencher: Bencher) {
    let mut net = cppn();
    let mut out = [0.0; 3];
    let mut x = 0.0;
    bencher.bench_local(|| {
        x += 1e-3;
        net.activate(divan::black_box(&[0.3, x, -0.2, 0.9, 1.0]), &mut out);
        out[0]
    });
}

fn paper_controller() -> SubstrateController {
    decode(
        &mut cppn(),
        &layout((3, 5), (3, 3)),
        &HyperParams::default(),
    )
    .unwrap()
}

#[divan::bench]
fn controller_step_paper(bencher: Bencher) {
    let mut c = paper_controller();
    // Sensor readings as on a road edge: a mix of road (1), grass (0) and sand.
    let inputs: [f64; 15] = [
        1.0, 1.0, 0.0, 0.72, 1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.39, 1.0, 0.0, 0.0, 1.0,
    ];
    let mut out = [0.0; 9];
    bencher.bench_local(|| {
        c.activate(divan::black_box(&inputs), &mut out);
        out[3] - out[5]
    });
}

/// 1000 steps of five controllers, as in one evaluation (without the simulator).
#[divan::bench]
fn controller_episode_paper(bencher: Bencher) {
    let mut robots: Vec<SubstrateController> = (0..5).map(|_| paper_controller()).collect();
    let mut inputs = [0.0; 15];
    let mut out = [0.0; 9];
    bencher.bench_local(|| {
        for r in robots.iter_mut() {
            r.reset();
        }
        for step in 0..1000 {
            for (i, r) in robots.iter_mut().enumerate() {
                for (k, v) in inputs.iter_mut().enumerate() {
                    *v = f64::from(((step + i + k) % 3 == 0) as u8);
                }
                r.activate(&inputs, &mut out);
            }
        }
        out[3]
    });
}

/// One batched update of 5 robots (as in one evaluation step) in each
/// precision: the paper's 3×5 → 3×3 controller and the camera's 32×96 → 9×9.
fn batch_step(bencher: Bencher, sensors: (usize, usize), neurons: (usize, usize), precision: &str) {
    let mut c = decode(
        &mut cppn(),
        &layout(sensors, neurons),
        &HyperParams::default(),
    )
    .unwrap();
    c.set_precision(vivae_neat::Precision::from_name(precision).unwrap());
    let robots = 5;
    let ni = Network::num_inputs(&c);
    let inputs: Vec<f64> = (0..robots * ni)
        .map(|k| [1.0, 0.0, 0.72, 0.39][k % 4])
        .collect();
    let mut out = vec![0.0; robots * c.num_neurons()];
    let mut states = c.batch_state(robots);
    bencher.bench_local(|| {
        c.activate_batch(&mut states, divan::black_box(&inputs), &mut out);
        out[3]
    });
}

/// `batch_step` of the paper's controller, exact vs fast.
#[divan::bench(args = ["exact", "fast"])]
fn controller_batch_step_paper(bencher: Bencher, precision: &str) {
    batch_step(bencher, (3, 5), (3, 3), precision);
}

/// `batch_step` of the camera-resolution controller (32×96 → 9×9), exact vs fast.
#[divan::bench(args = ["exact", "fast"])]
fn controller_batch_step_camera(bencher: Bencher, precision: &str) {
    batch_step(bencher, (32, 96), (9, 9), precision);
}
