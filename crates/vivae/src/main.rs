//! The `vivae` command-line program: [`vivae::run_cli`] with the built-in
//! tasks and strategies (the command line is the library's `cli` module, one
//! file per command).

fn main() -> std::process::ExitCode {
    vivae::run_cli()
}
