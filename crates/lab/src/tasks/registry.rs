//! The tasks a run can evolve for: the built-in [`TASKS`] and those a
//! program [`register`]s (a crate of its own adding a task to the `vivae`
//! command line without editing vivae).

use std::sync::RwLock;

use super::{TASKS, TaskEntry};

/// The tasks programs added with [`register`].
static REGISTERED: RwLock<Vec<&'static TaskEntry>> = RwLock::new(Vec::new());

/// Every task's name, built-in then registered, once [`names`] has listed
/// them since the last [`register`].
static NAMES: RwLock<Option<&'static [&'static str]>> = RwLock::new(None);

/// Adds a task to those a config can name (`experiment.task = "its name"`,
/// `--task`), beside the built-in [`TASKS`]; the error says why not (a name
/// or a shipped scenario's name taken).
pub fn register(entry: &'static TaskEntry) -> Result<(), String> {
    let mut added = REGISTERED.write().unwrap_or_else(|e| e.into_inner());
    let all = || TASKS.iter().chain(added.iter());
    // Registering the same entry twice is harmless (tests, re-imports).
    if all().any(|t| std::ptr::eq(*t, entry)) {
        return Ok(());
    }
    if all().any(|t| t.name == entry.name) {
        return Err(format!(
            "a task called '{}' is registered already",
            entry.name
        ));
    }
    let shipped = |name: &str| all().flat_map(|t| t.scenarios).any(|s| s.name == name);
    if let Some(s) = entry.scenarios.iter().find(|s| shipped(s.name)) {
        return Err(format!(
            "task '{}': a shipped scenario called '{}' is registered already",
            entry.name, s.name
        ));
    }
    added.push(entry);
    *NAMES.write().unwrap_or_else(|e| e.into_inner()) = None;
    Ok(())
}

/// Every task a config can name: the built-in ones, then the registered.
pub fn entries() -> Vec<&'static TaskEntry> {
    let added = REGISTERED.read().unwrap_or_else(|e| e.into_inner());
    TASKS.iter().chain(added.iter()).copied().collect()
}

/// The names of [`entries`], in their order.
pub fn names() -> &'static [&'static str] {
    if let Some(names) = *NAMES.read().unwrap_or_else(|e| e.into_inner()) {
        return names;
    }
    let mut cached = NAMES.write().unwrap_or_else(|e| e.into_inner());
    // Kept for the rest of the process (a checkpoint's fields are named by
    // them): one small list for each registration that is followed by a look-up.
    let names: &'static [&'static str] = Vec::leak(entries().into_iter().map(|t| t.name).collect());
    *cached = Some(names);
    names
}

#[cfg(test)]
mod tests {
    use vivae_neat::Network;
    use vivae_neat::driver::Evaluation;

    use super::*;
    use crate::tasks::plain::{Described, Plain, Trace, entry};

    /// A toy: the network's one output should be its input's opposite.
    struct Negate;

    impl Described for Negate {
        const NAME: &'static str = "negate-registered-in-a-test";
        const ABOUT: &'static str = "negation";
        const SCORING: &'static str = "fitness = 1 - |out + in| at in = 0.5";
        const INPUTS: usize = 2;
        const OUTPUTS: usize = 1;
        const OUTPUT_MEANING: &'static str = "the input's opposite";
    }

    impl Plain for Negate {
        const STEPS: u64 = 1;

        fn evaluate(net: &mut dyn Network, _seed: u64, _trace: Option<&mut Trace>) -> Evaluation {
            let mut out = [0.0];
            net.activate(&[0.5, 1.0], &mut out);
            Evaluation::fitness(1.0 - (out[0] + 0.5).abs())
        }
    }

    static NEGATE: TaskEntry = entry::<Negate>();
    static CARTPOLE_AGAIN: TaskEntry = entry::<crate::tasks::cartpole::CartPole>();

    #[test]
    fn a_registered_task_is_named_like_a_built_in_one() {
        let before = names().len();
        register(&NEGATE).unwrap();
        register(&NEGATE).unwrap();
        assert_eq!(names().len(), before + 1);
        assert_eq!(names().last(), Some(&Negate::NAME));
        assert!(std::ptr::eq(
            crate::tasks::entry(Negate::NAME).unwrap(),
            &NEGATE
        ));
        let config = (NEGATE.default_config)();
        assert_eq!(config.experiment.task.name(), Negate::NAME);
        crate::tasks::check(&config).unwrap();
        let why = register(&CARTPOLE_AGAIN).unwrap_err();
        assert_eq!(why, "a task called 'cartpole' is registered already");
        let unknown = crate::tasks::entry("nowhere").unwrap_err();
        assert!(unknown.ends_with(Negate::NAME), "{unknown}");
    }
}
