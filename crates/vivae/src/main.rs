//! The `vivae` command-line program.
//!
//! Exit codes: 0 ok, 1 internal error, 2 bad input or usage, 130 interrupted.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use anyhow::Context as _;
use clap::{Args, Parser, Subcommand};
use vivae::report;
use vivae_lab::config::{Config, TaskName};
use vivae_lab::evolve::{Outcome, Run};
use vivae_lab::experiment::Experiment;
use vivae_lab::io::{bad_input, load_scenario, one_line, write_atomic};
use vivae_lab::maps::TrainingMap;
use vivae_lab::rundir::{self, GenerationRecord, files};
use vivae_lab::substrate::PolarGrid;
use vivae_lab::tasks::read_config;
use vivae_lab::tasks::{Finished, HeaderContext};
use vivae_neat::driver::Task;

mod portable_libm;

/// HyperNEAT-controlled robots that learn to drive on roads (ViVAE).
#[derive(Parser, Debug)]
#[command(name = "vivae", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Evolve a driving controller (with no options: the paper's experiment).
    Evolve(EvolveArgs),
    /// Continue an interrupted run, or extend a finished one.
    Resume(ResumeArgs),
    /// Run a genome (a run's champion) and draw its trajectories.
    Replay(ReplayArgs),
    /// Continue a run's final population on a re-sampled substrate.
    Retrain(RetrainArgs),
    /// Rebuild a run's self-contained report.html.
    Report {
        /// The run directory.
        run_dir: PathBuf,
    },
    /// Watch robots drive in the browser (a local web server).
    View(vivae::view::ViewArgs),
    /// Compare runs: fitness per generation and per wall-clock second, figure and table.
    Compare(vivae::figures::compare::CompareArgs),
    /// Inspect and draw scenarios.
    #[command(subcommand)]
    Scenario(ScenarioCommand),
    /// Print configuration files and references.
    #[command(subcommand)]
    Config(ConfigCommand),
}

/// The substrate's resolution; a genome's CPPN is re-sampled onto any.
#[derive(Args, Debug, Default, Clone, Copy)]
struct Resolution {
    /// Surface sensors as RINGSxANGLES (default: the run's, or the config's;
    /// paper: 3x5); a run's genomes are re-sampled onto it.
    #[arg(long, value_name = "RxA")]
    sensors: Option<PolarGrid>,
    /// Output neurons as RINGSxANGLES (default: the run's, or the config's;
    /// paper: 3x3); a run's genomes are re-sampled onto it.
    #[arg(long, value_name = "RxA")]
    neurons: Option<PolarGrid>,
}

/// How the substrate's links are weighted and which are kept.
#[derive(Args, Debug, Default, Clone, Copy)]
struct Wiring {
    /// With substrate.normalize: count (the paper's) or area (each node by its
    /// share of the sheet's polar area).
    #[arg(long, value_name = "count|area")]
    normalize_by: Option<vivae_lab::config::NormalizeBy>,
    /// With substrate.normalize: false keeps self-loops at the CPPN's weight
    /// at any neuron resolution (default true, the paper's).
    #[arg(long, value_name = "true|false")]
    normalize_self_loops: Option<bool>,
    /// Neuron→neuron links kept: full (the paper's), self (self-loops only,
    /// no lateral links) or none.
    #[arg(long, value_name = "full|self|none")]
    recurrence: Option<vivae_lab::config::Recurrence>,
}

/// The evaluation thread pool.
#[derive(Args, Debug, Default, Clone, Copy)]
struct Threads {
    /// Evaluation threads (0 = one per core); results do not depend on it.
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
}

/// Where a new run goes.
#[derive(Args, Debug)]
struct NewRun {
    /// New run directory (default: runs/<timestamp>).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Overwrite an existing run directory.
    #[arg(long)]
    force: bool,
}

/// Terminal output of the evolving commands.
#[derive(Args, Debug, Clone, Copy)]
struct Quiet {
    /// No progress output.
    #[arg(short, long)]
    quiet: bool,
}

