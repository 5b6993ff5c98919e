//! The efficacy examples' task scorers (`examples/common/*_task.rs`): a
//! hand-written perfect solution reaches each task's known maximum, and a
//! wrong one scores less.

#[path = "../../examples/common/mux_task.rs"]
mod mux_task;
#[path = "../../examples/common/prey_task.rs"]
mod prey_task;
#[path = "../../examples/common/sine_task.rs"]
mod sine_task;

use vivae_neat::{Network, math};

/// A network given by a function of its inputs and a step counter.
struct Scripted<F> {
    inputs: usize,
    outputs: usize,
    step: usize,
    f: F,
}

impl<F: FnMut(&[f64], usize, &mut [f64])> Network for Scripted<F> {
    fn num_inputs(&self) -> usize {
        self.inputs
    }
    fn num_outputs(&self) -> usize {
        self.outputs
    }
    fn activate(&mut self, inputs: &[f64], outputs: &mut [f64]) {
        (self.f)(inputs, self.step, outputs);
        self.step += 1;
    }
    fn reset(&mut self) {
        self.step = 0;
    }
}

fn scripted<F>(inputs: usize, outputs: usize, f: F) -> Scripted<F> {
    Scripted {
        inputs,
        outputs,
        step: 0,
        f,
    }
}

#[test]
fn multiplexer_gives_2048_to_the_multiplexer_and_less_to_a_guess() {
    let mut perfect = scripted(12, 1, |x: &[f64], _, y: &mut [f64]| {
        let address = (x[1] + 2.0 * x[2] + 4.0 * x[3]) as usize;
        y[0] = x[4 + address];
    });
    assert_eq!(mux_task::mux_fitness(&mut perfect), 2048.0);
    let mut half = scripted(12, 1, |_: &[f64], _, y: &mut [f64]| y[0] = 0.5);
    assert_eq!(mux_task::mux_fitness(&mut half), 2048.0 * 0.75);
    // Wrong on exactly the cases whose address is 0: 256 cases lose 1 each.
    let mut one_wrong = scripted(12, 1, |x: &[f64], _, y: &mut [f64]| {
        let address = (x[1] + 2.0 * x[2] + 4.0 * x[3]) as usize;
        y[0] = if address == 0 {
            1.0 - x[4]
        } else {
            x[4 + address]
        };
    });
    assert_eq!(mux_task::mux_fitness(&mut one_wrong), 2048.0 - 256.0);
}

/// The example's lane scorer gives the bits of the one-case-at-a-time one
/// on evolved-looking networks (hidden nodes, links of every sign).
#[test]
fn multiplexer_lanes_give_the_bits_of_single_cases() {
    use rand::SeedableRng;
    use vivae_neat::mutation::{mutate_add_link, mutate_add_node, mutate_weights};
    use vivae_neat::{FeedForwardNetwork, Genome, GenomeSpec, InnovationTracker, NeatParams};
    let (spec, params) = (GenomeSpec::plain(12, 1), NeatParams::plain_neat());
    let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
    let mut tracker = InnovationTracker::new(13);
    let mut scratch = Vec::new();
    for _ in 0..20 {
        let mut g = Genome::minimal(&spec, &params, &mut tracker, &mut rng);
        for _ in 0..6 {
            mutate_add_node(&mut g, &spec, &mut tracker, &mut rng);
            mutate_add_link(&mut g, &spec, &params, &mut tracker, &mut rng);
            mutate_weights(&mut g, &params, &mut rng);
        }
        let mut net = FeedForwardNetwork::from_genome(&g);
        let lanes = mux_task::mux_fitness_lanes(&net, &mut scratch);
        assert_eq!(lanes.to_bits(), mux_task::mux_fitness(&mut net).to_bits());
    }
}

#[test]
fn sinewave_gives_1000_to_the_sine_and_less_to_a_flat_line() {
    let sine = sine_task::Sine::new();
    let (mid, scale) = (sine.mid, sine.scale);
    let mut perfect = scripted(1, 1, move |_: &[f64], step: usize, y: &mut [f64]| {
        let k = step.saturating_sub(3);
        let x = 25.132_741_23 / 79.0 * k as f64;
        y[0] = (math::sin(x) - mid) / scale + 0.5;
    });
    let best = sine.fitness(&mut perfect);
    assert!((best - 1000.0).abs() < 1e-6, "perfect sine scored {best}");
    let mut flat = scripted(1, 1, |_: &[f64], _, y: &mut [f64]| y[0] = 0.5);
    assert!(sine.fitness(&mut flat) < 100.0);
    let mut runaway = scripted(1, 1, |_: &[f64], _, y: &mut [f64]| y[0] = f64::INFINITY);
    assert_eq!(sine.fitness(&mut runaway), 0.0);
}

