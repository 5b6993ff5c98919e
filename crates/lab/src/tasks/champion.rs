//! Reading a run's champion back (`champion.json`, or a champion file of
//! its own): its recorded config is checked by the rules of its task.

use std::path::{Path, PathBuf};

use crate::config::Config;
use crate::error::{Error, Result};
use crate::io::read_text;
use crate::rundir::{Champion, files};
use crate::tasks::scenarios::resolve_map;

use super::{check, read_config};

/// Reads a genome source for `replay`: a run directory (its champion and
/// `config.toml`) or a champion JSON file (the config it records; the default
/// config for files that record none). Returns the folder outputs go beside.
pub fn load_genome_source(source: &Path) -> Result<(Champion, Config, PathBuf)> {
    if source.is_dir() {
        let champion = read_champion(&source.join(files::CHAMPION))?;
        let config = read_config(&source.join(files::CONFIG))?;
        Ok((champion, config, source.to_path_buf()))
    } else {
        let champion = read_champion(source)?;
        let base = source.parent().map(Path::to_path_buf).unwrap_or_default();
        let config = match &champion.config {
            Some(recorded) => {
                let mut config = recorded.clone();
                // As in a config file, a relative scenario is relative to the file's folder.
                let scenario = &mut config.experiment.scenario;
                if !scenario.is_empty() && Path::new(scenario.as_str()).is_relative() {
                    *scenario = base.join(&*scenario).to_string_lossy().into_owned();
                }
                for map in &mut config.experiment.scenarios {
                    *map = resolve_map(&base, map);
                }
                config.experiment.init_population.clear();
                config
            }
            None => Config::default(),
        };
        Ok((champion, config, base))
    }
}

/// Reads `champion.json` (or any file in its format); the genome is checked as it is read.
pub fn read_champion(path: &Path) -> Result<Champion> {
    let text = read_text(path)?;
    let invalid = |reason: String| Error::Genome {
        path: path.to_path_buf(),
        reason,
    };
    let champion: Champion = serde_json::from_str(&text)
        .map_err(|e| invalid(format!("not a vivae champion genome: {e}")))?;
    if champion.format != "vivae-champion" {
        return Err(invalid(format!(
            "format is {:?}, expected \"vivae-champion\"",
            champion.format
        )));
    }
    if let Some(config) = &champion.config {
        check(config).map_err(|e| invalid(format!("its recorded config: {e}")))?;
    }
    // The genome validated itself while being deserialised.
    Ok(champion)
}
