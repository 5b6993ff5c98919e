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

/// The pole speed examples' main: fixed-length runs of the library's task, never stopped early.
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
    // An infinite target: a run that balances keeps evaluating until its time is up.
    if let Some(line) = crate::efficacy::sample(name, title, params, &spec, f64::INFINITY, task) {
        println!("{line}");
        println!("{}", steps_line(name, clock.elapsed().as_secs_f64()));
    }
}
