//! The library's error type: what went wrong, and whether the user's input was at fault.
//!
//! Every message is one line that names the file (or flag) and what is wrong
//! with it. Reasons are part of the message rather than a `source()` chain so
//! that printing an error once says everything, with nothing repeated.

use std::path::PathBuf;

use vivae_sim::ScenarioError;

use crate::config::ConfigError;
use crate::simd::SimdError;

/// Why a driving episode cannot be set up.
#[derive(Debug, thiserror::Error)]
pub enum EpisodeError {
    /// The scenario cannot host the episode.
    #[error("{0}")]
    Scenario(String),
    /// The parameters do not fit together.
    #[error("{0}")]
    Config(String),
    /// The genome does not fit this episode's substrate.
    #[error("{0}")]
    Genome(String),
}

/// Collapses a message onto one line.
pub fn one_line(message: &str) -> String {
    message.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// `name` after the indefinite article its first sound takes (`an
/// acrobot`, `a maze`, `an nsga2`, `a one-plus-lambda`), for a message that
/// names a task, a strategy or a scenario.
pub fn a(name: &str) -> String {
    format!("{} {name}", article(name))
}

/// The indefinite article of `word`: `an` before a vowel sound, else `a`.
pub fn article(word: &str) -> &'static str {
    let word = word.to_ascii_lowercase();
    // A vowel letter sounding a consonant, and an initialism or a silent h
    // opening with a vowel sound.
    const CONSONANT_SOUND: [&str; 6] = ["one", "once", "uni", "use", "usu", "eu"];
    const VOWEL_SOUND: [&str; 5] = ["nsga", "mpi", "xor", "hour", "honest"];
    let starts = |prefixes: &[&str]| prefixes.iter().any(|p| word.starts_with(p));
    let vowel = word.starts_with(['a', 'e', 'i', 'o', 'u']);
    if (vowel && !starts(&CONSONANT_SOUND)) || starts(&VOWEL_SOUND) {
        "an"
    } else {
        "a"
    }
}

/// One piece of a [`Refusal`]'s message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Part {
    /// Words, said as they are.
    Text(String),
    /// A setting by its key (`out`): `--out` on the command line, `out=` in Python.
    Key(&'static str),
    /// A switch turned on (`force`): `--force` on the command line, `force=True` in Python.
    On(&'static str),
    /// A setting given a value (`runs`, `5000`): `--runs 5000`, `runs=5000`.
    Set(&'static str, String),
}

/// A message that names settings as data, so that the command line and
/// Python each say them in their own spelling and the library in its keys.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Refusal(pub Vec<Part>);

impl Refusal {
    /// Starts a message with `text`.
    pub fn text(text: impl Into<String>) -> Self {
        Refusal(vec![Part::Text(text.into())])
    }

    /// Goes on with `text`.
    pub fn then(mut self, text: impl Into<String>) -> Self {
        self.0.push(Part::Text(text.into()));
        self
    }

    /// Goes on with the setting `key`.
    pub fn key(mut self, key: &'static str) -> Self {
        self.0.push(Part::Key(key));
        self
    }

    /// Goes on with the switch `key` turned on.
    pub fn on(mut self, key: &'static str) -> Self {
        self.0.push(Part::On(key));
        self
    }

    /// Goes on with the setting `key` given `value`.
    pub fn set(mut self, key: &'static str, value: impl std::fmt::Display) -> Self {
        self.0.push(Part::Set(key, value.to_string()));
        self
    }

    /// The message with each setting written by `key` (as the prefix of its
    /// value: `--runs `, `runs=`) and each switch by `on`.
    pub fn spelled(&self, key: impl Fn(&str) -> String, on: impl Fn(&str) -> String) -> String {
        (self.0.iter())
            .map(|p| match p {
                Part::Text(t) => t.clone(),
                Part::Key(k) => key(k).trim_end().to_string(),
                Part::On(k) => on(k),
                Part::Set(k, v) => format!("{}{v}", key(k)),
            })
            .collect()
    }
}

/// The library's spelling: settings by their keys (`out`, `force = true`).
impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let own = (self.0.iter()).map(|p| match p {
            Part::Text(t) => t.clone(),
            Part::Key(k) => format!("`{k}`"),
            Part::On(k) => format!("`{k} = true`"),
            Part::Set(k, v) => format!("`{k} = {v}`"),
        });
        f.write_str(&own.collect::<String>())
    }
}

