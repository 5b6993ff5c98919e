//! The user docs — `README.md` and `docs/**/*.md` outside `docs/notebook/` —
//! are written for readers and kept current, in three checks:
//!
//! * no date (`2026-12-05`), UTC time, commit id in prose, issue number
//!   ("issue 36") or absolute path of a particular machine (`/work/…`,
//!   `/root/…`); such history belongs in `docs/notebook/` or in commit
//!   messages;
//! * every relative Markdown link, and every `#anchor` (GitHub's heading
//!   slugs), resolves;
//! * every `vivae …` command line of a `sh`, `bash`, `shell` or `console`
//!   block parses with the program's own command line ([`vivae::cli::Cli`]), so
//!   a renamed or removed flag or command fails here.
//!
//! Each check prints `file:line` of every offence. The last test runs the
//! checks on bad fixture text, so each is shown to fail.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use clap::{CommandFactory, Parser};
use vivae::cli::Cli;

/// One Markdown file: its path relative to the repository root, and its text.
struct Doc {
    rel: String,
    text: String,
}

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// README.md and every `.md` under `docs/` except `docs/notebook/`, sorted.
fn user_docs() -> Vec<Doc> {
    let root = repo_root();
    let mut rels = vec!["README.md".to_string()];
    let mut dirs = vec![root.join("docs")];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).expect("docs/ is readable") {
            let path = entry.expect("a docs/ entry").path();
            let rel = path
                .strip_prefix(&root)
                .expect("under the root")
                .to_string_lossy()
                .replace('\\', "/");
            if path.is_dir() {
                if rel != "docs/notebook" {
                    dirs.push(path);
                }
            } else if rel.ends_with(".md") {
                rels.push(rel);
            }
        }
    }
    rels.sort();
    rels.into_iter()
        .map(|rel| Doc {
            text: std::fs::read_to_string(root.join(&rel)).expect("a user doc is UTF-8"),
            rel,
        })
        .collect()
}

#[test]
fn user_docs_have_no_dates_times_commit_ids_issue_numbers_or_machine_paths() {
    let docs = user_docs();
    assert!(docs.len() >= 10, "found only {} user docs", docs.len());
    let offences = forbidden_patterns(&docs);
    assert!(
        offences.is_empty(),
        "user docs hold history that belongs in docs/notebook/ or a commit message:\n{}",
        offences.join("\n")
    );
}

#[test]
fn user_docs_links_and_anchors_resolve() {
    let all = user_docs();
    let broken = broken_links(&all, &user_docs(), &repo_root());
    assert!(
        broken.is_empty(),
        "broken links in the user docs:\n{}",
        broken.join("\n")
    );
}

#[test]
fn user_docs_vivae_commands_parse_with_the_programs_cli() {
    let docs = user_docs();
    let (count, failures) = unparsable_commands(&docs);
    assert!(count >= 50, "found only {count} vivae commands in the docs");
    assert!(
        failures.is_empty(),
        "vivae commands in the docs that the program would refuse:\n{}",
        failures.join("\n")
    );
}