/// Options that override config keys.
#[derive(Args, Debug, Default)]
struct Overrides {
    /// Scenario SVG file, or the name of a shipped one (`vivae scenario list`;
    /// default: the embedded road scenario). Repeat it to train on several
    /// maps at once (fitness = the mean over maps).
    #[arg(long, value_name = "FILE|NAME")]
    scenario: Vec<PathBuf>,
    /// Generations to evolve.
    #[arg(long, value_name = "N")]
    generations: Option<u32>,
    /// Population size.
    #[arg(long, value_name = "N")]
    population: Option<usize>,
    /// Random seed.
    #[arg(long, value_name = "N")]
    seed: Option<u64>,
    #[command(flatten)]
    resolution: Resolution,
    /// Simulation steps per evaluation.
    #[arg(long, value_name = "N")]
    steps: Option<u32>,
    /// Robots: the scenario's first N (0 = all of them; paper: 5).
    #[arg(long, value_name = "N")]
    robots: Option<usize>,
    #[command(flatten)]
    threads: Threads,
    /// Multi-resolution evolution: evaluate every genome at these neuron
    /// sheets (e.g. 3x3,5x5,9x9) and aggregate; --neurons stays the one reported.
    #[arg(long, value_name = "RxA,...", value_delimiter = ',')]
    train_neurons: Option<Vec<PolarGrid>>,
    /// Multi-resolution evolution: evaluate every genome at these sensor sheets
    /// (e.g. 3x5,3x6), with each of --train-neurons.
    #[arg(long, value_name = "RxA,...", value_delimiter = ',')]
    train_sensors: Option<Vec<PolarGrid>>,
    /// How the training resolutions' fitnesses combine: mean (default) or min.
    #[arg(long, value_name = "mean|min")]
    train_aggregate: Option<vivae_lab::config::Aggregate>,
    /// Substrate kind: polar (the dense neuron sheet, the paper's) or
    /// es-hyperneat (hidden neurons placed by the CPPN; keys in [substrate.es]).
    #[arg(long, value_name = "polar|es-hyperneat")]
    substrate: Option<vivae_lab::es_controller::SubstrateKind>,
    #[command(flatten)]
    wiring: Wiring,
    /// Search strategy (strategy.kind; default neat, the paper's).
    #[arg(long, value_name = "neat|novelty|map-elites|nsga2")]
    strategy: Option<vivae_lab::strategy_config::StrategyKind>,
    /// Behaviour descriptor of novelty and map-elites (strategy.behaviour).
    #[arg(long, value_name = "end-position|end-positions|side-speed|trajectory")]
    behaviour: Option<vivae_lab::descriptors::BehaviourKind>,
    /// Task (experiment.task): driving (default) or maze (Lehman & Stanley's
    /// maze with a plain NEAT network; default scenario hard-maze).
    #[arg(long, value_name = "driving|maze", value_parser = parse_task)]
    task: Option<TaskName>,
}

#[derive(Args, Debug)]
struct EvolveArgs {
    /// Config file (TOML); flags override its keys.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    #[command(flatten)]
    overrides: Overrides,
    #[command(flatten)]
    new_run: NewRun,
    #[command(flatten)]
    quiet: Quiet,
}

#[derive(Args, Debug)]
struct ResumeArgs {
    /// The run directory.
    run_dir: PathBuf,
    /// Total generations (extends a finished run).
    #[arg(long, value_name = "N")]
    generations: Option<u32>,
    #[command(flatten)]
    threads: Threads,
    #[command(flatten)]
    quiet: Quiet,
}

#[derive(Args, Debug)]
struct ReplayArgs {
    /// A run directory or a genome JSON file (champion.json).
    source: PathBuf,
    /// Scenario SVG file or shipped name (default: the run's).
    #[arg(long, value_name = "FILE|NAME")]
    scenario: Option<PathBuf>,
    #[command(flatten)]
    resolution: Resolution,
    /// Simulation steps.
    #[arg(long, value_name = "N")]
    steps: Option<u32>,
    /// Robots: the scenario's first N, 0 = all (default: the run's number on
    /// the run's scenario, all of them on another scenario).
    #[arg(long, value_name = "N")]
    robots: Option<usize>,
    /// Replay the elite of this cell of a map-elites run's archive (archive.csv).
    #[arg(long, value_name = "CELL", conflicts_with = "front")]
    elite: Option<usize>,
    /// Replay this member of an nsga2 run's Pareto front (front.csv; 0 = the fittest).
    #[arg(long, value_name = "N")]
    front: Option<usize>,
    /// Folder for the trajectory figure (default: replay/ beside the source).
    #[arg(short, long, value_name = "DIR")]
    out: Option<PathBuf>,
    #[command(flatten)]
    wiring: Wiring,
}

#[derive(Args, Debug)]
#[command(mut_arg("sensors", |a| a.required_unless_present("neurons")))]
struct RetrainArgs {
    /// The run whose final population continues.
    run_dir: PathBuf,
    #[command(flatten)]
    resolution: Resolution,
    /// Generations to evolve on the new substrate.
    #[arg(long, value_name = "N")]
    generations: u32,
    #[command(flatten)]
    new_run: NewRun,
    #[command(flatten)]
    threads: Threads,
    #[command(flatten)]
    quiet: Quiet,
}

