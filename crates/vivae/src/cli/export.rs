//! `vivae export`: a run's controller (its champion, a generation's best, an
//! elite or a front member), decoded at any resolution, as ONNX, C or JSON
//! (`vivae_lab::export`).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use vivae_lab::export::choose::exported;
use vivae_lab::export::{Format, write};
use vivae_lab::output_path::{check_outputs, export_outputs};

use super::args::{GenomeChoice, Resolution};

/// Options of `vivae export`.
#[derive(Args, Debug)]
pub struct ExportArgs {
    /// A run directory or a genome JSON file (champion.json).
    pub source: PathBuf,
    #[command(flatten)]
    pub genome: GenomeChoice,
    #[command(flatten)]
    pub resolution: Resolution,
    /// The artifact: onnx (opset 17; f64, f32 in fast precision), c (a .c file and its .h) or json.
    #[arg(long, value_name = "onnx|c|json")]
    pub format: Format,
    /// The file to write (c: the header goes beside it, ending in .h). Its
    /// folder must exist and not be a run directory; an existing file is
    /// replaced only when it is an earlier vivae export (or with --force).
    #[arg(short, long, value_name = "FILE")]
    pub out: PathBuf,
    /// Replace an existing file at --out (or its header) that is not an
    /// earlier vivae export of this format.
    #[arg(long)]
    pub force: bool,
    /// Arithmetic of the exported step (default: the run's): exact (f64) or
    /// fast (f32, vivae's --precision fast step: the CPPN decoded in f32, C
    /// in float for a processor with a single-precision FPU). Dense polar
    /// substrate only.
    #[arg(long, value_name = "exact|fast")]
    pub precision: Option<vivae_neat::Precision>,
}

/// Runs `vivae export`.
pub fn run(args: ExportArgs) -> anyhow::Result<ExitCode> {
    let outputs = export_outputs(args.format, &args.out, "-o")?;
    check_outputs(&outputs, args.force)?;
    let exported = exported(
        &args.source,
        args.genome.pick(),
        args.resolution.sensors,
        args.resolution.neurons,
        args.precision,
    )?;
    let written = write(&exported, args.format, &args.out)?;
    let net = &exported.net;
    println!(
        "{}: {} inputs, {} outputs, {} nodes, {} links ({})",
        exported.description,
        net.inputs,
        net.outputs.len(),
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
