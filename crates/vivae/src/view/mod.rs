//! `vivae view`: a local web server where a task's robots move live in the
//! browser.
//!
//! What a page shows is its task's (its program-side tools in
//! `crate::tasks`): a task's live world ([`WorldPage`], e.g. the driving
//! robots on a run's scenario, a genome's or any scenario, following a
//! running evolution) or a page of its own for a run ([`OwnPage`], e.g. a
//! predator–prey run's two teams meet). The robots are simulated here, one
//! simulation per open page, and streamed to the page over a WebSocket
//! (`server`). The pages are plain HTML/CSS/JS embedded in the binary. The
//! server answers only its own assets, a fixed list of the given run's
//! files and the WebSocket; every other path is a 404.

pub(crate) mod hosts;
pub(crate) mod keys;
pub(crate) mod server;
pub(crate) mod source;

pub use server::IDLE_TIMEOUT;

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

pub use source::Source;
use vivae_lab::search::files::Member;

use vivae_lab::io::bad_input;

/// How `vivae view` serves: where it listens, what a page starts with and
/// offers, and how many pages it simulates at once.
#[derive(Debug, Clone)]
pub struct ViewOptions {
    /// The archive or front member a new page drives (none: the champion);
    /// the page's controller list offers every one.
    pub member: Option<Member>,
    /// Address and port to listen on (port 0: any free port); anything but a
    /// loopback address lets the network watch.
    pub addr: SocketAddr,
    /// Extra scenarios to offer: every `.svg` file in this folder.
    pub scenarios: Option<PathBuf>,
    /// Other Host names to answer besides the listening address and
    /// `localhost` (a defence against DNS rebinding).
    pub allow_host: Vec<String>,
    /// Most pages simulated at once (at least 1); more are refused until one closes.
    pub max_viewers: usize,
    /// How long a page may stay silent before it is dropped and its slot freed.
    pub idle_timeout: Duration,
}

/// A task's page of its own for its runs (its program-side tools' `view`).
#[derive(Debug, Clone, Copy)]
pub struct OwnPage {
    /// Loads the run in a directory for its page, refusing in one line what
    /// cannot be shown (or options that do not apply); the line saying what is shown.
    pub open: fn(&Path, &ViewOptions) -> vivae_lab::Result<String>,
    /// Serves the page of the run in a directory on `runtime` until the process is stopped.
    pub serve: fn(&tokio::runtime::Runtime, Served) -> std::io::Result<()>,
}

/// A task's live world, what `vivae view` serves for a run, a genome or a
/// scenario of a task without a page of its own (its program-side tools'
/// `world`).
#[derive(Debug, Clone, Copy)]
pub struct WorldPage {
    /// Serves the world page of what `served` shows on `runtime` until the process is stopped.
    pub serve: fn(&tokio::runtime::Runtime, WorldServed) -> std::io::Result<()>,
}

/// What a world page is served on: the listener, what it shows, the limits.
#[derive(Debug)]
pub struct WorldServed {
    /// Where it listens.
    pub listener: tokio::net::TcpListener,
    /// The run, genome or scenario shown (and the scenarios offered).
    pub source: Source,
    /// Most pages simulated at once.
    pub max_viewers: usize,
    /// The Host names it answers.
    pub hosts: hosts::HostPolicy,
    /// How long a page may stay silent.
    pub idle: Duration,
}

