//! The exported step is vivae's step, bit for bit, for every kind of controller.

use super::frames::record;
use super::*;
use crate::config::Config;
use crate::controller::es::SubstrateKind;
use crate::controller::substrate::PolarGrid;
// The driving episode is the fixture: the task whose controller is a substrate network.
use crate::tasks::driving::episode::Episode;
use crate::tasks::scenarios::load_scenario;
use vivae_neat::{Population, Precision};

fn episode(config: &Config) -> Episode {
    Episode::new(config, &load_scenario(None).unwrap().scenario).unwrap()
}

/// Steps `net` through every recorded step of `genome`'s episode and
/// returns how many genomes' wheels differed in any bit (0 expected).
fn replays_bit_identically(
    config: &Config,
    genomes: usize,
    want: impl Fn(&StepNet) -> bool,
) -> usize {
    let exp = episode(config);
    let pop = Population::new(config.neat.clone(), exp.cppn_spec(), 3).unwrap();
    let mut checked = 0;
    for g in pop.genomes().iter().take(genomes) {
        let c = exp.robot_controller(g).unwrap();
        let e = Exported::new(&exp, &c, "test");
        if !want(&e.net) {
            continue;
        }
        let rec = record(&exp, &c, 1, exp.steps()).unwrap();
        let (mut state, mut scratch) = (vec![0.0; e.net.nodes], vec![0.0; e.net.nodes]);
        for (x, w) in rec.sensors.chunks_exact(rec.inputs).zip(&rec.wheels) {
            let mut out = [0.0; 2];
            e.net.step(x, &mut state, &mut scratch, &mut out);
            assert_eq!(out.map(f64::to_bits), w.map(f64::to_bits));
        }
        checked += 1;
    }
    checked
}

#[test]
fn the_polar_step_is_vivaes_at_any_resolution() {
    let mut config = Config::default();
    config.experiment.steps = 200;
    assert_eq!(replays_bit_identically(&config, 12, |_| true), 12);
    config.surface_sensors.rings = 4;
    config.surface_sensors.angles = 9;
    config.surface_sensors.fov = 360.0;
    config.substrate.neurons = PolarGrid::new(5, 5).unwrap();
    config.distance_sensors.rays = 3;
    assert_eq!(replays_bit_identically(&config, 6, |_| true), 6);
}

#[test]
fn the_fast_polar_step_is_vivaes_fast_step() {
    let mut config = Config::default();
    config.experiment.steps = 200;
    config.experiment.precision = Precision::Fast;
    let fast = |n: &StepNet| n.precision == Precision::Fast;
    assert_eq!(replays_bit_identically(&config, 12, fast), 12);
    // A re-sampled sheet with distance rays (read in f64, rounded) as well.
    config.surface_sensors.rings = 4;
    config.surface_sensors.angles = 9;
    config.substrate.neurons = PolarGrid::new(5, 5).unwrap();
    config.distance_sensors.rays = 3;
    assert_eq!(replays_bit_identically(&config, 6, fast), 6);
}

#[test]
fn the_fast_step_differs_from_the_exact_one_of_the_same_genome() {
    // Else the fast replay above could pass on an f64 step.
    let mut config = Config::default();
    config.experiment.steps = 100;
    let exact = episode(&config);
    config.experiment.precision = Precision::Fast;
    let fast = episode(&config);
    let pop = Population::new(config.neat.clone(), exact.cppn_spec(), 3).unwrap();
    let mut differing = 0;
    for g in pop.genomes().iter().take(6) {
        let (ce, cf) = (
            exact.robot_controller(g).unwrap(),
            fast.robot_controller(g).unwrap(),
        );
        let (ne, nf) = (
            Exported::new(&exact, &ce, "e").net,
            Exported::new(&fast, &cf, "f").net,
        );
        assert_eq!(
            (ne.precision, nf.precision),
            (Precision::Exact, Precision::Fast)
        );
        let rec = record(&fast, &cf, 1, 100).unwrap();
        let mut states = [vec![0.0; ne.nodes], vec![0.0; nf.nodes]];
        let mut scratch = vec![0.0; ne.nodes];
        for x in rec.sensors.chunks_exact(rec.inputs) {
            let (mut we, mut wf) = ([0.0; 2], [0.0; 2]);
            ne.step(x, &mut states[0], &mut scratch, &mut we);
            nf.step(x, &mut states[1], &mut scratch, &mut wf);
            differing += usize::from(we != wf);
            // Both steps compute the same function to about f32's precision.
            for (a, b) in we.iter().zip(&wf) {
                assert!((a - b).abs() < 1e-2, "{we:?} against {wf:?}");
            }
        }
    }
    assert!(differing > 100, "{differing} of 600 steps differ");
}

