//! The benchmark examples' command line (`examples/common/cli.rs`): `--help`
//! is recognised, and an unknown argument or a bad number is one line of error
//! (the examples print it and exit with code 2) instead of a panic.

#[path = "../../examples/common/cli.rs"]
mod cli;

use cli::{Args, Parsed};

fn parse(a: &[String], switches: &[&str]) -> Result<Parsed, String> {
    cli::parse(a, switches, &[])
}

fn args(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

#[test]
fn help_is_recognised_anywhere() {
    assert_eq!(parse(&args(&["--help"]), &[]), Ok(Parsed::Help));
    assert_eq!(parse(&args(&["--runs", "3", "-h"]), &[]), Ok(Parsed::Help));
}

#[test]
fn known_arguments_are_parsed() {
    let got = parse(
        &args(&[
            "--markov",
            "--runs",
            "3",
            "--seed",
            "7",
            "--max-generations",
            "9",
            "--set",
            "population_size=10",
        ]),
        &["--markov"],
    );
    let want = Args {
        runs: Some(3),
        seed: Some(7),
        max_generations: Some(9),
        sets: vec!["population_size=10".to_string()],
        switches: vec!["--markov".to_string()],
        options: vec![],
    };
    assert_eq!(got, Ok(Parsed::Run(want)));
}

#[test]
fn unknown_argument_is_one_line_naming_it() {
    let e = parse(&args(&["--runs", "2", "--velocity"]), &["--markov"]).unwrap_err();
    assert!(e.contains("--velocity") && !e.contains('\n'), "{e}");
    // A switch of another example is unknown here.
    assert!(parse(&args(&["--markov"]), &[]).is_err());
}

#[test]
fn bad_or_missing_values_are_one_line_errors() {
    for bad in [
        &["--runs"][..],
        &["--runs", "many"],
        &["--seed", "-1"],
        &["--max-generations", "1.5"],
        &["--set"],
        &["--set", "population_size"],
    ] {
        let e = parse(&args(bad), &[]).unwrap_err();
        assert!(e.starts_with(bad[0]) && !e.contains('\n'), "{bad:?}: {e}");
    }
}

#[test]
fn an_example_option_takes_its_value_and_needs_one() {
    let got = cli::parse(&args(&["--mode", "leo", "--runs", "2"]), &[], &["--mode"]);
    let want = Args {
        runs: Some(2),
        options: vec![("--mode".to_string(), "leo".to_string())],
        ..Args::default()
    };
    assert_eq!(got, Ok(Parsed::Run(want)));
    let e = cli::parse(&args(&["--mode"]), &[], &["--mode"]).unwrap_err();
    assert!(e.starts_with("--mode") && !e.contains('\n'), "{e}");
    // Another example's option is unknown here.
    assert!(parse(&args(&["--mode", "leo"]), &[]).is_err());
}
