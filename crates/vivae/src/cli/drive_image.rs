//! `vivae drive-image`: a run's controller driven by pictures instead of the
//! simulator: a sequence of camera frames, or one top-down map and a list of
//! poses (`vivae_lab::export::image` states the camera model). Prints the
//! wheel commands of every frame as CSV.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use vivae_lab::export::choose::choose;
use vivae_lab::export::image::{Camera, Image, ImageSensors, drive_frames};
use vivae_lab::export::{Exported, StepNet};
use vivae_lab::io::bad_input;
use vivae_lab::output_path::{Output, OutputKind, check_outputs};
use vivae_sim::DVec2;

use super::args::{GenomeChoice, Resolution};

/// Options of `vivae drive-image`.
#[derive(Args, Debug)]
pub struct DriveImageArgs {
    /// A run directory or a genome JSON file (champion.json).
    pub source: PathBuf,
    /// PNG frames, in order (with --poses: the one top-down map).
    #[arg(required_unless_present = "draw_map", value_name = "PNG")]
    pub frames: Vec<PathBuf>,
    /// Only write the run's map as a top-down PNG for --poses (one pixel per
    /// scenario px, no robots, no anti-aliasing), then stop.
    #[arg(long, value_name = "PNG", conflicts_with_all = ["frames", "poses"])]
    pub draw_map: Option<PathBuf>,
    /// A CSV of robot poses on the map (x,y,heading in scenario px and
    /// degrees clockwise from up; a header line is skipped): one frame each.
    #[arg(long, value_name = "CSV")]
    pub poses: Option<PathBuf>,
    /// The robot's centre in each frame, pixels, as X,Y (default: the frame's middle).
    #[arg(long, value_name = "X,Y", conflicts_with = "poses")]
    pub centre: Option<String>,
    /// Image pixels per scenario px (with --draw-map: at most what keeps the
    /// map within 100,000,000 pixels).
    #[arg(long, value_name = "S", default_value_t = 1.0)]
    pub scale: f64,
    /// The robot's heading in each frame, degrees clockwise from the image's up.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        conflicts_with = "poses"
    )]
    pub heading: f64,
    /// Pixels farther than this from the centre read 0 (an omnidirectional mirror's disc).
    #[arg(long, value_name = "PX")]
    pub radius: Option<f64>,
    #[command(flatten)]
    pub genome: GenomeChoice,
    #[command(flatten)]
    pub resolution: Resolution,
    /// Write the CSV here instead of printing it (its folder must exist and
    /// not be a run directory).
    #[arg(short, long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Replace an existing -o or --draw-map file that is not an earlier one
    /// of drive-image's.
    #[arg(long)]
    pub force: bool,
    /// Arithmetic of the controller's step (default: the run's): exact (f64)
    /// or fast (f32), as `vivae export --precision` writes it.
    #[arg(long, value_name = "exact|fast")]
    pub precision: Option<vivae_neat::Precision>,
}

/// The CSV `drive-image -o` writes: an earlier one opens with its header.
const WHEELS_CSV: OutputKind = OutputKind {
    what: "vivae drive-image CSV",
    earlier: |b| b.starts_with(CSV_HEADER.as_bytes()),
};

/// The first line of the wheel commands' CSV.
const CSV_HEADER: &str = "frame,left,right\n";

/// The text chunk that marks a map `--draw-map` wrote (after the PNG's
/// signature and its IHDR chunk, 33 bytes in).
const MAP_MARK: &[u8] = b"Software\0vivae drive-image --draw-map";

/// The PNG `--draw-map` writes, recognised by [`MAP_MARK`].
const MAP_PNG: OutputKind = OutputKind {
    what: "vivae drive-image --draw-map PNG",
    earlier: |b| {
        b.get(37..)
            .is_some_and(|c| c.starts_with(b"tEXt") && c[4..].starts_with(MAP_MARK))
    },
};

/// `png` with a `tEXt` chunk holding [`MAP_MARK`] after its IHDR chunk.
fn marked(png: Vec<u8>) -> Vec<u8> {
    const AFTER_IHDR: usize = 8 + 25;
    if png.len() < AFTER_IHDR {
        return png;
    }
    let mut chunk = Vec::with_capacity(MAP_MARK.len() + 12);
    chunk.extend_from_slice(&(MAP_MARK.len() as u32).to_be_bytes());
    chunk.extend_from_slice(b"tEXt");
    chunk.extend_from_slice(MAP_MARK);
    chunk.extend_from_slice(&crc32(&chunk[4..]).to_be_bytes());
    let mut out = png[..AFTER_IHDR].to_vec();
    out.extend_from_slice(&chunk);
    out.extend_from_slice(&png[AFTER_IHDR..]);
    out
}

/// The CRC-32 (ISO 3309, as PNG's chunks use) of `bytes` (public for the
/// tests that build PNG files).
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// Reads a PNG file.
fn read_png(path: &Path) -> anyhow::Result<Image> {
    let bytes = vivae_lab::io::read_regular(path, 1 << 30).map_err(|e| {
        bad_input(format!(
            "{}: {}",
            path.display(),
            vivae_lab::io::io_reason(&e)
        ))
    })?;
    Ok(Image::from_png(&bytes, &path.display().to_string())?)
}