/// The result type of the vivae library.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong in the vivae library.
///
/// [`Error::is_bad_input`] separates the user's mistakes (the program exits
/// with code 2) from failures of the machine or the program (code 1).
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file the user named cannot be read: missing, unreadable or not UTF-8.
    #[error("{}: {reason}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why it cannot be read.
        reason: String,
    },
    /// A config file is malformed or holds an invalid value.
    #[error("{}: {error}", path.display())]
    Config {
        /// The config file.
        path: PathBuf,
        /// The key and what is wrong with it.
        error: ConfigError,
    },
    /// A scenario cannot be loaded (the error names the file).
    #[error("{}", one_line(&.0.to_string()))]
    Scenario(ScenarioError),
    /// The configuration does not fit the scenario, or its parts do not fit together.
    #[error("{0}")]
    Episode(EpisodeError),
    /// A run directory or checkpoint is missing, damaged or not vivae's.
    #[error("{}: {reason}", path.display())]
    Checkpoint {
        /// The run directory or checkpoint file.
        path: PathBuf,
        /// What is wrong with it.
        reason: String,
    },
    /// A genome file is not a valid vivae champion genome.
    #[error("{}: {reason}", path.display())]
    Genome {
        /// The genome file.
        path: PathBuf,
        /// What is wrong with it.
        reason: String,
    },
    /// Any other invalid request: a command-line value, an existing output directory.
    #[error("{0}")]
    Invalid(String),
    /// An invalid request whose message names the settings that would change
    /// it, as data: each front end spells them its own way ([`Refusal::spelled`]).
    #[error("{0}")]
    Refused(Refusal),
    /// A file or directory the program writes could not be written, created or removed.
    #[error("cannot {action} {}: {error}", path.display())]
    Io {
        /// What was attempted: `write`, `create`, `read`, …
        action: &'static str,
        /// The file or directory.
        path: PathBuf,
        /// The operating system's error.
        error: std::io::Error,
    },
    /// One of a run directory's own files (a CSV file) is malformed.
    #[error("{}: {reason}", path.display())]
    RunFile {
        /// The file.
        path: PathBuf,
        /// Where and what is wrong.
        reason: String,
    },
    /// An output the program makes (a figure, a report) could not be made.
    #[error("{0}")]
    Output(String),
    /// The simulator could not render a picture of the world.
    #[error("rendering {what}: {reason}")]
    Render {
        /// What was being drawn.
        what: &'static str,
        /// The renderer's message.
        reason: String,
    },
    /// A run ended without evaluating a single genome.
    #[error("the run evaluated no genome")]
    NoChampion,
    /// The evolution driver failed (the evaluator or the population).
    #[error("{0}")]
    Evolution(String),
    /// Data could not be serialised (a bug: every vivae type serialises).
    #[error("serialising {what}: {reason}")]
    Serialize {
        /// What was being serialised.
        what: &'static str,
        /// The serialiser's message.
        reason: String,
    },
    /// An environment variable holds an invalid value.
    #[error("{0}")]
    Simd(SimdError),
    /// The evaluation worker threads could not be started.
    #[error("starting worker threads: {0}")]
    Threads(String),
}

impl Error {
    /// Whether the user's input is at fault (exit code 2) rather than the machine or the program.
    pub fn is_bad_input(&self) -> bool {
        matches!(
            self,
            Error::Read { .. }
                | Error::Config { .. }
                | Error::Scenario(_)
                | Error::Episode(_)
                | Error::Checkpoint { .. }
                | Error::Genome { .. }
                | Error::RunFile { .. }
                | Error::Invalid(_)
                | Error::Refused(_)
                | Error::Simd(_)
        ) || self.is_path_mistake()
    }

    /// Whether an output failed because of the path the user gave: a missing
    /// folder, a file where a folder should be, a folder where a file should
    /// be, no permission. A full disk or any other failure is the machine's.
    fn is_path_mistake(&self) -> bool {
        use std::io::ErrorKind as K;
        match self {
            Error::Io { error, .. } => matches!(
                error.kind(),
                K::NotFound
                    | K::NotADirectory
                    | K::IsADirectory
                    | K::PermissionDenied
                    | K::ReadOnlyFilesystem
                    | K::InvalidFilename
            ),
            _ => false,
        }
    }

    /// An [`Error::Io`] for `action` on `path` (for `map_err`).
    pub fn io(
        action: &'static str,
        path: impl Into<PathBuf>,
    ) -> impl FnOnce(std::io::Error) -> Error {
        let path = path.into();
        move |error| Error::Io {
            action,
            path,
            error,
        }
    }
}

impl From<ScenarioError> for Error {
    fn from(e: ScenarioError) -> Self {
        Error::Scenario(e)
    }
}

