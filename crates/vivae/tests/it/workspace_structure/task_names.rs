//! No privileged task: outside a task's folder (`tasks/<task>/` or
//! `tasks/<task>.rs` of each crate), code names no task module, neither the
//! crate's own (`crate::tasks::maze`, `super::maze` in `tasks/`) nor the
//! library's (`vivae_lab::tasks::maze`); generic code reaches a task through
//! its entry. Each crate's registry (`tasks/mod.rs`) may name each task once:
//! its registration line (`mod` declarations are not paths). The tasks are
//! those the library registers in its `TASKS` list. Comments, strings and
//! `#[cfg(test)]` code are not read (a test may use a task as its fixture).

use std::collections::BTreeSet;

use super::{ModPath, SourceFile, Tok, Token, linear_path, parsed_modules, use_tree};

/// Files outside a task's folder that still name a task module in code, as
/// `crate: file: task`, not moved yet: the test fails on any other, and on a
/// listed one that no longer names it (so the list only shrinks).
const TASK_NAMINGS_NOT_YET_REMOVED: &[&str] = &[];

#[test]
fn no_file_outside_a_tasks_folder_names_the_task() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let registry = std::fs::read_to_string(root.join("crates/lab/src/tasks/mod.rs")).unwrap();
    let tasks = registered_tasks(&registry);
    assert!(tasks.len() >= 3, "no TASKS list read: {tasks:?}");
    let mut found = BTreeSet::new();
    for (name, src) in &super::workspace_crates() {
        for f in task_namings(&super::read_sources(src), &tasks) {
            found.insert(format!("{name}: {f}"));
        }
    }
    let listed: BTreeSet<String> = (TASK_NAMINGS_NOT_YET_REMOVED.iter())
        .map(|s| s.to_string())
        .collect();
    println!(
        "NOTE: {} places outside a task's folder name the task, in {} files",
        found.len(),
        (found.iter())
            .map(|f| f.rsplit_once(": ").unwrap().0)
            .collect::<BTreeSet<_>>()
            .len()
    );
    let new: Vec<_> = found.difference(&listed).collect();
    let gone: Vec<_> = listed.difference(&found).collect();
    assert!(
        new.is_empty() && gone.is_empty(),
        "outside a task's folder, name the task through its entry instead:\n  {}\n\
         no longer naming it (remove them from TASK_NAMINGS_NOT_YET_REMOVED):\n  {}",
        (new.iter().map(|s| s.as_str()).collect::<Vec<_>>()).join("\n  "),
        (gone.iter().map(|s| s.as_str()).collect::<Vec<_>>()).join("\n  ")
    );
}

/// The module names of the tasks a registry declares: the names in its
/// `built_in! { … }` list, and any `&name::TASK` entries of a `TASKS` list.
fn registered_tasks(registry: &str) -> Vec<String> {
    let t = super::tokenize(registry);
    let mut out = Vec::new();
    let opens_list = |w: &[Token]| {
        matches!((&w[0].tok, &w[1].tok, &w[2].tok),
            (Tok::Ident(m), Tok::Punct('!'), Tok::Punct('{')) if m == "built_in")
    };
    if let Some(start) = t.windows(3).position(opens_list) {
        let list = t[start + 3..]
            .iter()
            .take_while(|x| !matches!(x.tok, Tok::Punct('}')));
        for tok in list {
            if let Tok::Ident(name) = &tok.tok {
                out.push(name.clone());
            }
        }
    }
    for (i, w) in t.windows(3).enumerate() {
        // `$task::TASK` in the macro's body is its parameter, not a task.
        let metavariable = i > 0 && matches!(t[i - 1].tok, Tok::Punct('$'));
        if let (Tok::Ident(name), Tok::PathSep, Tok::Ident(item)) =
            (&w[0].tok, &w[1].tok, &w[2].tok)
            && item == "TASK"
            && !metavariable
        {
            out.push(name.clone());
        }
    }
    out
}

/// Every `file: task` where a file of one crate (`files`) outside that
/// task's folder names one of `tasks`' modules; a registry file
/// (`tasks/mod.rs`) only from its second naming of a task on.
fn task_namings(files: &[SourceFile], tasks: &[String]) -> Vec<String> {
    let modules = parsed_modules(files);
    let known: BTreeSet<ModPath> = modules.keys().cloned().collect();
    let mut out = Vec::new();
    for (module, (rel, tokens)) in &modules {
        let mut named: Vec<String> = paths(tokens)
            .into_iter()
            .filter_map(|p| task_of(&p, module, &known, tasks))
            .filter(|task| !module.starts_with(&["tasks".to_string(), task.clone()]))
            .collect();
        if module.as_slice() == ["tasks"] {
            // The registry names each task once, in its registration.
            let mut seen = BTreeSet::new();
            named.retain(|task| !seen.insert(task.clone()));
        }
        let named: BTreeSet<String> = named.into_iter().collect();
        out.extend(named.into_iter().map(|task| format!("{rel}: {task}")));
    }
    out
}