#[derive(Subcommand, Debug)]
enum ScenarioCommand {
    /// The scenarios shipped with vivae (usable as `--scenario NAME`).
    List,
    /// Arena size, objects by kind, robots and warnings.
    Info {
        /// Scenario SVG file or shipped name (default: the embedded one).
        file: Option<PathBuf>,
        /// One JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Draw a scenario to PNG or SVG (by the extension of OUT).
    Render {
        /// Scenario SVG file or shipped name (default: the embedded one).
        file: Option<PathBuf>,
        /// Output file, .png or .svg.
        #[arg(short, long, value_name = "OUT")]
        out: PathBuf,
        /// Draw surface sensors of this layout (RINGSxANGLES) on every robot.
        #[arg(long, value_name = "RxA")]
        sensors: Option<PolarGrid>,
    },
}

#[derive(Subcommand, Debug)]
enum ConfigCommand {
    /// The full default config, a comment on every key.
    Default,
    /// A Markdown table of every key (the guide's reference).
    Reference,
    /// Check a config file and print it fully resolved.
    Check {
        /// The config file.
        file: PathBuf,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if let Err(err) = vivae_lab::simd::apply_env() {
        eprintln!("error: {err}");
        return ExitCode::from(2);
    }
    let interrupted = Arc::new(AtomicBool::new(false));
    // Under an MPI launcher the evolving commands join the job; MPI ends when `_mpi` drops.
    #[cfg(feature = "mpi")]
    let _mpi = matches!(
        cli.command,
        Command::Evolve(_) | Command::Resume(_) | Command::Retrain(_)
    )
    .then(vivae::mpi::Launch::init);
    match dispatch(cli, &interrupted) {
        Ok(code) => code,
        Err(err) => {
            eprintln!("error: {}", one_line(&format!("{err:#}")));
            let users_fault = err
                .chain()
                .filter_map(|c| c.downcast_ref::<vivae_lab::Error>())
                .any(vivae_lab::Error::is_bad_input);
            if users_fault {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}

fn dispatch(cli: Cli, interrupted: &Arc<AtomicBool>) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Evolve(args) => cmd_evolve(args, interrupted),
        Command::Resume(args) => cmd_resume(args, interrupted),
        Command::Replay(args) => cmd_replay(args),
        Command::Retrain(args) => cmd_retrain(args, interrupted),
        Command::Report { run_dir } => {
            refuse_other_task(&run_dir, "report")?;
            let path = vivae::report_html::write(&run_dir)?;
            eprintln!("report: {}", path.display());
            Ok(ExitCode::SUCCESS)
        }
        Command::View(args) => {
            if let Some(source) = &args.source {
                refuse_other_task(source, "view")?;
            }
            Ok(vivae::view::run(args)?)
        }
        Command::Compare(args) => {
            print!("{}", vivae::figures::compare::run(&args)?);
            eprintln!("figure: {}", args.out.display());
            Ok(ExitCode::SUCCESS)
        }
        Command::Scenario(c) => cmd_scenario(c),
        Command::Config(c) => cmd_config(c),
    }
}

fn apply_overrides(config: &mut Config, o: &Overrides) -> anyhow::Result<()> {
    // Flags replace the config file's map(s): one --scenario is a single-map
    // run, several are a multi-map run.
    match o.scenario.as_slice() {
        [] => {}
        [one] => {
            config.experiment.scenario = one.to_string_lossy().into_owned();
            config.experiment.scenarios.clear();
        }
        several => {
            config.experiment.scenario.clear();
            config.experiment.scenarios = several
                .iter()
                .map(|p| p.to_string_lossy().into_owned())
                .collect();
        }
    }
    if let Some(n) = o.generations {
        config.experiment.generations = n;
    }
    if let Some(n) = o.population {
        config.neat.population_size = n;
    }
    if let Some(n) = o.seed {
        config.experiment.seed = n;
    }
    if let Some(g) = o.resolution.sensors {
        config.surface_sensors.rings = g.rings;
        config.surface_sensors.angles = g.angles;
    }
    if let Some(g) = o.resolution.neurons {
        config.substrate.neurons = g;
    }
    if let Some(n) = o.steps {
        config.experiment.steps = n;
    }
    if let Some(n) = o.robots {
        config.experiment.robots = n;
    }
    if let Some(n) = o.threads.threads {
        config.run.threads = n;
    }
    if let Some(g) = &o.train_neurons {
        config.substrate.train_neurons = g.clone();
    }
    if let Some(g) = &o.train_sensors {
        config.substrate.train_sensors = g.clone();
    }
    if let Some(a) = o.train_aggregate {
        config.substrate.train_aggregate = a;
    }
    if let Some(k) = o.substrate {
        config.substrate.kind = k;
    }
    if let Some(b) = o.wiring.normalize_by {
        config.substrate.normalize_by = b;
    }
    if let Some(b) = o.wiring.normalize_self_loops {
        config.substrate.normalize_self_loops = b;
    }
    if let Some(r) = o.wiring.recurrence {
        config.substrate.recurrence = r;
    }
    if let Some(k) = o.strategy {
        config.strategy.kind = k;
    }
    if let Some(b) = o.behaviour {
        config.strategy.behaviour = b;
    }
    vivae_lab::tasks::check(config).map_err(|e| bad_input(format!("command line: {e}")).into())
}

/// `--task NAME`: a registered task.
fn parse_task(name: &str) -> Result<TaskName, String> {
    vivae_lab::tasks::entry(name).map(|_| TaskName(name.to_string()))
}

fn scenario_path(config: &Config) -> Option<PathBuf> {
    (!config.experiment.scenario.is_empty()).then(|| PathBuf::from(&config.experiment.scenario))
}

fn install_ctrlc(flag: &Arc<AtomicBool>) {
    let flag = flag.clone();
    // A second Ctrl-C while finishing the generation aborts at once.
    let _ = ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
        eprintln!(
            "\ninterrupt: finishing the current generation, then writing a checkpoint (Ctrl-C again to abort)"
        );
    });
}

fn cmd_evolve(args: EvolveArgs, interrupted: &Arc<AtomicBool>) -> anyhow::Result<ExitCode> {
    let task = args.overrides.task.clone();
    let mut config = match &args.config {
        Some(p) => read_config(p)?,
        None => vivae_lab::tasks::default_config(task.as_ref()).map_err(bad_input)?,
    };
    if let Some(why) = args
        .config
        .as_ref()
        .and_then(|_| config.task_mismatch(task.as_ref()))
    {
        let t = task.as_ref().map_or("", TaskName::name);
        return Err(bad_input(format!("--task {t}: {why}")).into());
    }
    apply_overrides(&mut config, &args.overrides)?;
    let task_defaults = task.is_some() && args.config.is_none();
    let setup = || -> vivae_lab::Result<_> {
        let maps = vivae_lab::maps::load(&config)?;
        let experiment = vivae_lab::tasks::build(&config, &maps)?;
        let init = if config.experiment.init_population.is_empty() {
            None
        } else {
            let path = Path::new(&config.experiment.init_population);
            Some(rundir::population_from_checkpoint(path)?.1)
        };
        Ok((maps, experiment, init))
    };
    // Problems with what a config file names are reported against that file too.
    let prepared = match &args.config {
        Some(path) => setup().with_context(|| path.display().to_string()),
        None => setup().map_err(anyhow::Error::from),
    };
    let quiet = args.quiet.quiet;
    let joining = (prepared.as_ref()).map(|(m, e, _)| (&config, m.as_slice(), e as &dyn Task));
    if let Some(code) = join_mpi_job(joining, config.run.threads, quiet)? {
        return Ok(code);
    }
    let (maps, experiment, init) = prepared?;
    if task_defaults {
        // Settings the task fits to its scenario (the maze's MAP-Elites grid).
        experiment.fit_defaults(&mut config);
    }
    if !quiet {
        for m in &maps {
            for w in &m.loaded.scenario.warnings {
                eprintln!("warning: {w}");
            }
        }
    }
    warn_repeated_maps(&maps);
    let dir = args
        .new_run
        .out
        .clone()
        .unwrap_or_else(vivae_lab::io::default_run_dir);
    let source = experiment.describe(&maps);
    let first = &maps[0].loaded.text;
    let threads = config.run.threads;
    let force = args.new_run.force;
    let maps = if vivae_lab::maps::is_multi_map(&config) {
        &maps[..]
    } else {
        &[]
    };
    let run = Run::create_task(&dir, config, experiment, first, maps, init, force)?;
    drive(run, "evolve", &source, threads, quiet, interrupted)
}

fn cmd_resume(args: ResumeArgs, interrupted: &Arc<AtomicBool>) -> anyhow::Result<ExitCode> {
    let quiet = args.quiet.quiet;
    if launched_by_mpi() {
        // Every rank reads the run (rank 0 writes to it only after the handshake).
        let prepared = (|| -> anyhow::Result<_> {
            let checkpoint = rundir::latest_checkpoint(&args.run_dir)?;
            let (config, _) = rundir::population_from_checkpoint(&checkpoint)?;
            let maps = vivae_lab::rundir::load_run(&args.run_dir, &config, None)?;
            let experiment = vivae_lab::tasks::build(&config, &maps)?;
            Ok((config, maps, experiment))
        })();
        let recorded = prepared.as_ref().map_or(0, |(c, _, _)| c.run.threads);
        let joining = (prepared.as_ref()).map(|(c, m, e)| (c, m.as_slice(), e as &dyn Task));
        if let Some(code) = join_mpi_job(joining, args.threads.threads.unwrap_or(recorded), quiet)?
        {
            return Ok(code);
        }
    }
    let run = Run::resume(&args.run_dir, args.generations, args.threads.threads)?;
    let total = run.config().experiment.generations;
    if let Some(at) = run.target_progress().and_then(|m| m.solved_at) {
        let task = run.config().experiment.task.name();
        eprintln!(
            "{} is already finished: the {task} was solved after {at} evaluations (a {task} run stops when solved)",
            run.dir().display()
        );
        return Ok(ExitCode::SUCCESS);
    }
    if run.done() >= total {
        let dir = run.dir().display();
        eprintln!(
            "{dir} is already finished ({total} of {total} generations); to extend it: vivae resume {dir} --generations N (N > {total})"
        );
        // A run that stopped before its figures and report showed every
        // generation (killed while drawing them) gets them now.
        if run.experiment().is_some()
            && vivae_lab::rundir::drawn_generations(run.dir()) != Some(run.done())
        {
            report::finish_run(&run).context("writing figures")?;
            eprintln!("figures: {}", run.dir().join(files::FIGURES).display());
            eprintln!("report: {}", run.dir().join(files::REPORT).display());
        }
        return Ok(ExitCode::SUCCESS);
    }
    let source = if vivae_lab::maps::is_multi_map(run.config()) {
        let dir = run.dir();
        run.config()
            .experiment
            .scenarios
            .iter()
            .map(|s| dir.join(s).display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    } else {
        run.dir().join(files::SCENARIO).display().to_string()
    };
    // The pool runs on the threads given now, if any, not the recorded ones.
    let threads = args.threads.threads.unwrap_or(run.config().run.threads);
    drive(run, "resume", &source, threads, quiet, interrupted)
}

fn cmd_retrain(args: RetrainArgs, interrupted: &Arc<AtomicBool>) -> anyhow::Result<ExitCode> {
    let checkpoint = rundir::latest_checkpoint(&args.run_dir)?;
    let (mut config, population) = rundir::population_from_checkpoint(&checkpoint)?;
    if !config.experiment.task.is_driving() {
        return Err(bad_input(format!(
            "{}: a {} run evolves plain networks, which have no substrate to re-sample: retrain is for driving runs",
            args.run_dir.display(),
            config.experiment.task
        ))
        .into());
    }
    if vivae_lab::maps::is_multi_map(&config) {
        // A multi-map run retrains on the copies of its maps.
        for s in &mut config.experiment.scenarios {
            *s = args.run_dir.join(&*s).to_string_lossy().into_owned();
        }
    } else {
        config.experiment.scenario = args
            .run_dir
            .join(files::SCENARIO)
            .to_string_lossy()
            .into_owned();
    }
    config.experiment.init_population = checkpoint.to_string_lossy().into_owned();
    let overrides = Overrides {
        generations: Some(args.generations),
        resolution: args.resolution,
        threads: args.threads,
        ..Overrides::default()
    };
    apply_overrides(&mut config, &overrides)?;
    let prepared = (|| -> anyhow::Result<_> {
        let maps = vivae_lab::maps::load(&config)?;
        let experiment = vivae_lab::training::Training::new(&config, &maps)?;
        Ok((maps, experiment))
    })();
    let quiet = args.quiet.quiet;
    let joining = (prepared.as_ref()).map(|(m, e)| (&config, m.as_slice(), e as &dyn Task));
    if let Some(code) = join_mpi_job(joining, config.run.threads, quiet)? {
        return Ok(code);
    }
    let (maps, experiment) = prepared?;
    warn_repeated_maps(&maps);
    let dir = args
        .new_run
        .out
        .clone()
        .unwrap_or_else(vivae_lab::io::default_run_dir);
    let source = experiment.describe(&maps);
    let threads = config.run.threads;
    let run = Run::create_on_maps(
        &dir,
        config,
        experiment,
        &maps[0].loaded.text,
        &maps,
        Some(population),
        args.new_run.force,
    )?;
    drive(run, "retrain", &source, threads, quiet, interrupted)
}

/// Warns (even with `-q`: the run's result is at stake) about a training
/// map given more than once, which trains twice and counts double.
fn warn_repeated_maps(maps: &[vivae_lab::maps::TrainingMap]) {
    for w in vivae_lab::maps::repeat_warnings(maps) {
        eprintln!("warning: {w}");
    }
}

/// What a run is about to do, for a person reading the terminal, under the
/// name of the `command` that runs it; `threads` is the evaluation pool's
/// size as asked for (0 = one per core).
fn header(run: &Run, command: &str, scenario: &str, threads: usize) -> String {
    let c = run.config();
    let threads = match threads {
        0 => format!(
            "{} (one per core)",
            std::thread::available_parallelism().map_or(1, |n| n.get())
        ),
        t => t.to_string(),
    };
    let start = match run.done() {
        0 => String::new(),
        d => format!(" (resuming after generation {d})"),
    };
    let ctx = HeaderContext {
        command,
        scenario,
        start: &start,
        threads: &threads,
        strategy: &strategy_line(c),
        output: &run.dir().display().to_string(),
    };
    run.task().header(c, &ctx)
}

/// The header's line on the search strategy (none for NEAT, the paper's).
fn strategy_line(c: &Config) -> String {
    (vivae_lab::search::entry(c.strategy.kind).header_line)(c)
}

/// The closing summary: rounded figures and the run directory's main files;
/// `started_after` is the generation this invocation started after (0 for a new run).
fn closing(
    run: &Run,
    summary: &report::RunSummary,
    started_after: u32,
    wall: f64,
    steps_per_s: f64,
) -> String {
    let dir = run.dir().display();
    let mut figures: Vec<String> = run
        .figure_genomes()
        .map(|(g, _, _)| format!("trajectories-gen{g:03}.png"))
        .collect();
    figures.push("trajectories-champion.png".into());
    figures.extend(
        summary
            .per_map
            .iter()
            .map(|(label, _)| format!("{}.png", report::champion_map_figure(label))),
    );
    figures.extend(["convergence.png", "network.png"].map(String::from));
    for name in ["archive.png", "front.png"] {
        if run.dir().join(files::FIGURES).join(name).exists() {
            figures.push(name.into());
        }
    }
    let plural = |n: u32| if n == 1 { "" } else { "s" };
    let (done, ran) = (run.done(), run.done() - started_after);
    let done = match started_after {
        0 => format!("{done} generation{}", plural(done)),
        s => format!(
            "{ran} generation{} (generations {}–{done}; {done} in all)",
            plural(ran),
            s + 1
        ),
    };
    let per_map = match per_map_field(summary) {
        None => String::new(),
        Some(p) => format!("\n  on each training map: {}", p.replace(',', ", ")),
    };
    format!(
        "done: {done} in {wall:.1} s ({:.2} M robot-steps/s)\n\
         champion: fitness {:.3} px/step (generation {}), {:.1}% of robot-steps on road{per_map}\n\
         run directory: {dir}/\n\
         \x20 report.html     every figure on one page: open {dir}/{}\n\
         \x20 config.toml     the resolved config: vivae evolve --config {dir}/config.toml repeats the run\n\
         \x20 champion.json   the best genome and its config: vivae replay {dir}/champion.json\n\
         \x20 generations.csv, population.csv, timing.csv, checkpoints/\n\
         \x20 figures/        {} (and .svg)\n\
         watch them drive: vivae view {dir}",
        steps_per_s / 1e6,
        summary.champion_fitness,
        summary.champion_generation,
        100.0 * summary.champion_on_road,
        files::REPORT,
        figures.join(", "),
    )
}

/// The champion's fitness on each training map, `roads:3.1,oval:2.8` (3
/// decimals), or none on one map.
fn per_map_field(summary: &report::RunSummary) -> Option<String> {
    (!summary.per_map.is_empty()).then(|| {
        summary
            .per_map
            .iter()
            .map(|(label, f)| format!("{label}:{f:.3}"))
            .collect::<Vec<_>>()
            .join(",")
    })
}

/// Whether an MPI launcher started this process (never without the `mpi` feature).
fn launched_by_mpi() -> bool {
    #[cfg(feature = "mpi")]
    return vivae::mpi::launched_by_mpi();
    #[cfg(not(feature = "mpi"))]
    false
}

/// Under an MPI launcher, the start-up handshake of every rank (see
/// `vivae::mpi`), for every command that evolves: each rank brings the run it
/// prepared (config, training maps, experiment) or why it could not, and the
/// evaluation threads it will use. `Some(code)` on a worker rank whose work is
/// done, `None` where the run goes on (always, without MPI).
fn join_mpi_job(
    prepared: Result<(&Config, &[TrainingMap], &dyn Task), &anyhow::Error>,
    threads: usize,
    quiet: bool,
) -> anyhow::Result<Option<ExitCode>> {
    #[cfg(feature = "mpi")]
    {
        use vivae::mpi::{MpiError, Setup, Started, start};
        let fingerprint = prepared.as_ref().map_or_else(
            |_| String::new(),
            |(_, maps, _)| vivae_lab::maps::fingerprint_text(maps),
        );
        let setup = prepared
            .map(|(config, _, training)| Setup {
                config,
                scenario_text: &fingerprint,
                task: training,
                threads,
            })
            .map_err(|e| one_line(&format!("{e:#}")));
        match start(setup, quiet) {
            Ok(Started::Lead) => Ok(None),
            Ok(Started::WorkerDone) => Ok(Some(ExitCode::SUCCESS)),
            Err(e @ MpiError::Refused(_)) => Err(bad_input(e.to_string()).into()),
            Err(e) => Err(e.into()),
        }
    }
    #[cfg(not(feature = "mpi"))]
    {
        let _ = (prepared, threads, quiet);
        Ok(None)
    }
}

/// Runs the generations of `run`; rank 0 of an MPI job spreads each one over the job's ranks.
fn run_generations(
    run: &mut Run,
    interrupted: &AtomicBool,
    on_generation: impl FnMut(&GenerationRecord),
) -> vivae_lab::Result<Outcome> {
    #[cfg(feature = "mpi")]
    if let Some(evaluator) = vivae::mpi::MpiEvaluator::for_leader(run.task().clone(), run.pool()) {
        return run.run_on(evaluator, interrupted, on_generation);
    }
    run.run(interrupted, on_generation)
}

/// Runs evolution with progress output, then writes the figures.
fn drive(
    mut run: Run,
    command: &str,
    scenario: &str,
    threads: usize,
    quiet: bool,
    interrupted: &Arc<AtomicBool>,
) -> anyhow::Result<ExitCode> {
    install_ctrlc(interrupted);
    if !quiet {
        eprintln!("{}", header(&run, command, scenario, threads));
    }
    let started_after = run.done();
    let start = Instant::now();
    let total = run.config().experiment.generations;
    let bar = (!quiet && std::io::stderr().is_terminal()).then(|| progress_bar(total, run.done()));
    let mut robot_steps = 0.0;
    let mut busy = 0.0;
    let outcome = run_generations(&mut run, interrupted, |r: &GenerationRecord| {
        robot_steps += r.robot_steps_per_second * r.seconds;
        busy += r.seconds;
        let line = format!(
            "gen {}/{} best {:.4} mean {:.4} species {} best-ever {:.4}",
            r.generation, r.total, r.best, r.mean, r.species, r.best_ever
        );
        match &bar {
            Some(b) => {
                b.set_position(u64::from(r.generation));
                b.set_message(format!(
                    "best {:.4} mean {:.4} species {}",
                    r.best, r.mean, r.species
                ));
            }
            None if !quiet => eprintln!("{line}"),
            None => {}
        }
    })?;
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let rate = robot_steps / busy.max(1e-9);
    conclude(&run, outcome, started_after, start, rate, quiet)
}

/// The end of [`drive`]: figures, the closing summary and the summary line
/// (a task without figures' by [`conclude_without_figures`]); `rate` is robot-steps per second.
fn conclude(
    run: &Run,
    outcome: Outcome,
    started_after: u32,
    start: Instant,
    rate: f64,
    quiet: bool,
) -> anyhow::Result<ExitCode> {
    let dir = run.dir().display().to_string();
    if run.task().driving().is_none() {
        let wall = start.elapsed().as_secs_f64();
        return conclude_without_figures(run, outcome, wall, rate, quiet);
    }
    if outcome == Outcome::Interrupted {
        // The figures show the run so far; a resumed run redraws them at its end.
        if run.done() > 0 {
            report::finish_run(run).context("writing figures")?;
        }
        eprintln!(
            "interrupted after generation {}; checkpoint written. Resume with: vivae resume {dir}",
            run.done()
        );
        return Ok(ExitCode::from(130));
    }
    let summary = report::finish_run(run).context("writing figures")?;
    let wall = start.elapsed().as_secs_f64();
    if !quiet {
        eprintln!("{}", closing(run, &summary, started_after, wall, rate));
    }
    // The machine-readable summary, for scripts.
    let per_map = per_map_field(&summary).map_or_else(String::new, |p| format!(" per_map={p}"));
    println!(
        "evolve: generations={} best={} champion_generation={} on_road={:.4}{per_map}{} wall_s={:.1} robot_steps_per_s={:.0} out={dir}",
        run.done(),
        summary.champion_fitness,
        summary.champion_generation,
        summary.champion_on_road,
        vivae_lab::strategy_files::summary_fields(run.search()),
        wall,
        rate,
    );
    Ok(ExitCode::SUCCESS)
}

/// [`conclude`] for a task that draws no figures (the maze: docs/guide.md,
/// "The maze from the command line"): its own summary says how it went.
fn conclude_without_figures(
    run: &Run,
    outcome: Outcome,
    wall: f64,
    rate: f64,
    quiet: bool,
) -> anyhow::Result<ExitCode> {
    let dir = run.dir().display().to_string();
    if outcome == Outcome::Interrupted {
        eprintln!(
            "interrupted after generation {}; checkpoint written. Resume with: vivae resume {dir}",
            run.done()
        );
        return Ok(ExitCode::from(130));
    }
    let champion = run.champion().ok_or(vivae_lab::Error::NoChampion)?;
    let finished = Finished {
        champion: &champion.genome,
        fitness: champion.fitness,
        generation: champion.generation,
        progress: run.target_progress().copied().unwrap_or_default(),
        generations: run.done(),
        wall,
        rate,
        dir: &dir,
        strategy_fields: &vivae_lab::strategy_files::summary_fields(run.search()),
    };
    let (person, line) = (run.task().summary(&finished))
        .ok_or_else(|| bad_input("the run's task has no summary"))?;
    if !quiet {
        eprintln!("{person}");
    }
    println!("{line}");
    Ok(ExitCode::SUCCESS)
}

fn progress_bar(total: u32, done: u32) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(u64::from(total));
    bar.set_style(
        indicatif::ProgressStyle::with_template("gen {pos}/{len} [{bar:30}] {msg} ETA {eta}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_position(u64::from(done));
    bar
}

fn replay_member(args: &ReplayArgs) -> Option<vivae_lab::strategy_files::Member> {
    use vivae_lab::strategy_files::Member;
    (args.elite.map(Member::Elite)).or(args.front.map(Member::Front))
}

fn cmd_replay(args: ReplayArgs) -> anyhow::Result<ExitCode> {
    let (mut champion, mut config, base) = vivae_lab::rundir::load_genome_source(&args.source)?;
    let member = replay_member(&args);
    if let Some(member) = member {
        use vivae_lab::strategy_files::read_member;
        (champion.genome, champion.fitness, champion.generation) =
            read_member(&args.source, member)?;
    }
    if !config.experiment.task.is_driving() {
        return replay_without_figures(&args, &champion, config);
    }
    // A multi-map run replays on its first training map unless told otherwise.
    if args.scenario.is_none() && vivae_lab::maps::is_multi_map(&config) {
        let maps = std::mem::take(&mut config.experiment.scenarios);
        eprintln!(
            "replaying on the first training map, {} (of {}: {}); choose another with --scenario",
            maps[0],
            maps.len(),
            maps.join(", ")
        );
        config.experiment.scenario = maps[0].clone();
    }
    let overrides = Overrides {
        scenario: args.scenario.iter().cloned().collect(),
        resolution: args.resolution,
        steps: args.steps,
        // Another scenario has its own robot starts: all of them, unless told.
        robots: args.robots.or(args.scenario.as_ref().map(|_| 0)),
        wiring: args.wiring,
        ..Overrides::default()
    };
    apply_overrides(&mut config, &overrides)?;
    let path = scenario_path(&config);
    if let Some(p) = path
        .as_deref()
        .filter(|p| args.scenario.is_none() && !p.exists())
    {
        return Err(bad_input(format!(
            "{}: the champion's scenario {} is not there; name one with --scenario FILE",
            args.source.display(),
            p.display()
        ))
        .into());
    }
    let scenario = load_scenario(path.as_deref())?;
    let experiment =
        Experiment::new(&config, &scenario.scenario).map_err(vivae_lab::Error::from)?;
    // Checked before anything is written: a genome that does not fit is bad input.
    experiment
        .robot_controller(&champion.genome)
        .map_err(|e| vivae_lab::Error::Genome {
            path: args.source.clone(),
            reason: format!("the genome's {e}"),
        })?;
    // Said once the genome is known to fit, so that an error stays one line.
    if champion.config.is_none() && !args.source.is_dir() {
        eprintln!(
            "warning: {} records no config (written by an older vivae): replaying with the default config and flags; replay its run directory instead if you have it",
            args.source.display()
        );
    }
    let out = args.out.clone().unwrap_or_else(|| base.join("replay"));
    vivae_lab::io::create_dirs(&out)?;
    let name = report::replay_scenario_name(path.as_deref(), &scenario.text);
    let replay = report::replay(&experiment, &config, &champion, &name, &out, member)?;
    println!(
        "fitness={} on_road={:.4} {}",
        replay.fitness,
        replay.on_road,
        replay.behaviour.fields()
    );
    eprintln!("figure: {}", replay.figure.display());
    Ok(ExitCode::SUCCESS)
}

/// `vivae replay` of a genome of a task that draws no figures (the maze):
/// its episode's end, on stdout.
fn replay_without_figures(
    args: &ReplayArgs,
    champion: &rundir::Champion,
    mut config: Config,
) -> anyhow::Result<ExitCode> {
    let overrides = Overrides {
        scenario: args.scenario.iter().cloned().collect(),
        resolution: args.resolution,
        steps: args.steps,
        robots: args.robots,
        wiring: args.wiring,
        ..Overrides::default()
    };
    apply_overrides(&mut config, &overrides)?;
    let maps = vivae_lab::maps::load(&config)?;
    let task = vivae_lab::tasks::build(&config, &maps)?;
    task.check_genome(&champion.genome)
        .map_err(|reason| vivae_lab::Error::Genome {
            path: args.source.clone(),
            reason,
        })?;
    let (line, note) = (task.replay_text(&champion.genome))
        .ok_or_else(|| bad_input("the run's task has no replay"))?;
    println!("{line}");
    eprintln!("{note}");
    Ok(ExitCode::SUCCESS)
}

/// Refuses, in one line, `command` on a run of a task other than driving (a
/// run directory or a genome file recording its config): the command draws
/// driving runs only.
fn refuse_other_task(path: &Path, command: &str) -> anyhow::Result<()> {
    let config = if path.is_dir() {
        read_config(&path.join(files::CONFIG)).ok()
    } else {
        rundir::read_champion(path).ok().and_then(|c| c.config)
    };
    match config {
        Some(c) if !c.experiment.task.is_driving() => Err(bad_input(format!(
            "{}: a {} run: `vivae {command}` shows driving runs only; its curves are in generations.csv and `vivae replay` prints its champion's end",
            path.display(),
            c.experiment.task
        ))
        .into()),
        _ => Ok(()),
    }
}

fn cmd_scenario(command: ScenarioCommand) -> anyhow::Result<ExitCode> {
    match command {
        ScenarioCommand::List => {
            for s in vivae_lab::shipped::SHIPPED {
                println!("{:<10} {}", s.name, s.what);
            }
        }
        ScenarioCommand::Info { file, json } => {
            let loaded = load_scenario(file.as_deref())?;
            let summary = loaded.scenario.summary();
            let marks: Vec<String> = loaded.scenario.marks.iter().map(|m| m.id.clone()).collect();
            if json {
                let mut value = serde_json::to_value(&summary)?;
                value["mark_names"] = serde_json::json!(marks);
                println!("{}", serde_json::to_string(&value)?);
            } else {
                print!("{}", report::scenario_text(&summary, &marks));
            }
        }
        ScenarioCommand::Render { file, out, sensors } => {
            let loaded = load_scenario(file.as_deref())?;
            let bytes = report::render_scenario(&loaded.scenario, sensors, &out)?;
            write_atomic(&out, &bytes)?;
            eprintln!("figure: {}", out.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn cmd_config(command: ConfigCommand) -> anyhow::Result<ExitCode> {
    match command {
        ConfigCommand::Default => print!("{}", Config::default_commented()),
        ConfigCommand::Reference => print!("{}", Config::markdown_reference()),
        ConfigCommand::Check { file } => print!("{}", read_config(&file)?.to_toml()),
    }
    Ok(ExitCode::SUCCESS)
}