#[test]
fn user_docs_checks_fail_on_a_bad_fixture() {
    let bad = Doc {
        rel: "docs/fixture.md".into(),
        text: "# Fixture\n\
               Measured on 2026-12-05 at 08:32 UTC.\n\
               Fixed at 9f53ede, see issue 36.\n\
               Run `vivae evolve --out /work/main/runs/x`.\n\
               The `9f53ede` in code is fine; so are 4294967295 and /etc/passwd.\n\
               [ok](#fixture) [no anchor](#nope) [gone](missing.md) [ok too](other.md#second-part)\n\
               [bad anchor](other.md#first) [web](https://example.com/#x)\n\
               ```sh\n\
               vivae evolve --generations 5 --out runs/<run>   # fine\n\
               vivae evolve --generatoins 5\n\
               cargo run --release -p vivae -- evolve --no-such-flag\n\
               for s in neat novelty; do vivae evolve --strategy $s --seeds 2; done\n\
               vivae frobnicate\n\
               vivae evolve --seed N --sensors RxA --out runs/RUN\n\
               vivae evolve --seeed N\n\
               ```\n"
            .into(),
    };
    let other = Doc {
        rel: "docs/other.md".into(),
        text: "# Other\n## Second part\n```sh\n# first\n```\n".into(),
    };
    let offences = forbidden_patterns(std::slice::from_ref(&bad));
    for expected in [
        "docs/fixture.md:2: date",
        "docs/fixture.md:2: UTC time",
        "docs/fixture.md:3: commit id",
        "docs/fixture.md:3: issue number",
        "docs/fixture.md:4: machine path",
    ] {
        assert!(
            offences.iter().any(|o| o.starts_with(expected)),
            "{expected} not found in {offences:#?}"
        );
    }
    assert_eq!(offences.len(), 5, "{offences:#?}");

    let docs = [bad, other];
    let broken = broken_links(&docs, &docs[..1], &repo_root());
    assert_eq!(broken.len(), 3, "{broken:#?}");
    assert!(
        broken[0].starts_with("docs/fixture.md:6: #nope"),
        "{broken:#?}"
    );
    assert!(
        broken[1].starts_with("docs/fixture.md:6: missing.md"),
        "{broken:#?}"
    );
    assert!(
        broken[2].starts_with("docs/fixture.md:7: other.md#first"),
        "{broken:#?}"
    );

    let (count, failures) = unparsable_commands(&docs[..1]);
    assert_eq!(count, 7, "{failures:#?}");
    assert_eq!(failures.len(), 5, "{failures:#?}");
    assert!(
        failures[0].starts_with("docs/fixture.md:10:"),
        "{failures:#?}"
    );
    assert!(
        failures[1].starts_with("docs/fixture.md:11:"),
        "{failures:#?}"
    );
    assert!(failures[2].contains("--seeds"), "{failures:#?}");
    assert!(
        failures[3].starts_with("docs/fixture.md:13:"),
        "{failures:#?}"
    );
    assert!(
        failures[4].starts_with("docs/fixture.md:15:"),
        "{failures:#?}"
    );
}

// ---------------------------------------------------------------------------
// Forbidden patterns

/// Every date, UTC time, commit id in prose, issue number and absolute
/// machine path in `docs`, as `file:line: what: the line`.
fn forbidden_patterns(docs: &[Doc]) -> Vec<String> {
    let mut out = Vec::new();
    for doc in docs {
        let mut fence = Fence::default();
        for (i, line) in doc.text.lines().enumerate() {
            let in_code = fence.update(line);
            let prose = if in_code {
                String::new()
            } else {
                without_code_spans(line)
            };
            let mut found = Vec::new();
            if has_date(line) {
                found.push("date");
            }
            if has_utc_time(line) {
                found.push("UTC time");
            }
            if has_commit_id(&prose) {
                found.push("commit id");
            }
            if has_issue_number(line) {
                found.push("issue number");
            }
            if has_machine_path(line) {
                found.push("machine path");
            }
            for what in found {
                out.push(format!("{}:{}: {what}: {}", doc.rel, i + 1, line.trim()));
            }
        }
    }
    out
}

/// `YYYY-MM-DD`.
fn has_date(line: &str) -> bool {
    let b = line.as_bytes();
    let digits = |r: std::ops::Range<usize>| b[r].iter().all(u8::is_ascii_digit);
    (0..b.len().saturating_sub(9)).any(|i| {
        (i == 0 || !b[i - 1].is_ascii_alphanumeric())
            && digits(i..i + 4)
            && b[i + 4] == b'-'
            && digits(i + 5..i + 7)
            && b[i + 7] == b'-'
            && digits(i + 8..i + 10)
            && b.get(i + 10).is_none_or(|c| !c.is_ascii_digit())
    })
}

/// A clock time (`08:32`, `13:35–14:02`) shortly before the word `UTC`.
fn has_utc_time(line: &str) -> bool {
    line.match_indices("UTC").any(|(at, _)| {
        let before = &line.as_bytes()[at.saturating_sub(20)..at];
        before
            .windows(4)
            .any(|w| w[0].is_ascii_digit() && w[1] == b':' && w[2..].iter().all(u8::is_ascii_digit))
    })
}

/// A word of 7–40 hex digits with both a digit and a letter (`9f53ede`).
fn has_commit_id(prose: &str) -> bool {
    words(prose).any(|w| {
        (7..=40).contains(&w.len())
            && w.bytes().all(|c| matches!(c, b'0'..=b'9' | b'a'..=b'f'))
            && w.bytes().any(|c| c.is_ascii_digit())
            && w.bytes().any(|c| c.is_ascii_alphabetic())
    })
}

