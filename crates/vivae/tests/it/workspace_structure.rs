//! Structure rules for every crate of the workspace (`crates/*/src`) and the
//! Python package's native crate (`python/src`): module imports form no
//! cycles, no function is longer than 80 lines, no file is longer than 700
//! lines before its tests; the experiment library has at most 12 top-level
//! files and the program's `main.rs` at most 250 lines.
//!
//! Self-contained and std only: a small tokenizer drops comments and string
//! and char literals, `#[cfg(test)]` items are cut out, and the rest is read
//! for paths (`use` trees and `crate::`/`super::`/`self::` paths anywhere in
//! the code) and for `fn` bodies. A module is a file: `foo.rs` or `foo/mod.rs`
//! is `foo`, `a/b.rs` is `a::b`, and `lib.rs`/`main.rs` is the crate root.
//! A path resolves to the longest module prefix that exists; imports of a
//! module's own ancestors or descendants are not edges (a child using its
//! parent's types is no cycle). Code under `tests/`, `benches/`, `examples/`
//! is not read. Crates in the skip lists below have their findings printed
//! (`cargo test --release -p vivae --test it workspace_structure -- --nocapture`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

mod task_names;

/// Crates whose module cycles are not fixed yet: their cycles are printed,
/// not failed on. Remove a crate once it is clean (the test says when).
const NOT_YET_CHECKED: &[&str] = &[];

/// Crates whose over-long functions are not split yet: printed, not failed on.
/// Remove a crate once it is clean (the test says when).
const LONG_FUNCTIONS_NOT_YET_CHECKED: &[&str] = &[];

/// The longest a function may be, from its `fn` line to its closing brace.
const MAX_FN_LINES: usize = 80;

#[test]
fn module_imports_have_no_cycles() {
    check_every_crate(
        "module import cycles",
        NOT_YET_CHECKED,
        "NOT_YET_CHECKED",
        module_cycles,
    );
}

/// Imports between top-level modules that point from a lower layer up and
/// close circles, not removed yet, per crate: the test fails on any circle
/// among the other imports, and on a listed import that is gone (so the list
/// only shrinks). The intended layers of vivae-lab, bottom up: simd, config,
/// error, controller, io, shipped, rundir, search, tasks, run, reproduce, export,
/// output_path. Empty: no crate has one left.
const UPWARD_IMPORTS_NOT_YET_REMOVED: &[(&str, &[(&str, &str)])] = &[];

