//! `vivae report`: rebuilds a run's report.html (a driving run's; that of
//! a run whose task's program-side tools draw its own, e.g. a predator–prey
//! run's with its CIAO figure; for any other task its curves alone); and the
//! refusal, shared with `vivae view`, of a command that shows robots driven
//! by a substrate network.

use std::path::Path;
use std::process::ExitCode;

use vivae_lab::io::bad_input;
use vivae_lab::rundir::files;
use vivae_lab::tasks::{entry_of_run, has_substrate, names_with, read_config};

/// Runs `vivae report` on the run directory `run_dir`.
pub fn run(run_dir: &Path) -> anyhow::Result<ExitCode> {
    let path = if let Some(tools) = crate::tasks::of_run(run_dir) {
        // A task's own report (two co-evolved populations: the CIAO figure, both sides' curves).
        (tools.report)(run_dir)?
    } else {
        refuse_own_driver(run_dir, "report")?;
        crate::report_html::write(run_dir)?
    };
    eprintln!("report: {}", path.display());
    Ok(ExitCode::SUCCESS)
}

/// Refuses, in one line, `command` on a run of a task on its own driver
/// (two co-evolved populations, whose files are not a one-population run's).
pub fn refuse_own_driver(path: &Path, command: &str) -> anyhow::Result<()> {
    let own = path.is_dir().then(|| entry_of_run(path)).flatten();
    if let Some(task) = own.filter(|e| e.own_driver.is_some()) {
        let records = crate::tasks::of_task(task.name).map_or("its own", |t| t.records);
        return Err(bad_input(format!(
            "{}: a run of two co-evolved populations: `vivae {command}` shows one-population runs only; its records are {records}",
            path.display()
        ))
        .into());
    }
    Ok(())
}

/// Refuses, in one line, `command` on a run (a run directory or a genome
/// file recording its config) of a task without a robot's substrate
/// controller ([`TaskEntry::substrate`](vivae_lab::tasks::TaskEntry::substrate)),
/// naming the tasks that have one: the command shows robots driven by one.
pub fn refuse_other_task(path: &Path, command: &str) -> anyhow::Result<()> {
    refuse_own_driver(path, command)?;
    let config = if path.is_dir() {
        read_config(&path.join(files::CONFIG)).ok()
    } else {
        vivae_lab::tasks::read_champion(path)
            .ok()
            .and_then(|c| c.config)
    };
    match config {
        Some(c) if !has_substrate(&c) => Err(bad_input(format!(
            "{}: {} run: `vivae {command}` shows robots driven by a substrate network, \
             which runs of {} have; its curves: `vivae report {}`",
            path.display(),
            vivae_lab::error::a(c.experiment.task.name()),
            names_with(|t| t.substrate),
            path.display()
        ))
        .into()),
        _ => Ok(()),
    }
}