/// The example's lane scorer gives each genome the fitness its network
/// scores alone, with its own trials' seed: start networks and grown
/// recurrent ones side by side, more genomes than lanes (so finished lanes
/// take the next genome mid-run), at several lane counts.
#[test]
fn prey_capture_lanes_give_each_genome_its_fitness_alone() {
    use rand::SeedableRng;
    use vivae_neat::mutation::{mutate_add_link, mutate_add_node, mutate_weights};
    use vivae_neat::{
        Genome, GenomeSpec, InnovationTracker, NeatParams, RecurrentLanes, RecurrentNetwork,
    };
    let spec = GenomeSpec {
        allow_recurrent: true,
        ..GenomeSpec::plain(14, 4)
    };
    let params = NeatParams::plain_neat();
    let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
    let mut tracker = InnovationTracker::new(18);
    let genomes: Vec<Genome> = (0..40)
        .map(|i| {
            let mut g = Genome::minimal(&spec, &params, &mut tracker, &mut rng);
            for _ in 0..i % 5 {
                mutate_add_node(&mut g, &spec, &mut tracker, &mut rng);
                mutate_weights(&mut g, &params, &mut rng);
            }
            // Links among the hidden and output nodes too, loops and
            // cycles among them: state that carries from step to step.
            for _ in 0..12 * (i % 5) {
                mutate_add_link(&mut g, &spec, &params, &mut tracker, &mut rng);
            }
            g
        })
        .collect();
    let seeds: Vec<u64> = (0..genomes.len() as u64).map(|i| 1000 + 7 * i).collect();
    let world = prey_task::SHARPNEAT_PREY;
    let alone: Vec<f64> = genomes
        .iter()
        .zip(&seeds)
        .map(|(g, &s)| world.fitness(&mut RecurrentNetwork::from_genome(g), s))
        .collect();
    // Not a degenerate case: the networks catch different numbers of prey.
    let distinct: std::collections::BTreeSet<u64> = alone.iter().map(|f| f.to_bits()).collect();
    assert!(distinct.len() >= 4, "fitnesses {alone:?}");
    for capacity in [1, 3, prey_task::PREY_LANES] {
        let mut lanes = RecurrentLanes::new(capacity);
        let mut out = vec![-1.0];
        world.fitness_lanes(&genomes, &seeds, &mut lanes, &mut out);
        assert_eq!(out[0], -1.0, "what was in `out` stays");
        assert_eq!(
            out[1..].iter().map(|f| f.to_bits()).collect::<Vec<_>>(),
            alone.iter().map(|f| f.to_bits()).collect::<Vec<_>>(),
            "{capacity} lanes"
        );
    }
}

/// Moves towards the sector the prey is sensed in (north first on diagonals).
fn chase(x: &[f64], _: usize, y: &mut [f64]) {
    y.fill(0.0);
    // Sectors 1..=8 are NE, N, NW, W, SW, S, SE, E; outputs are N, E, S, W.
    const MOVE: [usize; 8] = [0, 0, 3, 3, 2, 2, 1, 1];
    if let Some(s) = (1..9).find(|&s| x[s] == 1.0) {
        y[MOVE[s - 1]] = 1.0;
    }
}

#[test]
fn prey_capture_catches_a_still_prey_every_trial_only_when_chasing() {
    let still = prey_task::Prey {
        speed: 0.0,
        ..prey_task::SHARPNEAT_PREY
    };
    assert_eq!(still.fitness(&mut scripted(14, 4, chase), 7), 100.0);
    let idle = |_: &[f64], _, y: &mut [f64]| y.fill(0.0);
    assert_eq!(still.fitness(&mut scripted(14, 4, idle), 7), 0.0);
    let tied = |_: &[f64], _, y: &mut [f64]| y.fill(1.0);
    assert_eq!(still.fitness(&mut scripted(14, 4, tied), 7), 0.0);
    let moving = prey_task::SHARPNEAT_PREY;
    let caught = moving.fitness(&mut scripted(14, 4, chase), 7);
    assert!(caught > 0.0 && caught <= 100.0, "caught {caught}");
    assert_eq!(caught, moving.fitness(&mut scripted(14, 4, chase), 7));
}
