//! A multi-map run's copies of its training maps (`scenarios/` with a manifest) and loading them back.

use super::*;

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

/// Loads the training maps of the run in `dir` (its config `config`): the
/// copies under `scenarios/` for a multi-map run, else `scenario.svg` (none
/// for a task without maps).
/// With `hashes` (from the checkpoint), a copy whose text changed is refused.
pub fn load_run(dir: &Path, config: &Config, hashes: Option<&[u64]>) -> Result<Vec<TrainingMap>> {
    if !crate::tasks::maps::uses_maps(config) {
        return Ok(Vec::new());
    }
    if !is_multi_map(config) {
        let path = dir.join(files::SCENARIO);
        return Ok(vec![TrainingMap {
            label: crate::io::scenario_name(Some(&path)),
            loaded: load_scenario(Some(&path))?,
        }]);
    }
    let names = &config.experiment.scenarios;
    if let Some(h) = hashes
        && h.len() != names.len()
    {
        return Err(Error::Checkpoint {
            path: dir.to_path_buf(),
            reason: format!(
                "the checkpoint records {} training maps, config.toml names {}",
                h.len(),
                names.len()
            ),
        });
    }
    let mut maps = Vec::with_capacity(names.len());
    for (i, name) in names.iter().enumerate() {
        // A run's maps are its own copies, `scenarios/FILE`. The config may
        // name them as written (relative to the run) or as `read_config`
        // resolved them (relative to the working directory, or absolute):
        // the file name finds the copy either way, and nothing outside it.
        let file = Path::new(name).file_name().unwrap_or_default();
        let path = dir.join(MAPS_DIR).join(file);
        let text = crate::io::read_text(&path)?;
        if let Some(h) = hashes
            && h[i] != fnv1a(text.as_bytes())
        {
            return Err(Error::Checkpoint {
                path,
                reason: format!(
                    "training map {} was edited since the run started (its hash is not the one the checkpoint records); restore it, or start a new run",
                    i + 1
                ),
            });
        }
        maps.push(TrainingMap {
            label: crate::io::scenario_name(Some(&path)),
            loaded: load_scenario(Some(&path))?,
        });
    }
    Ok(maps)
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
