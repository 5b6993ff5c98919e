//! `vivae view`: a local web server where robots drive live in the browser.
//!
//! The robots are simulated here, by the real [`Experiment`] controller and
//! `vivae-sim` world, one simulation per open page, and streamed to the page
//! over a WebSocket ([`session`]). The page is plain HTML/CSS/JS embedded in
//! the binary. The server answers only its own assets, a fixed list of the
//! given run's files and the WebSocket; every other path is a 404.

#[doc(hidden)]
pub mod fuzzing;
mod hosts;
mod server;
mod session;
mod source;

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use source::Source;
use vivae_lab::strategy_files::Member;

use vivae_lab::io::bad_input;

/// Command-line options of `vivae view`.
#[derive(Args, Debug, Clone)]
pub struct ViewArgs {
    /// A run directory (follows it while it runs), a champion genome JSON, or a
    /// scenario SVG (drive by keyboard). Default: the embedded road scenario.
    pub source: Option<PathBuf>,
    /// Drive the elite of this cell of a map-elites run's archive (archive.csv)
    /// when a page opens; the page's controller list offers every elite.
    #[arg(long, value_name = "CELL", conflicts_with = "front")]
    pub elite: Option<usize>,
    /// Drive this member of an nsga2 run's Pareto front (front.csv; 0 = the
    /// fittest) when a page opens; the page's list offers every member.
    #[arg(long, value_name = "N")]
    pub front: Option<usize>,
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
    #[arg(long, hide = true, default_value_t = server::IDLE_TIMEOUT.as_secs_f64(), value_name = "SECS")]
    pub idle_timeout: f64,
}

/// Runs `vivae view` until interrupted.
pub fn run(args: ViewArgs) -> vivae_lab::Result<ExitCode> {
    if args.max_viewers == 0 {
        return Err(bad_input("--max-viewers 0: must be at least 1"));
    }
    if !(args.idle_timeout.is_finite() && (0.1..=86_400.0).contains(&args.idle_timeout)) {
        return Err(bad_input("--idle-timeout: must be 0.1 to 86400 seconds"));
    }
    let idle = std::time::Duration::from_secs_f64(args.idle_timeout);
    let hosts = hosts::HostPolicy::new(args.host, &args.allow_host)?;
    let mut source = Source::load(args.source.as_deref(), args.scenarios.as_deref())?;
    let member = (args.elite.map(Member::Elite)).or(args.front.map(Member::Front));
    if let Some(member) = member {
        source.start_with(member)?;
    }
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(|e| vivae_lab::Error::Threads(e.to_string()))?;
    let addr = SocketAddr::new(args.host, args.port);
    let listener = runtime
        .block_on(tokio::net::TcpListener::bind(addr))
        .map_err(|e| {
            let why = match e.kind() {
                std::io::ErrorKind::AddrInUse => {
                    "port already in use (choose another --port)".into()
                }
                std::io::ErrorKind::AddrNotAvailable => "no such address on this machine".into(),
                std::io::ErrorKind::PermissionDenied => "permission denied".into(),
                _ => e.to_string(),
            };
            bad_input(format!("cannot listen on {addr}: {why}"))
        })?;
    let io = |action: &'static str| {
        move |error: std::io::Error| vivae_lab::Error::Io {
            action,
            path: std::path::PathBuf::from(addr.to_string()),
            error,
        }
    };
    let local = listener.local_addr().map_err(io("listen on"))?;
    // An IPv4-mapped loopback address (::ffff:127.0.0.1) is loopback too.
    if !args.host.to_canonical().is_loopback() {
        eprintln!(
            "warning: listening on {} — anyone who can reach this machine on the network can watch this run",
            args.host
        );
    }
    let shown = if args.host.is_unspecified() {
        SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), local.port())
    } else {
        local
    };
    println!("vivae view: http://{shown}/");
    eprintln!("{} (Ctrl-C stops the server)", source.describe());
    if let Some(note) = source.unusable_note() {
        eprintln!("{note}");
    }
    use std::io::Write as _;
    let _ = std::io::stdout().flush();
    runtime
        .block_on(server::serve(
            listener,
            source,
            args.max_viewers,
            hosts,
            idle,
        ))
        .map_err(io("serve on"))?;
    Ok(ExitCode::SUCCESS)
}
