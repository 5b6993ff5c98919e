//! The HTTP side of `vivae view`: routes, the WebSocket, the run watcher.

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use axum::Router;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Path as UrlPath, State};
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use tokio::sync::watch;

use super::hosts::HostPolicy;
use super::session::Sim;
use super::source::{SharedSnapshot, Source};
use crate::report_html::{PLOTS_JS, SCENE_JS, STYLE_CSS};
use vivae_lab::rundir::files;

/// The viewer page.
const INDEX_HTML: &str = include_str!("../../assets/view.html");
/// The viewer page's script.
const VIEW_JS: &str = include_str!("../../assets/view.js");

/// Run files a page may fetch (as `/run/NAME`); nothing else of the disk is served.
const RUN_FILES: [(&str, &str); 7] = [
    (files::CONFIG, "text/plain; charset=utf-8"),
    (files::SCENARIO, "image/svg+xml"),
    (files::GENERATIONS, "text/csv; charset=utf-8"),
    (files::POPULATION, "text/csv; charset=utf-8"),
    (files::CHAMPION, "application/json"),
    (files::BEST_GENOMES, "text/plain; charset=utf-8"),
    (files::REPORT, "text/html; charset=utf-8"),
];

/// How often a followed run directory is checked for new generations.
const POLL: Duration = Duration::from_millis(700);
/// Interval between frames sent to a page.
pub(super) const FRAME: Duration = Duration::from_millis(16);
/// Largest message a page may send.
pub(super) const MAX_MESSAGE: usize = 16 * 1024;
/// Pages silent this long (no message, not even the answer to a ping, which
/// browsers send by themselves) are dropped and their viewer slot freed.
pub const IDLE_TIMEOUT: Duration = Duration::from_secs(120);
/// Size of the pieces a run file is sent in (memory per request stays this).
const CHUNK: usize = 64 * 1024;

#[derive(Clone)]
struct App {
    source: Arc<Source>,
    snapshot: watch::Receiver<SharedSnapshot>,
    viewers: Arc<AtomicUsize>,
    max_viewers: usize,
    hosts: Arc<HostPolicy>,
    /// See [`IDLE_TIMEOUT`].
    idle: Duration,
}

/// Frees a viewer slot when its page's session ends (however it ends).
pub(super) struct ViewerSlot(pub(super) Arc<AtomicUsize>);

