//! Helpers shared by the command-line integration tests.
#![allow(dead_code)]

pub mod browser;

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The `vivae` binary under test.
pub fn vivae() -> Command {
    Command::new(env!("CARGO_BIN_EXE_vivae"))
}

/// A fresh, empty scratch directory for one test.
pub fn scratch(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("vivae-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch {
        path: dir.clone(),
        root: dir,
    }
}

/// A test's scratch directory, removed when the test is done with it; a
/// failing test's is kept (and named) for a look at what went wrong. Without
/// it, every test that forgot to clean up left its runs and compiled
/// programs in the temporary directory, a few hundred after a day's work.
#[derive(Debug)]
pub struct Scratch {
    /// The path the test works in: the scratch directory or a path inside it.
    path: PathBuf,
    /// The scratch directory [`scratch`] made, removed on drop.
    root: PathBuf,
}

impl Scratch {
    /// The same scratch, standing for `rel` inside it.
    pub fn into_sub(mut self, rel: &str) -> Scratch {
        // The directory becomes the new value's to remove; `self` is left
        // with no root, so dropping it removes nothing.
        let root = std::mem::take(&mut self.root);
        Scratch {
            path: root.join(rel),
            root,
        }
    }
}

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<std::ffi::OsStr> for Scratch {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.path.as_os_str()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if self.root.as_os_str().is_empty() {
            // Handed on by `into_sub`.
        } else if std::thread::panicking() {
            eprintln!("kept the failing test's scratch {}", self.root.display());
        } else {
            // A test may have removed it already.
            let _ = std::fs::remove_dir_all(&self.root);
        }
    }
}

/// A small but complete experiment config: quick to run, still the real pipeline.
pub fn small_config(generations: u32) -> String {
    format!(
        "[experiment]\nseed = 7\ngenerations = {generations}\nsteps = 150\n\n[neat]\npopulation_size = 24\n"
    )
}

/// The value of the `key=value` field of a `key=value …` line (a summary
/// line, a replay's line); panics, showing the line, when it has none.
pub fn field<'a>(line: &'a str, key: &str) -> &'a str {
    (line.split_whitespace())
        .find_map(|f| f.strip_prefix(key)?.strip_prefix('='))
        .unwrap_or_else(|| panic!("no {key}= in {line:?}"))
}

/// [`field`] parsed as a number.
pub fn number(line: &str, key: &str) -> f64 {
    let value = field(line, key);
    (value.parse()).unwrap_or_else(|_| panic!("{key}={value} is not a number in {line:?}"))
}

/// Writes `small_config(generations)` to `dir/c.toml` and returns its path.
pub fn write_small_config(dir: &Path, generations: u32) -> PathBuf {
    let path = dir.join("c.toml");
    std::fs::write(&path, small_config(generations)).unwrap();
    path
}

/// `vivae evolve -q [extra…] --config CONFIG --out OUT`, which must succeed; returns stdout.
pub fn evolve(config: &Path, out: &Path, extra: &[&str]) -> String {
    ok(vivae()
        .args(["evolve", "-q"])
        .args(extra)
        .arg("--config")
        .arg(config)
        .arg("--out")
        .arg(out))
}

/// A 2-generation run of 5-ray robots with progress fitness on the shipped
/// `corridor` (blocks placed per episode) in `dir`: the distance-sheet
/// champion the replay tests look inside. Returns the run directory.
pub fn rays_corridor_run(dir: &Path) -> PathBuf {
    let config = dir.join("rays.toml");
    std::fs::write(
        &config,
        small_config(2) + "[distance_sensors]\nrays = 5\n[fitness]\nkind = \"progress\"\n",
    )
    .unwrap();
    let run = dir.join("rays");
    evolve(&config, &run, &["--scenario", "corridor"]);
    run
}

/// A finished small run of `generations` (seed 7) in a fresh scratch
/// directory `name`; returns the run directory (its parent is the scratch,
/// removed with it).
pub fn small_run(name: &str, generations: u32) -> Scratch {
    let dir = scratch(name);
    let config = write_small_config(&dir, generations);
    let out = dir.join("run");
    evolve(&config, &out, &[]);
    dir.into_sub("run")
}

/// Makes a FIFO at `path` (a special file that blocks a reader until a writer comes).
pub fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo").arg(path).status().unwrap();
    assert!(status.success(), "mkfifo {}", path.display());
}