/// `X,Y` as two numbers.
fn pair(text: &str, flag: &str) -> anyhow::Result<[f64; 2]> {
    let v: Vec<f64> = (text.split(',').map(|t| t.trim().parse::<f64>()))
        .collect::<Result<_, _>>()
        .map_err(|_| bad_input(format!("{flag} {text}: expected two numbers X,Y")))?;
    match v[..] {
        [x, y] if x.is_finite() && y.is_finite() => Ok([x, y]),
        _ => Err(bad_input(format!("{flag} {text}: expected two numbers X,Y")).into()),
    }
}

/// The poses of a CSV file: (x, y, heading in radians).
fn read_poses(path: &Path) -> anyhow::Result<Vec<(DVec2, f64)>> {
    let text = vivae_lab::io::read_text(path)?;
    let mut poses = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let v: Result<Vec<f64>, _> = line.split(',').map(|t| t.trim().parse::<f64>()).collect();
        match v.as_deref() {
            Ok([x, y, h]) if x.is_finite() && y.is_finite() && h.is_finite() => {
                poses.push((DVec2::new(*x, *y), h.to_radians()));
            }
            _ if i == 0 => {} // a header
            _ => {
                return Err(bad_input(format!(
                    "{} line {}: expected x,y,heading",
                    path.display(),
                    i + 1
                ))
                .into());
            }
        }
    }
    Ok(poses)
}

/// Refuses a camera that cannot be: a scale or radius that is not a
/// positive number, a heading that is not finite.
fn check_camera(args: &DriveImageArgs) -> anyhow::Result<()> {
    if !Camera::usable(args.scale, args.radius) {
        return Err(bad_input("--scale and --radius must be positive numbers").into());
    }
    if !args.heading.is_finite() {
        return Err(bad_input(format!(
            "--heading {}: expected a finite number of degrees",
            args.heading
        ))
        .into());
    }
    Ok(())
}

/// Refuses a `--draw-map` scale at which `scenario`'s map would exceed the
/// drawing's pixel cap (it would be drawn smaller without a word).
fn check_map_scale(scenario: &vivae_sim::Scenario, scale: f64) -> anyhow::Result<()> {
    let (w, h) = (scenario.width(), scenario.height());
    let most = (vivae_sim::draw::MAX_PIXELS / (w * h)).sqrt();
    if scale <= most {
        return Ok(());
    }
    Err(bad_input(format!(
        "--scale {scale}: the {w} x {h} px map can be drawn with at most {} pixels: use a scale from 0 to {:.2}",
        vivae_sim::draw::MAX_PIXELS,
        (most * 100.0).floor() / 100.0
    ))
    .into())
}

/// Runs `vivae drive-image`.
pub fn run(args: DriveImageArgs) -> anyhow::Result<ExitCode> {
    check_camera(&args)?;
    let outputs: Vec<Output> = [
        args.out.as_ref().map(|p| Output::new(p, "-o", WHEELS_CSV)),
        args.draw_map
            .as_ref()
            .map(|p| Output::new(p, "--draw-map", MAP_PNG)),
    ]
    .into_iter()
    .flatten()
    .collect();
    check_outputs(&outputs, args.force)?;
    let pick = args.genome.pick();
    let chosen = choose(
        &args.source,
        pick,
        args.resolution.sensors,
        args.resolution.neurons,
        args.precision,
    )?;
    if let Some(path) = &args.draw_map {
        check_map_scale(chosen.episode.world().scenario(), args.scale)?;
        let svg = vivae_lab::export::frames::ground_svg(chosen.episode.world(), true)?;
        let png = vivae_sim::draw::svg_to_png(&svg, args.scale)
            .map_err(|e| bad_input(format!("{}: {e}", path.display())))?;
        vivae_lab::io::write_atomic(path, &marked(png))?;
        eprintln!("wrote {}", path.display());
        return Ok(ExitCode::SUCCESS);
    }
    let sensors = ImageSensors::new(&chosen.episode, None)?;
    let net: StepNet = Exported::new(&chosen.episode, &chosen.controller, "").net;
    let wheels = match &args.poses {
        Some(poses) => {
            let [map] = &args.frames[..] else {
                return Err(bad_input("--poses takes exactly one image: the map").into());
            };
            let map = read_png(map)?;
            let cameras = read_poses(poses)?.into_iter().map(|(p, h)| {
                let mut c = Camera::on_map(p, h, args.scale);
                c.radius = args.radius;
                (&map, c)
            });
            drive_frames(&net, &sensors, cameras)?
        }
        None => {
            let frames: Vec<Image> = args
                .frames
                .iter()
                .map(|f| read_png(f))
                .collect::<Result<_, _>>()?;
            let centre = args
                .centre
                .as_deref()
                .map(|c| pair(c, "--centre"))
                .transpose()?;
            let cameras = frames.iter().map(|f| {
                let centre = centre.unwrap_or([f.width as f64 / 2.0, f.height as f64 / 2.0]);
                let c = Camera {
                    centre,
                    scale: args.scale,
                    heading: args.heading.to_radians(),
                    radius: args.radius,
                };
                (f, c)
            });
            drive_frames(&net, &sensors, cameras)?
        }
    };
    let mut csv = String::from(CSV_HEADER);
    for (i, [l, r]) in wheels.iter().enumerate() {
        let _ = writeln!(csv, "{i},{l},{r}");
    }
    match &args.out {
        Some(path) => vivae_lab::io::write_atomic(path, csv.as_bytes())?,
        None => print!("{csv}"),
    }
    eprintln!("{}: {} frames", chosen.description, wheels.len());
    Ok(ExitCode::SUCCESS)
}