/// "issue 36", "Issue #36", "issues 36 and 37".
fn has_issue_number(line: &str) -> bool {
    let lower = line.to_lowercase();
    lower.match_indices("issue").any(|(at, _)| {
        let starts_word = lower[..at]
            .chars()
            .next_back()
            .is_none_or(|c| !c.is_alphanumeric());
        let rest = &lower[at + "issue".len()..];
        let rest = rest.strip_prefix('s').unwrap_or(rest);
        let number = rest.trim_start_matches([' ', '#']);
        starts_word && number.len() < rest.len() && number.starts_with(|c: char| c.is_ascii_digit())
    })
}

/// An absolute path into a particular machine's folders.
fn has_machine_path(line: &str) -> bool {
    const ROOTS: &[&str] = &[
        "/work/",
        "/root/",
        "/home/",
        "/Users/",
        "/mnt/",
        "/scratch/",
    ];
    ROOTS.iter().any(|root| {
        line.match_indices(root).any(|(at, _)| {
            line[..at]
                .chars()
                .next_back()
                .is_none_or(|c| !(c.is_alphanumeric() || matches!(c, '.' | '_' | '-' | '~' | '/')))
        })
    })
}

/// The maximal runs of ASCII letters and digits.
fn words(text: &str) -> impl Iterator<Item = &str> {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|w| !w.is_empty())
}

/// Tracks fenced code blocks line by line.
#[derive(Default)]
struct Fence {
    open: Option<(char, usize)>,
    lang: String,
}

impl Fence {
    /// Whether `line` is code (a fence line counts as code).
    fn update(&mut self, line: &str) -> bool {
        let t = line.trim_start();
        let fence_of = |c: char| t.chars().take_while(|&x| x == c).count();
        match self.open {
            Some((c, n)) => {
                if fence_of(c) >= n && t.trim_start_matches(c).trim().is_empty() {
                    self.open = None;
                }
                true
            }
            None => {
                for c in ['`', '~'] {
                    let n = fence_of(c);
                    if n >= 3 {
                        self.open = Some((c, n));
                        self.lang = t[n..].trim().to_lowercase();
                        return true;
                    }
                }
                false
            }
        }
    }
}

/// The line with its `code spans` blanked out.
fn without_code_spans(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut rest = line;
    while let Some(at) = rest.find('`') {
        out.push_str(&rest[..at]);
        let ticks = rest[at..].chars().take_while(|&c| c == '`').count();
        let after = &rest[at + ticks..];
        let close = "`".repeat(ticks);
        match after.find(&close) {
            Some(end) => {
                out.push(' ');
                rest = &after[end + ticks..];
            }
            None => {
                out.push_str(&rest[at..]);
                rest = "";
            }
        }
    }
    out.push_str(rest);
    out
}

// ---------------------------------------------------------------------------
// Links and anchors

/// Every relative link of `checked` whose file or `#anchor` does not exist,
/// as `file:line: target: why`. Anchors of a linked Markdown file come from
/// `all` when it is there, else from the file on disk under `root`.
fn broken_links(all: &[Doc], checked: &[Doc], root: &Path) -> Vec<String> {
    let by_rel: BTreeMap<&str, &str> = all
        .iter()
        .map(|d| (d.rel.as_str(), d.text.as_str()))
        .collect();
    let mut anchors_of: BTreeMap<String, Option<BTreeSet<String>>> = BTreeMap::new();
    let mut out = Vec::new();
    for doc in checked {
        let dir = Path::new(&doc.rel).parent().unwrap_or(Path::new(""));
        for (line, target) in links(&doc.text) {
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            let (path, anchor) = match target.split_once('#') {
                Some((p, a)) => (p, Some(a)),
                None => (target.as_str(), None),
            };
            let rel = if path.is_empty() {
                doc.rel.clone()
            } else {
                normalise(&dir.join(path))
            };
            let exists = by_rel.contains_key(rel.as_str()) || root.join(&rel).exists();
            let why = if !exists {
                Some("no such file")
            } else if let Some(anchor) = anchor.filter(|_| rel.ends_with(".md")) {
                let anchors = anchors_of.entry(rel.clone()).or_insert_with(|| {
                    let text = by_rel
                        .get(rel.as_str())
                        .map(|t| t.to_string())
                        .or_else(|| std::fs::read_to_string(root.join(&rel)).ok());
                    text.map(|t| heading_anchors(&t))
                });
                match anchors {
                    Some(a) if a.contains(anchor) => None,
                    Some(_) => Some("no such heading"),
                    None => Some("unreadable"),
                }
            } else {
                None
            };
            if let Some(why) = why {
                out.push(format!("{}:{line}: {target}: {why} ({rel})", doc.rel));
            }
        }
    }
    out
}

