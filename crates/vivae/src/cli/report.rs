//! `vivae report`: rebuilds a run's report.html; and the refusal, shared with
//! `vivae view`, of a command that shows driving runs only.

use std::path::Path;
use std::process::ExitCode;

use vivae_lab::io::bad_input;
use vivae_lab::rundir::{self, files};
use vivae_lab::tasks::read_config;

/// Runs `vivae report` on the run directory `run_dir`.
pub fn run(run_dir: &Path) -> anyhow::Result<ExitCode> {
    refuse_other_task(run_dir, "report")?;
    let path = vivae::report_html::write(run_dir)?;
    eprintln!("report: {}", path.display());
    Ok(ExitCode::SUCCESS)
}

/// Refuses, in one line, `command` on a run of a task other than driving (a
/// run directory or a genome file recording its config): the command draws
/// driving runs only.
pub fn refuse_other_task(path: &Path, command: &str) -> anyhow::Result<()> {
    let config = if path.is_dir() {
        read_config(&path.join(files::CONFIG)).ok()
    } else {
        rundir::read_champion(path).ok().and_then(|c| c.config)
    };
    match config {
        Some(c) if !c.experiment.task.is_driving() => Err(bad_input(format!(
            "{}: a {} run: `vivae {command}` shows driving runs only; its curves are in generations.csv and `vivae replay` prints its champion's end",
            path.display(),
            c.experiment.task
        ))
        .into()),
        _ => Ok(()),
    }
}
