//! The HTTP side of `vivae view`: routes, the WebSocket, the run watcher.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use axum::Router;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Path as UrlPath, State};
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use futures_util::future::BoxFuture;

use super::hosts::HostPolicy;
use crate::report_html::{SCENE_JS, STYLE_CSS};
use vivae_lab::rundir::files;

/// The viewers' WebSocket and status line, loaded by both viewer pages.
const SOCKET_JS: &str = include_str!("../../assets/socket.js");
/// The viewers' playback controls (play, step, reset, speed), put where a
/// page says `<!--VIVAE-PLAYBACK-->`.
const PLAYBACK_HTML: &str = include_str!("../../assets/playback.html");

/// Assets every viewer serves (`/assets/NAME`): name, content type, body.
const COMMON_ASSETS: [(&str, &str, &str); 3] = [
    ("style.css", "text/css; charset=utf-8", STYLE_CSS),
    ("scene.js", "text/javascript; charset=utf-8", SCENE_JS),
    ("socket.js", "text/javascript; charset=utf-8", SOCKET_JS),
];

/// Files of every run a viewer's page may fetch (`/run/NAME`), with their
/// content types.
const COMMON_RUN_FILES: [(&str, &str); 3] = [
    (files::CONFIG, "text/plain; charset=utf-8"),
    (files::SCENARIO, "image/svg+xml"),
    (files::REPORT, "text/html; charset=utf-8"),
];

/// Interval between frames sent to a page.
pub(crate) const FRAME: Duration = Duration::from_millis(16);
/// Largest message a page may send.
pub(crate) const MAX_MESSAGE: usize = 16 * 1024;
/// Pages silent this long (no message, not even the answer to a ping, which
/// browsers send by themselves) are dropped and their viewer slot freed.
pub const IDLE_TIMEOUT: Duration = Duration::from_secs(120);
/// Size of the pieces a run file is sent in (memory per request stays this).
const CHUNK: usize = 64 * 1024;

/// Frees a viewer slot when its page's session ends (however it ends).
struct ViewerSlot(Arc<AtomicUsize>);

impl Drop for ViewerSlot {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

/// What a viewer serves besides its WebSocket: its page, the assets the page
/// loads and the run files it may fetch.
pub(crate) struct Site {
    /// The page at `/` (see [`page`]).
    pub page: String,
    /// The page's own `/assets/NAME` besides [`COMMON_ASSETS`]: name,
    /// content type, body.
    pub assets: &'static [(&'static str, &'static str, &'static str)],
    /// Run files a page may fetch (as `/run/NAME`) besides
    /// [`COMMON_RUN_FILES`], with their content types; nothing else of the
    /// disk is served.
    pub run_files: &'static [(&'static str, &'static str)],
    /// The run directory they are read from (none: no run files).
    pub run_dir: Option<PathBuf>,
}

/// A viewer page from its template: the shared pieces put in their places.
pub(crate) fn page(template: &str) -> String {
    template.replacen("      <!--VIVAE-PLAYBACK-->\n", PLAYBACK_HTML, 1)
}

/// Plays one page's WebSocket session to its end.
pub(crate) type Session = Arc<dyn Fn(WebSocket) -> BoxFuture<'static, ()> + Send + Sync>;

/// The state every route of a viewer shares.
#[derive(Clone)]
struct Shared {
    site: Arc<Site>,
    viewers: Arc<AtomicUsize>,
    max_viewers: usize,
    hosts: Arc<HostPolicy>,
    session: Session,
}

/// Serves `site`, and a [`Session`] for each page's WebSocket (at most
/// `max_viewers` at once), to the Host names `hosts` allows, until the
/// process is stopped.
pub(crate) async fn serve_site(
    listener: tokio::net::TcpListener,
    site: Site,
    max_viewers: usize,
    hosts: HostPolicy,
    session: Session,
) -> std::io::Result<()> {
    let shared = Shared {
        site: Arc::new(site),
        viewers: Arc::new(AtomicUsize::new(0)),
        max_viewers,
        hosts: Arc::new(hosts),
        session,
    };
    let router = Router::new()
        .route("/", get(index))
        .route("/assets/{name}", get(asset))
        .route("/run/{name}", get(run_file))
        .route("/ws", get(ws))
        .fallback(not_found)
        .layer(axum::middleware::from_fn_with_state(
            shared.clone(),
            known_host,
        ))
        .with_state(shared);
    axum::serve(listener, router).await
}

/// Answers only requests addressed to a Host name this server accepts (see
/// [`HostPolicy`]): a DNS-rebinding page, which names its own site, is refused
/// on every path, the WebSocket upgrade included.
async fn known_host(
    State(shared): State<Shared>,
    request: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    let host = request
        .headers()
        .get(header::HOST)
        .and_then(|h| h.to_str().ok());
    if !shared.hosts.allows(host) {
        return (
            StatusCode::FORBIDDEN,
            "unknown Host name (vivae view --allow-host NAME accepts another)\n",
        )
            .into_response();
    }
    next.run(request).await
}

pub(crate) async fn not_found() -> Response {
    (StatusCode::NOT_FOUND, "not found\n").into_response()
}

pub(crate) fn text(content_type: &'static str, body: impl Into<axum::body::Body>) -> Response {
    (
        [
            (header::CONTENT_TYPE, content_type),
            (header::CACHE_CONTROL, "no-store"),
        ],
        body.into(),
    )
        .into_response()
}

