//! NEAT benchmarks: CPPN activation, recurrent activation, one generation of
//! reproduction, one whole XOR run, and the efficacy examples' evaluation
//! paths (the multiplexer one case at a time against 16 as lanes, a
//! recurrent network built per genome against recompiled in place, the
//! sinewave one network at a time against 8 side by side as lanes, one prey
//! capture evaluation, a first double-pole generation one trial at a time
//! against its trials as lanes).

use divan::{Bencher, black_box};
use rand::SeedableRng;
use rand_pcg::Pcg64;
use vivae_neat::mutation::{mutate_add_link, mutate_add_node};
use vivae_neat::{
    FeedForwardNetwork, Genome, GenomeSpec, InnovationTracker, NeatParams, Network, Population,
    RecurrentLanes, RecurrentNetwork,
};

#[path = "../examples/common/mux_task.rs"]
mod mux_task;
#[path = "../examples/common/prey_task.rs"]
mod prey_task;
#[path = "../examples/common/sine_task.rs"]
mod sine_task;
#[path = "../examples/common/xor_task.rs"]
mod xor_task;

fn main() {
    divan::main();
}

/// A grown genome: the minimal one plus `nodes` add-node and `2·nodes` add-link mutations.
fn grown(spec: &GenomeSpec, nodes: usize) -> Genome {
    let params = NeatParams::default();
    let mut rng = Pcg64::seed_from_u64(11);
    let mut t = InnovationTracker::new((spec.inputs + spec.outputs) as u32);
    let mut g = Genome::minimal(spec, &params, &mut t, &mut rng);
    for _ in 0..nodes {
        mutate_add_node(&mut g, spec, &mut t, &mut rng);
        mutate_add_link(&mut g, spec, &params, &mut t, &mut rng);
        mutate_add_link(&mut g, spec, &params, &mut t, &mut rng);
    }
    g
}

/// One CPPN query (5 inputs, 3 outputs) — what HyperNEAT decoding does per connection.
#[divan::bench(args = [0, 10, 30])]
fn cppn_activate(bencher: Bencher, hidden: usize) {
    let mut net = FeedForwardNetwork::from_genome(&grown(&GenomeSpec::cppn(), hidden));
    let mut out = [0.0; 3];
    let mut x = 0.0f64;
    bencher.bench_local(|| {
        x += 0.001;
        net.activate(black_box(&[x, 0.3, -0.2, 0.7, 1.0]), &mut out);
        black_box(out[0])
    });
}

/// A grown recurrent genome (5 inputs, 3 outputs, `hidden` hidden nodes).
fn recurrent_genome(hidden: usize) -> Genome {
    let spec = GenomeSpec {
        allow_recurrent: true,
        ..GenomeSpec::cppn()
    };
    grown(&spec, hidden)
}

/// One synchronous update of a recurrent network with `hidden` hidden nodes.
#[divan::bench(args = [0, 10, 30])]
fn recurrent_activate(bencher: Bencher, hidden: usize) {
    let mut net = RecurrentNetwork::from_genome(&recurrent_genome(hidden));
    let mut out = [0.0; 3];
    bencher.bench_local(|| {
        net.activate(black_box(&[0.1, 0.3, -0.2, 0.7, 1.0]), &mut out);
        black_box(out[0])
    });
}

/// One generation of reproduction (speciation, sharing, crossover, mutation) of an
/// evaluated CPPN population that has evolved for 20 generations.
#[divan::bench(args = [100, 1000], sample_count = 10)]
fn reproduction(bencher: Bencher, size: usize) {
    let params = NeatParams {
        population_size: size,
        ..NeatParams::default()
    };
    let mut pop = Population::new(params, GenomeSpec::cppn(), 3).unwrap();
    let fit = |g: &Genome| g.links().iter().map(|l| l.weight.sin()).sum::<f64>();
    for _ in 0..20 {
        pop.evaluate(|g, _| fit(g));
        pop.next_generation();
    }
    pop.evaluate(|g, _| fit(g));
    bencher
        .with_inputs(|| pop.clone())
        .bench_local_values(|mut p| {
            p.next_generation();
            p
        });
}

