//! The pole packs (`pole-markov`, `pole-nonmarkov`): double pole balancing
//! with and without velocities (Stanley & Miikkulainen 2002; Gomez,
//! Schmidhuber & Miikkulainen 2008), the runs of `cargo run -p vivae-neat
//! --example pole` (`vivae_neat::benchmarks::pole`; docs/neat-benchmarks.md).

use vivae_neat::benchmarks::pole::{PoleRun, Setup, run};

use crate::error::{Error, Result};
use crate::reproduce::{Options, Pack, Table, stats, thousands};

/// Stanley & Miikkulainen 2002, as read from the journal's text.
const STANLEY: &str = "Stanley & Miikkulainen 2002, Evol. Comput. 10(2):99–127";
/// Gomez, Schmidhuber & Miikkulainen 2008, as read from JMLR's text.
const GOMEZ: &str = "Gomez, Schmidhuber & Miikkulainen 2008, JMLR 9:937–965";

/// `vivae reproduce pole-markov`.
pub const MARKOV: Pack = Pack {
    name: "pole-markov",
    what: "NEAT on double pole balancing with velocities (Stanley & Miikkulainen 2002; Gomez et al. 2008)",
    methods: super::pack::no_methods,
    run: run_markov,
};

/// `vivae reproduce pole-nonmarkov`.
pub const NONMARKOV: Pack = Pack {
    name: "pole-nonmarkov",
    what: "NEAT on double pole balancing without velocities, on Stanley's 2002 and Gomez et al.'s 2008 terms",
    methods: super::pack::no_methods,
    run: run_nonmarkov,
};

