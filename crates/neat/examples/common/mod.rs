//! What the benchmark examples share: one run's result, parameter overrides,
//! the command line and the summary line over many runs.

pub mod cli;

use std::cell::RefCell;
use std::time::Instant;

use vivae_neat::{Genome, NeatParams, RecurrentNetwork, stats};

/// The outcome of one run.
pub struct RunResult {
    /// Evaluations until the first solving genome, `None` when unsolved.
    pub evals: Option<usize>,
    /// Hidden nodes of the solving genome.
    pub hidden: usize,
    /// Generalisation score of the solving genome, for tasks that have one.
    pub generalisation: Option<usize>,
}

impl RunResult {
    /// A run that did not solve the task.
    // Each example compiles its own copy of this module; boxes never needs it.
    #[allow(dead_code)]
    pub fn unsolved() -> RunResult {
        RunResult {
            evals: None,
            hidden: 0,
            generalisation: None,
        }
    }
}

/// `f` of this thread's recurrent network, recompiled for `g`: one network
/// per worker thread reused across genomes, so an evaluation allocates
/// nothing once its arrays are large enough (building a network per genome
/// was 10–15 % of the efficacy tasks' time).
// Each example compiles its own copy of this module; only the recurrent tasks use it.
#[allow(dead_code)]
pub fn with_recurrent<T>(g: &Genome, f: impl FnOnce(&mut RecurrentNetwork) -> T) -> T {
    thread_local! {
        static NET: RefCell<Option<RecurrentNetwork>> = const { RefCell::new(None) };
    }
    NET.with_borrow_mut(|slot| match slot {
        Some(net) => {
            net.recompile(g);
            f(net)
        }
        None => f(slot.insert(RecurrentNetwork::from_genome(g))),
    })
}

/// Applies `field=value` (value in JSON) to the parameters, for experiments;
/// the error is one line naming the override and what is wrong with it.
pub fn override_param(params: &NeatParams, kv: &str) -> Result<NeatParams, String> {
    let (k, v) = kv
        .split_once('=')
        .ok_or_else(|| format!("--set {kv}: expected field=json_value"))?;
    let mut json = serde_json::to_value(params).map_err(|e| format!("--set {kv}: {e}"))?;
    // Unset options are left out of the JSON, so a missing key may still be a
    // field: deserialising (which refuses unknown fields) decides.
    let known = json.get(k).is_some();
    json[k] = serde_json::from_str(v).map_err(|e| format!("--set {kv}: value is not JSON: {e}"))?;
    let p: NeatParams = serde_json::from_value(json).map_err(|e| {
        if !known && e.to_string().starts_with("unknown field") {
            format!("--set {kv}: unknown parameter `{k}`")
        } else {
            format!("--set {kv}: {e}")
        }
    })?;
    p.validate().map_err(|e| format!("--set {kv}: {e}"))?;
    Ok(p)
}

/// Applies every `--set` override in order.
pub fn apply_overrides(mut params: NeatParams, sets: &[String]) -> Result<NeatParams, String> {
    for kv in sets {
        params = override_param(&params, kv)?;
    }
    Ok(params)
}

/// Parses the command line, printing the usage for `--help` (returns `None`)
/// and a one-line error with exit code 2 for anything it does not accept.
/// `switches` and `options` are the example's own flags without and with a value.
pub fn args_or_exit(
    name: &str,
    usage: &str,
    switches: &[&str],
    options: &[&str],
) -> Option<cli::Args> {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    match cli::parse(&argv, switches, options) {
        Ok(cli::Parsed::Run(a)) => Some(a),
        Ok(cli::Parsed::Help) => {
            print!("{usage}");
            None
        }
        Err(e) => fail(name, &e),
    }
}

