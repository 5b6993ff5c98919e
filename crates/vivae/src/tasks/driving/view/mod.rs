//! The driving task's live world in `vivae view`: its robots drive on a
//! run's scenario (followed while the run goes on), a genome's or any
//! scenario, steered by the chosen genome or the arrow keys. One
//! simulation per open page (`session`), streamed over the viewer's
//! WebSocket.

#[doc(hidden)]
pub mod fuzzing;
pub(crate) mod session;

use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use axum::extract::ws::{Message, WebSocket};
use tokio::sync::watch;

use crate::report_html::PLOTS_JS;
use crate::view::keys::REAL_TIME_STEPS;
use crate::view::server::{Play, Session, Site, error_msg, page, play, send_within, serve_site};
use crate::view::source::{SharedSnapshot, Source};
use crate::view::{WorldPage, WorldServed};
use session::Sim;
use vivae_lab::rundir::files;

/// The driving robots' live world.
pub static WORLD: WorldPage = WorldPage { serve: serve_world };

/// The viewer page.
const INDEX_HTML: &str = include_str!("../../../../assets/view.html");
/// The viewer page's script.
const VIEW_JS: &str = include_str!("../../../../assets/view.js");

/// A driving run's own files a page may fetch.
const RUN_FILES: [(&str, &str); 4] = [
    (files::GENERATIONS, "text/csv; charset=utf-8"),
    (files::POPULATION, "text/csv; charset=utf-8"),
    (files::CHAMPION, "application/json"),
    (files::BEST_GENOMES, "text/plain; charset=utf-8"),
];

/// How often a followed run directory is checked for new generations.
const POLL: Duration = Duration::from_millis(700);

#[derive(Clone)]
struct App {
    source: Arc<Source>,
    snapshot: watch::Receiver<SharedSnapshot>,
    /// See [`crate::view::IDLE_TIMEOUT`].
    idle: Duration,
}

/// Serves the driving world of `served` on `runtime` until the process is stopped.
fn serve_world(runtime: &tokio::runtime::Runtime, served: WorldServed) -> std::io::Result<()> {
    runtime.block_on(serve(served))
}

/// Serves a driving run (or a genome, a scenario) until the process is stopped.
async fn serve(served: WorldServed) -> std::io::Result<()> {
    let WorldServed {
        listener,
        source,
        max_viewers,
        hosts,
        idle,
    } = served;
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
    let run_dir = source.run_dir().map(Path::to_path_buf);
    let app = App {
        source,
        snapshot: rx,
        idle,
    };
    let site = Site {
        page: page(INDEX_HTML),
        assets: &[
            ("plots.js", "text/javascript; charset=utf-8", PLOTS_JS),
            ("view.js", "text/javascript; charset=utf-8", VIEW_JS),
        ],
        run_files: &RUN_FILES,
        run_dir,
    };
    let session: Session = Arc::new(move |socket| Box::pin(session(socket, app.clone())));
    serve_site(listener, site, max_viewers, hosts, session).await
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
        "real_time_steps": REAL_TIME_STEPS,
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

/// A page's driving simulation, following the run's snapshot.
struct Driving {
    sim: Sim,
    snap: SharedSnapshot,
    app: App,
    /// Whether the snapshot can still change (a followed run).
    watching: bool,
}

impl Play for Driving {
    fn handle(&mut self, text: &str) -> Result<(), String> {
        self.sim.handle(text, &self.app.source, &self.snap)
    }

    fn advance(&mut self, dt: f64) {
        self.sim.advance(dt);
    }

    async fn news(&mut self) -> Option<Message> {
        if !self.watching {
            return std::future::pending().await;
        }
        if self.app.snapshot.changed().await.is_err() {
            // No watcher (not a run): nothing will change.
            self.watching = false;
            return None;
        }
        self.snap = self.app.snapshot.borrow_and_update().clone();
        let p = serde_json::to_string(&self.snap.progress()).unwrap_or_default();
        Some(Message::Text(p.into()))
    }

    fn owed(&mut self, out: &mut Vec<Message>) {
        if self.sim.scene_dirty {
            self.sim.scene_dirty = false;
            out.push(Message::Text(self.sim.scene_msg(&self.app.source).into()));
        }
        if self.sim.dirty {
            out.push(Message::Text(self.sim.frame_msg().into()));
        }
    }
}

/// One page's session on a driving run or scenario.
async fn session(mut socket: WebSocket, mut app: App) {
    let Some((sim, snap)) = open_session(&mut socket, &mut app).await else {
        return;
    };
    let idle = app.idle;
    let driving = Driving {
        sim,
        snap,
        app,
        watching: true,
    };
    play(socket, driving, idle).await;
}