/// A setting of ours and the published numbers it is compared with.
struct Row {
    label: &'static str,
    /// The setting's name in progress lines.
    tag: &'static str,
    setup: fn() -> Setup,
    /// The example's flags giving the same runs.
    flags: &'static str,
    /// Published: runs, mean evaluations (sd), generalisation, source.
    paper: [&'static str; 4],
}

/// Stanley & Miikkulainen's double pole without velocities (both of our
/// settings on his terms compare with it).
const STANLEY_NONMARKOV: [&str; 4] = [
    "20",
    "33,184 (21,790)",
    "286",
    "Stanley & Miikkulainen 2002, Table 2, p. 116",
];

const MARKOV_ROWS: [Row; 2] = [
    Row {
        tag: "markov",
        label: "NEAT, population 150 (vs Stanley's Table 1)",
        setup: Setup::markov,
        flags: "--markov",
        paper: [
            "120",
            "3,600 (2,704)",
            "—",
            "Stanley & Miikkulainen 2002, Table 1, p. 115",
        ],
    },
    Row {
        tag: "markov",
        label: "the same runs (vs Gomez et al.'s Table 3; their best, CoSyNE: 954)",
        setup: Setup::markov,
        flags: "--markov",
        paper: [
            "50",
            "3,600 (sd not given)",
            "—",
            "Gomez et al. 2008, Table 3, p. 954",
        ],
    },
];

const NONMARKOV_ROWS: [Row; 3] = [
    Row {
        tag: "stanley-1000",
        label: "Stanley's terms: population 1,000, ≥ 200 of 625 generalisation starts",
        setup: || Setup::nonmarkov(false),
        flags: "",
        paper: STANLEY_NONMARKOV,
    },
    Row {
        tag: "stanley-150",
        label: "Stanley's terms, population 150, 10 species, survival 0.4",
        setup: || Setup::nonmarkov(true),
        flags: "--small",
        paper: STANLEY_NONMARKOV,
    },
    Row {
        tag: "gomez-16",
        label: "Gomez et al.'s terms: damping fitness, their rule (100,000 steps, no generalisation test), 4.0°, population 16, restarts counted",
        setup: Setup::gomez,
        flags: "--small --set population_size=16 --set target_species=2 --criterion gomez --start-angle 4.0 --restart-after 250 --set weight_perturb_power=0.5 --max-generations 9375",
        paper: [
            "50",
            "6,929 (sd not given; Stanley 2004, population 16)",
            "not required",
            "Gomez et al. 2008, Table 4, p. 955",
        ],
    },
];

const COLUMNS: [&str; 10] = [
    "setting",
    "ours: solved",
    "ours: mean evaluations (sd)",
    "ours: median",
    "ours: mean generalisation",
    "ours: mean hidden nodes",
    "paper: runs",
    "paper: mean evaluations (sd)",
    "paper: generalisation",
    "source",
];

fn run_markov(o: &Options, progress: &mut dyn FnMut(&str)) -> Result<Table> {
    let mut t = table(
        "Double pole balancing with velocities",
        &MARKOV_ROWS,
        o,
        progress,
    )?;
    t.notes.push(format!("{STANLEY}: \"NEAT results are averaged over 120 experiments\" (Table 1's caption); {GOMEZ}: \"the average of 50 simulations\" (Table 3's caption)"));
    Ok(t)
}

fn run_nonmarkov(o: &Options, progress: &mut dyn FnMut(&str)) -> Result<Table> {
    let mut t = table(
        "Double pole balancing without velocities",
        &NONMARKOV_ROWS,
        o,
        progress,
    )?;
    t.notes.push(format!("{STANLEY}, Table 2: \"All results are averages over 20 simulations. The standard deviation for NEAT is 21,790 evaluations.\""));
    t.notes.push(format!("{GOMEZ}, Table 4's NEAT entry is taken from Stanley's 2004 thesis (\"NEAT, using small populations of size 16 (Stanley, 2004)\", p. 955), which could not be read here: how it counted is not verified"));
    Ok(t)
}

/// Runs every row's setting `runs` times, seeds `o.seed`…; the table.
fn table(what: &str, rows: &[Row], o: &Options, progress: &mut dyn FnMut(&str)) -> Result<Table> {
    let runs = o.runs.unwrap_or(if o.quick { 10 } else { 50 });
    let mut out = Vec::new();
    let mut notes = Vec::new();
    // The same setting twice (two papers' rows) runs once.
    let mut last: Option<(&str, Vec<PoleRun>)> = None;
    for row in rows {
        let mut setup = (row.setup)();
        if let Some(e) = o.evaluations {
            let population = setup.params.population_size as u64;
            setup.max_generations = u32::try_from(e.div_ceil(population)).unwrap_or(u32::MAX);
        }
        let results = match &last {
            Some((flags, r)) if *flags == row.flags => r.clone(),
            _ => {
                let mut r = Vec::new();
                for k in 0..runs {
                    let seed = o.seed + k as u64;
                    let one =
                        run(&setup, seed).map_err(|e| Error::Invalid(format!("pole: {e}")))?;
                    let said = one.evals.map_or("unsolved".into(), |e| {
                        format!("solved after {e} evaluations")
                    });
                    progress(&format!("pole {} seed {seed}: {said}", row.tag));
                    r.push(one);
                }
                notes.push(format!(
                    "the row \"{}\": cargo run --release -p vivae-neat --example pole --{} --runs {runs} --seed {} (at most {} generations)",
                    row.label,
                    if row.flags.is_empty() {
                        String::new()
                    } else {
                        format!(" {}", row.flags)
                    },
                    o.seed,
                    setup.max_generations
                ));
                r
            }
        };
        out.push(cells(row, &results));
        last = Some((row.flags, results));
    }
    notes.insert(
        0,
        format!(
            "ours: {runs} runs a setting, seeds {}–{}; means over solved runs; evaluations counted as Stanley counted (Markov: up to the solver; without velocities: whole generations, every restart's included)",
            o.seed,
            o.seed + runs as u64 - 1
        ),
    );
    Ok(Table::new(
        format!("{what} (NEAT), ours beside the papers'"),
        &COLUMNS,
        out,
        notes,
    ))
}

fn cells(row: &Row, results: &[PoleRun]) -> Vec<String> {
    let solved: Vec<&PoleRun> = results.iter().filter(|r| r.evals.is_some()).collect();
    let evals: Vec<u64> = solved
        .iter()
        .filter_map(|r| r.evals)
        .map(|e| e as u64)
        .collect();
    let ours = stats(&evals);
    let mean = |xs: Vec<f64>| {
        if xs.is_empty() {
            "—".to_string()
        } else {
            format!("{:.2}", xs.iter().sum::<f64>() / xs.len() as f64)
        }
    };
    let generalisation: Vec<f64> = solved
        .iter()
        .filter_map(|r| r.generalisation)
        .map(|g| g as f64)
        .collect();
    let mut c = vec![
        row.label.to_string(),
        format!("{}/{}", solved.len(), results.len()),
        ours.map_or("—".into(), |(m, sd, _)| {
            format!("{} ({})", thousands(m), thousands(sd))
        }),
        ours.map_or("—".into(), |(_, _, med)| thousands(med)),
        mean(generalisation),
        mean(solved.iter().map(|r| r.hidden as f64).collect()),
    ];
    c.extend(row.paper.iter().map(|s| s.to_string()));
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pole_packs_print_ours_beside_both_papers() {
        let options = Options {
            runs: Some(2),
            evaluations: Some(1_500),
            ..Options::default()
        };
        let mut lines = Vec::new();
        let t = crate::reproduce::run("pole-markov", &options, &mut |l| lines.push(l.to_string()))
            .unwrap();
        assert_eq!(lines.len(), 2, "one setting, two papers' rows: {lines:?}");
        assert_eq!(t.rows.len(), 2);
        assert_eq!(t.rows[0][1..6], t.rows[1][1..6], "the same runs");
        let direct: Vec<PoleRun> = (1..=2)
            .map(|s| {
                let setup = Setup {
                    max_generations: 10,
                    ..Setup::markov()
                };
                run(&setup, s).unwrap()
            })
            .collect();
        assert_eq!(t.rows[0], cells(&MARKOV_ROWS[0], &direct));
        assert!(t.markdown().contains("Table 1, p. 115"));

        let options = Options {
            runs: Some(1),
            evaluations: Some(32),
            ..Options::default()
        };
        let t = crate::reproduce::run("pole-nonmarkov", &options, &mut |_| {}).unwrap();
        assert_eq!(t.rows.len(), 3);
        assert!(t.rows.iter().all(|r| r.len() == COLUMNS.len()));
        assert_eq!(t.rows[2][7], NONMARKOV_ROWS[2].paper[1]);
        assert!(t.markdown().contains("Table 4, p. 955"));
    }
}