/// The usage text of an example with only the common options: `title` on
/// top, the defaults of `--runs` and `--max-generations`, an example value of
/// `--set` (may be empty), and what the summary line holds (`prints`).
// Each example compiles its own copy of this module; some write their own text.
#[allow(dead_code)]
pub fn usage(
    name: &str,
    title: &str,
    runs: usize,
    generations: u32,
    set: &str,
    prints: &str,
) -> String {
    let set = if set.is_empty() {
        String::new()
    } else {
        format!(", e.g. --set {set}")
    };
    format!(
        "{title}

Usage: cargo run --release -p vivae-neat --example {name} -- [OPTIONS]

Options:
  --runs N              runs, with seeds S, S+1, ... (default {runs})
  --seed S              seed of the first run (default 1)
  --max-generations G   generations before a run counts as unsolved (default {generations})
  --set FIELD=JSON      override one NeatParams field (repeatable){set}
  -h, --help            print this help

Prints `{name}: {prints}`
on stdout and one line per run on stderr.
"
    )
}

/// The main of an example with only the common options: parses them
/// (`usage`'s arguments, the defaults `runs` and `generations`), runs
/// `run(params, seed, max_generations)` for each seed from plain NEAT with
/// the `--set` overrides, prints the summary line.
#[allow(dead_code)]
pub fn plain_main(
    name: &str,
    (title, summary, set): (&str, &str, &str),
    (runs, generations): (usize, u32),
    run: impl Fn(&NeatParams, u64, u32) -> RunResult,
) {
    let help = usage(name, title, runs, generations, set, summary);
    let Some(args) = args_or_exit(name, &help, &[], &[]) else {
        return;
    };
    let params =
        apply_overrides(NeatParams::plain_neat(), &args.sets).unwrap_or_else(|e| fail(name, &e));
    let (runs, seed) = (args.runs.unwrap_or(runs), args.seed.unwrap_or(1));
    let generations = args.max_generations.unwrap_or(generations);
    println!(
        "{}",
        summarize(name, runs, seed, |s| run(&params, s, generations))
    );
}

/// Prints `NAME: MESSAGE` on stderr and exits with code 2 (bad input).
pub fn fail(name: &str, message: &str) -> ! {
    eprintln!("{name}: {message}");
    std::process::exit(2)
}

/// Runs `run(seed + r)` for `r` in `0..runs` and returns the summary line
/// `NAME: solved=S/RUNS mean_evals=M median_evals=D mean_hidden=H mean_ms=T`,
/// with ` mean_generalisation=G` before `mean_ms` when the task has a score.
pub fn summarize(
    name: &str,
    runs: usize,
    seed: u64,
    mut run: impl FnMut(u64) -> RunResult,
) -> String {
    let mut evals = Vec::new();
    let mut hidden = 0usize;
    let mut scores = Vec::new();
    let mut total_ms = 0.0;
    for r in 0..runs {
        let t = Instant::now();
        let run_seed = seed.wrapping_add(r as u64);
        let res = run(run_seed);
        let ms = t.elapsed().as_secs_f64() * 1e3;
        total_ms += ms;
        // One line per run on stderr, for distributions and re-runs of single seeds.
        eprintln!(
            "{name} seed={run_seed} evals={} hidden={} generalisation={} ms={ms:.0}",
            res.evals.map_or("unsolved".to_string(), |e| e.to_string()),
            res.hidden,
            res.generalisation
                .map_or("-".to_string(), |g| g.to_string()),
        );
        if let Some(e) = res.evals {
            evals.push(e);
            hidden += res.hidden;
            scores.extend(res.generalisation.map(|g| g as f64));
        }
    }
    let solved = evals.len();
    let evals: Vec<f64> = evals.iter().map(|&e| e as f64).collect();
    let mean = stats::mean(&evals).unwrap_or(0.0);
    let median = stats::median(&evals).unwrap_or(0.0);
    let generalisation =
        stats::mean(&scores).map_or(String::new(), |g| format!(" mean_generalisation={g:.0}"));
    format!(
        "{name}: solved={solved}/{runs} mean_evals={mean:.0} median_evals={median:.0} mean_hidden={:.2}{generalisation} mean_ms={:.1}",
        hidden as f64 / solved.max(1) as f64,
        total_ms / runs.max(1) as f64
    )
}