impl Drop for ViewerSlot {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Serves until the process is stopped.
pub(super) async fn serve(
    listener: tokio::net::TcpListener,
    source: Source,
    max_viewers: usize,
    hosts: HostPolicy,
    idle: Duration,
) -> std::io::Result<()> {
    let source = Arc::new(source);
    let (tx, rx) = watch::channel(Arc::new(source.snapshot()));
    if source.run_dir().is_some() {
        let watched = source.clone();
        tokio::spawn(async move {
            let mut stamp = watched.stamp();
            loop {
                tokio::time::sleep(POLL).await;
                let now = watched.stamp();
                if now != stamp {
                    stamp = now;
                    let w = watched.clone();
                    if let Ok(snap) = tokio::task::spawn_blocking(move || w.snapshot()).await {
                        let _ = tx.send(Arc::new(snap));
                    }
                }
            }
        });
    }
    let app = App {
        source,
        snapshot: rx,
        viewers: Arc::new(AtomicUsize::new(0)),
        max_viewers,
        hosts: Arc::new(hosts),
        idle,
    };
    let router = Router::new()
        .route("/", get(index))
        .route("/assets/{name}", get(asset))
        .route("/run/{name}", get(run_file))
        .route("/ws", get(ws))
        .fallback(not_found)
        .layer(axum::middleware::from_fn_with_state(
            app.clone(),
            known_host,
        ))
        .with_state(app);
    axum::serve(listener, router).await?;
    Ok(())
}

/// Answers only requests addressed to a Host name this server accepts (see
/// [`HostPolicy`]): a DNS-rebinding page, which names its own site, is refused
/// on every path, the WebSocket upgrade included.
async fn known_host(
    State(app): State<App>,
    request: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    let host = request
        .headers()
        .get(header::HOST)
        .and_then(|h| h.to_str().ok());
    if !app.hosts.allows(host) {
        return (
            StatusCode::FORBIDDEN,
            "unknown Host name (vivae view --allow-host NAME accepts another)\n",
        )
            .into_response();
    }
    next.run(request).await
}

pub(super) async fn not_found() -> Response {
    (StatusCode::NOT_FOUND, "not found\n").into_response()
}

pub(super) fn text(content_type: &'static str, body: impl Into<axum::body::Body>) -> Response {
    (
        [
            (header::CONTENT_TYPE, content_type),
            (header::CACHE_CONTROL, "no-store"),
        ],
        body.into(),
    )
        .into_response()
}

async fn index() -> Response {
    text("text/html; charset=utf-8", INDEX_HTML)
}

async fn asset(UrlPath(name): UrlPath<String>) -> Response {
    match name.as_str() {
        "style.css" => text("text/css; charset=utf-8", STYLE_CSS),
        "scene.js" => text("text/javascript; charset=utf-8", SCENE_JS),
        "plots.js" => text("text/javascript; charset=utf-8", PLOTS_JS),
        "view.js" => text("text/javascript; charset=utf-8", VIEW_JS),
        _ => not_found().await,
    }
}

async fn run_file(State(app): State<App>, UrlPath(name): UrlPath<String>) -> Response {
    let Some(dir) = app.source.run_dir() else {
        return not_found().await;
    };
    // Only the exact names listed: no path of the page's choosing reaches the disk.
    let Some((file, content_type)) = RUN_FILES.iter().find(|(n, _)| *n == name) else {
        return not_found().await;
    };
    let (dir, path) = (dir.to_path_buf(), dir.join(file));
    match tokio::task::spawn_blocking(move || open_run_file(&dir, &path)).await {
        Ok(Ok((file, len))) => text(content_type, file_body(file, len)),
        _ => not_found().await,
    }
}

/// Opens a run file to be served: it must be a regular file inside the run
/// directory once symlinks are followed (a link to `/etc/passwd`, a FIFO or
/// `/dev/zero` is refused, without waiting on it).
pub(super) fn open_run_file(dir: &Path, path: &Path) -> std::io::Result<(std::fs::File, u64)> {
    let real = std::fs::canonicalize(path)?;
    if !real.starts_with(std::fs::canonicalize(dir)?) {
        return Err(std::io::ErrorKind::PermissionDenied.into());
    }
    let (file, meta) = vivae_lab::io::open_regular(&real)?;
    Ok((file, meta.len()))
}

/// The first `len` bytes of `file`, read and sent a chunk at a time.
pub(super) fn file_body(file: std::fs::File, len: u64) -> axum::body::Body {
    use tokio::io::AsyncReadExt;
    let reader = tokio::fs::File::from_std(file).take(len);
    let chunks = futures_util::stream::unfold(Some(reader), |reader| async move {
        let mut reader = reader?;
        let mut buf = vec![0u8; CHUNK];
        match reader.read(&mut buf).await {
            Ok(0) => None,
            Ok(n) => {
                buf.truncate(n);
                Some((Ok(buf), Some(reader)))
            }
            Err(e) => Some((Err(e), None)),
        }
    });
    axum::body::Body::from_stream(chunks)
}

/// A browser page may open the WebSocket only from this server's own page:
/// another site open in the same browser must not read the run.
pub(super) fn same_origin(headers: &HeaderMap) -> bool {
    let Some(origin) = headers.get(header::ORIGIN) else {
        // Not a browser page (a script or a test client).
        return true;
    };
    let host = headers.get(header::HOST).and_then(|h| h.to_str().ok());
    match (origin.to_str().ok(), host) {
        (Some(o), Some(h)) => o == format!("http://{h}") || o == format!("https://{h}"),
        _ => false,
    }
}

async fn ws(State(app): State<App>, headers: HeaderMap, upgrade: WebSocketUpgrade) -> Response {
    if !same_origin(&headers) {
        return (StatusCode::FORBIDDEN, "foreign origin\n").into_response();
    }
    if app.viewers.fetch_add(1, Ordering::SeqCst) >= app.max_viewers {
        app.viewers.fetch_sub(1, Ordering::SeqCst);
        return (
            StatusCode::SERVICE_UNAVAILABLE,
            "too many viewers: close another page first\n",
        )
            .into_response();
    }
    let slot = ViewerSlot(app.viewers.clone());
    upgrade
        .max_message_size(MAX_MESSAGE)
        .max_frame_size(MAX_MESSAGE)
        .on_upgrade(move |socket| async move {
            let _slot = slot;
            session(socket, app).await;
        })
}

pub(super) fn error_msg(message: &str) -> String {
    serde_json::json!({"type": "error", "message": message}).to_string()
}

/// Sends `text`, giving up (`false`) if the page has not taken it within
/// `idle`: a page that stops reading must not hold its slot either.
pub(super) async fn send_within(socket: &mut WebSocket, message: Message, idle: Duration) -> bool {
    matches!(
        tokio::time::timeout(idle, socket.send(message)).await,
        Ok(Ok(()))
    )
}

/// Starts a page's session: its simulation, and the `info` and `progress`
/// messages; `None` if the page is gone (or was told why there is none).
async fn open_session(socket: &mut WebSocket, app: &mut App) -> Option<(Sim, SharedSnapshot)> {
    let snap = app.snapshot.borrow_and_update().clone();
    let sim = match tokio::task::block_in_place(|| Sim::new(&app.source, &snap)) {
        Ok(sim) => sim,
        Err(e) => {
            send_within(socket, Message::Text(error_msg(&e).into()), app.idle).await;
            return None;
        }
    };
    let info = serde_json::json!({
        "type": "info",
        "source": app.source.describe(),
        "run": app.source.run_dir().is_some(),
        "scenarios": app.source.scenarios.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(),
        "unusable": app.source.unusable,
        "real_time_steps": super::session::REAL_TIME_STEPS,
        "behaviour_names": app.source.behaviour_names(&snap),
        "objective_names": app.source.objective_names(),
    });
    let progress = serde_json::to_string(&snap.progress()).unwrap_or_default();
    for m in [info.to_string(), progress] {
        if !send_within(socket, Message::Text(m.into()), app.idle).await {
            return None;
        }
    }
    Some((sim, snap))
}

/// One page's session: runs its simulation until the page goes away, or
/// has been silent for [`App::idle`] (it is pinged meanwhile; a browser
/// answers pings by itself, so an open page is never silent).
async fn session(mut socket: WebSocket, mut app: App) {
    let Some((mut sim, mut snap)) = open_session(&mut socket, &mut app).await else {
        return;
    };
    let mut tick = tokio::time::interval(FRAME);
    tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    let mut ping = tokio::time::interval(app.idle / 4);
    let mut heard = tokio::time::Instant::now();
    let mut last = Instant::now();
    let mut watching = true;
    loop {
        let mut out: Vec<Message> = Vec::new();
        tokio::select! {
            msg = socket.recv() => match msg {
                // A closed tab ends its simulation here.
                None | Some(Err(_)) | Some(Ok(Message::Close(_))) => break,
                Some(Ok(m)) => {
                    heard = tokio::time::Instant::now();
                    out.extend(page_message(m, &mut sim, &app, &snap));
                }
            },
            _ = tokio::time::sleep_until(heard + app.idle) => break,
            _ = ping.tick() => out.push(Message::Ping(Default::default())),
            _ = tick.tick() => {
                let now = Instant::now();
                // A stalled page does not make the simulation jump ahead.
                sim.advance((now - last).as_secs_f64().min(0.25));
                last = now;
            }
            changed = app.snapshot.changed(), if watching => {
                if changed.is_err() {
                    // No watcher (not a run): nothing will change.
                    watching = false;
                } else {
                    snap = app.snapshot.borrow_and_update().clone();
                    let p = serde_json::to_string(&snap.progress()).unwrap_or_default();
                    out.push(Message::Text(p.into()));
                }
            }
        }
        if sim.scene_dirty {
            sim.scene_dirty = false;
            out.push(Message::Text(sim.scene_msg(&app.source).into()));
        }
        if sim.dirty {
            out.push(Message::Text(sim.frame_msg().into()));
        }
        for m in out {
            if !send_within(&mut socket, m, app.idle).await {
                return;
            }
        }
    }
}

/// Obeys one message from the page; what to answer (an error, if any).
fn page_message(m: Message, sim: &mut Sim, app: &App, snap: &SharedSnapshot) -> Option<Message> {
    let error = match m {
        Message::Text(t) => sim.handle(t.as_str(), &app.source, snap).err(),
        Message::Binary(_) => Some("binary messages are not understood".into()),
        // Pongs (and pings) only show that the page is there.
        _ => None,
    };
    error.map(|e| Message::Text(error_msg(&e).into()))
}
