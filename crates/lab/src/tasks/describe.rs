//! A task built to read what it declares (its genome's shape, what its
//! exported network reads and means), not to play it. A task whose episodes
//! a host plays (Gymnasium's, played by the Python package) cannot be built
//! to run in the program, yet its runs export like any other: built through
//! [`build`], such a task stands without its player and asks [`describing`].

use std::cell::Cell;

use super::maps::TrainingMap;
use super::seam::RunTask;
use crate::config::Config;
use crate::error::Result;

thread_local! {
    static DESCRIBING: Cell<bool> = const { Cell::new(false) };
}

/// Lowers the flag when the build returns (or unwinds).
struct Lowered;

impl Drop for Lowered {
    fn drop(&mut self) {
        DESCRIBING.with(|d| d.set(false));
    }
}

/// The task of `config` on `maps`, as [`super::build`] builds it, for
/// reading what it declares: one whose episodes a host plays builds even
/// where no host is, and refuses to play any.
pub fn build(config: &Config, maps: &[TrainingMap]) -> Result<Box<dyn RunTask>> {
    DESCRIBING.with(|d| d.set(true));
    let _lowered = Lowered;
    super::build(config, maps)
}

/// Whether the task being built on this thread is only read ([`build`]).
pub fn describing() -> bool {
    DESCRIBING.with(Cell::get)
}