/// A C99 hexadecimal float (`[-]0x<d>[.<hex>]p<exp>`) read back exactly,
/// as a C compiler or Python's `float.fromhex` would.
fn read_hex(s: &str) -> f64 {
    let (sign, s) = s.strip_prefix('-').map_or((1.0, s), |s| (-1.0, s));
    let (mantissa, exp) = s.strip_prefix("0x").unwrap().split_once('p').unwrap();
    let (lead, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits = format!("{lead}{frac}");
    let m = u64::from_str_radix(&digits, 16).unwrap();
    let e: i32 = exp.parse::<i32>().unwrap() - 4 * frac.len() as i32;
    // m < 2^53 and the scaling by powers of two is exact down to the subnormals.
    let scale = |e: i32| 2f64.powi(e);
    sign * m as f64 * scale(e / 2) * scale(e - e / 2)
}

#[test]
fn hex_floats_read_back_to_the_same_bits() {
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let mut values: Vec<u64> = (0..20_000).map(|_| next()).collect();
    values.extend([0, 1, 0x000f_ffff_ffff_ffff, 0x0010_0000_0000_0000, 1 << 63]);
    for bits in values {
        let v = f64::from_bits(bits);
        if v.is_finite() {
            let back = read_hex(&super::json::hex64(v));
            assert_eq!(back.to_bits(), bits, "{v:e} as {}", super::json::hex64(v));
            let f = f32::from_bits(bits as u32);
            if f.is_finite() {
                let back = read_hex(&super::json::hex32(f)) as f32;
                assert_eq!(back.to_bits(), f.to_bits(), "{f:e}");
            }
        }
    }
    assert_eq!(super::json::hex64(1.5), "0x1.8p+0");
    assert_eq!(super::json::hex32(-4.9), "-0x1.39999ap+2");
}

#[test]
fn the_json_arithmetic_gives_vivaes_constants_to_the_bit() {
    use vivae_neat::math::exp_constants as e64;
    use vivae_neat::precision::exp_f32_constants as e32;
    let exp = episode(&Config::default());
    let pop = Population::new(Config::default().neat, exp.cppn_spec(), 3).unwrap();
    let c = exp.robot_controller(&pop.genomes()[0]).unwrap();
    let doc: serde_json::Value =
        serde_json::from_str(&super::json::to_json(&Exported::new(&exp, &c, "t"))).unwrap();
    assert_eq!(doc["version"], 4);
    assert_eq!(doc["net"]["outputs"].as_array().map(Vec::len), Some(2));
    assert_eq!(doc["outputs"], WHEELS);
    let a = &doc["arithmetic"];
    let read = |v: &serde_json::Value| read_hex(v.as_str().unwrap());
    let exact = &a["exact"]["exp"]["constants"];
    let fast = &a["fast"]["exp"]["constants"];
    assert_eq!(read(&exact["ln2_hi"]).to_bits(), e64::LN2_HI.to_bits());
    assert_eq!(read(&exact["ln2_lo"]).to_bits(), e64::LN2_LO.to_bits());
    assert_eq!(read(&exact["log2e"]).to_bits(), e64::LOG2E.to_bits());
    assert_eq!(read(&exact["shift"]), e64::SHIFT);
    let taylor: Vec<f64> = (exact["taylor"].as_array().unwrap().iter())
        .map(read)
        .collect();
    assert_eq!(taylor[0], e64::TAYLOR_FIRST);
    assert_eq!(taylor[1..], e64::TAYLOR);
    for (key, want) in [
        ("ln2_hi", e32::LN2_HI),
        ("ln2_lo", e32::LN2_LO),
        ("log2e", e32::LOG2E),
        ("low", e32::LOW),
        ("high", e32::HIGH),
    ] {
        assert_eq!((read(&fast[key]) as f32).to_bits(), want.to_bits(), "{key}");
    }
    let p: Vec<f32> = (fast["p"].as_array().unwrap().iter())
        .map(|v| read(v) as f32)
        .collect();
    assert_eq!(p, e32::P);
    assert_eq!(read(&a["exact"]["sigmoid"]["constants"]["slope"]), -4.9);
    assert_eq!(
        read(&a["fast"]["sigmoid"]["constants"]["slope"]) as f32,
        -4.9f32
    );
}

#[test]
fn a_reading_is_clamped_to_the_sensors_range_nan_as_zero() {
    assert_eq!(reading(f64::NAN), 0.0);
    assert_eq!(reading(f64::INFINITY), 1.0);
    assert_eq!(reading(f64::NEG_INFINITY), 0.0);
    assert_eq!(reading(-1e-300), 0.0);
    assert_eq!(reading(1.0 + f64::EPSILON), 1.0);
    for v in [0.0, 1e-310, 0.25, 0.999_999, 1.0] {
        assert_eq!(reading(v).to_bits(), v.to_bits());
    }
}

#[test]
fn the_es_step_is_vivaes_recurrent_or_feed_forward() {
    let mut config = Config::default();
    config.experiment.steps = 150;
    config.substrate.kind = SubstrateKind::EsHyperneat;
    let hidden = |n: &StepNet| n.nodes > 2;
    assert!(replays_bit_identically(&config, 30, |n| hidden(n) && n.synchronous) >= 3);
    config.substrate.es.recurrent = false;
    // Random first-generation CPPNs discover no hidden node without cycles:
    // the wheels straight from the sensors (a layered net is checked below).
    assert_eq!(replays_bit_identically(&config, 10, |n| !n.synchronous), 10);
}

#[test]
fn the_geometry_lists_every_input_where_the_simulator_reads_it() {
    let mut config = Config::default();
    config.distance_sensors.rays = 4;
    let exp = episode(&config);
    let pop = Population::new(config.neat.clone(), exp.cppn_spec(), 3).unwrap();
    let c = exp.robot_controller(&pop.genomes()[0]).unwrap();
    let e = Exported::new(&exp, &c, "test");
    let total: usize = e.sheets.iter().map(|s| s.places.len()).sum();
    assert_eq!(total, e.net.inputs);
    assert_eq!(e.sheets[0].sensor, "surface");
    assert_eq!(e.sheets[1].first_input, 15);
    assert_eq!(e.sheets[0].fov_deg, 180.0);
    assert_eq!(e.sheets[0].places[0].angle_deg, -90.0);
    assert_eq!(e.sheets[0].places[14].distance, 50.0);
}

#[test]
fn formats_parse_by_name() {
    assert_eq!("onnx".parse::<Format>(), Ok(Format::Onnx));
    assert_eq!("c".parse::<Format>(), Ok(Format::C));
    assert!(
        "png"
            .parse::<Format>()
            .unwrap_err()
            .contains("onnx, c or json")
    );
}

/// A feed-forward net of three levels and a recurrent one, from their links.
fn sparse(recurrent: bool) -> SparseNetwork {
    use vivae_neat::hyperneat::SparseLink;
    let l = |source, target, weight| SparseLink {
        source,
        target,
        weight,
    };
    // Inputs 0..3, wheels 3 and 4, hidden 5 and 6: 0,1 → 5 → 6 → wheels, 2 → 4.
    let mut links = vec![
        l(0, 5, 1.3),
        l(1, 5, -0.7),
        l(5, 6, 2.1),
        l(6, 3, -1.9),
        l(6, 4, 0.4),
    ];
    links.extend([l(2, 4, 0.9), l(5, 3, 0.3)]);
    if recurrent {
        links.extend([l(3, 5, 0.8), l(6, 6, -0.5)]);
    }
    let bias = vec![0.1, -0.2, 0.05, 0.0];
    SparseNetwork::new(3, 2, vec![[0.1, 0.2], [0.3, -0.4]], bias, links).unwrap()
}

#[test]
fn a_layered_or_recurrent_sparse_net_steps_as_vivae_does() {
    use vivae_neat::Network;
    for recurrent in [false, true] {
        let mut net = sparse(recurrent);
        let step = StepNet::from_sparse(&net);
        assert_eq!(step.synchronous, recurrent);
        if !recurrent {
            assert_eq!(super::onnx::levels(&step).len(), 3, "{:?}", step.order);
        }
        let (mut state, mut scratch) = (vec![0.0; 4], vec![0.0; 4]);
        let mut want = [0.0; 2];
        for t in 0..20 {
            // In range, out of range and NaN: the step reads each as `reading` of it.
            let x = [(t as f64 * 0.37).sin(), 0.5, 1.5 - (t as f64) / 7.0];
            let x = if t % 7 == 3 {
                [f64::NAN, x[1], x[2]]
            } else {
                x
            };
            net.activate(&x.map(reading), &mut want);
            let mut got = [0.0; 2];
            step.step(&x, &mut state, &mut scratch, &mut got);
            assert_eq!(
                got.map(f64::to_bits),
                want.map(f64::to_bits),
                "recurrent {recurrent}, step {t}"
            );
        }
    }
}

#[test]
fn a_plain_network_exports_every_output_in_every_format() {
    use crate::tasks::acrobot::Acrobot;
    use crate::tasks::plain::{Described, spec};
    let pop = Population::new(Config::default().neat, spec::<Acrobot>(), 3).unwrap();
    let genome = &pop.genomes()[0];
    let e = Exported::plain(
        genome,
        false,
        Readings::UNBOUNDED,
        Acrobot::OUTPUT_MEANING,
        "t",
    )
    .unwrap();
    assert_eq!(e.net.outputs, [0, 1, 2]);
    assert!(!e.drives_wheels());
    assert!(
        e.outputs.starts_with("3 outputs, out[0] .. out[2]"),
        "{}",
        e.outputs
    );
    assert!(e.outputs.contains("argmax"), "{}", e.outputs);
    let header = super::c::header(&e);
    assert!(header.contains("#define VIVAE_OUTPUTS 3\n"), "{header}");
    assert!(header.contains("/* Outputs: 3 outputs"), "{header}");
    let source = super::c::source(&e, "controller.h");
    assert!(source.contains("    out[2] = state[2];\n"), "{source}");
    assert!(!source.contains("out[3]"));
    let doc: serde_json::Value = serde_json::from_str(&super::json::to_json(&e)).unwrap();
    assert_eq!(doc["net"]["outputs"], serde_json::json!([0, 1, 2]));
    assert_eq!(doc["outputs"], e.outputs.as_str());
    assert!(doc.get("wheels").is_none() && doc["net"].get("wheels").is_none());
    // The ONNX model's outputs: `outputs` alone for a plain network.
    let onnx = super::onnx::to_onnx(&e);
    let has = |name: &[u8]| onnx.windows(name.len()).any(|w| w == name);
    assert!(has(b"output_index") && has(b"outputs") && !has(b"wheels"));
}
