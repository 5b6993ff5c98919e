//! What the benchmark examples share: one run's result, parameter overrides
//! and the summary line over many runs.

use std::time::Instant;

use vivae_neat::{NeatParams, stats};

/// The outcome of one run.
pub struct RunResult {
    /// Evaluations until the first solving genome, `None` when unsolved.
    pub evals: Option<usize>,
    /// Hidden nodes of the solving genome.
    pub hidden: usize,
}

/// Applies `field=value` (value in JSON) to the parameters, for experiments.
pub fn override_param(params: &NeatParams, kv: &str) -> NeatParams {
    let (k, v) = kv.split_once('=').expect("--set needs field=json_value");
    let mut json = serde_json::to_value(params).expect("params serialise");
    json[k] = serde_json::from_str(v).expect("value must be JSON");
    let p: NeatParams = serde_json::from_value(json).expect("known field");
    p.validate().expect("valid value");
    p
}

/// Runs `run(seed + r)` for `r` in `0..runs` and returns the summary line
/// `NAME: solved=S/RUNS mean_evals=M median_evals=D mean_hidden=H mean_ms=T`.
pub fn summarize(
    name: &str,
    runs: usize,
    seed: u64,
    mut run: impl FnMut(u64) -> RunResult,
) -> String {
    let mut evals = Vec::new();
    let mut hidden = 0usize;
    let mut total_ms = 0.0;
    for r in 0..runs {
        let t = Instant::now();
        let res = run(seed.wrapping_add(r as u64));
        total_ms += t.elapsed().as_secs_f64() * 1e3;
        if let Some(e) = res.evals {
            evals.push(e);
            hidden += res.hidden;
        }
    }
    let solved = evals.len();
    let evals: Vec<f64> = evals.iter().map(|&e| e as f64).collect();
    let mean = stats::mean(&evals).unwrap_or(0.0);
    let median = stats::median(&evals).unwrap_or(0.0);
    format!(
        "{name}: solved={solved}/{runs} mean_evals={mean:.0} median_evals={median:.0} mean_hidden={:.2} mean_ms={:.1}",
        hidden as f64 / solved.max(1) as f64,
        total_ms / runs.max(1) as f64
    )
}
