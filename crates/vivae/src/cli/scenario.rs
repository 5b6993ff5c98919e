//! `vivae scenario`: lists the shipped scenarios, describes one, or draws it.

use std::path::PathBuf;
use std::process::ExitCode;

use crate::report;
use clap::Subcommand;
use vivae_lab::controller::substrate::PolarGrid;
use vivae_lab::io::write_atomic;
use vivae_lab::tasks::scenarios::load_scenario;

/// The subcommands of `vivae scenario`.
#[derive(Subcommand, Debug)]
pub enum ScenarioCommand {
    /// The scenarios shipped with vivae (usable as `--scenario NAME`).
    List,
    /// Arena size, objects by kind, robots and warnings.
    Info {
        /// Scenario SVG file or shipped name (default: the embedded one).
        file: Option<PathBuf>,
        /// One JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Draw a scenario to PNG or SVG (by the extension of OUT).
    Render {
        /// Scenario SVG file or shipped name (default: the embedded one).
        file: Option<PathBuf>,
        /// Output file, .png or .svg.
        #[arg(short, long, value_name = "OUT")]
        out: PathBuf,
        /// Draw surface sensors of this layout (RINGSxANGLES) on every robot.
        #[arg(long, value_name = "RxA")]
        sensors: Option<PolarGrid>,
    },
}

/// Runs `vivae scenario …`.
pub fn run(command: ScenarioCommand) -> anyhow::Result<ExitCode> {
    match command {
        ScenarioCommand::List => {
            for s in vivae_lab::tasks::scenarios::all() {
                println!("{:<10} {}", s.name, s.what);
            }
        }
        ScenarioCommand::Info { file, json } => {
            let loaded = load_scenario(file.as_deref())?;
            let summary = loaded.scenario.summary();
            let marks: Vec<String> = loaded.scenario.marks.iter().map(|m| m.id.clone()).collect();
            if json {
                let mut value = serde_json::to_value(&summary)?;
                value["mark_names"] = serde_json::json!(marks);
                println!("{}", serde_json::to_string(&value)?);
            } else {
                print!("{}", report::scenario_text(&summary, &marks));
            }
        }
        ScenarioCommand::Render { file, out, sensors } => {
            let loaded = load_scenario(file.as_deref())?;
            let bytes = report::render_scenario(&loaded.scenario, sensors, &out)?;
            write_atomic(&out, &bytes)?;
            eprintln!("figure: {}", out.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}
