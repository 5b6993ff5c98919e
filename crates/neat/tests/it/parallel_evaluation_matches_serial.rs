//! Evaluating with one thread or several gives the same fitness and the same run.

use vivae_neat::{FeedForwardNetwork, GenomeSpec, NeatParams, Network, Population};

fn run(threads: usize) -> Population {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut pop = Population::new(NeatParams::default(), GenomeSpec::cppn(), 7).unwrap();
        for _ in 0..10 {
            pop.evaluate(|g, ctx| {
                let mut net = FeedForwardNetwork::from_genome(g);
                let mut out = [0.0; 3];
                let x = (ctx.seed % 1000) as f64 / 1000.0;
                net.activate(&[x, -x, 0.5, 0.25, 1.0], &mut out);
                out.iter().sum::<f64>()
            });
            pop.next_generation();
        }
        pop
    })
}

#[test]
fn one_thread_equals_four_threads() {
    let serial = run(1);
    let parallel = run(4);
    assert_eq!(serial, parallel);
}