/// Runs a command to completion; panics with its stderr if it could not start.
pub fn run(cmd: &mut Command) -> Output {
    cmd.output().expect("vivae runs")
}

/// Asserts success and returns stdout.
pub fn ok(cmd: &mut Command) -> String {
    let out = run(cmd);
    assert!(
        out.status.success(),
        "command failed ({:?}): {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Reads a file of a run directory.
pub fn read(dir: &Path, name: &str) -> Vec<u8> {
    std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{}/{name}: {e}", dir.display()))
}

/// The files that must be bit-identical between two runs of the same config.
pub const DETERMINISTIC_FILES: [&str; 3] = ["generations.csv", "population.csv", "champion.json"];

/// Asserts the deterministic outputs of two run directories are identical.
pub fn assert_same_results(a: &Path, b: &Path) {
    for name in DETERMINISTIC_FILES {
        assert!(
            read(a, name) == read(b, name),
            "{name} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

/// `vivae evolve -q --generations 12 --seed 2 --out OUT`: the short run the
/// determinism tests compare.
pub fn short_run_command(out: &Path) -> Command {
    let mut cmd = vivae();
    cmd.args([
        "evolve",
        "-q",
        "--generations",
        "12",
        "--seed",
        "2",
        "--out",
    ])
    .arg(out);
    cmd
}

/// The ViVAE scenario corpus, `../shared/vivae-scenarios` beside the clone
/// (a clone from the web lacks it). `None` when it is absent: the caller
/// returns, and the test counts as passed after a printed SKIPPED note, unless
/// `VIVAE_REQUIRE_SHARED=1` (as `.ci/run` sets), which makes the absence a failure.
pub fn shared_scenarios() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/vivae-scenarios");
    let required = std::env::var("VIVAE_REQUIRE_SHARED").is_ok_and(|v| v == "1");
    corpus_at(&dir, required)
}

/// `Some(dir)` if it is a directory; else fails when `required`, or prints a
/// note (straight to stderr, past the test harness's capture) and gives `None`.
pub fn corpus_at(dir: &Path, required: bool) -> Option<PathBuf> {
    if dir.is_dir() {
        return Some(dir.to_path_buf());
    }
    assert!(
        !required,
        "the scenario corpus {} is absent, and VIVAE_REQUIRE_SHARED=1 requires it: put ../shared/vivae-scenarios beside the clone",
        dir.display()
    );
    skipped(&format!(
        "../shared/vivae-scenarios is absent (a clone from the web); CI requires it (looked for {})",
        dir.display()
    ));
    None
}

/// Prints `SKIPPED: {why}` as one line straight to stderr, past the test
/// harness's capture, so that a test that returns early is seen to skip.
/// The test's name (libtest names each test's thread after it) ends the line.
pub fn skipped(why: &str) {
    let thread = std::thread::current();
    let test = thread.name().unwrap_or("?");
    let _ = writeln!(std::io::stderr(), "SKIPPED: {why} [{test}]");
}

/// Waits until `path` exists; panics after `secs` seconds, so that a run that
/// died early fails the test instead of hanging it.
pub fn wait_for_file(path: &Path, secs: u64) {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(secs);
    while !path.exists() {
        assert!(
            std::time::Instant::now() < deadline,
            "{} did not appear within {secs} s",
            path.display()
        );
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
}

/// Starts `vivae evolve -q --threads 1 --config CONFIG --out RUN_DIR`, sends
/// `signal` (e.g. `"-INT"`) once generation `generation`'s checkpoint exists,
/// and returns what the process did (its stderr captured).
pub fn evolve_until_signalled(
    config: &Path,
    run_dir: &Path,
    generation: u32,
    signal: &str,
) -> Output {
    let child = vivae()
        .args(["evolve", "-q", "--threads", "1", "--config"])
        .arg(config)
        .arg("--out")
        .arg(run_dir)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    wait_for_file(
        &run_dir.join(format!("checkpoints/gen-{generation:06}.ckpt")),
        300,
    );
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    child.wait_with_output().unwrap()
}

/// FNV-1a 64 of `bytes`, continuing from the hash `h`.
pub fn fnv1a_from(h: u64, bytes: &[u8]) -> u64 {
    bytes
        .iter()
        .fold(h, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}
