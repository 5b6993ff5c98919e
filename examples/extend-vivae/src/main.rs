//! The `vivae` command line with one task and one strategy of this crate's
//! added: `cargo run -p extend-vivae -- evolve --task seek --strategy
//! random-search`. Everything else (configs, run directories, resume,
//! replay, report, export) is the program's own.

mod random_search;
mod seek;

use std::process::ExitCode;

fn main() -> ExitCode {
    let added = vivae_lab::tasks::register(&seek::TASK)
        .and_then(|()| vivae_lab::search::register(&random_search::STRATEGY));
    if let Err(why) = added {
        eprintln!("error: {why}");
        return ExitCode::from(1);
    }
    vivae::run_cli()
}