/// One whole XOR run of the `xor` example (Stanley's settings, population 150)
/// with seed 1: evaluation, speciation and reproduction until it solves
/// (after 2,468 evaluations: 16 generations and 68 genomes of the 17th;
/// the mean over the example's 100 seeds is 4,130).
#[divan::bench(sample_count = 20)]
fn xor_run(bencher: Bencher) {
    let params = NeatParams::plain_neat();
    bencher.bench_local(|| xor_task::run_xor(black_box(&params), black_box(1), 500));
}

/// A multiplexer network as the example evolves them (12 inputs, 1 output, `hidden` hidden nodes).
fn mux_genome(hidden: usize) -> Genome {
    grown(&GenomeSpec::plain(12, 1), hidden)
}

/// One multiplexer evaluation (2,048 cases), one case at a time.
#[divan::bench(args = [0, 5])]
fn mux_fitness_single(bencher: Bencher, hidden: usize) {
    let mut net = FeedForwardNetwork::from_genome(&mux_genome(hidden));
    bencher.bench_local(|| black_box(mux_task::mux_fitness(&mut net)));
}

/// The same evaluation, 16 cases as the lanes of one pass (the example's path; same bits).
#[divan::bench(args = [0, 5])]
fn mux_fitness_lanes(bencher: Bencher, hidden: usize) {
    let net = FeedForwardNetwork::from_genome(&mux_genome(hidden));
    let mut scratch = Vec::new();
    bencher.bench_local(|| black_box(mux_task::mux_fitness_lanes(&net, &mut scratch)));
}

/// A recurrent network built for a genome with `hidden` hidden nodes.
#[divan::bench(args = [0, 10, 30])]
fn recurrent_from_genome(bencher: Bencher, hidden: usize) {
    let g = recurrent_genome(hidden);
    bencher.bench_local(|| black_box(RecurrentNetwork::from_genome(black_box(&g))));
}

/// The same network recompiled in place in a reused one (the efficacy examples' path).
#[divan::bench(args = [0, 10, 30])]
fn recurrent_recompile(bencher: Bencher, hidden: usize) {
    let g = recurrent_genome(hidden);
    let mut net = RecurrentNetwork::from_genome(&g);
    bencher.bench_local(|| {
        net.recompile(black_box(&g));
        black_box(net.num_outputs())
    });
}

/// Eight sinewave networks as the example evolves them (1 input, 1 output,
/// recurrent, `hidden` hidden nodes; different weights each).
fn sine_genomes(hidden: usize) -> Vec<Genome> {
    let spec = GenomeSpec {
        allow_recurrent: true,
        ..GenomeSpec::plain(1, 1)
    };
    let params = NeatParams::default();
    let mut rng = Pcg64::seed_from_u64(5);
    let mut t = InnovationTracker::new(2);
    (0..sine_task::MAX_LANES)
        .map(|_| {
            let mut g = Genome::minimal(&spec, &params, &mut t, &mut rng);
            for _ in 0..hidden {
                mutate_add_node(&mut g, &spec, &mut t, &mut rng);
                mutate_add_link(&mut g, &spec, &params, &mut t, &mut rng);
            }
            g
        })
        .collect()
}

/// Eight sinewave evaluations (83 steps each), one network at a time.
#[divan::bench(args = [0, 3])]
fn sine_fitness_single(bencher: Bencher, hidden: usize) {
    let genomes = sine_genomes(hidden);
    let sine = sine_task::Sine::new();
    let mut net = RecurrentNetwork::from_genome(&genomes[0]);
    bencher.bench_local(|| {
        let mut f = 0.0;
        for g in &genomes {
            net.recompile(g);
            f += sine.fitness(&mut net);
        }
        black_box(f)
    });
}

/// The same eight evaluations side by side as lanes (the example's path; same bits).
#[divan::bench(args = [0, 3])]
fn sine_fitness_lanes(bencher: Bencher, hidden: usize) {
    let genomes = sine_genomes(hidden);
    let sine = sine_task::Sine::new();
    let mut lanes = RecurrentLanes::new(sine_task::MAX_LANES);
    let mut out = Vec::new();
    bencher.bench_local(|| {
        lanes.recompile(&genomes);
        out.clear();
        sine.fitness_lanes(&mut lanes, &mut out);
        black_box(out.iter().sum::<f64>())
    });
}