#[test]
fn top_level_modules_import_each_other_in_no_circle() {
    let mut failures = Vec::new();
    for (name, src) in &workspace_crates() {
        let mut graph = top_level_graph(&read_sources(src));
        let listed: &[(&str, &str)] = (UPWARD_IMPORTS_NOT_YET_REMOVED.iter())
            .find(|(c, _)| c == name)
            .map_or(&[], |(_, k)| k);
        for (from, to) in listed {
            let edges = graph.get_mut(*from);
            if !edges.is_some_and(|e| e.remove(*to)) {
                failures.push(format!(
                    "crate {name}: {from} no longer imports {to}: remove it from UPWARD_IMPORTS_NOT_YET_REMOVED"
                ));
            }
        }
        let found = cycles_of(&graph);
        if !found.is_empty() {
            failures.push(format!(
                "crate {name}: circles of top-level modules:\n  {}",
                found.join("\n  ")
            ));
        }
        if !listed.is_empty() {
            let all = cycles_of(&top_level_graph(&read_sources(src)));
            println!(
                "NOTE: crate {name} has {} circles of top-level modules through its {} listed upward imports",
                all.len(),
                listed.len()
            );
        }
    }
    for (c, _) in UPWARD_IMPORTS_NOT_YET_REMOVED {
        if !workspace_crates().iter().any(|(n, _)| n == c) {
            failures.push(format!(
                "UPWARD_IMPORTS_NOT_YET_REMOVED lists {c}, which is not a crate"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_circle_through_several_files_is_seen() {
    // `a/mod.rs` only declares its child; `a/inner.rs` imports `b`, and `b`
    // imports `a`: no file imports a file that imports it back, but the
    // top-level modules `a` and `b` import each other.
    let file = |rel: &str, text: &str| SourceFile {
        rel: rel.into(),
        text: text.into(),
    };
    let files = [
        file("lib.rs", "mod a; mod b; mod c;"),
        file("a/mod.rs", "pub mod inner; pub use inner::A;"),
        file("a/inner.rs", "use crate::b::B; pub struct A(B);"),
        file("b.rs", "pub struct B; pub fn f(_: crate::a::A) {}"),
        file("c.rs", "use crate::a::A;"),
    ];
    assert!(
        module_cycles(&files).is_empty(),
        "{:?}",
        module_cycles(&files)
    );
    let graph = top_level_graph(&files);
    assert_eq!(cycles_of(&graph), vec!["a → b → a".to_string()]);
}

#[test]
fn no_function_is_longer_than_80_lines() {
    check_every_crate(
        "functions longer than 80 lines",
        LONG_FUNCTIONS_NOT_YET_CHECKED,
        "LONG_FUNCTIONS_NOT_YET_CHECKED",
        |files| {
            long_functions(files, MAX_FN_LINES)
                .into_iter()
                .map(|f| format!("{}:{}: `{}` is {} lines", f.file, f.line, f.name, f.lines))
                .collect()
        },
    );
}

/// Runs `findings` on every crate's sources; fails on findings in a crate
/// not in `skip`, and on a crate in `skip` that has none (so the list shrinks).
fn check_every_crate(
    what: &str,
    skip: &[&str],
    skip_name: &str,
    findings: impl Fn(&[SourceFile]) -> Vec<String>,
) {
    let mut failures = Vec::new();
    let crates = workspace_crates();
    assert!(!crates.is_empty(), "no crates found under crates/*/src");
    for (name, src) in &crates {
        let found = findings(&read_sources(src));
        let skipped = skip.contains(&name.as_str());
        match (skipped, found.is_empty()) {
            (false, true) => {}
            (false, false) => {
                failures.push(format!("crate {name}: {what}:\n  {}", found.join("\n  ")));
            }
            (true, false) => println!(
                "NOTE: crate {name} is in {skip_name}, so these {what} are not failed on yet:\n  {}",
                found.join("\n  ")
            ),
            (true, true) => failures.push(format!(
                "crate {name} has no {what} any more: remove it from {skip_name}"
            )),
        }
    }
    for s in skip {
        if !crates.iter().any(|(n, _)| n == s) {
            failures.push(format!("{skip_name} lists {s}, which is not a crate"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The longest a source file may be before its `#[cfg(test)]` module.
const MAX_FILE_LINES: usize = 700;

#[test]
fn no_source_file_is_longer_than_700_lines_before_its_tests() {
    check_every_crate(
        "files longer than 700 lines before their tests",
        &[],
        "(none)",
        |files| {
            files
                .iter()
                .filter_map(|f| {
                    let lines = f
                        .text
                        .lines()
                        .position(|l| l.starts_with("#[cfg(test)]"))
                        .unwrap_or_else(|| f.text.lines().count());
                    (lines > MAX_FILE_LINES).then(|| format!("{}: {lines} lines", f.rel))
                })
                .collect()
        },
    );
}

#[test]
fn the_library_and_the_program_keep_their_shape() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let lab = std::fs::read_dir(root.join("crates/lab/src")).expect("crates/lab/src");
    let top: Vec<String> = lab
        .filter_map(|e| e.ok())
        .filter(|e| e.path().is_file())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        top.len() <= 12,
        "crates/lab/src has {} top-level files: {top:?}",
        top.len()
    );
    let main = std::fs::read_to_string(root.join("crates/vivae/src/main.rs")).expect("main.rs");
    let lines = main.lines().count();
    assert!(
        lines <= 250,
        "crates/vivae/src/main.rs is {lines} lines: commands go in cli/"
    );
}

/// `(crate directory name, its src directory)` for every `crates/*/src`, and
/// `python` for the Python package's native crate, sorted.
fn workspace_crates() -> Vec<(String, PathBuf)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut out: Vec<(String, PathBuf)> = std::fs::read_dir(root.join("crates"))
        .expect("the workspace's crates/ directory")
        .filter_map(|e| e.ok())
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                e.path().join("src"),
            )
        })
        .filter(|(_, src)| src.is_dir())
        .collect();
    let python = root.join("python/src");
    if python.is_dir() {
        out.push(("python".into(), python));
    }
    out.sort();
    out
}

/// One source file: its path relative to `src/` (with `/`) and its text.
struct SourceFile {
    rel: String,
    text: String,
}

/// Every `.rs` file under `src`, skipping `tests/`, `benches/`, `examples/`.
fn read_sources(src: &Path) -> Vec<SourceFile> {
    let mut out = Vec::new();
    let mut dirs = vec![src.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().filter_map(|e| e.ok()) {
            let path = entry.path();
            let name = entry.file_name().to_string_lossy().into_owned();
            if path.is_dir() {
                if !matches!(name.as_str(), "tests" | "benches" | "examples") {
                    dirs.push(path);
                }
            } else if name.ends_with(".rs") {
                let rel = path.strip_prefix(src).unwrap();
                let rel = rel.to_string_lossy().replace('\\', "/");
                let text = std::fs::read_to_string(&path).unwrap();
                out.push(SourceFile { rel, text });
            }
        }
    }
    out.sort_by(|a, b| a.rel.cmp(&b.rel));
    out
}

// ---------------------------------------------------------------- tokens

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    /// `::`
    PathSep,
    Punct(char),
    /// A number (strings, chars and comments are dropped altogether).
    Number,
}

#[derive(Clone, Debug)]
struct Token {
    tok: Tok,
    line: usize,
}

/// Splits Rust source into tokens, dropping comments, whitespace, lifetimes
/// and string, byte-string, raw-string and char literals.
fn tokenize(src: &str) -> Vec<Token> {
    let c: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < c.len() {
        let start_line = line;
        let ch = c[i];
        let next = c.get(i + 1).copied();
        if ch == '\n' {
            line += 1;
            i += 1;
        } else if ch.is_whitespace() {
            i += 1;
        } else if ch == '/' && next == Some('/') {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if ch == '/' && next == Some('*') {
            i = skip_block_comment(&c, i, &mut line);
        } else if let Some(end) = string_literal_end(&c, i, &mut line) {
            i = end;
        } else if ch == '\'' || (ch == 'b' && next == Some('\'')) {
            i = skip_char_or_lifetime(&c, if ch == 'b' { i + 1 } else { i });
        } else if ch == 'r' && next == Some('#') && c.get(i + 2).is_some_and(|&x| is_ident_start(x))
        {
            let end = ident_end(&c, i + 2);
            out.push(tok(Tok::Ident(c[i + 2..end].iter().collect()), start_line));
            i = end;
        } else if is_ident_start(ch) {
            let end = ident_end(&c, i);
            out.push(tok(Tok::Ident(c[i..end].iter().collect()), start_line));
            i = end;
        } else if ch.is_ascii_digit() {
            i = number_end(&c, i);
            out.push(tok(Tok::Number, start_line));
        } else if ch == ':' && next == Some(':') {
            out.push(tok(Tok::PathSep, start_line));
            i += 2;
        } else {
            out.push(tok(Tok::Punct(ch), start_line));
            i += 1;
        }
    }
    out
}

fn tok(tok: Tok, line: usize) -> Token {
    Token { tok, line }
}

fn is_ident_start(c: char) -> bool {
    c.is_alphabetic() || c == '_'
}

fn ident_end(c: &[char], mut i: usize) -> usize {
    while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
        i += 1;
    }
    i
}

fn number_end(c: &[char], mut i: usize) -> usize {
    loop {
        while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
            i += 1;
        }
        // `1.5` continues; `x.0.1` and `1..2` do not need to.
        if i + 1 < c.len() && c[i] == '.' && c[i + 1].is_ascii_digit() {
            i += 1;
        } else {
            return i;
        }
    }
}

/// Skips a (nested) block comment starting at `i`; returns the index after it.
fn skip_block_comment(c: &[char], mut i: usize, line: &mut usize) -> usize {
    let mut depth = 0;
    while i < c.len() {
        if c[i] == '/' && c.get(i + 1) == Some(&'*') {
            depth += 1;
            i += 2;
        } else if c[i] == '*' && c.get(i + 1) == Some(&'/') {
            depth -= 1;
            i += 2;
            if depth == 0 {
                return i;
            }
        } else {
            *line += usize::from(c[i] == '\n');
            i += 1;
        }
    }
    i
}

/// If a string literal (`"…"`, `b"…"`, `c"…"`, `r#"…"#`, `br"…"`, …) starts
/// at `i`, returns the index after it.
fn string_literal_end(c: &[char], i: usize, line: &mut usize) -> Option<usize> {
    let mut j = i;
    if matches!(c[j], 'b' | 'c') {
        j += 1;
    }
    let raw = c.get(j) == Some(&'r');
    if raw {
        j += 1;
    }
    let hashes = c[j.min(c.len())..]
        .iter()
        .take_while(|&&x| x == '#')
        .count();
    j += hashes;
    if c.get(j) != Some(&'"') || (!raw && hashes > 0) {
        return None;
    }
    j += 1;
    while j < c.len() {
        if c[j] == '\n' {
            *line += 1;
        }
        if !raw && c[j] == '\\' {
            *line += usize::from(c.get(j + 1) == Some(&'\n'));
            j += 2;
            continue;
        }
        if c[j] == '"'
            && c[j + 1..]
                .iter()
                .take(hashes)
                .filter(|&&x| x == '#')
                .count()
                == hashes
        {
            return Some(j + 1 + hashes);
        }
        j += 1;
    }
    Some(j)
}

/// At a `'`: skips a char literal (`'a'`, `'\n'`, `'\u{7f}'`, `'{'`) or a
/// lifetime / label (`'a`), returning the index after it.
fn skip_char_or_lifetime(c: &[char], i: usize) -> usize {
    if c.get(i + 1) == Some(&'\\') {
        let mut j = i + 3;
        while j < c.len() && c[j] != '\'' {
            j += 1;
        }
        return j + 1;
    }
    if c.get(i + 2) == Some(&'\'') {
        return i + 3;
    }
    ident_end(c, i + 1)
}

/// Index of the `}` matching the `{` at `open`, or the last index.
fn matching_brace(t: &[Token], open: usize) -> usize {
    let mut depth = 0usize;
    for (k, x) in t.iter().enumerate().skip(open) {
        match x.tok {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => {
                depth -= 1;
                if depth == 0 {
                    return k;
                }
            }
            _ => {}
        }
    }
    t.len() - 1
}

fn is_ident(t: &Token, s: &str) -> bool {
    matches!(&t.tok, Tok::Ident(x) if x == s)
}

fn is_punct(t: Option<&Token>, ch: char) -> bool {
    t.is_some_and(|t| t.tok == Tok::Punct(ch))
}

// ------------------------------------------------------ #[cfg(test)] items

/// Drops every item marked `#[cfg(test)]` (with its other attributes);
/// returns the tokens left and the names of `#[cfg(test)] mod name;` files.
fn strip_cfg_test(t: &[Token]) -> (Vec<Token>, Vec<String>) {
    let (mut out, mut test_files) = (Vec::new(), Vec::new());
    let mut i = 0;
    while i < t.len() {
        if !is_cfg_test_attr(t, i) {
            out.push(t[i].clone());
            i += 1;
            continue;
        }
        let mut j = i;
        while is_punct(t.get(j), '#') && is_punct(t.get(j + 1), '[') {
            j = attribute_end(t, j);
        }
        let end = item_end(t, j);
        if let [kw, name, semi] | [_, kw, name, semi] = &t[j..end.min(t.len())]
            && is_ident(kw, "mod")
            && semi.tok == Tok::Punct(';')
            && let Tok::Ident(n) = &name.tok
        {
            test_files.push(n.clone());
        }
        i = end;
    }
    (out, test_files)
}

fn is_cfg_test_attr(t: &[Token], i: usize) -> bool {
    let want = [
        Tok::Punct('#'),
        Tok::Punct('['),
        Tok::Ident("cfg".into()),
        Tok::Punct('('),
        Tok::Ident("test".into()),
        Tok::Punct(')'),
        Tok::Punct(']'),
    ];
    t.len() >= i + want.len()
        && t[i..i + want.len()]
            .iter()
            .zip(&want)
            .all(|(a, b)| a.tok == *b)
}

/// The index after the attribute `#[…]` starting at `i`.
fn attribute_end(t: &[Token], i: usize) -> usize {
    let mut depth = 0usize;
    for (k, x) in t.iter().enumerate().skip(i + 1) {
        match x.tok {
            Tok::Punct('[') => depth += 1,
            Tok::Punct(']') => {
                depth -= 1;
                if depth == 0 {
                    return k + 1;
                }
            }
            _ => {}
        }
    }
    t.len()
}

/// The index after the item starting at `i`: its `;`, or the `}` closing its
/// body (`= … ;` items such as `const X: T = T { … };` end at the `;`).
fn item_end(t: &[Token], i: usize) -> usize {
    let (mut depth, mut assigned) = (0usize, false);
    let mut k = i;
    while k < t.len() {
        match t[k].tok {
            Tok::Punct('(' | '[') => depth += 1,
            Tok::Punct(')' | ']') => depth = depth.saturating_sub(1),
            Tok::Punct('=') if depth == 0 => assigned = true,
            Tok::Punct(';') if depth == 0 => return k + 1,
            Tok::Punct('{') if depth == 0 && !assigned => return matching_brace(t, k) + 1,
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => depth = depth.saturating_sub(1),
            _ => {}
        }
        k += 1;
    }
    t.len()
}

// ------------------------------------------------------------- modules

/// A module path inside a crate (`[]` is the crate root).
type ModPath = Vec<String>;

/// The module a file under `src/` is: `lib.rs` and `main.rs` are the root,
/// `a/mod.rs` is `a`, `a/b.rs` is `a::b`.
fn module_of(rel: &str) -> ModPath {
    let mut parts: Vec<String> = rel
        .trim_end_matches(".rs")
        .split('/')
        .map(String::from)
        .collect();
    let root = parts.len() == 1 && matches!(parts[0].as_str(), "lib" | "main");
    if root || parts.last().unwrap() == "mod" {
        parts.pop();
    }
    parts
}

fn show(m: &[String]) -> String {
    if m.is_empty() {
        "crate".into()
    } else {
        m.join("::")
    }
}

/// Every crate source file, tokenized, with `#[cfg(test)]` code (items and
/// the files of `#[cfg(test)] mod x;`) removed.
fn parsed_modules(files: &[SourceFile]) -> BTreeMap<ModPath, (String, Vec<Token>)> {
    let mut out = BTreeMap::new();
    let mut test_only = Vec::new();
    for f in files {
        let module = module_of(&f.rel);
        let (tokens, test_files) = strip_cfg_test(&tokenize(&f.text));
        for name in test_files {
            let mut m = module.clone();
            m.push(name);
            test_only.push(m);
        }
        out.insert(module, (f.rel.clone(), tokens));
    }
    out.retain(|m, _| !test_only.iter().any(|t| m.starts_with(t)));
    out
}

/// The import graph of `files`: module → the modules it names a path into
/// (edges to its own ancestors and descendants left out).
fn import_graph(files: &[SourceFile]) -> BTreeMap<ModPath, BTreeSet<ModPath>> {
    let modules = parsed_modules(files);
    let known: BTreeSet<ModPath> = modules.keys().cloned().collect();
    let mut graph = BTreeMap::new();
    for (module, (_, tokens)) in &modules {
        let edges: BTreeSet<ModPath> = named_paths(module, tokens, &known)
            .into_iter()
            .map(|p| longest_module_prefix(&p, &known))
            .filter(|target| !target.starts_with(module) && !module.starts_with(target))
            .collect();
        graph.insert(module.clone(), edges);
    }
    graph
}

fn longest_module_prefix(path: &[String], known: &BTreeSet<ModPath>) -> ModPath {
    (0..=path.len())
        .rev()
        .map(|n| path[..n].to_vec())
        .find(|p| known.contains(p))
        .unwrap_or_default()
}

/// Every path inside the crate that the tokens of `file_module` name, made
/// absolute: `use` trees (grouped, `pub use`, relative to a child module),
/// and `crate::…`, `super::…`, `self::…` paths anywhere in the code.
fn named_paths(file_module: &ModPath, t: &[Token], known: &BTreeSet<ModPath>) -> Vec<ModPath> {
    let mut out = Vec::new();
    // Inline `mod x { … }` blocks: (module path, brace depth inside them).
    let mut scopes: Vec<(ModPath, usize)> = vec![(file_module.clone(), 0)];
    let mut depth = 0usize;
    let mut i = 0;
    while i < t.len() {
        let here = scopes.last().unwrap().0.clone();
        match &t[i].tok {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => {
                if scopes.len() > 1 && scopes.last().unwrap().1 == depth {
                    scopes.pop();
                }
                depth = depth.saturating_sub(1);
            }
            Tok::Ident(k) if k == "mod" && is_punct(t.get(i + 2), '{') => {
                if let Tok::Ident(name) = &t[i + 1].tok {
                    let mut inner = here.clone();
                    inner.push(name.clone());
                    scopes.push((inner, depth + 1));
                }
            }
            Tok::Ident(k) if k == "use" => {
                let (trees, _) = use_tree(t, i + 1, Vec::new());
                out.extend(trees.iter().filter_map(|p| absolute(&here, p, known, true)));
            }
            Tok::Ident(k)
                if matches!(k.as_str(), "crate" | "super" | "self")
                    && t.get(i + 1).is_some_and(|x| x.tok == Tok::PathSep)
                    && !(i > 0 && t[i - 1].tok == Tok::PathSep) =>
            {
                let (path, end) = linear_path(t, i);
                out.extend(absolute(&here, &path, known, false));
                i = end;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// Reads `a::b::c` starting at `i`; returns the segments and the index after.
fn linear_path(t: &[Token], mut i: usize) -> (Vec<String>, usize) {
    let mut segs = Vec::new();
    while let Some(Tok::Ident(s)) = t.get(i).map(|x| &x.tok) {
        segs.push(s.clone());
        i += 1;
        if t.get(i).is_some_and(|x| x.tok == Tok::PathSep) {
            i += 1;
        } else {
            break;
        }
    }
    (segs, i)
}

/// Expands the use tree starting at `i` (after `use`, or inside a group) into
/// full paths under `prefix`; returns them and the index after the tree.
fn use_tree(t: &[Token], mut i: usize, prefix: Vec<String>) -> (Vec<Vec<String>>, usize) {
    let mut path = prefix;
    while i < t.len() {
        match &t[i].tok {
            Tok::PathSep => i += 1,
            Tok::Ident(s) => {
                // `self` inside a group names the group's own prefix.
                if s != "self" || path.is_empty() {
                    path.push(s.clone());
                }
                i += 1;
                if t.get(i).is_some_and(|x| is_ident(x, "as")) {
                    i += 2;
                }
                if t.get(i).is_none_or(|x| x.tok != Tok::PathSep) {
                    break;
                }
            }
            Tok::Punct('*') => {
                i += 1;
                break;
            }
            Tok::Punct('{') => {
                let mut all = Vec::new();
                i += 1;
                while i < t.len() && !is_punct(t.get(i), '}') {
                    let (sub, next) = use_tree(t, i, path.clone());
                    all.extend(sub);
                    i = next;
                    if is_punct(t.get(i), ',') {
                        i += 1;
                    }
                }
                return (all, i + 1);
            }
            _ => break,
        }
    }
    (vec![path], i)
}

/// Makes `path`, written in module `here`, absolute; `None` when it leaves the
/// crate. A first segment that is neither `crate`, `super` nor `self` is a
/// path relative to `here` only in a `use` and only if it names a child module.
fn absolute(
    here: &ModPath,
    path: &[String],
    known: &BTreeSet<ModPath>,
    in_use: bool,
) -> Option<ModPath> {
    let first = path.first()?;
    let (mut base, rest) = match first.as_str() {
        "crate" | "$crate" => (Vec::new(), &path[1..]),
        "self" => (here.clone(), &path[1..]),
        "super" => {
            let ups = path.iter().take_while(|s| *s == "super").count();
            let base = here[..here.len().saturating_sub(ups)].to_vec();
            (base, &path[ups..])
        }
        _ if in_use => {
            let mut child = here.clone();
            child.push(first.clone());
            if !known.contains(&child) {
                return None;
            }
            (here.clone(), path)
        }
        _ => return None,
    };
    base.extend(rest.iter().cloned());
    Some(base)
}

// -------------------------------------------------------------- cycles

/// Every elementary cycle of the crate's import graph, as `a → b → a`
/// (each starting from its smallest module; at most 200 listed).
fn module_cycles(files: &[SourceFile]) -> Vec<String> {
    const CAP: usize = 200;
    let graph = import_graph(files);
    let nodes: Vec<&ModPath> = graph.keys().collect();
    let index: BTreeMap<&ModPath, usize> = nodes.iter().enumerate().map(|(k, m)| (*m, k)).collect();
    let adj: Vec<Vec<usize>> = nodes
        .iter()
        .map(|m| {
            graph[*m]
                .iter()
                .filter_map(|t| index.get(t).copied())
                .collect()
        })
        .collect();
    let mut cycles = Vec::new();
    for start in 0..nodes.len() {
        let mut stack = vec![start];
        cycles_from(start, start, &adj, &mut stack, &mut cycles, CAP);
    }
    let mut out: Vec<String> = cycles
        .iter()
        .map(|c| {
            let mut names: Vec<String> = c.iter().map(|&k| show(nodes[k])).collect();
            names.push(show(nodes[c[0]]));
            names.join(" → ")
        })
        .collect();
    if out.len() >= CAP {
        out.push(format!("… (stopped after {CAP} cycles)"));
    }
    out
}

/// The imports among the crate's top-level modules, each module standing
/// for all its files (a `use` anywhere under `a/` is `a`'s).
fn top_level_graph(files: &[SourceFile]) -> BTreeMap<String, BTreeSet<String>> {
    let top = |m: &ModPath| m.first().cloned();
    let mut tops: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (module, targets) in &import_graph(files) {
        let Some(from) = top(module) else { continue };
        let edges = tops.entry(from.clone()).or_default();
        edges.extend(targets.iter().filter_map(top).filter(|t| *t != from));
    }
    tops
}

/// Every elementary cycle of `graph`, as `a → b → a` (at most 500).
fn cycles_of(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<String> {
    let nodes: Vec<&String> = graph.keys().collect();
    let index: BTreeMap<&String, usize> = nodes.iter().enumerate().map(|(k, m)| (*m, k)).collect();
    let adj: Vec<Vec<usize>> = (nodes.iter())
        .map(|m| {
            graph[*m]
                .iter()
                .filter_map(|t| index.get(t).copied())
                .collect()
        })
        .collect();
    let mut cycles = Vec::new();
    for start in 0..nodes.len() {
        let mut stack = vec![start];
        cycles_from(start, start, &adj, &mut stack, &mut cycles, 500);
    }
    (cycles.iter())
        .map(|c| {
            let mut names: Vec<&str> = c.iter().map(|&k| nodes[k].as_str()).collect();
            names.push(nodes[c[0]]);
            names.join(" → ")
        })
        .collect()
}

/// Depth-first search for cycles back to `start` through nodes above it.
fn cycles_from(
    start: usize,
    at: usize,
    adj: &[Vec<usize>],
    stack: &mut Vec<usize>,
    cycles: &mut Vec<Vec<usize>>,
    cap: usize,
) {
    for &next in &adj[at] {
        if cycles.len() >= cap {
            return;
        }
        if next == start {
            cycles.push(stack.clone());
        } else if next > start && !stack.contains(&next) {
            stack.push(next);
            cycles_from(start, next, adj, stack, cycles, cap);
            stack.pop();
        }
    }
}

// ---------------------------------------------------------- long functions

#[derive(Debug, PartialEq)]
struct LongFn {
    file: String,
    line: usize,
    name: String,
    lines: usize,
}

/// Every `fn` (outside `#[cfg(test)]` code) that spans more than `max` lines
/// from its `fn` line to its closing brace, both counted.
fn long_functions(files: &[SourceFile], max: usize) -> Vec<LongFn> {
    let mut out = Vec::new();
    for (rel, t) in parsed_modules(files).into_values() {
        for i in 0..t.len() {
            let Some(Tok::Ident(name)) = t.get(i + 1).map(|x| &x.tok) else {
                continue;
            };
            if !is_ident(&t[i], "fn") {
                continue;
            }
            let Some(open) = body_start(&t, i + 2) else {
                continue;
            };
            let lines = t[matching_brace(&t, open)].line - t[i].line + 1;
            if lines > max {
                out.push(LongFn {
                    file: rel.clone(),
                    line: t[i].line,
                    name: name.clone(),
                    lines,
                });
            }
        }
    }
    out
}

/// The `{` opening the body of the `fn` whose signature starts at `i`, or
/// `None` for a declaration without a body (`fn f();`).
fn body_start(t: &[Token], i: usize) -> Option<usize> {
    let mut depth = 0usize;
    for (k, x) in t.iter().enumerate().skip(i) {
        match x.tok {
            Tok::Punct('(' | '[') => depth += 1,
            Tok::Punct(')' | ']') => depth = depth.saturating_sub(1),
            Tok::Punct(';') if depth == 0 => return None,
            Tok::Punct('{') if depth == 0 => return Some(k),
            _ => {}
        }
    }
    None
}

// ------------------------------------------------- the checker's own tests

fn files(list: &[(&str, &str)]) -> Vec<SourceFile> {
    list.iter()
        .map(|(rel, text)| SourceFile {
            rel: rel.to_string(),
            text: text.to_string(),
        })
        .collect()
}

#[test]
fn checker_finds_a_cycle_of_use_lines() {
    let f = files(&[
        ("lib.rs", "pub mod a; pub mod b; pub mod c;"),
        ("a.rs", "use crate::b::B;\npub struct A;"),
        (
            "b/mod.rs",
            "pub use crate::c::{C, self as cc};\npub struct B;",
        ),
        ("c.rs", "use super::a::A;\npub struct C;"),
    ]);
    assert_eq!(module_cycles(&f), ["a → b → c → a"]);
}

#[test]
fn checker_finds_a_cycle_through_paths_in_expressions_and_groups() {
    let f = files(&[
        ("lib.rs", "mod x; mod y;"),
        ("x/mod.rs", "mod inner;\nfn f() -> u8 { 1 + crate::y::g() }"),
        ("x/inner.rs", "fn h() { super::f(); }"),
        (
            "y.rs",
            "use crate::{not_a_module, x::{self as xx}};\npub fn g() -> u8 { 0 }",
        ),
    ]);
    // x → y by an expression, y → x by a grouped `use`; x → its own child
    // and x::inner → its parent are not edges.
    assert_eq!(module_cycles(&f), ["x → y → x"]);
}

#[test]
fn checker_ignores_comments_strings_and_test_code() {
    let f = files(&[
        ("lib.rs", "mod a; mod b;"),
        (
            "a.rs",
            "// use crate::b::B;\n/* crate::b::B /* nested */ crate::b */\n\
             fn f() { let s = \"crate::b::B\"; let r = r#\"use crate::b;\"#; let c = '\"'; let q = '{'; }\n\
             #[cfg(test)]\nmod tests { use crate::b::B; }",
        ),
        ("b.rs", "use crate::a::f; pub struct B;"),
    ]);
    assert_eq!(import_graph(&f)[&vec!["a".to_string()]], BTreeSet::new());
    assert!(module_cycles(&f).is_empty());
}

#[test]
fn checker_ignores_parent_and_child_but_not_sibling_imports() {
    let f = files(&[
        ("lib.rs", "pub mod s;"),
        (
            "s/mod.rs",
            "mod ids; mod load; pub use load::Loaded; pub struct Err;",
        ),
        (
            "s/ids.rs",
            "use super::Err;\nfn f() -> bool { super::load::is_shape() }",
        ),
        (
            "s/load.rs",
            "use super::ids::unique; use super::Err; pub fn is_shape() -> bool { true }",
        ),
    ]);
    assert_eq!(module_cycles(&f), ["s::ids → s::load → s::ids"]);
}

#[test]
fn checker_measures_functions_from_fn_line_to_closing_brace() {
    let body = |n: usize| "    let _x = 1;\n".repeat(n);
    let text = format!(
        "fn ok() {{\n{}}}\nfn long(a: [u8; 2]) -> u8\nwhere u8: Copy,\n{{\n    let c = '}}';\n{}}}\n\
         #[cfg(test)]\nmod tests {{\n    fn also_long() {{\n{}    }}\n}}\nfn decl_only();\n",
        body(78),
        body(77),
        body(100),
    );
    let found = long_functions(&files(&[("lib.rs", &text)]), 80);
    assert_eq!(
        found,
        [LongFn {
            file: "lib.rs".into(),
            line: 81,
            name: "long".into(),
            lines: 82
        }]
    );
}
