//! The HTTP side of `vivae view` on a predator–prey run: its page, the
//! shared assets, a fixed list of the run's files and the WebSocket of a
//! page's [`Game`]. Host names, origins, viewer slots and idle pages are
//! handled as for a driving run ([`crate::view::server`]).

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use axum::Router;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Path as UrlPath, State};
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::get;

use super::{Game, Hall};
use crate::report_html::{SCENE_JS, STYLE_CSS};
use crate::view::hosts::HostPolicy;
use crate::view::server::{
    FRAME, MAX_MESSAGE, ViewerSlot, error_msg, file_body, not_found, open_run_file, same_origin,
    send_within, text,
};
use vivae_lab::rundir::files as run_files;
use vivae_lab::tasks::predator_prey::run::files;

/// The predator–prey viewer page.
const INDEX_HTML: &str = include_str!("../../../assets/coevo.html");
/// Its script.
const COEVO_JS: &str = include_str!("../../../assets/coevo.js");

/// Run files a page may fetch (as `/run/NAME`); nothing else of the disk is served.
const RUN_FILES: [(&str, &str); 9] = [
    (run_files::CONFIG, "text/plain; charset=utf-8"),
    (run_files::SCENARIO, "image/svg+xml"),
    (files::HUNTERS, "text/csv; charset=utf-8"),
    (files::PREY, "text/csv; charset=utf-8"),
    (files::CIAO, "text/csv; charset=utf-8"),
    (files::CHAMPIONS, "application/json"),
    (run_files::REPORT, "text/html; charset=utf-8"),
    ("ciao.png", "image/png"),
    ("coevolution.png", "image/png"),
];

#[derive(Clone)]
struct App {
    dir: Arc<PathBuf>,
    viewers: Arc<AtomicUsize>,
    max_viewers: usize,
    hosts: Arc<HostPolicy>,
    idle: Duration,
}

/// Serves the predator–prey run in `dir` until the process is stopped.
pub(in crate::view) async fn serve(
    listener: tokio::net::TcpListener,
    dir: PathBuf,
    max_viewers: usize,
    hosts: HostPolicy,
    idle: Duration,
) -> std::io::Result<()> {
    let app = App {
        dir: Arc::new(dir),
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
    axum::serve(listener, router).await
}

/// Answers only requests addressed to a Host name this server accepts.
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

async fn index() -> Response {
    text("text/html; charset=utf-8", INDEX_HTML)
}

async fn asset(UrlPath(name): UrlPath<String>) -> Response {
    match name.as_str() {
        "style.css" => text("text/css; charset=utf-8", STYLE_CSS),
        "scene.js" => text("text/javascript; charset=utf-8", SCENE_JS),
        "coevo.js" => text("text/javascript; charset=utf-8", COEVO_JS),
        _ => not_found().await,
    }
}

async fn run_file(State(app): State<App>, UrlPath(name): UrlPath<String>) -> Response {
    // Only the exact names listed: no path of the page's choosing reaches the disk.
    let Some((file, content_type)) = RUN_FILES.iter().find(|(n, _)| *n == name) else {
        return not_found().await;
    };
    let (dir, path) = (app.dir.to_path_buf(), app.dir.join(file));
    match tokio::task::spawn_blocking(move || open_run_file(&dir, &path)).await {
        Ok(Ok((file, len))) => text(content_type, file_body(file, len)),
        _ => not_found().await,
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

/// Starts a page's game on the run as it is now (a running run's newer
/// generations appear when the page is reloaded): `info` and `scene` sent.
async fn open_game(socket: &mut WebSocket, app: &App) -> Option<(Hall, Game)> {
    let dir = app.dir.clone();
    let loaded = tokio::task::spawn_blocking(move || {
        let hall = Hall::load(&dir).map_err(|e| vivae_lab::io::one_line(&e.to_string()))?;
        let game = Game::new(&hall)?;
        Ok::<_, String>((hall, game))
    })
    .await
    .unwrap_or_else(|e| Err(e.to_string()));
    let (hall, game) = match loaded {
        Ok(x) => x,
        Err(e) => {
            send_within(socket, Message::Text(error_msg(&e).into()), app.idle).await;
            return None;
        }
    };
    for m in [hall.info(), Game::scene_msg(&hall)] {
        if !send_within(socket, Message::Text(m.into()), app.idle).await {
            return None;
        }
    }
    Some((hall, game))
}

/// One page's session: plays its game until the page goes away or has been
/// silent for [`App::idle`] (pinged meanwhile).
async fn session(mut socket: WebSocket, app: App) {
    let Some((hall, mut game)) = open_game(&mut socket, &app).await else {
        return;
    };
    let mut tick = tokio::time::interval(FRAME);
    tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    let mut ping = tokio::time::interval(app.idle / 4);
    let mut heard = tokio::time::Instant::now();
    let mut last = Instant::now();
    loop {
        let mut out: Vec<Message> = Vec::new();
        tokio::select! {
            msg = socket.recv() => match msg {
                None | Some(Err(_)) | Some(Ok(Message::Close(_))) => break,
                Some(Ok(m)) => {
                    heard = tokio::time::Instant::now();
                    let error = match m {
                        Message::Text(t) => game.handle(t.as_str(), &hall).err(),
                        Message::Binary(_) => Some("binary messages are not understood".into()),
                        _ => None,
                    };
                    out.extend(error.map(|e| Message::Text(error_msg(&e).into())));
                }
            },
            _ = tokio::time::sleep_until(heard + app.idle) => break,
            _ = ping.tick() => out.push(Message::Ping(Default::default())),
            _ = tick.tick() => {
                let now = Instant::now();
                game.advance(&hall, (now - last).as_secs_f64().min(0.25));
                last = now;
            }
        }
        if game.dirty {
            out.push(Message::Text(game.frame_msg(&hall).into()));
        }
        for m in out {
            if !send_within(&mut socket, m, app.idle).await {
                return;
            }
        }
    }
}