/// One prey capture evaluation (100 trials of up to 70 steps) of a start
/// network (14 inputs, 4 outputs, 56 links), the like-for-like network.
#[divan::bench(sample_count = 50)]
fn prey_fitness(bencher: Bencher) {
    let spec = GenomeSpec {
        allow_recurrent: true,
        ..GenomeSpec::plain(14, 4)
    };
    let mut net = RecurrentNetwork::from_genome(&grown(&spec, 0));
    bencher.bench_local(|| black_box(prey_task::SHARPNEAT_PREY.fitness(&mut net, black_box(7))));
}

/// Sixteen start networks of prey capture (14 inputs, 4 outputs, 56 links;
/// different weights each), the like-for-like networks.
fn prey_genomes() -> Vec<Genome> {
    let spec = GenomeSpec {
        allow_recurrent: true,
        ..GenomeSpec::plain(14, 4)
    };
    let params = NeatParams::default();
    let mut rng = Pcg64::seed_from_u64(5);
    let mut t = InnovationTracker::new(18);
    (0..prey_task::PREY_LANES)
        .map(|_| Genome::minimal(&spec, &params, &mut t, &mut rng))
        .collect()
}

/// Sixteen prey capture evaluations, one network at a time.
#[divan::bench(sample_count = 20)]
fn prey_fitness_16_single(bencher: Bencher) {
    let genomes = prey_genomes();
    let mut net = RecurrentNetwork::from_genome(&genomes[0]);
    bencher.bench_local(|| {
        let mut f = 0.0;
        for (i, g) in genomes.iter().enumerate() {
            net.recompile(g);
            f += prey_task::SHARPNEAT_PREY.fitness(&mut net, i as u64);
        }
        black_box(f)
    });
}

/// The same sixteen evaluations side by side as lanes (the example's path; same bits).
#[divan::bench(sample_count = 20)]
fn prey_fitness_16_lanes(bencher: Bencher) {
    let genomes = prey_genomes();
    let seeds: Vec<u64> = (0..genomes.len() as u64).collect();
    let mut lanes = RecurrentLanes::new(prey_task::PREY_LANES);
    let mut out = Vec::new();
    bencher.bench_local(|| {
        out.clear();
        prey_task::SHARPNEAT_PREY.fitness_lanes(&genomes, &seeds, &mut lanes, &mut out);
        black_box(out.iter().sum::<f64>())
    });
}

/// A first generation of the double pole (`markov`: with velocities,
/// population 150; without: 1,000), built from seed 1.
fn pole_generation(markov: bool) -> Vec<Genome> {
    use vivae_neat::benchmarks::pole::{pole_params, spec};
    let pop = Population::new(pole_params(markov), spec(markov), 1).expect("valid parameters");
    pop.genomes().to_vec()
}

/// Scoring a first pole generation one trial at a time (`pole::score` per genome).
#[divan::bench(args = [false, true], sample_count = 20)]
fn pole_generation_one_at_a_time(bencher: Bencher, markov: bool) {
    use vivae_neat::benchmarks::pole::{score, start_state};
    let genomes = pole_generation(markov);
    let start = start_state(markov, 4.5);
    bencher.bench_local(|| {
        let mut sum = 0.0;
        for g in &genomes {
            sum += if markov {
                score(&mut FeedForwardNetwork::from_genome(g), true, start).0
            } else {
                score(&mut RecurrentNetwork::from_genome(g), false, start).0
            };
        }
        black_box(sum)
    });
}

/// The same generation's trials side by side as lanes (`pole_lanes::score_lanes`; same bits).
#[divan::bench(args = [false, true], sample_count = 20)]
fn pole_generation_lanes(bencher: Bencher, markov: bool) {
    use vivae_neat::benchmarks::pole::start_state;
    use vivae_neat::benchmarks::pole_lanes::score_lanes;
    let genomes = pole_generation(markov);
    let start = start_state(markov, 4.5);
    let mut out = Vec::new();
    bencher.bench_local(|| {
        if markov {
            let mut nets: Vec<_> = genomes
                .iter()
                .map(FeedForwardNetwork::from_genome)
                .collect();
            score_lanes(&mut nets, true, start, &mut out);
        } else {
            let mut nets: Vec<_> = genomes.iter().map(RecurrentNetwork::from_genome).collect();
            score_lanes(&mut nets, false, start, &mut out);
        }
        black_box(out.iter().map(|o| o.0).sum::<f64>())
    });
}