async fn index(State(shared): State<Shared>) -> Response {
    text("text/html; charset=utf-8", shared.site.page.clone())
}

async fn asset(State(shared): State<Shared>, UrlPath(name): UrlPath<String>) -> Response {
    let mut assets = COMMON_ASSETS.iter().chain(shared.site.assets);
    match assets.find(|(n, _, _)| *n == name) {
        Some((_, content_type, body)) => text(content_type, *body),
        None => not_found().await,
    }
}

async fn run_file(State(shared): State<Shared>, UrlPath(name): UrlPath<String>) -> Response {
    let Some(dir) = shared.site.run_dir.as_deref() else {
        return not_found().await;
    };
    // Only the exact names listed: no path of the page's choosing reaches the disk.
    let mut listed = COMMON_RUN_FILES.iter().chain(shared.site.run_files);
    let Some((file, content_type)) = listed.find(|(n, _)| *n == name) else {
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
pub(crate) fn open_run_file(dir: &Path, path: &Path) -> std::io::Result<(std::fs::File, u64)> {
    let real = std::fs::canonicalize(path)?;
    if !real.starts_with(std::fs::canonicalize(dir)?) {
        return Err(std::io::ErrorKind::PermissionDenied.into());
    }
    let (file, meta) = vivae_lab::io::open_regular(&real)?;
    Ok((file, meta.len()))
}

/// The first `len` bytes of `file`, read and sent a chunk at a time.
pub(crate) fn file_body(file: std::fs::File, len: u64) -> axum::body::Body {
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
pub(crate) fn same_origin(headers: &HeaderMap) -> bool {
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

async fn ws(
    State(shared): State<Shared>,
    headers: HeaderMap,
    upgrade: WebSocketUpgrade,
) -> Response {
    if !same_origin(&headers) {
        return (StatusCode::FORBIDDEN, "foreign origin\n").into_response();
    }
    if shared.viewers.fetch_add(1, Ordering::SeqCst) >= shared.max_viewers {
        shared.viewers.fetch_sub(1, Ordering::SeqCst);
        return (
            StatusCode::SERVICE_UNAVAILABLE,
            "too many viewers: close another page first\n",
        )
            .into_response();
    }
    let slot = ViewerSlot(shared.viewers.clone());
    upgrade
        .max_message_size(MAX_MESSAGE)
        .max_frame_size(MAX_MESSAGE)
        .on_upgrade(move |socket| async move {
            let _slot = slot;
            (shared.session)(socket).await;
        })
}

pub(crate) fn error_msg(message: &str) -> String {
    serde_json::json!({"type": "error", "message": message}).to_string()
}

/// Sends `text`, giving up (`false`) if the page has not taken it within
/// `idle`: a page that stops reading must not hold its slot either.
pub(crate) async fn send_within(socket: &mut WebSocket, message: Message, idle: Duration) -> bool {
    matches!(
        tokio::time::timeout(idle, socket.send(message)).await,
        Ok(Ok(()))
    )
}

/// What a page plays in its session: a task's simulation (e.g. the driving
/// robots, a predator–prey game).
pub(crate) trait Play: Send {
    /// Obeys one text message from the page; what went wrong, if anything.
    fn handle(&mut self, text: &str) -> Result<(), String>;
    /// Moves on by `dt` seconds of wall time.
    fn advance(&mut self, dt: f64);
    /// Waits for news from outside the page (a followed run's new
    /// generations) and says what to tell it; never, if nothing can change.
    fn news(&mut self) -> impl Future<Output = Option<Message>> + Send;
    /// Adds to `out` what the page is owed after a turn (a new frame).
    fn owed(&mut self, out: &mut Vec<Message>);
}

/// One page's session: plays `game` until the page goes away, or has been
/// silent for `idle` (it is pinged meanwhile; a browser answers pings by
/// itself, so an open page is never silent).
pub(crate) async fn play(mut socket: WebSocket, mut game: impl Play, idle: Duration) {
    let mut tick = tokio::time::interval(FRAME);
    tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    let mut ping = tokio::time::interval(idle / 4);
    let mut heard = tokio::time::Instant::now();
    let mut last = Instant::now();
    loop {
        let mut out: Vec<Message> = Vec::new();
        tokio::select! {
            msg = socket.recv() => match msg {
                // A closed tab ends its simulation here.
                None | Some(Err(_)) | Some(Ok(Message::Close(_))) => break,
                Some(Ok(m)) => {
                    heard = tokio::time::Instant::now();
                    out.extend(page_message(m, &mut game));
                }
            },
            _ = tokio::time::sleep_until(heard + idle) => break,
            _ = ping.tick() => out.push(Message::Ping(Default::default())),
            _ = tick.tick() => {
                let now = Instant::now();
                // A stalled page does not make the simulation jump ahead.
                game.advance((now - last).as_secs_f64().min(0.25));
                last = now;
            }
            news = game.news() => out.extend(news),
        }
        game.owed(&mut out);
        for m in out {
            if !send_within(&mut socket, m, idle).await {
                return;
            }
        }
    }
}

/// Obeys one message from the page; what to answer (an error, if any).
fn page_message(m: Message, game: &mut impl Play) -> Option<Message> {
    let error = match m {
        Message::Text(t) => game.handle(t.as_str()).err(),
        Message::Binary(_) => Some("binary messages are not understood".into()),
        // Pongs (and pings) only show that the page is there.
        _ => None,
    };
    error.map(|e| Message::Text(error_msg(&e).into()))
}
