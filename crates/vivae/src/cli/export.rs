//! `vivae export`: a run's controller (its champion, a generation's best, an
//! elite or a front member), decoded at any resolution, as ONNX, C or JSON
//! (`vivae_lab::export`).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use vivae_lab::export::choose::{Pick, choose};
use vivae_lab::export::{Exported, Format, write};

use super::args::{MemberChoice, Resolution};

/// Options of `vivae export`.
#[derive(Args, Debug)]
pub struct ExportArgs {
    /// A run directory or a genome JSON file (champion.json).
    pub source: PathBuf,
    /// Export the best genome of this generation (best-genomes.jsonl) instead of the champion.
    #[arg(long, value_name = "G", conflicts_with_all = ["elite", "front"])]
    pub generation: Option<u32>,
    #[command(flatten)]
    pub member: MemberChoice,
    #[command(flatten)]
    pub resolution: Resolution,
    /// The artifact: onnx (opset 17, f64), c (a .c file and its .h) or json.
    #[arg(long, value_name = "onnx|c|json")]
    pub format: Format,
    /// The file to write (c: the header goes beside it, ending in .h).
    #[arg(short, long, value_name = "FILE")]
    pub out: PathBuf,
}

/// What `args` picks.
pub fn pick(generation: Option<u32>, member: &MemberChoice) -> Pick {
    match (generation, member.member()) {
        (Some(g), _) => Pick::Generation(g),
        (None, Some(m)) => Pick::Member(m),
        (None, None) => Pick::Champion,
    }
}

/// Runs `vivae export`.
pub fn run(args: ExportArgs) -> anyhow::Result<ExitCode> {
    let chosen = choose(
        &args.source,
        pick(args.generation, &args.member),
        args.resolution.sensors,
        args.resolution.neurons,
    )?;
    let exported = Exported::new(&chosen.episode, &chosen.controller, &chosen.description);
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        vivae_lab::io::create_dirs_for(dir, &args.out)?;
    }
    let written = write(&exported, args.format, &args.out)?;
    let net = &exported.net;
    println!(
        "{}: {} inputs, {} nodes, {} links ({})",
        chosen.description,
        net.inputs,
        net.nodes,
        net.links(),
        if net.synchronous {
            "recurrent: one synchronous update a step"
        } else {
            "feed-forward"
        }
    );
    for f in written {
        eprintln!("wrote {}", f.display());
    }
    Ok(ExitCode::SUCCESS)
}
