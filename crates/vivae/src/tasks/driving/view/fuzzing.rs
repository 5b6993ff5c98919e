//! A page's session without its socket, for the `view_messages` fuzz target
//! (`fuzz/`): the messages a page sends, handled as the server handles them.

use std::path::Path;

use super::session::Sim;
use crate::view::source::{RunSnapshot, Source};

/// Duration of one frame of playing between two messages (as at 60 frames/s).
const FRAME_SECONDS: f64 = 1.0 / 60.0;

/// What `vivae view SOURCE` serves, and a runtime to run its pages on.
pub struct PageHarness {
    source: Source,
    snap: RunSnapshot,
    runtime: tokio::runtime::Runtime,
}

impl PageHarness {
    /// The viewer of `source`, as `vivae view SOURCE` loads it (`None`: the embedded scenario).
    pub fn new(source: Option<&Path>) -> vivae_lab::Result<PageHarness> {
        let source = Source::load(source, None)?;
        let snap = source.snapshot();
        // Multi-threaded, as the server's: decoding runs in `block_in_place`.
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .enable_all()
            .build()
            .map_err(|e| vivae_lab::Error::Threads(e.to_string()))?;
        Ok(PageHarness {
            source,
            snap,
            runtime,
        })
    }

    /// Opens a fresh page and sends it `messages` in order, each followed by
    /// one frame of playing and what the server would send after it (its
    /// error, a new scene, a new frame). Returns the bytes sent to the page.
    pub fn session<'a>(&self, messages: impl IntoIterator<Item = &'a str>) -> usize {
        self.runtime.block_on(async {
            let mut sim = match Sim::new(&self.source, &self.snap) {
                Ok(sim) => sim,
                Err(e) => return e.len(),
            };
            let mut sent = 0;
            for text in messages {
                if let Err(e) = sim.handle(text, &self.source, &self.snap) {
                    sent += e.len();
                }
                sim.advance(FRAME_SECONDS);
                if sim.scene_dirty {
                    sim.scene_dirty = false;
                    sent += sim.scene_msg(&self.source).len();
                }
                if sim.dirty {
                    sent += sim.frame_msg().len();
                }
            }
            sent
        })
    }
}