/// What `vivae view` shows: a run on its task's page of its own, or a run, a
/// genome, a scenario or nothing (the embedded road scenario) in a task's
/// live world.
#[derive(Debug, Clone, Copy)]
pub enum Shown<'a> {
    /// The run directory on its task's own page.
    Own(&'a Path, OwnPage),
    /// The source (none: the embedded scenario) in the task's world.
    World(Option<&'a Path>, WorldPage),
}

/// What a page of its own is served on: the listener, the run, the limits.
#[derive(Debug)]
pub struct Served {
    /// Where it listens.
    pub listener: tokio::net::TcpListener,
    /// The run directory.
    pub dir: PathBuf,
    /// Most pages simulated at once.
    pub max_viewers: usize,
    /// The Host names it answers.
    pub hosts: hosts::HostPolicy,
    /// How long a page may stay silent.
    pub idle: Duration,
}

/// Runs `vivae view` on what is `shown` (in a world: a run directory, which
/// it follows while it runs, a genome JSON, a scenario SVG, or none: the
/// embedded road scenario) until interrupted; the pages come from the
/// task's program-side tools (`crate::tasks`).
pub fn run(shown: Shown<'_>, options: &ViewOptions) -> vivae_lab::Result<ExitCode> {
    let host = options.addr.ip();
    let hosts = hosts::HostPolicy::new(host, &options.allow_host)?;
    // Refused now, in one line, rather than on every page.
    let ready = match shown {
        Shown::Own(dir, page) => Ready::Own(dir.to_path_buf(), page, (page.open)(dir, options)?),
        Shown::World(source, page) => {
            let mut loaded = Source::load(source, options.scenarios.as_deref())?;
            if let Some(member) = options.member {
                loaded.start_with(member)?;
            }
            Ready::World(Box::new(loaded), page)
        }
    };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(|e| vivae_lab::Error::Threads(e.to_string()))?;
    let addr = options.addr;
    let listener = runtime
        .block_on(tokio::net::TcpListener::bind(addr))
        .map_err(|e| cannot_listen(addr, &e))?;
    let io = |action: &'static str| {
        move |error: std::io::Error| vivae_lab::Error::Io {
            action,
            path: std::path::PathBuf::from(addr.to_string()),
            error,
        }
    };
    let local = listener.local_addr().map_err(io("listen on"))?;
    // An IPv4-mapped loopback address (::ffff:127.0.0.1) is loopback too.
    if !host.to_canonical().is_loopback() {
        eprintln!(
            "warning: listening on {host} — anyone who can reach this machine on the network can watch this run"
        );
    }
    let url = if host.is_unspecified() {
        SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), local.port())
    } else {
        local
    };
    println!("vivae view: http://{url}/");
    match &ready {
        Ready::Own(_, _, showing) => eprintln!("{showing}"),
        Ready::World(source, _) => {
            eprintln!("{} (Ctrl-C stops the server)", source.describe());
            if let Some(note) = source.unusable_note() {
                eprintln!("{note}");
            }
        }
    }
    use std::io::Write as _;
    let _ = std::io::stdout().flush();
    let (max, idle) = (options.max_viewers, options.idle_timeout);
    let served = match ready {
        Ready::Own(dir, page, _) => {
            let served = Served {
                listener,
                dir,
                max_viewers: max,
                hosts,
                idle,
            };
            (page.serve)(&runtime, served)
        }
        Ready::World(source, page) => {
            let served = WorldServed {
                listener,
                source: *source,
                max_viewers: max,
                hosts,
                idle,
            };
            (page.serve)(&runtime, served)
        }
    };
    served.map_err(io("serve on"))?;
    Ok(ExitCode::SUCCESS)
}

/// What is shown, loaded and checked: a run on its own page (with the line
/// saying what is shown), or a source in a world.
enum Ready {
    Own(PathBuf, OwnPage, String),
    World(Box<Source>, WorldPage),
}

/// Why `vivae view` cannot listen on `addr`, in one line.
fn cannot_listen(addr: SocketAddr, e: &std::io::Error) -> vivae_lab::Error {
    let why = match e.kind() {
        std::io::ErrorKind::AddrInUse => "port already in use (choose another --port)".into(),
        std::io::ErrorKind::AddrNotAvailable => "no such address on this machine".into(),
        std::io::ErrorKind::PermissionDenied => "permission denied".into(),
        _ => e.to_string(),
    };
    bad_input(format!("cannot listen on {addr}: {why}"))
}
