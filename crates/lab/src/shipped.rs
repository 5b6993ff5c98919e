//! A scenario shipped in `scenarios/`, built into the program so that
//! `--scenario NAME` works wherever `vivae` is installed. Each task lists
//! the ones drawn for it in its entry ([`crate::tasks::TaskEntry::scenarios`]);
//! [`crate::tasks::scenarios`] looks them up and loads them.

/// A shipped scenario: its name (file name without `.svg`), what it is, its SVG text.
#[derive(Debug, Clone, Copy)]
pub struct Shipped {
    /// Name, e.g. `oval` (the file `scenarios/oval.svg`).
    pub name: &'static str,
    /// One line on what it is.
    pub what: &'static str,
    /// The SVG text.
    pub svg: &'static str,
    /// The task (`experiment.task`) it is drawn for.
    pub task: &'static str,
}
