//! The HTTP side of `vivae view` on a predator–prey run: its page, the
//! shared assets, a fixed list of the run's files and the WebSocket of a
//! page's [`Game`]. Host names, origins, viewer slots and idle pages are
//! handled as for a driving run ([`crate::view::server`]).

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use axum::extract::ws::{Message, WebSocket};

use super::{Game, Hall};
use crate::view::Served;
use crate::view::server::{Play, Session, Site, error_msg, page, play, send_within, serve_site};
use vivae_lab::tasks::predator_prey::run::files;

/// The predator–prey viewer page.
const INDEX_HTML: &str = include_str!("../../../../assets/coevo.html");
/// Its script.
const COEVO_JS: &str = include_str!("../../../../assets/coevo.js");

/// A predator–prey run's own files a page may fetch (as `/run/NAME`).
const RUN_FILES: [(&str, &str); 4] = [
    (files::HUNTERS, "text/csv; charset=utf-8"),
    (files::PREY, "text/csv; charset=utf-8"),
    (files::CIAO, "text/csv; charset=utf-8"),
    (files::CHAMPIONS, "application/json"),
];

/// Serves the predator–prey run in `dir` until the process is stopped.
pub(super) async fn serve(served: Served) -> std::io::Result<()> {
    let Served {
        listener,
        dir,
        max_viewers,
        hosts,
        idle,
    } = served;
    let site = Site {
        page: page(INDEX_HTML),
        assets: &[("coevo.js", "text/javascript; charset=utf-8", COEVO_JS)],
        run_files: &RUN_FILES,
        run_dir: Some(dir.clone()),
    };
    let dir = Arc::new(dir);
    let session: Session = Arc::new(move |socket| Box::pin(session(socket, dir.clone(), idle)));
    serve_site(listener, site, max_viewers, hosts, session).await
}

/// Starts a page's game on the run as it is now (a running run's newer
/// generations appear when the page is reloaded): `info` and `scene` sent.
async fn open_game(
    socket: &mut WebSocket,
    dir: Arc<PathBuf>,
    idle: Duration,
) -> Option<(Hall, Game)> {
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
            send_within(socket, Message::Text(error_msg(&e).into()), idle).await;
            return None;
        }
    };
    for m in [hall.info(), Game::scene_msg(&hall)] {
        if !send_within(socket, Message::Text(m.into()), idle).await {
            return None;
        }
    }
    Some((hall, game))
}

/// A page's game on the run's hall of fame.
struct Playing {
    hall: Hall,
    game: Game,
}

impl Play for Playing {
    fn handle(&mut self, text: &str) -> Result<(), String> {
        self.game.handle(text, &self.hall)
    }

    fn advance(&mut self, dt: f64) {
        self.game.advance(&self.hall, dt);
    }

    async fn news(&mut self) -> Option<Message> {
        // The hall is read once: a page reload shows newer generations.
        std::future::pending().await
    }

    fn owed(&mut self, out: &mut Vec<Message>) {
        if self.game.dirty {
            out.push(Message::Text(self.game.frame_msg(&self.hall).into()));
        }
    }
}

/// One page's session: plays its game until the page goes away or has been
/// silent for `idle` (pinged meanwhile).
async fn session(mut socket: WebSocket, dir: Arc<PathBuf>, idle: Duration) {
    let Some((hall, game)) = open_game(&mut socket, dir, idle).await else {
        return;
    };
    play(socket, Playing { hall, game }, idle).await;
}
