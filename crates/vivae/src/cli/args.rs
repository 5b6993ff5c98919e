//! Options several commands share, each declared once and flattened into the
//! commands' own options (`#[command(flatten)]`). A command that words an
//! option differently rewords it with `mut_arg`, so the flag stays one
//! declaration.

use std::path::PathBuf;

use clap::Args;
use vivae_lab::controller::substrate::PolarGrid;
use vivae_lab::export::choose::Pick;
use vivae_lab::search::files::Member;

/// The substrate's resolution; a genome's CPPN is re-sampled onto any.
#[derive(Args, Debug, Default, Clone, Copy)]
pub struct Resolution {
    /// Surface sensors as RINGSxANGLES (default: the run's, or the config's;
    /// paper: 3x5); a run's genomes are re-sampled onto it.
    #[arg(long, value_name = "RxA")]
    pub sensors: Option<PolarGrid>,
    /// Output neurons as RINGSxANGLES (default: the run's, or the config's;
    /// paper: 3x3); a run's genomes are re-sampled onto it.
    #[arg(long, value_name = "RxA")]
    pub neurons: Option<PolarGrid>,
}

/// How the substrate's links are weighted and which are kept.
#[derive(Args, Debug, Default, Clone, Copy)]
pub struct Wiring {
    /// With substrate.normalize: count (the paper's) or area (each node by its
    /// share of the sheet's polar area).
    #[arg(long, value_name = "count|area")]
    pub normalize_by: Option<vivae_lab::config::NormalizeBy>,
    /// With substrate.normalize: false keeps self-loops at the CPPN's weight
    /// at any neuron resolution (default true, the paper's).
    #[arg(long, value_name = "true|false")]
    pub normalize_self_loops: Option<bool>,
    /// Neuron→neuron links kept: full (the paper's), self (self-loops only,
    /// no lateral links) or none.
    #[arg(long, value_name = "full|self|none")]
    pub recurrence: Option<vivae_lab::config::Recurrence>,
}

/// The evaluation thread pool.
#[derive(Args, Debug, Default, Clone, Copy)]
pub struct Threads {
    /// Evaluation threads (0 = one per core, at most 1024); results do not depend on it.
    #[arg(long, value_name = "N", value_parser = threads)]
    pub threads: Option<usize>,
}

/// Most worker threads a command starts (as a config's `run.threads`).
pub const MAX_THREADS: usize = 1024;

/// A `--threads` value: a whole number up to [`MAX_THREADS`], refused
/// before any thread is started.
pub fn threads(text: &str) -> Result<usize, String> {
    let n: usize = (text.parse()).map_err(|_| "expected a whole number".to_string())?;
    if n > MAX_THREADS {
        return Err(format!("at most {MAX_THREADS}"));
    }
    Ok(n)
}

/// An episode's length and robots (`evolve`'s wording; `replay` rewords them).
#[derive(Args, Debug, Default, Clone, Copy)]
pub struct EpisodeArgs {
    /// Simulation steps per evaluation.
    #[arg(long, value_name = "N")]
    pub steps: Option<u32>,
    /// Robots: the scenario's first N (0 = all of them; paper: 5).
    #[arg(long, value_name = "N")]
    pub robots: Option<usize>,
}

/// How many generations a run has or gets (`evolve`'s wording; `resume` and
/// `retrain` reword it).
#[derive(Args, Debug, Default, Clone, Copy)]
pub struct Generations {
    /// Generations to evolve.
    #[arg(long, value_name = "N")]
    pub generations: Option<u32>,
}

/// Where a new run goes.
#[derive(Args, Debug)]
pub struct NewRun {
    /// New run directory (default: runs/<timestamp>).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Overwrite an existing run directory.
    #[arg(long)]
    pub force: bool,
}

/// Terminal output of the evolving commands.
#[derive(Args, Debug, Clone, Copy)]
pub struct Quiet {
    /// No progress output.
    #[arg(short, long)]
    pub quiet: bool,
}

/// A member of a map-elites archive or an nsga2 front, instead of the
/// champion (`replay`'s wording; `view` rewords it).
#[derive(Args, Debug, Default, Clone, Copy)]
pub struct MemberChoice {
    /// Replay the elite of this cell of a map-elites run's archive (archive.csv).
    #[arg(long, value_name = "CELL", conflicts_with = "front")]
    pub elite: Option<usize>,
    /// Replay this member of an nsga2 run's Pareto front (front.csv; 0 = the fittest).
    #[arg(long, value_name = "N")]
    pub front: Option<usize>,
}

impl MemberChoice {
    /// The archive or front member asked for, if any.
    pub fn member(&self) -> Option<Member> {
        (self.elite.map(Member::Elite)).or(self.front.map(Member::Front))
    }
}

/// Which genome of a run: the champion (default), a generation's best, or an
/// archive or front member (`export`'s and `drive-image`'s choice).
#[derive(Args, Debug, Default, Clone, Copy)]
pub struct GenomeChoice {
    /// Use the best genome of this generation (best-genomes.jsonl) instead of the champion.
    #[arg(long, value_name = "G", conflicts_with_all = ["elite", "front"])]
    pub generation: Option<u32>,
    #[command(flatten)]
    pub member: MemberChoice,
}

impl GenomeChoice {
    /// The library's name for the genome asked for.
    pub fn pick(&self) -> Pick {
        match (self.generation, self.member.member()) {
            (Some(g), _) => Pick::Generation(g),
            (None, Some(m)) => Pick::Member(m),
            (None, None) => Pick::Champion,
        }
    }
}

impl NewRun {
    /// The new run's directory: `--out`, else `runs/<timestamp>`.
    pub fn dir(&self) -> PathBuf {
        self.out
            .clone()
            .unwrap_or_else(vivae_lab::io::default_run_dir)
    }
}
