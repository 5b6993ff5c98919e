//! The library's double pole task (`vivae_neat::benchmarks::pole::score`) as
//! the speed examples score it, with a count of the network activations
//! (control steps), so that a reader can see how much work an evaluation did.
//! Wieland's equations, 4th-order Runge–Kutta in 0.01 s steps, the action
//! held for two of them; failure at |x| > 2.4 m or a pole beyond
//! ±36°. Markov: 6 scaled inputs and a bias of 0.5, fitness = steps balanced
//! (at most 100,000). Non-Markov: x, θ1, θ2 and the bias, Gruau's damping
//! fitness over at most 1,000 steps.

use std::sync::atomic::{AtomicU64, Ordering};

use vivae_neat::Network;
use vivae_neat::benchmarks::pole::{State, score};

/// Network activations over all evaluations so far.
pub static STEPS: AtomicU64 = AtomicU64::new(0);
/// Evaluations so far.
pub static EVALS: AtomicU64 = AtomicU64::new(0);

/// The library's fitness of `net` from `start`, counting its activations.
pub fn fitness(net: &mut impl Network, markov: bool, start: State) -> f64 {
    let (f, steps) = score(net, markov, start);
    STEPS.fetch_add(u64::from(steps), Ordering::Relaxed);
    EVALS.fetch_add(1, Ordering::Relaxed);
    f
}

/// `name: steps_per_eval=... steps_per_s=...` over `seconds` of runs.
pub fn steps_line(name: &str, seconds: f64) -> String {
    let steps = STEPS.load(Ordering::Relaxed) as f64;
    let evals = EVALS.load(Ordering::Relaxed).max(1) as f64;
    format!(
        "{name}: steps_per_eval={:.1} steps_per_s={:.0}",
        steps / evals,
        steps / seconds.max(1e-9)
    )
}

/// The task scored a group of genomes at a time, their trials side by side
/// as vector lanes (`benchmarks::pole_lanes`: the bits of one at a time).
#[derive(Clone)]
pub struct PoleLanes {
    /// With velocities (feed-forward networks) or without (recurrent).
    pub markov: bool,
    /// The start state.
    pub start: State,
}

impl vivae_neat::driver::GroupTask for PoleLanes {
    fn group_size(&self) -> usize {
        // Enough trials to keep the lanes full while short ones end (256:
        // as fast as the whole population, and still a group per thread).
        16 * vivae_neat::benchmarks::pole_lanes::LANES
    }

    fn evaluate_group(
        &self,
        genomes: &[vivae_neat::Genome],
        _: &[vivae_neat::EvalContext],
        out: &mut Vec<vivae_neat::driver::Evaluation>,
    ) {
        use std::cell::RefCell;
        use vivae_neat::benchmarks::pole_lanes::score_lanes;
        use vivae_neat::driver::Evaluation;
        use vivae_neat::{FeedForwardNetwork, RecurrentNetwork};
        // Networks recompiled in place group after group (no allocation once warm).
        thread_local! {
            static SCORES: RefCell<Vec<(f64, u32)>> = const { RefCell::new(Vec::new()) };
            static FF: RefCell<Vec<FeedForwardNetwork>> = const { RefCell::new(Vec::new()) };
            static REC: RefCell<Vec<RecurrentNetwork>> = const { RefCell::new(Vec::new()) };
        }
        SCORES.with_borrow_mut(|scores| {
            if self.markov {
                FF.with_borrow_mut(|nets| {
                    recompile(nets, genomes, FeedForwardNetwork::from_genome, |n, g| {
                        n.recompile(g)
                    });
                    score_lanes(&mut nets[..genomes.len()], true, self.start, scores);
                });
            } else {
                REC.with_borrow_mut(|nets| {
                    recompile(nets, genomes, RecurrentNetwork::from_genome, |n, g| {
                        n.recompile(g)
                    });
                    score_lanes(&mut nets[..genomes.len()], false, self.start, scores);
                });
            }
            for &(f, steps) in scores.iter() {
                STEPS.fetch_add(u64::from(steps), Ordering::Relaxed);
                EVALS.fetch_add(1, Ordering::Relaxed);
                out.push(Evaluation::fitness(f));
            }
        })
    }
}

/// Makes `nets[i]` the network of `genomes[i]`, recompiling those there are.
fn recompile<N>(
    nets: &mut Vec<N>,
    genomes: &[vivae_neat::Genome],
    build: impl Fn(&vivae_neat::Genome) -> N,
    again: impl Fn(&mut N, &vivae_neat::Genome),
) {
    for (i, g) in genomes.iter().enumerate() {
        match nets.get_mut(i) {
            Some(n) => again(n, g),
            None => nets.push(build(g)),
        }
    }
}

/// The pole speed examples' main: fixed-length runs of the library's task,
/// never stopped early; trials side by side unless `--one-at-a-time`.
pub fn speed_main(name: &str, title: &str, markov: bool) {
    use std::cell::RefCell;
    use vivae_neat::benchmarks::pole::{pole_params, spec, start_state};
    use vivae_neat::{EvalContext, FeedForwardNetwork, Genome};
    let start = start_state(markov, 4.5);
    let task = |g: &Genome, _: &EvalContext| {
        if !markov {
            return crate::common::with_recurrent(g, |net| fitness(net, false, start));
        }
        // One network per thread, recompiled in place for each genome.
        thread_local! {
            static NET: RefCell<Option<FeedForwardNetwork>> = const { RefCell::new(None) };
        }
        NET.with_borrow_mut(|slot| {
            let net = slot.get_or_insert_with(|| FeedForwardNetwork::from_genome(g));
            net.recompile(g);
            fitness(net, true, start)
        })
    };
    let clock = std::time::Instant::now();
    let (params, spec) = (pole_params(markov), spec(markov));
    let alone = std::env::args().any(|a| a == "--one-at-a-time");
    // An infinite target: a run that balances keeps evaluating until its time is up.
    let line = if alone {
        crate::efficacy::sample(name, title, params, &spec, f64::INFINITY, task)
    } else {
        let lanes = PoleLanes { markov, start };
        crate::efficacy::sample_grouped(name, title, params, &spec, f64::INFINITY, lanes)
    };
    if let Some(line) = line {
        println!("{line}");
        println!("{}", steps_line(name, clock.elapsed().as_secs_f64()));
    }
}
