//! The options that stand for config keys ([`Overrides`]): one flag per row
//! of the library's [`SETTINGS`], which Python's keyword arguments follow
//! too, under the same names; each flag's text is the library's to parse.

use clap::builder::{PossibleValuesParser, TypedValueParser as _};
use clap::{Arg, ArgAction, ArgMatches, Command};
use vivae_lab::config::{Config, TaskName};
use vivae_lab::io::bad_input;
use vivae_lab::run::prepare::{self, SETTINGS, Setting, ValueKind};

/// Options that override config keys: the library's overrides they give.
#[derive(Debug, Default)]
pub struct Overrides {
    /// The settings the flags gave.
    pub lab: prepare::Overrides,
}

impl clap::Args for Overrides {
    fn augment_args(cmd: Command) -> Command {
        cmd.args(SETTINGS.iter().map(flag))
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

impl clap::FromArgMatches for Overrides {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut o = Overrides::default();
        o.update_from_arg_matches(matches)?;
        Ok(o)
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        for s in SETTINGS {
            for text in (matches.get_many::<String>(s.key)).into_iter().flatten() {
                (self.lab.set(s.key, text))
                    .map_err(|e| clap::Error::raw(clap::error::ErrorKind::ValueValidation, e))?;
            }
        }
        Ok(())
    }
}

/// The flag of setting `s`: `--train-neurons RxA,...`, its text checked by
/// the library (or one of its registry's names); a scenario repeats.
fn flag(s: &'static Setting) -> Arg {
    let arg = Arg::new(s.key)
        .long(s.key.replace('_', "-"))
        .value_name(s.value_name)
        .help(s.help);
    let arg = match s.choices {
        Some(names) => arg.value_parser(PossibleValuesParser::new(names())),
        None => arg.value_parser(move |text: &str| {
            prepare::Overrides::check(s.key, text).map(|()| text.to_string())
        }),
    };
    match s.kind {
        ValueKind::Scenarios => arg.action(ArgAction::Append),
        _ => arg.action(ArgAction::Set),
    }
}

/// `--task NAME`: one of the registered tasks (listed by `--help`).
pub(super) fn task_names() -> impl clap::builder::TypedValueParser<Value = TaskName> {
    let names = vivae_lab::tasks::names().iter().copied();
    PossibleValuesParser::new(names).map(TaskName)
}

/// How the command line's settings are named in the library's refusals:
/// `--flag-name`, from the command line.
pub const SPELLING: vivae_lab::run::prepare::Spelling = vivae_lab::run::prepare::Spelling {
    origin: "command line",
    key: |k| format!("--{} ", k.replace('_', "-")),
    on: |k| format!("--{}", k.replace('_', "-")),
};

/// Sets each config key `o` gives, then checks the result by every rule of
/// the config's task.
pub fn apply_overrides(config: &mut Config, o: &prepare::Overrides) -> anyhow::Result<()> {
    let refused = |e: String| anyhow::Error::from(bad_input(format!("command line: {e}")));
    o.apply(config).map_err(refused)?;
    vivae_lab::tasks::check(config).map_err(|e| refused(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::{Args as _, FromArgMatches as _};

    /// A value setting `s` takes, as a command line writes it.
    fn sample(s: &Setting) -> String {
        match (s.kind, s.choices) {
            (_, Some(names)) => names()[0].to_string(),
            (ValueKind::Whole { .. }, _) => "3".into(),
            (ValueKind::Grid, _) => "3x5".into(),
            (ValueKind::Grids, _) => "3x3,5x5".into(),
            (ValueKind::Bool, _) => "false".into(),
            (ValueKind::Scenarios, _) => "oval".into(),
            // The first of the names its placeholder lists (`mean|min`).
            (ValueKind::Name, _) if s.value_name.contains('|') => {
                s.value_name.split('|').next().unwrap_or_default().into()
            }
            (ValueKind::Name, _) => "vivae".into(),
        }
    }

    fn parse(args: &[String]) -> Result<prepare::Overrides, clap::Error> {
        let cmd = Overrides::augment_args(Command::new("vivae"));
        let matches =
            cmd.try_get_matches_from(std::iter::once("vivae".into()).chain(args.iter().cloned()))?;
        Ok(Overrides::from_arg_matches(&matches)?.lab)
    }

    #[test]
    fn the_flags_are_the_library_overrides_that_python_takes_too() {
        // Every key's flag, spelled with dashes, sets what the library's
        // `set` of the same text sets; a scenario repeats.
        let mut args = Vec::new();
        let mut expected = prepare::Overrides::default();
        for s in SETTINGS {
            let text = sample(s);
            args.extend([format!("--{}", s.key.replace('_', "-")), text.clone()]);
            expected.set(s.key, &text).unwrap();
        }
        args.extend(["--scenario".into(), "roads".into()]);
        expected.set("scenario", "roads").unwrap();
        assert_eq!(parse(&args).unwrap(), expected);
        assert_eq!(expected.scenario, ["oval", "roads"]);
        let keys = Overrides::augment_args(Command::new("vivae"));
        let ids: Vec<&str> = keys.get_arguments().map(|a| a.get_id().as_str()).collect();
        assert_eq!(ids, prepare::Overrides::KEYS);
    }

    #[test]
    fn a_bad_value_is_refused_naming_its_flag_and_what_it_takes() {
        for (flag, text, says) in [
            (
                "--steps",
                "many",
                "expected a whole number from 0 to 4294967295",
            ),
            ("--threads", "2000", "at most 1024"),
            ("--train-neurons", "3x3,5", "5"),
            ("--normalize-self-loops", "yes", "expected true or false"),
            ("--precision", "half", "expected exact or fast"),
            ("--task", "chess", "chess"),
        ] {
            let e = parse(&[flag.into(), text.into()]).unwrap_err();
            assert_eq!(e.exit_code(), 2);
            let line = e.to_string().lines().next().unwrap_or_default().to_string();
            assert!(line.contains(flag) && line.contains(says), "{flag}: {line}");
        }
        let twice = ["--steps", "3", "--steps", "4"].map(String::from);
        assert!(parse(&twice).is_err(), "one value per setting");
    }
}
