//! `vivae view`: serves a run, a genome or a scenario to the browser (see
//! `crate::view`).

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use crate::view::{IDLE_TIMEOUT, Shown, ViewOptions};
use clap::Args;
use vivae_lab::io::bad_input;
use vivae_lab::rundir::files;
use vivae_lab::tasks::{read_champion, read_config};

use super::args::MemberChoice;
use super::report::refuse_other_task;

/// Options of `vivae view`.
#[derive(Args, Debug, Clone)]
#[command(mut_arg("elite", |a| a.help(
    "Drive the elite of this cell of the run's archive (archive.csv, runs whose strategy keeps one) \
     when a page opens; the page's controller list offers every elite"
)))]
#[command(mut_arg("front", |a| a.help(
    "Drive this member of the run's Pareto front (front.csv, runs whose strategy keeps one; 0 = the \
     fittest) when a page opens; the page's list offers every member"
)))]
pub struct ViewArgs {
    /// A run directory (follows it while it runs), a champion genome JSON, or a
    /// scenario SVG (drive by keyboard). Default: the embedded road scenario.
    pub source: Option<PathBuf>,
    #[command(flatten)]
    pub member: MemberChoice,
    /// Port to listen on (0 = any free port).
    #[arg(long, default_value_t = 7878, value_name = "N")]
    pub port: u16,
    /// Address to listen on; anything but a loopback address lets the network watch.
    #[arg(long, default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST), value_name = "ADDR")]
    pub host: IpAddr,
    /// Extra scenarios to offer: every `.svg` file in this folder.
    #[arg(long, value_name = "DIR")]
    pub scenarios: Option<PathBuf>,
    /// Another Host name to answer (repeatable), e.g. this machine's name on
    /// the network; besides it only the listening address and `localhost` are
    /// answered (a defence against DNS rebinding).
    #[arg(long, value_name = "NAME")]
    pub allow_host: Vec<String>,
    /// Most pages simulated at once; more are refused until one closes.
    #[arg(long, default_value_t = 8, value_name = "N")]
    pub max_viewers: usize,
    /// Seconds a page may stay silent before it is dropped and its slot freed
    /// (hidden: for tests; browsers answer the server's pings by themselves).
    #[arg(long, hide = true, default_value_t = IDLE_TIMEOUT.as_secs_f64(), value_name = "SECS")]
    pub idle_timeout: f64,
}

/// Runs `vivae view` until interrupted.
pub fn run(args: ViewArgs) -> anyhow::Result<ExitCode> {
    // A run whose task has a page of its own (its program-side tools) is
    // served that page; anything else its task's live world.
    let source = args.source.as_deref();
    let own_page = source.and_then(crate::tasks::of_run).and_then(|t| t.view);
    let shown = match (source, own_page) {
        (Some(dir), Some(page)) => Shown::Own(dir, page),
        _ => {
            if let Some(source) = source {
                refuse_other_task(source, "view")?;
            }
            let task = task_of(source);
            let world = (crate::tasks::of_task(&task).and_then(|t| t.world)).ok_or_else(|| {
                bad_input(format!("vivae view: task {task} has no world to show"))
            })?;
            Shown::World(source, world)
        }
    };
    if args.max_viewers == 0 {
        return Err(bad_input("--max-viewers 0: must be at least 1").into());
    }
    if !(args.idle_timeout.is_finite() && (0.1..=86_400.0).contains(&args.idle_timeout)) {
        return Err(bad_input("--idle-timeout: must be 0.1 to 86400 seconds").into());
    }
    let options = ViewOptions {
        member: args.member.member(),
        addr: SocketAddr::new(args.host, args.port),
        scenarios: args.scenarios,
        allow_host: args.allow_host,
        max_viewers: args.max_viewers,
        idle_timeout: Duration::from_secs_f64(args.idle_timeout),
    };
    Ok(crate::view::run(shown, &options)?)
}

/// The task of what `vivae view` shows: a run's (by its config), a genome
/// file's (by the config it records), else the default config's (a
/// scenario, or none).
fn task_of(source: Option<&Path>) -> String {
    let config = match source {
        Some(dir) if dir.is_dir() => read_config(&dir.join(files::CONFIG)).ok(),
        Some(file) => read_champion(file).ok().and_then(|c| c.config),
        None => None,
    };
    config
        .unwrap_or_default()
        .experiment
        .task
        .name()
        .to_string()
}