/// `a/b/../c` → `a/c`, with `/` separators.
fn normalise(path: &Path) -> String {
    let mut parts: Vec<String> = Vec::new();
    for c in path.components() {
        match c {
            std::path::Component::ParentDir => {
                if parts.pop().is_none() {
                    parts.push("..".into());
                }
            }
            std::path::Component::CurDir => {}
            other => parts.push(other.as_os_str().to_string_lossy().into_owned()),
        }
    }
    parts.join("/")
}

/// `(line, target)` of every inline link or image and reference definition
/// outside code.
fn links(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut fence = Fence::default();
    for (i, line) in text.lines().enumerate() {
        if fence.update(line) {
            continue;
        }
        let prose = without_code_spans(line);
        let mut rest = prose.as_str();
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            let mut depth = 1;
            let end = after
                .char_indices()
                .find(|&(_, c)| {
                    match c {
                        '(' => depth += 1,
                        ')' => depth -= 1,
                        _ => {}
                    }
                    depth == 0
                })
                .map_or(after.len(), |(j, _)| j);
            let target = after[..end].split_whitespace().next().unwrap_or("");
            let target = target.trim_start_matches('<').trim_end_matches('>');
            if !target.is_empty() {
                out.push((i + 1, target.to_string()));
            }
            rest = &after[end.min(after.len())..];
        }
        // A reference definition: `[label]: target`.
        if let Some((label, target)) = prose.trim_start().split_once("]:")
            && label.starts_with('[')
            && !label[1..].contains(['[', ']'])
            && let Some(target) = target.split_whitespace().next()
        {
            out.push((i + 1, target.to_string()));
        }
    }
    out
}

/// The anchors GitHub gives a Markdown file's headings (`-1`, `-2` for
/// repeats), plus explicit `id="…"` and `name="…"` anchors.
fn heading_anchors(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut fence = Fence::default();
    for line in text.lines() {
        if fence.update(line) {
            continue;
        }
        let html = without_code_spans(line);
        for key in ["id=\"", "name=\""] {
            for (at, _) in html.match_indices(key) {
                if let Some(end) = html[at + key.len()..].find('"') {
                    out.insert(html[at + key.len()..at + key.len() + end].to_string());
                }
            }
        }
        let t = line.trim_start();
        let hashes = t.chars().take_while(|&c| c == '#').count();
        if !(1..=6).contains(&hashes) || !t[hashes..].starts_with(' ') {
            continue;
        }
        let slug = github_slug(t[hashes..].trim().trim_end_matches('#').trim());
        let n = seen.entry(slug.clone()).or_insert(0);
        out.insert(if *n == 0 {
            slug.clone()
        } else {
            format!("{slug}-{n}")
        });
        *n += 1;
    }
    out
}

/// GitHub's anchor of a heading: its rendered text (code spans' and links'
/// text, no markup) lower-cased, with everything but letters, digits, `_`,
/// `-` and spaces dropped, and spaces turned into `-`.
fn github_slug(heading: &str) -> String {
    let mut text = String::new();
    let mut rest = heading;
    // Links: keep their text.
    while let Some(open) = rest.find('[') {
        match rest[open..].find("](") {
            Some(mid) => {
                let after = &rest[open + mid + 2..];
                let close = after.find(')').unwrap_or(after.len());
                text.push_str(&rest[..open]);
                text.push_str(&rest[open + 1..open + mid]);
                rest = &after[(close + 1).min(after.len())..];
            }
            None => break,
        }
    }
    text.push_str(rest);
    text.to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '_' || c == '-' => Some(c),
            _ => None,
        })
        .collect()
}

// ---------------------------------------------------------------------------
// Commands

/// Shell words that may stand before a command (`do vivae …`).
const SHELL_KEYWORDS: &[&str] = &["do", "then", "else", "!", "{", "("];

/// Words that run the command after them (`nice -n 10 vivae …`).
const WRAPPERS: &[&str] = &[
    "nice", "time", "env", "exec", "mpirun", "mpiexec", "srun", "timeout",
];

