//! `vivae config`: the default config, the reference of its keys, or a
//! config file checked and resolved.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Subcommand;
use vivae_lab::config::{Config, TaskName};
use vivae_lab::tasks::read_config;

/// The subcommands of `vivae config`.
#[derive(Subcommand, Debug)]
pub enum ConfigCommand {
    /// The full default config, a comment on every key.
    Default {
        /// Only task NAME's: its defaults and only the sections it reads.
        #[arg(long, value_name = "NAME", value_parser = super::overrides::task_names())]
        task: Option<TaskName>,
    },
    /// The reference of every key as a Markdown page (docs/reference/config.md).
    Reference {
        /// Only the table of every key, for a page that embeds it.
        #[arg(long)]
        table: bool,
    },
    /// Check a config file and the maps it names, and print it fully resolved.
    Check {
        /// The config file.
        file: PathBuf,
    },
}

/// Runs `vivae config …`.
pub fn run(command: ConfigCommand) -> anyhow::Result<ExitCode> {
    let sections = vivae_lab::tasks::sections();
    match command {
        ConfigCommand::Default { task: None } => {
            print!("{}", Config::default_commented(&sections))
        }
        ConfigCommand::Default { task: Some(task) } => {
            let text = vivae_lab::tasks::default_commented(task.name())
                .map_err(|why| anyhow::anyhow!("--task {why}"))?;
            print!("{text}")
        }
        ConfigCommand::Reference { table: false } => {
            let read_by = vivae_lab::tasks::read_by;
            print!("{}", Config::markdown_reference_page(&sections, &read_by))
        }
        ConfigCommand::Reference { table: true } => {
            print!("{}", Config::markdown_reference(&sections))
        }
        ConfigCommand::Check { file } => {
            let config = read_config(&file)?;
            // The maps too: a scenario the run would refuse is refused here.
            vivae_lab::tasks::maps::load(&config)?;
            print!("{}", vivae_lab::tasks::config_text(&config));
        }
    }
    Ok(ExitCode::SUCCESS)
}
