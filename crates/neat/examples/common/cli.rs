//! The benchmark examples' command line: `--runs N --seed S --max-generations G
//! --set field=json` plus each example's own switches, `--help`, and a
//! one-line error (the caller exits with code 2) for anything else.

/// What the command line asked for.
#[derive(Debug, Default, PartialEq)]
pub struct Args {
    /// `--runs N`.
    pub runs: Option<usize>,
    /// `--seed S`.
    pub seed: Option<u64>,
    /// `--max-generations G`.
    pub max_generations: Option<u32>,
    /// Every `--set field=json_value`, in order.
    pub sets: Vec<String>,
    /// The example's own switches that were given (e.g. `--markov`).
    pub switches: Vec<String>,
    /// The example's own options with a value, as given (e.g. `--mode leo`).
    pub options: Vec<(String, String)>,
}

impl Args {
    /// The value of the example's own option `key` given last, if any.
    // Each example compiles its own copy of this module; most have no options.
    #[allow(dead_code)]
    pub fn option(&self, key: &str) -> Option<&str> {
        self.options
            .iter()
            .rev()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
}

/// The outcome of parsing: run with these arguments, or print the usage.
#[derive(Debug, PartialEq)]
pub enum Parsed {
    /// Run the benchmark.
    Run(Args),
    /// `--help` or `-h` was given.
    Help,
}

/// Parses `args` (without the program name); `switches` are the example's own
/// flags that take no value, `options` its own that take one value. The error
/// is one line naming the bad argument.
pub fn parse(args: &[String], switches: &[&str], options: &[&str]) -> Result<Parsed, String> {
    let mut out = Args::default();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--help" | "-h" => return Ok(Parsed::Help),
            "--runs" => out.runs = Some(number(a, it.next())?),
            "--seed" => out.seed = Some(number(a, it.next())?),
            "--max-generations" => out.max_generations = Some(number(a, it.next())?),
            "--set" => match it.next() {
                Some(kv) if kv.contains('=') => out.sets.push(kv.clone()),
                _ => return Err("--set needs field=json_value".to_string()),
            },
            s if switches.contains(&s) => out.switches.push(s.to_string()),
            s if options.contains(&s) => match it.next() {
                Some(v) => out.options.push((s.to_string(), v.clone())),
                None => return Err(format!("{s} needs a value")),
            },
            other => return Err(format!("unknown argument `{other}` (see --help)")),
        }
    }
    Ok(Parsed::Run(out))
}

fn number<T: std::str::FromStr>(name: &str, value: Option<&String>) -> Result<T, String> {
    let v = value.ok_or_else(|| format!("{name} needs a whole number"))?;
    v.parse()
        .map_err(|_| format!("{name} needs a whole number, got `{v}`"))
}