/// How many `vivae` command lines the shell blocks of `docs` hold, and every
/// one the program's command line refuses, as `file:line: command: error`.
fn unparsable_commands(docs: &[Doc]) -> (usize, Vec<String>) {
    let mut count = 0;
    let mut failures = Vec::new();
    for doc in docs {
        for (line, command) in shell_lines(&doc.text) {
            for args in vivae_invocations(&command) {
                count += 1;
                if let Err(why) = check_args(&args) {
                    failures.push(format!("{}:{line}: {}: {why}", doc.rel, command.trim()));
                }
            }
        }
    }
    (count, failures)
}

/// `(first line, command)` of every command in a sh/bash/shell/console
/// block: continuation lines joined, `console` output lines left out.
fn shell_lines(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut fence = Fence::default();
    let mut pending: Option<(usize, String)> = None;
    for (i, line) in text.lines().enumerate() {
        let was_open = fence.open.is_some();
        let in_code = fence.update(line);
        if !in_code || !was_open || fence.open.is_none() {
            pending = None;
            continue;
        }
        let lang = fence.lang.split([' ', ',', '{']).next().unwrap_or("");
        if !matches!(lang, "sh" | "bash" | "shell" | "console") {
            continue;
        }
        let mut text = line.trim();
        if pending.is_none() && lang == "console" {
            match text.strip_prefix("$ ") {
                Some(cmd) => text = cmd,
                None => continue,
            }
        }
        let (start, mut joined) = pending.take().unwrap_or((i + 1, String::new()));
        match text.strip_suffix('\\') {
            Some(head) => {
                joined.push_str(head);
                joined.push(' ');
                pending = Some((start, joined));
            }
            None => {
                joined.push_str(text);
                out.push((start, joined));
            }
        }
    }
    out
}

/// A shell word, or an operator between commands.
#[derive(Debug, PartialEq)]
enum Token {
    Word(String),
    Op,
}

/// A word being read, and whether it is a redirection's target (dropped).
#[derive(Default)]
struct WordBuf {
    text: String,
    started: bool,
    redirect_target: bool,
}

impl WordBuf {
    /// Ends the word: onto `out`, unless it is a redirection's target.
    fn end(&mut self, out: &mut Vec<Token>) {
        if self.started && !self.redirect_target {
            out.push(Token::Word(std::mem::take(&mut self.text)));
        }
        *self = WordBuf::default();
    }
}

/// Splits a command line as the shell would, roughly: quotes and
/// backslashes, `#` comments, `|`, `&&`, `;` and redirections (dropped with
/// their targets). A `<word>` placeholder is a word.
fn tokenize(line: &str) -> Vec<Token> {
    let mut out = Vec::new();
    let mut chars = line.chars().peekable();
    let mut word = WordBuf::default();
    while let Some(c) = chars.next() {
        match c {
            ' ' | '\t' => word.end(&mut out),
            '#' if !word.started => break,
            '\'' => {
                word.started = true;
                word.text.extend(chars.by_ref().take_while(|&q| q != '\''));
            }
            '"' => {
                word.started = true;
                while let Some(q) = chars.next() {
                    match q {
                        '"' => break,
                        '\\' => word.text.extend(chars.next()),
                        q => word.text.push(q),
                    }
                }
            }
            '\\' => {
                word.started = true;
                word.text.extend(chars.next());
            }
            '|' | ';' | '&' => {
                word.end(&mut out);
                while chars.next_if(|&n| matches!(n, '|' | '&' | ';')).is_some() {}
                out.push(Token::Op);
            }
            '<' if !word.started => {
                let rest: String = chars.clone().take_while(|&n| n != ' ').collect();
                word.started = true;
                if rest.len() > 1 && rest.ends_with('>') {
                    word.text.push('<');
                } else {
                    word.redirect_target = true;
                    while chars.next_if(|&n| n == ' ').is_some() {}
                }
            }
            '>' if word.text.chars().all(|d| d.is_ascii_digit()) && !word.redirect_target => {
                // `> file`, `>> file`, `2> file`, `2>&1`: dropped with the target.
                word = WordBuf::default();
                while chars.next_if(|&n| matches!(n, '>' | '&')).is_some() {}
                if chars.next_if(|&n| n == '1' || n == '2').is_some() {
                    continue;
                }
                while chars.next_if(|&n| n == ' ').is_some() {}
                word.started = true;
                word.redirect_target = true;
            }
            c => {
                word.started = true;
                word.text.push(c);
            }
        }
    }
    word.end(&mut out);
    out
}

