//! The `retina` pack: the left & right retina problem (Verbancsics &
//! Stanley 2011; Risi & Stanley 2012), plain HyperNEAT against HyperNEAT
//! with LEO and the locality seed; the runs of `cargo run -p vivae-neat
//! --example retina` (`vivae_neat::benchmarks::retina`;
//! docs/hyperneat-benchmarks.md).

use vivae_neat::NeatParams;
use vivae_neat::benchmarks::retina::{Mode, Pixels, RetinaRun, Substrate, run};

use crate::error::{Error, Result};
use crate::reproduce::{Options, Pack, Table, stats, thousands};

/// `vivae reproduce retina`.
pub const RETINA: Pack = Pack {
    name: "retina",
    what: "the left & right retina problem (Verbancsics & Stanley 2011): HyperNEAT vs HyperNEAT-LEO with the locality seed",
    methods: super::pack::no_methods,
    run: run_pack,
};

/// The modes compared, as the example names them, and the published
/// claim each row is read against.
const MODES: [(Mode, &str, &str); 2] = [
    (Mode::HyperNeat, "hyperneat", "not verified (text not read)"),
    (
        Mode::LeoSeed,
        "leo-seed",
        "not verified (text not read); the papers' direction: LEO with the seed solves more often than plain HyperNEAT",
    ),
];

fn run_pack(o: &Options, progress: &mut dyn FnMut(&str)) -> Result<Table> {
    let runs = o.runs.unwrap_or(if o.quick { 5 } else { 20 });
    let params = NeatParams::paper_cppn();
    let population = params.population_size as u64;
    let generations = o.evaluations.map_or(if o.quick { 100 } else { 500 }, |e| {
        u32::try_from(e.div_ceil(population)).unwrap_or(u32::MAX)
    });
    let sub = Substrate::default();
    let mut rows = Vec::new();
    for (mode, flag, paper) in MODES {
        let mut results = Vec::new();
        for k in 0..runs {
            let seed = o.seed + k as u64;
            let r = run(&params, mode, &sub, Pixels::ZeroOne, seed, generations)
                .map_err(|e| Error::Invalid(format!("retina: {e}")))?;
            progress(&format!(
                "retina {flag} seed {seed}: {}; best accuracy {:.3}",
                r.evals.map_or("unsolved".into(), |e| format!(
                    "solved after {e} evaluations"
                )),
                r.best_right as f64 / 512.0
            ));
            results.push(r);
        }
        rows.push(row(flag, paper, &results));
    }
    Ok(Table::new(
        "The left & right retina problem (HyperNEAT), ours beside the papers'",
        &[
            "mode",
            "ours: solved (all 512 answers right)",
            "ours: mean evaluations (sd)",
            "ours: mean best accuracy",
            "ours: mean substrate hidden nodes",
            "paper",
            "source",
        ],
        rows,
        vec![
            format!(
                "ours: {runs} runs a mode, seeds {}–{}, population {population} (NeatParams::paper_cppn), at most {generations} generations, the retina on a line, 0/1 pixels; best accuracy = the best share of the 512 answers any genome got right, mean over runs",
                o.seed,
                o.seed + runs as u64 - 1
            ),
            format!(
                "the same runs: cargo run --release -p vivae-neat --example retina -- --mode hyperneat|leo-seed --runs {runs} --seed {} --max-generations {generations}",
                o.seed
            ),
            "the papers (Verbancsics & Stanley 2011, GECCO; Risi & Stanley 2012, Artificial Life 18(4)) could not be read here: no published number is quoted. The public reproduction AHNI runs 30 runs of 2,500 generations of 500 (1,250,000 evaluations a run) on a 3-D substrate with ±3 pixels (docs/hyperneat-benchmarks.md)".into(),
        ],
    ))
}

fn row(flag: &str, paper: &str, results: &[RetinaRun]) -> Vec<String> {
    let evals: Vec<u64> = results
        .iter()
        .filter_map(|r| r.evals)
        .map(|e| e as u64)
        .collect();
    let n = results.len().max(1) as f64;
    vec![
        flag.into(),
        format!("{}/{}", evals.len(), results.len()),
        stats(&evals).map_or("—".into(), |(m, sd, _)| {
            format!("{} ({})", thousands(m), thousands(sd))
        }),
        format!(
            "{:.3}",
            results
                .iter()
                .map(|r| r.best_right as f64 / 512.0)
                .sum::<f64>()
                / n
        ),
        format!(
            "{:.1}",
            results
                .iter()
                .map(|r| r.substrate_hidden as f64)
                .sum::<f64>()
                / n
        ),
        paper.into(),
        "Verbancsics & Stanley 2011; Risi & Stanley 2012".into(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_retina_pack_runs_both_modes_and_quotes_no_unread_number() {
        let options = Options {
            runs: Some(1),
            evaluations: Some(200),
            ..Options::default()
        };
        let mut lines = 0;
        let t = crate::reproduce::run("retina", &options, &mut |_| lines += 1).unwrap();
        assert_eq!(lines, 2);
        let direct = run(
            &NeatParams::paper_cppn(),
            Mode::LeoSeed,
            &Substrate::default(),
            Pixels::ZeroOne,
            1,
            2,
        )
        .unwrap();
        assert_eq!(t.rows[1], row("leo-seed", MODES[1].2, &[direct]));
        assert!(t.rows.iter().all(|r| r.len() == t.columns.len()));
        assert!(t.markdown().contains("not verified"));
    }
}
