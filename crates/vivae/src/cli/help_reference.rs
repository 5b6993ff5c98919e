//! `vivae help-reference` (hidden): the command-line reference,
//! docs/reference/cli.md, written from the clap definitions of every command,
//! so that the page cannot fall behind the program (a test compares the two;
//! `scripts/update-reference.sh` rewrites the page).

use std::fmt::Write as _;

use clap::{Arg, ArgAction, Command};

/// The whole Markdown page for the program `root`: one section per command
/// and subcommand (hidden ones left out), each with its usage, its
/// description, its arguments and its options.
pub fn markdown(mut root: Command) -> String {
    // Building fills in what derive leaves to parse time (usage, bin names).
    root.build();
    let name = root.get_name().to_string();
    let mut out = String::new();
    let _ = writeln!(out, "# Command-line reference\n");
    let _ = writeln!(
        out,
        "Every command and option of `{name}`, generated from the program's own \
         definitions (`scripts/update-reference.sh` rewrites this page; a test fails \
         while it differs from the program). `{name} COMMAND --help` prints the same \
         at the terminal. The config keys the options stand for are in \
         [the config reference](config.md).\n"
    );
    if let Some(about) = root.get_about() {
        let _ = writeln!(out, "{}\n", text(&about.to_string()));
    }
    let _ = writeln!(out, "| command | what it does |\n| --- | --- |");
    for (path, command) in commands(&root, &name) {
        let about = command
            .get_about()
            .map(|a| a.to_string())
            .unwrap_or_default();
        let _ = writeln!(
            out,
            "| [`{path}`](#{}) | {} |",
            anchor(&path),
            text(&about).replace('|', "\\|")
        );
    }
    out.push('\n');
    if let Some(after) = root.get_after_help() {
        let _ = writeln!(out, "{}\n", text(&after.to_string()));
    }
    for (path, command) in commands(&root, &name) {
        section(&mut out, &path, command);
    }
    // One newline at the end, as an editor leaves a file.
    while out.ends_with("\n\n") {
        out.pop();
    }
    out
}

/// Every visible command under `parent` (depth first, in declaration order)
/// with its full name, e.g. `vivae scenario render`.
fn commands<'a>(parent: &'a Command, prefix: &str) -> Vec<(String, &'a Command)> {
    let mut out = Vec::new();
    for command in parent.get_subcommands() {
        if command.is_hide_set() || command.get_name() == "help" {
            continue;
        }
        let path = format!("{prefix} {}", command.get_name());
        out.push((path.clone(), command));
        out.extend(commands(command, &path));
    }
    out
}

/// One command's section: heading, description, usage, arguments, options.
fn section(out: &mut String, path: &str, command: &Command) {
    let _ = writeln!(out, "## {path}\n");
    let about = command
        .get_long_about()
        .or(command.get_about())
        .map(|a| a.to_string())
        .unwrap_or_default();
    if !about.is_empty() {
        let _ = writeln!(out, "{}\n", text(&about));
    }
    let usage = usage(command);
    let _ = writeln!(out, "```text\n{usage}\n```\n");
    let visible: Vec<&Arg> = command
        .get_arguments()
        .filter(|a| !a.is_hide_set() && !is_builtin(a))
        .collect();
    let positionals: Vec<&Arg> = visible
        .iter()
        .copied()
        .filter(|a| a.is_positional())
        .collect();
    let options: Vec<&Arg> = visible
        .iter()
        .copied()
        .filter(|a| !a.is_positional())
        .collect();
    if !positionals.is_empty() {
        let _ = writeln!(out, "Arguments:\n");
        for arg in positionals {
            item(out, &positional_name(arg), arg);
        }
        out.push('\n');
    }
    if !options.is_empty() {
        let _ = writeln!(out, "Options:\n");
        for arg in options {
            item(out, &flags(arg), arg);
        }
        out.push('\n');
    }
    let visible_subcommands: Vec<&Command> = command
        .get_subcommands()
        .filter(|c| !c.is_hide_set() && c.get_name() != "help")
        .collect();
    if !visible_subcommands.is_empty() {
        let _ = writeln!(out, "Subcommands:\n");
        for sub in visible_subcommands {
            let sub_path = format!("{path} {}", sub.get_name());
            let about = sub.get_about().map(|a| a.to_string()).unwrap_or_default();
            let _ = writeln!(
                out,
                "- [`{sub_path}`](#{}): {}",
                anchor(&sub_path),
                text(&about)
            );
        }
        out.push('\n');
    }
}

/// The usage line as `--help` prints it (the built command knows its full name).
fn usage(command: &Command) -> String {
    let rendered = command.clone().render_usage().to_string();
    rendered
        .strip_prefix("Usage: ")
        .unwrap_or(&rendered)
        .to_string()
}

/// `--help` and `--version`, which every command has.
fn is_builtin(arg: &Arg) -> bool {
    matches!(arg.get_id().as_str(), "help" | "version")
}