/// The arguments after `vivae` of every command of the line that runs the
/// program: `vivae …`, `path/to/vivae …`, behind `VAR=value` or a wrapper,
/// or `cargo run … -p vivae -- …`.
fn vivae_invocations(line: &str) -> Vec<Vec<String>> {
    let tokens = tokenize(line);
    let mut out = Vec::new();
    for segment in tokens.split(|t| *t == Token::Op) {
        let words: Vec<&str> = segment
            .iter()
            .filter_map(|t| match t {
                Token::Word(w) => Some(w.as_str()),
                Token::Op => None,
            })
            .collect();
        let mut i = 0;
        while i < words.len() && (is_assignment(words[i]) || SHELL_KEYWORDS.contains(&words[i])) {
            i += 1;
        }
        let Some(&first) = words.get(i) else { continue };
        let is_vivae = |w: &str| w == "vivae" || w.ends_with("/vivae");
        let start = if is_vivae(first) {
            Some(i + 1)
        } else if WRAPPERS.contains(&first) {
            words[i..]
                .iter()
                .position(|w| is_vivae(w))
                .map(|p| i + p + 1)
        } else if first == "cargo"
            && words.get(i + 1) == Some(&"run")
            && words
                .windows(2)
                .any(|w| w == ["-p", "vivae"] || w == ["--bin", "vivae"])
        {
            words.iter().position(|w| *w == "--").map(|p| p + 1)
        } else {
            None
        };
        if let Some(start) = start {
            out.push(words[start..].iter().map(|w| w.to_string()).collect());
        }
    }
    out
}

fn is_assignment(word: &str) -> bool {
    word.split_once('=').is_some_and(|(name, _)| {
        !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    })
}

/// Parses `vivae ARGS` with the program's command line. A line with shell
/// variables (`$s`) cannot be parsed as written, nor a value that is a
/// placeholder (`--seed N`): their command words and flags are checked
/// against the program's instead.
fn check_args(args: &[String]) -> Result<(), String> {
    use clap::error::ErrorKind;
    if args.iter().any(|a| a.contains('$')) {
        return check_flags(args);
    }
    match Cli::try_parse_from(std::iter::once("vivae".to_string()).chain(args.iter().cloned())) {
        Ok(_) => Ok(()),
        Err(e) if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) => Ok(()),
        Err(e) if refuses_a_placeholder(&e) => check_flags(args),
        Err(e) => Err(e.to_string().lines().next().unwrap_or("").to_string()),
    }
}

/// Whether clap refused a placeholder value (`--seed N`).
fn refuses_a_placeholder(e: &clap::Error) -> bool {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    matches!(
        e.kind(),
        ErrorKind::InvalidValue | ErrorKind::ValueValidation
    ) && match e.get(ContextKind::InvalidValue) {
        Some(ContextValue::String(v)) => is_placeholder(v),
        _ => false,
    }
}

/// A value written as a placeholder: `N`, `SEED`, `RxA`.
fn is_placeholder(value: &str) -> bool {
    value.starts_with(|c: char| c.is_ascii_uppercase())
        && value
            .chars()
            .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || matches!(c, '_' | 'x'))
}

/// The command words of `args` name a command, and every `--long` or `-s`
/// flag is one of that command's.
fn check_flags(args: &[String]) -> Result<(), String> {
    let mut command = Cli::command();
    let mut rest = args;
    while let Some((word, tail)) = rest.split_first() {
        let sub = command
            .get_subcommands()
            .find(|s| s.get_name() == word || s.get_all_aliases().any(|a| a == word))
            .cloned();
        match sub {
            Some(sub) => {
                command = sub;
                rest = tail;
            }
            None => break,
        }
    }
    if command.has_subcommands() {
        return Err(format!("`{}` needs a command", command.get_name()));
    }
    for arg in rest {
        let known = if let Some(long) = arg.strip_prefix("--") {
            let name = long.split('=').next().unwrap_or("");
            long.is_empty()
                || name.contains('$')
                || name == "help"
                || command.get_arguments().any(|a| {
                    a.get_long() == Some(name)
                        || a.get_all_aliases().is_some_and(|v| v.contains(&name))
                })
        } else if let Some(short) = arg.strip_prefix('-').filter(|s| !s.is_empty()) {
            short.starts_with(|c: char| c.is_ascii_digit() || c == '$')
                || short
                    .chars()
                    .all(|s| s == 'h' || command.get_arguments().any(|a| a.get_short() == Some(s)))
        } else {
            true
        };
        if !known {
            return Err(format!(
                "`{arg}` is not a flag of `vivae {}`",
                command.get_name()
            ));
        }
    }
    Ok(())
}
