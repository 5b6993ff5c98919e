//! A multi-map run's copies of its training maps (`scenarios/` with a
//! manifest); loading them back is the task's ([`crate::tasks::maps`]).

use super::*;
use crate::io::LoadedScenario;

/// A training map as loaded: its label and its SVG.
#[derive(Debug, Clone)]
pub struct TrainingMap {
    /// Short name (the file stem, e.g. `oval`).
    pub label: String,
    /// The parsed scenario and its text.
    pub loaded: LoadedScenario,
}

/// Whether `config` trains on a list of maps (`experiment.scenarios`).
pub fn is_multi_map(config: &Config) -> bool {
    !config.experiment.scenarios.is_empty()
}

/// Copies the training maps of a multi-map run into `dir/scenarios/` with
/// their manifest, and points `experiment.scenarios` at the copies.
pub(crate) fn copy_maps(dir: &Path, config: &mut Config, maps: &[TrainingMap]) -> Result<()> {
    if maps.is_empty() {
        return Ok(());
    }
    let folder = dir.join(MAPS_DIR);
    fs::create_dir_all(&folder).map_err(Error::io("create", &folder))?;
    let names = copy_names(maps);
    for (name, m) in names.iter().zip(maps) {
        write_atomic(&folder.join(name), m.loaded.text.as_bytes())?;
    }
    write_atomic(&folder.join(MANIFEST), manifest(&names, maps).as_bytes())?;
    config.experiment.scenarios = names.iter().map(|n| format!("{}/{n}", MAPS_DIR)).collect();
    Ok(())
}

/// Folder of a multi-map run directory holding the copies of the training maps.
pub const MAPS_DIR: &str = "scenarios";
/// The manifest in [`MAPS_DIR`]: one line per map, `file fnv1a64 source`.
pub const MANIFEST: &str = "manifest.txt";

/// File names the copies of `maps` get in `scenarios/`: `LABEL.svg`, with
/// `-2`, `-3`, … after a label already taken.
pub fn copy_names(maps: &[TrainingMap]) -> Vec<String> {
    let mut names: Vec<String> = Vec::with_capacity(maps.len());
    for m in maps {
        let safe = safe_file_stem(&m.label);
        let mut name = format!("{safe}.svg");
        let mut k = 2;
        while names.contains(&name) {
            name = format!("{safe}-{k}.svg");
            k += 1;
        }
        names.push(name);
    }
    names
}

/// The manifest's text for copies `names` of `maps`.
pub fn manifest(names: &[String], maps: &[TrainingMap]) -> String {
    let mut out = String::from("# file fnv1a64 source (the training maps, in evaluation order)\n");
    for (name, m) in names.iter().zip(maps) {
        let _ = writeln!(
            out,
            "{name} {:016x} {}",
            fnv1a(m.loaded.text.as_bytes()),
            m.loaded.scenario.source
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::maps::load;

    #[test]
    fn copies_of_maps_with_one_name_get_distinct_files() {
        let mut c = Config::default();
        c.experiment.scenarios = ["oval", "oval", "roads"].map(String::from).to_vec();
        let maps = load(&c).unwrap();
        assert_eq!(copy_names(&maps), ["oval.svg", "oval-2.svg", "roads.svg"]);
        let m = manifest(&copy_names(&maps), &maps);
        assert_eq!(m.lines().count(), 4);
        assert!(m.contains("oval-2.svg "));
    }
}