/// Every path the tokens name: each `use` tree expanded, and each path
/// (`a::b…`) anywhere else.
fn paths(t: &[Token]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < t.len() {
        match &t[i].tok {
            Tok::Ident(k) if k == "use" => {
                let (trees, end) = use_tree(t, i + 1, Vec::new());
                out.extend(trees);
                i = end.max(i + 1);
            }
            Tok::Ident(_)
                if t.get(i + 1).is_some_and(|x| x.tok == Tok::PathSep)
                    && !(i > 0 && t[i - 1].tok == Tok::PathSep) =>
            {
                let (path, end) = linear_path(t, i);
                out.push(path);
                i = end;
            }
            _ => i += 1,
        }
    }
    out
}

/// The task `path`, written in `module`, names: a path into the crate's own
/// `tasks::<task>` (from `crate`, `super`, `self` or a child module's name)
/// or into the library's (`vivae_lab::tasks::<task>`).
fn task_of(
    path: &[String],
    module: &ModPath,
    known: &BTreeSet<ModPath>,
    tasks: &[String],
) -> Option<String> {
    let first = path.first()?;
    let absolute: Vec<String> = match first.as_str() {
        "crate" | "$crate" | "vivae_lab" => path[1..].to_vec(),
        "self" => module.iter().chain(&path[1..]).cloned().collect(),
        "super" => {
            let ups = path.iter().take_while(|s| *s == "super").count();
            let base = &module[..module.len().saturating_sub(ups)];
            base.iter().chain(&path[ups..]).cloned().collect()
        }
        _ => {
            let child: ModPath = module.iter().chain([first]).cloned().collect();
            if !known.contains(&child) {
                return None;
            }
            module.iter().chain(path).cloned().collect()
        }
    };
    match absolute.as_slice() {
        [tasks_module, task, ..] if tasks_module == "tasks" && tasks.contains(task) => {
            Some(task.clone())
        }
        _ => None,
    }
}

#[test]
fn a_task_named_outside_its_folder_is_found() {
    let tasks = registered_tasks("pub static TASKS: [&TaskEntry; 2] = [&maze::TASK, &cart::TASK];");
    assert_eq!(tasks, ["maze", "cart"]);
    let declared = registered_tasks(
        "macro_rules! built_in { ($($t:ident),*) => { pub static TASKS: &[&E] = &[$(&$t::TASK),*]; }; }\n\
         built_in! { maze, cart, }",
    );
    assert_eq!(declared, ["maze", "cart"]);
    let f = super::files(&[
        ("lib.rs", "pub mod run; pub mod tasks; mod view;"),
        (
            "tasks/mod.rs",
            "pub mod maze; pub mod cart; mod seam;\n\
             pub static TASKS: [&TaskEntry; 2] = [&maze::TASK, &cart::TASK];\n\
             pub use maze::Walls;",
        ),
        (
            "tasks/maze/mod.rs",
            "use crate::tasks::maze::walls::W; mod walls;",
        ),
        (
            "tasks/maze/walls.rs",
            "pub struct W; use super::super::cart::C;",
        ),
        (
            "tasks/cart.rs",
            "pub struct C; fn f() { crate::tasks::seam::g() }",
        ),
        (
            "tasks/seam.rs",
            "use super::{TaskEntry, cart};\npub fn g() {}",
        ),
        (
            "run.rs",
            "// crate::tasks::maze::W in a comment\n\
             fn f() { let s = \"crate::tasks::cart\"; crate::tasks::seam::g(); }\n\
             #[cfg(test)]\nmod tests { use crate::tasks::cart::C; }",
        ),
        (
            "view.rs",
            "use vivae_lab::tasks::{entry, maze::{self as m, Walls}};\n\
             fn f() -> usize { vivae_lab::tasks::cart::C::N }",
        ),
    ]);
    assert_eq!(
        task_namings(&f, &tasks),
        [
            "tasks/mod.rs: maze",
            "tasks/maze/walls.rs: cart",
            "tasks/seam.rs: cart",
            "view.rs: cart",
            "view.rs: maze",
        ]
    );
}
