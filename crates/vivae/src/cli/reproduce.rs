//! `vivae reproduce NAME`: a published experiment run with the paper's
//! settings (a pack of `vivae_lab::reproduce`), its table of ours beside
//! the paper's numbers printed and written to a Markdown file.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use vivae_lab::output_path::{Output, REPRODUCE_JOURNAL, REPRODUCE_TABLE, check_outputs};
use vivae_lab::reproduce::{Options, packs, run as run_pack};

/// Options of `vivae reproduce`.
#[derive(Args, Debug)]
pub struct ReproduceArgs {
    /// The pack: maze-medium, maze-hard, xor, pole-markov, pole-nonmarkov, boxes, retina, road or gym-classic (`vivae reproduce --list`).
    #[arg(value_name = "NAME", required_unless_present = "list")]
    pub name: Option<String>,
    /// Runs per method (default: the paper's).
    #[arg(long, value_name = "N")]
    pub runs: Option<usize>,
    /// The first run's seed; run k has seed SEED + k.
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// A few-minute version for a first look: fewer runs, a smaller budget.
    #[arg(long)]
    pub quick: bool,
    /// Evaluations per run at most (default: the paper's; --quick: a tenth).
    #[arg(long, value_name = "N")]
    pub evaluations: Option<u64>,
    /// Worker threads per run (0 = one per core); results do not depend on it.
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = super::args::threads)]
    pub threads: usize,
    /// Only these methods (maze packs: novelty, neat, map-elites); repeat or comma-separate.
    #[arg(long, value_name = "KIND", value_delimiter = ',')]
    pub method: Vec<String>,
    /// The Markdown file written (default: reproduce-NAME.md).
    #[arg(short, long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// The journal of finished runs, which a run again skips (default: the table's name with .runs.tsv).
    #[arg(long, value_name = "FILE", conflicts_with = "no_journal")]
    pub journal: Option<PathBuf>,
    /// Replace an existing -o or --journal file that is not an earlier
    /// table or journal of vivae reproduce.
    #[arg(long)]
    pub force: bool,
    /// Keep no journal: every run is run.
    #[arg(long)]
    pub no_journal: bool,
    /// No line per finished run.
    #[arg(short, long)]
    pub quiet: bool,
    /// List the packs and exit.
    #[arg(long)]
    pub list: bool,
}

/// Runs `vivae reproduce`: the table printed and written.
pub fn run(args: ReproduceArgs) -> anyhow::Result<ExitCode> {
    if args.list {
        for p in packs() {
            println!("{:<14} {}", p.name, p.what);
        }
        return Ok(ExitCode::SUCCESS);
    }
    let name = args.name.unwrap_or_default();
    let out_flag = if args.out.is_some() {
        "-o"
    } else {
        "the table"
    };
    let out = (args.out).unwrap_or_else(|| PathBuf::from(format!("reproduce-{name}.md")));
    let (journal, journal_flag) = match (args.no_journal, args.journal) {
        (true, _) => (None, ""),
        (false, Some(j)) => (Some(j), "--journal"),
        (false, None) => (Some(out.with_extension("runs.tsv")), "the journal"),
    };
    vivae_lab::reproduce::find(&name)?;
    let mut outputs = vec![Output::new(&out, out_flag, REPRODUCE_TABLE)];
    if let Some(j) = &journal {
        outputs.push(Output::new(j, journal_flag, REPRODUCE_JOURNAL));
    }
    check_outputs(&outputs, args.force)?;
    let options = Options {
        runs: args.runs,
        seed: args.seed,
        quick: args.quick,
        evaluations: args.evaluations,
        threads: args.threads,
        methods: args.method,
        journal,
    };
    // Ctrl-C or SIGTERM: the run under way is dropped with its scratch
    // directory; the journal keeps the finished ones.
    let _ = ctrlc::set_handler(|| {
        vivae_lab::reproduce::remove_scratch_dirs();
        eprintln!("\ninterrupted: the journal keeps the finished runs; the same command continues");
        std::process::exit(130);
    });
    let quiet = args.quiet;
    let table = run_pack(&name, &options, &mut |line| {
        if !quiet {
            eprintln!("{line}");
        }
    })?;
    let text = table.markdown();
    vivae_lab::io::write_atomic(&out, text.as_bytes())?;
    print!("{text}");
    eprintln!("table: {}", out.display());
    Ok(ExitCode::SUCCESS)
}