impl From<EpisodeError> for Error {
    fn from(e: EpisodeError) -> Self {
        Error::Episode(e)
    }
}

impl From<SimdError> for Error {
    fn from(e: SimdError) -> Self {
        Error::Simd(e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_name_takes_the_article_of_its_first_sound() {
        let tasks = [
            ("acrobot", "an"),
            ("cartpole", "a"),
            ("driving", "a"),
            ("gymnasium", "a"),
            ("maze", "a"),
            ("mountain-car", "a"),
            ("mountain-car-continuous", "a"),
            ("pendulum", "a"),
            ("predator-prey", "a"),
        ];
        let strategies = [
            ("neat", "a"),
            ("novelty", "a"),
            ("map-elites", "a"),
            ("nsga2", "an"),
            ("one-plus-lambda", "a"),
            ("random-search", "a"),
            ("es-hyperneat", "an"),
        ];
        for (name, article) in tasks.into_iter().chain(strategies) {
            assert_eq!(a(name), format!("{article} {name}"));
        }
        assert_eq!(a("int"), "an int");
        assert_eq!(a("Unit"), "a Unit");
        assert_eq!(a("umbrella"), "an umbrella");
        assert_eq!(a(""), "a ");
    }

    #[test]
    fn user_mistakes_are_bad_input_and_machine_failures_are_not() {
        let read = Error::Read {
            path: "a.toml".into(),
            reason: "no such file or directory".into(),
        };
        assert!(read.is_bad_input());
        assert_eq!(read.to_string(), "a.toml: no such file or directory");
        let io = Error::io("write", "out/b.csv")(std::io::Error::other("disk full"));
        assert!(!io.is_bad_input());
        let full = Error::io("write", "out/b.csv")(std::io::ErrorKind::StorageFull.into());
        assert!(
            !full.is_bad_input(),
            "a full disk is not the user's mistake"
        );
        let missing = Error::io("write", "no/such/b.csv")(std::io::ErrorKind::NotFound.into());
        assert!(missing.is_bad_input(), "a missing output folder is");
        assert_eq!(io.to_string(), "cannot write out/b.csv: disk full");
        assert!(!Error::NoChampion.is_bad_input());
    }

    #[test]
    fn messages_carry_their_reason_and_expose_no_source_chain() {
        use std::error::Error as _;
        let e = Error::Episode(EpisodeError::Config("substrate: bad".into()));
        assert!(e.source().is_none());
        assert_eq!(e.to_string(), "substrate: bad");
        let io = Error::io("create", "d")(std::io::Error::other("denied"));
        assert!(
            io.source().is_none(),
            "the reason is in the message already"
        );
    }

    /// The catch-all error crate belongs to the program's `main.rs` (and the
    /// modules only it declares); the library's functions return the typed [`Error`].
    #[test]
    fn only_the_program_uses_the_catch_all_error_crate() {
        fn rust_files(dir: &std::path::Path, out: &mut Vec<PathBuf>) {
            for entry in std::fs::read_dir(dir).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    rust_files(&path, out);
                } else if path.extension().is_some_and(|e| e == "rs") {
                    out.push(path);
                }
            }
        }
        let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        let mut files = Vec::new();
        rust_files(&src, &mut files);
        let program_only = ["main.rs", "portable_libm.rs"];
        // Spelled in two parts so that this file does not match itself.
        let needle = concat!("any", "how");
        let offenders: Vec<String> = files
            .iter()
            .filter(|p| {
                let name = p.strip_prefix(&src).unwrap().to_string_lossy().into_owned();
                !program_only.contains(&name.as_str())
                    && std::fs::read_to_string(p).unwrap().contains(needle)
            })
            .map(|p| p.display().to_string())
            .collect();
        assert!(files.len() > 5, "{files:?}");
        assert!(
            offenders.is_empty(),
            "library modules use {needle}: {offenders:?}"
        );
    }

    #[test]
    fn a_refusal_names_keys_and_each_front_end_spells_them() {
        let r = Refusal::text("pick ")
            .key("out")
            .then(", ")
            .on("force")
            .then(" or ")
            .set("runs", 3);
        assert_eq!(r.to_string(), "pick `out`, `force = true` or `runs = 3`");
        let flags = r.spelled(|k| format!("--{k} "), |k| format!("--{k}"));
        assert_eq!(flags, "pick --out, --force or --runs 3");
        let keywords = r.spelled(|k| format!("{k}="), |k| format!("{k}=True"));
        assert_eq!(keywords, "pick out=, force=True or runs=3");
    }
}
