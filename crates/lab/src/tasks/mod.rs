//! What a run evolves genomes for: the task seam.
//!
//! A task is one folder here with one [`TaskEntry`] registered in [`TASKS`]
//! (or, from a crate of its own, added with [`register`]):
//! its name (`experiment.task`), its default config and the rules it adds to
//! the shared ones, the metrics it measures, the columns it adds to
//! `generations.csv`, and how to build it as a [`RunTask`] (the driving
//! experiment: [`driving`]; Lehman & Stanley's maze: [`maze`]); a task of
//! plain NEAT networks is its [`plain::Plain`] shape and scoring ([`cartpole`]; the
//! classic-control family shares [`classic`]). Everything a
//! run, its recorder, the program or the Python package needs to know about a
//! task, it asks the [`RunTask`] or its entry; nothing outside a task's folder
//! matches on which task it is.

pub mod behaviours;
mod champion;
pub mod classic;
pub mod describe;
pub mod gymnasium;
mod hill;
pub mod maps;
pub mod plain;
mod registry;
pub mod robot;
pub mod scenarios;
mod seam;
pub mod sketch;
pub mod substrate;
mod target;
mod unread;
pub mod validation;

pub use champion::{load_genome_source, read_champion};
pub use registry::{entries, names, register};
pub use seam::{
    BuildTask, Finished, HeaderContext, OwnDriver, RunTask, RunTaskBase, Session, SetRobot, Step,
    Stepped, Stopped, TaskEntry, Threshold, any_map, build, check, check_shape, config_from_toml,
    config_text, default_commented, default_config, entry, entry_of, entry_of_run, has_substrate,
    metric_names, names_with, nothing_to_refuse, own_driver_of_run, read_by, read_config, readers,
    sections, set_robot,
};
pub use target::{StoredTarget, TargetProgress};

/// Declares each built-in task's module (a folder or file here) and lists
/// its entry (`its_module::TASK`) in [`TASKS`]: a new task is one name here.
macro_rules! built_in {
    ($($task:ident),* $(,)?) => {
        $(pub mod $task;)*

        /// The built-in tasks; `experiment.task` names one of these or a
        /// [`register`]ed one ([`entries`] lists both).
        pub static TASKS: &[&TaskEntry] = &[$(&$task::TASK),*];
    };
}

built_in! {
    driving,
    maze,
    predator_prey,
    cartpole,
    acrobot,
    mountain_car,
    mountain_car_continuous,
    pendulum,
    gym,
}