/// A positional argument as `FILE` (or `[FILE]` when optional, `FILE...` when repeated).
fn positional_name(arg: &Arg) -> String {
    let names = value_names(arg);
    let many = matches!(arg.get_action(), ArgAction::Append)
        || arg.get_num_args().is_some_and(|n| n.max_values() > 1);
    let name = if many { format!("{names}...") } else { names };
    if arg.is_required_set() {
        format!("`{name}`")
    } else {
        format!("`[{name}]`")
    }
}

/// An option's flags and value, e.g. `-o, --out <OUT>`.
fn flags(arg: &Arg) -> String {
    let mut spelled = Vec::new();
    if let Some(short) = arg.get_short() {
        spelled.push(format!("-{short}"));
    }
    if let Some(long) = arg.get_long() {
        spelled.push(format!("--{long}"));
    }
    let mut flag = spelled.join(", ");
    if arg.get_action().takes_values() {
        let _ = write!(flag, " <{}>", value_names(arg));
    }
    format!("`{flag}`")
}

/// The names of an argument's values (`VALUE_NAME`, or its id in capitals).
fn value_names(arg: &Arg) -> String {
    match arg.get_value_names() {
        Some(names) if !names.is_empty() => names
            .iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(" "),
        _ => arg.get_id().as_str().to_uppercase(),
    }
}

/// One list item: the argument, its help, then its default, values and
/// environment variable where it has them.
fn item(out: &mut String, name: &str, arg: &Arg) {
    let help = arg
        .get_long_help()
        .or(arg.get_help())
        .map(|h| h.to_string())
        .unwrap_or_default();
    let mut line = name.to_string();
    if arg.is_required_set() && !arg.is_positional() {
        line.push_str(" (required)");
    }
    let help = text(&help);
    if !help.is_empty() {
        let _ = write!(line, ": {help}");
    }
    let mut notes = Vec::new();
    let defaults: Vec<String> = arg
        .get_default_values()
        .iter()
        .map(|v| v.to_string_lossy().into_owned())
        .collect();
    // A flag's implicit `false` says nothing.
    if !defaults.is_empty() && arg.get_action().takes_values() {
        notes.push(format!("default `{}`", defaults.join(" ")));
    }
    let values: Vec<String> = arg
        .get_possible_values()
        .iter()
        .filter(|v| !v.is_hide_set())
        .map(|v| format!("`{}`", v.get_name()))
        .collect();
    // Unless the value name already spells them out (`<count|area>`).
    if !values.is_empty() && arg.get_action().takes_values() && !value_names(arg).contains('|') {
        notes.push(format!("one of {}", values.join(", ")));
    }
    if let Some(env) = arg.get_env() {
        notes.push(format!("environment `{}`", env.to_string_lossy()));
    }
    if !notes.is_empty() {
        let _ = write!(line, " ({})", notes.join("; "));
    }
    // Help of several paragraphs continues the item, indented.
    let _ = writeln!(out, "- {}", line.replace("\n\n", "\n\n  "));
}

/// Help text as Markdown: `<` outside code spans escaped (else a page
/// renderer takes `<timestamp>` for an HTML tag and hides it), lines of a
/// paragraph kept apart as clap keeps them.
fn text(help: &str) -> String {
    let mut out = String::with_capacity(help.len());
    for (i, piece) in help.trim().split('`').enumerate() {
        if i > 0 {
            out.push('`');
        }
        if i % 2 == 0 {
            out.push_str(&piece.replace('<', "\\<"));
        } else {
            out.push_str(piece);
        }
    }
    out
}

/// The anchor a Markdown renderer (GitHub's, mdBook's) gives a heading of
/// plain words: lower case, spaces as hyphens.
fn anchor(heading: &str) -> String {
    heading
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c.to_ascii_lowercase()),
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::{Arg, Command};

    fn program() -> Command {
        Command::new("prog").about("A program.").subcommand(
            Command::new("draw")
                .about("Draw a thing.")
                .arg(Arg::new("file").help("The `<in>` file, <or> not."))
                .arg(
                    Arg::new("out")
                        .short('o')
                        .long("out")
                        .value_name("OUT")
                        .required(true)
                        .help("Output file."),
                )
                .arg(
                    Arg::new("size")
                        .long("size")
                        .default_value("3")
                        .help("Size."),
                )
                .subcommand(Command::new("secret").hide(true)),
        )
    }

    #[test]
    fn a_command_gets_its_usage_arguments_and_options() {
        let page = markdown(program());
        assert!(page.contains("## prog draw\n\nDraw a thing.\n"), "{page}");
        assert!(page.contains("```text\nprog draw "), "{page}");
        assert!(
            page.contains("- `[FILE]`: The `<in>` file, \\<or> not.\n"),
            "{page}"
        );
        assert!(
            page.contains("- `-o, --out <OUT>` (required): Output file.\n"),
            "{page}"
        );
        assert!(
            page.contains("- `--size <SIZE>`: Size. (default `3`)\n"),
            "{page}"
        );
        assert!(page.contains("| [`prog draw`](#prog-draw) | Draw a thing. |"));
        assert!(
            !page.contains("secret"),
            "hidden commands are left out: {page}"
        );
        assert!(!page.contains("`-h, --help`"), "{page}");
        assert!(page.ends_with(")\n") && !page.ends_with("\n\n"), "{page:?}");
    }
}
