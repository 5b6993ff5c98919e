//! The `xor` pack: NEAT on XOR (Stanley & Miikkulainen 2002), the run of
//! `cargo run -p vivae-neat --example xor` (`vivae_neat::benchmarks::xor`).

use vivae_neat::NeatParams;
use vivae_neat::benchmarks::xor::run_xor;

use crate::error::Result;
use crate::reproduce::{Options, Pack, Table, stats, thousands};

/// Generations before a run counts as unsolved (the example's).
const MAX_GENERATIONS: u32 = 500;

/// `vivae reproduce xor`.
pub const XOR: Pack = Pack {
    name: "xor",
    what: "NEAT on XOR (Stanley & Miikkulainen 2002): 100 runs of population 150",
    methods: super::pack::no_methods,
    run,
};

fn run(o: &Options, progress: &mut dyn FnMut(&str)) -> Result<Table> {
    let runs = o.runs.unwrap_or(if o.quick { 20 } else { 100 });
    let generations = o
        .evaluations
        .map_or(MAX_GENERATIONS, |e| e.div_ceil(150) as u32);
    let params = NeatParams::plain_neat();
    let (mut evals, mut hidden) = (Vec::new(), Vec::new());
    for k in 0..runs {
        let seed = o.seed + k as u64;
        let result = run_xor(&params, seed, generations);
        let said = result.map_or("unsolved".into(), |(e, h)| {
            format!("solved after {e} evaluations, {h} hidden")
        });
        progress(&format!("xor seed {seed}: {said}"));
        if let Some((e, h)) = result {
            evals.push(e as u64);
            hidden.push(h as f64);
        }
    }
    let ours = stats(&evals);
    let mean_hidden = hidden.iter().sum::<f64>() / hidden.len().max(1) as f64;
    let fmt = |(m, sd, _): (f64, f64, f64)| format!("{} ({})", thousands(m), thousands(sd));
    Ok(Table::new(
        "XOR (Stanley & Miikkulainen 2002), ours beside the paper's",
        &[
            "method",
            "ours: solved",
            "ours: mean evaluations (sd)",
            "ours: median",
            "ours: mean hidden nodes",
            "paper: solved",
            "paper: mean evaluations (sd)",
            "paper: mean hidden nodes",
            "source",
        ],
        vec![vec![
            "NEAT, population 150".into(),
            format!("{}/{runs}", evals.len()),
            ours.map_or("—".into(), fmt),
            ours.map_or("—".into(), |(_, _, med)| thousands(med)),
            if hidden.is_empty() {
                "—".into()
            } else {
                format!("{mean_hidden:.2}")
            },
            "100/100".into(),
            "4,755 (2,553)".into(),
            "2.35".into(),
            "Stanley & Miikkulainen 2002, Evol. Comput. 10(2):99–127, Sec. 4.2, p. 112".into(),
        ]],
        vec![
            format!(
                "ours: {runs} runs, seeds {}–{}, at most {generations} generations a run, NeatParams::plain_neat; evaluations up to and including the first solver",
                o.seed,
                o.seed + runs as u64 - 1
            ),
            "the same runs: cargo run --release -p vivae-neat --example xor -- --runs N --seed S"
                .into(),
        ],
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_xor_pack_counts_the_examples_runs_beside_stanleys() {
        let options = Options {
            runs: Some(3),
            seed: 1,
            ..Options::default()
        };
        let mut lines = 0;
        let t = crate::reproduce::run("xor", &options, &mut |_| lines += 1).unwrap();
        assert_eq!(lines, 3);
        let row = &t.rows[0];
        assert_eq!(row.len(), t.columns.len());
        let evals: Vec<u64> = (1..=3)
            .filter_map(|s| run_xor(&NeatParams::plain_neat(), s, 500).map(|r| r.0 as u64))
            .collect();
        assert_eq!(row[1], format!("{}/3", evals.len()));
        let (mean, _, _) = stats(&evals).unwrap();
        assert!(row[2].starts_with(&thousands(mean)), "{row:?}");
        assert_eq!(row[5..8], ["100/100", "4,755 (2,553)", "2.35"]);
    }
}
