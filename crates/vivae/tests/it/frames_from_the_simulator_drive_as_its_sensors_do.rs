//! Images in: frames drawn from the simulator's own scenario (robot-centred
//! camera frames, and a top-down map with poses) drive an exported
//! controller as the simulator's sensors do, within the tolerance the guide
//! states; `vivae drive-image` gives the library's wheel commands.

use std::path::Path;

use vivae_lab::export::choose::{Pick, choose};
use vivae_lab::export::frames::{Recording, ground_svg, rasterize, record, robot_view};
use vivae_lab::export::image::{Camera, Image, ImageSensors, drive_frames};
use vivae_lab::export::{Exported, StepNet};
use vivae_neat::Precision;

use crate::common::*;

/// What the image path gave next to the simulator's: readings that differ
/// (of all), and the largest wheel difference.
struct Agreement {
    readings_off: usize,
    readings: usize,
    wheels_off: f64,
    /// Steps whose wheels differ by more than 0.05.
    steps_off: usize,
}

/// Reads every recorded step's sensors from `frames` and drives `net` with them.
fn agreement(
    net: &StepNet,
    sensors: &ImageSensors,
    rec: &Recording,
    frames: &[(Image, Camera)],
) -> Agreement {
    let mut x = vec![0.0; rec.inputs];
    let mut readings_off = 0;
    for ((image, camera), want) in frames.iter().zip(rec.sensors.chunks_exact(rec.inputs)) {
        sensors.read(image, camera, &mut x);
        readings_off += x.iter().zip(want).filter(|(a, b)| a != b).count();
    }
    let wheels = drive_frames(net, sensors, frames.iter().map(|(i, c)| (i, *c))).unwrap();
    let wheels_off = (wheels.iter().zip(&rec.wheels))
        .flat_map(|(a, b)| [(a[0] - b[0]).abs(), (a[1] - b[1]).abs()])
        .fold(0.0, f64::max);
    let steps_off = (wheels.iter().zip(&rec.wheels))
        .filter(|(a, b)| (a[0] - b[0]).abs() > 0.05 || (a[1] - b[1]).abs() > 0.05)
        .count();
    Agreement {
        steps_off,
        readings_off,
        readings: rec.sensors.len(),
        wheels_off,
    }
}

fn write_png(path: &Path, svg: &str) {
    std::fs::write(path, vivae_sim::draw::svg_to_png(svg, 1.0).unwrap()).unwrap();
}

#[test]
fn frames_from_the_simulator_drive_as_its_sensors_do() {
    let run = small_run("drive-image", 3);
    let chosen = choose(
        &run,
        Pick::Champion,
        Some("6x24".parse().unwrap()),
        None,
        None,
    )
    .unwrap();
    let (episode, controller) = (&chosen.episode, &chosen.controller);
    let rec = record(episode, controller, 0, 150).unwrap();
    let net = Exported::new(episode, controller, "").net;
    let sensors = ImageSensors::new(episode, None).unwrap();
    // Robot-centred camera frames, anti-aliased as a camera sees, at 1 and 2
    // pixels per scenario px: readings differ only on edge pixels, and the
    // wheels follow the simulator's but on the steps where such a reading flips.
    let ground = ground_svg(episode.world(), false).unwrap();
    for (scale, size) in [(1.0, 128), (2.0, 256)] {
        let frames: Vec<(Image, Camera)> = (rec.poses.iter())
            .map(|&(pos, heading)| {
                let (svg, camera) = robot_view(&ground, pos, heading, size, scale);
                (rasterize(&svg).unwrap(), camera)
            })
            .collect();
        let a = agreement(&net, &sensors, &rec, &frames);
        let share = a.readings_off as f64 / a.readings as f64;
        eprintln!(
            "camera frames at scale {scale}: {} of {} readings differ ({:.3}%), wheels within {:.2e}, {} of 150 steps off by > 0.05",
            a.readings_off,
            a.readings,
            100.0 * share,
            a.wheels_off,
            a.steps_off
        );
        assert!(share <= 0.01, "{share}");
        assert!(a.steps_off <= 150 / 8, "{} steps", a.steps_off);
    }
    // A top-down map drawn without anti-aliasing (a pixel is the surface
    // under its centre, as in the simulator's raster), one pose a frame.
    let map = rasterize(&ground_svg(episode.world(), true).unwrap()).unwrap();
    let frames: Vec<(Image, Camera)> = (rec.poses.iter())
        .map(|&(p, h)| (map.clone(), Camera::on_map(p, h, 1.0)))
        .collect();
    let a = agreement(&net, &sensors, &rec, &frames);
    let share = a.readings_off as f64 / a.readings as f64;
    eprintln!(
        "top-down map: {} of {} readings differ ({:.3}%), wheels within {:.2e}",
        a.readings_off,
        a.readings,
        100.0 * share,
        a.wheels_off
    );
    assert!(share <= 0.001, "{share}");
    assert!(a.wheels_off <= 1e-6, "{}", a.wheels_off);
}

/// The wheel commands of a `frame,left,right` CSV from `vivae drive-image`.
fn wheels_of(csv: &str) -> Vec<[f64; 2]> {
    (csv.lines().skip(1))
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|t| t.parse().unwrap()).collect();
            [v[1], v[2]]
        })
        .collect()
}

#[test]
fn drive_image_prints_the_librarys_wheel_commands() {
    let run = small_run("drive-image-cli", 2);
    let dir = run.parent().unwrap().to_path_buf();
    let chosen = choose(&run, Pick::Champion, None, None, None).unwrap();
    let rec = record(&chosen.episode, &chosen.controller, 2, 20).unwrap();
    let net = Exported::new(&chosen.episode, &chosen.controller, "").net;
    let sensors = ImageSensors::new(&chosen.episode, None).unwrap();
    let ground = ground_svg(chosen.episode.world(), true).unwrap();
    let mut files = Vec::new();
    let mut frames = Vec::new();
    let mut poses = String::from("x,y,heading\n");
    for (i, &(pos, heading)) in rec.poses.iter().enumerate() {
        let (svg, camera) = robot_view(&ground, pos, heading, 128, 1.0);
        let f = dir.join(format!("frame{i:03}.png"));
        write_png(&f, &svg);
        frames.push((rasterize(&svg).unwrap(), camera));
        files.push(f);
        poses.push_str(&format!("{},{},{}\n", pos.x, pos.y, heading.to_degrees()));
    }
    let want = drive_frames(&net, &sensors, frames.iter().map(|(i, c)| (i, *c))).unwrap();
    let csv = ok(vivae()
        .arg("drive-image")
        .arg(&run)
        .args(&files)
        .args(["--radius", "64"]));
    assert_eq!(wheels_of(&csv), want);
    // In fast precision: the f32 step of the controller decoded in f32, as exported.
    let fast = choose(&run, Pick::Champion, None, None, Some(Precision::Fast)).unwrap();
    let fast_net = Exported::new(&fast.episode, &fast.controller, "").net;
    assert_eq!(fast_net.precision, Precision::Fast);
    let want_fast = drive_frames(&fast_net, &sensors, frames.iter().map(|(i, c)| (i, *c))).unwrap();
    assert_ne!(want_fast, want, "the f32 step gives other bits");
    let csv = ok(vivae().arg("drive-image").arg(&run).args(&files).args([
        "--radius",
        "64",
        "--precision",
        "fast",
    ]));
    assert_eq!(wheels_of(&csv), want_fast);
    // The map and poses: the map's CSV is within the stated tolerance of the simulator's.
    std::fs::write(dir.join("poses.csv"), poses).unwrap();
    ok(vivae()
        .arg("drive-image")
        .arg(&run)
        .arg("--draw-map")
        .arg(dir.join("map.png")));
    let drawn = std::fs::read(dir.join("map.png")).unwrap();
    // The simulator's PNG, with a text chunk after its header that marks it
    // as drive-image's (so that a later --draw-map may replace it).
    let mark = u32::from_be_bytes(drawn[33..37].try_into().unwrap()) as usize;
    assert_eq!(&drawn[37..41], b"tEXt");
    let unmarked = [&drawn[..33], &drawn[33 + 12 + mark..]].concat();
    assert_eq!(unmarked, vivae_sim::draw::svg_to_png(&ground, 1.0).unwrap());
    let csv = ok(vivae()
        .arg("drive-image")
        .arg(&run)
        .arg(dir.join("map.png"))
        .arg("--poses")
        .arg(dir.join("poses.csv")));
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 20);
    for (row, w) in rows.iter().zip(&rec.wheels) {
        let v: Vec<f64> = row.split(',').map(|t| t.parse().unwrap()).collect();
        assert!(
            (v[1] - w[0]).abs() <= 0.05 && (v[2] - w[1]).abs() <= 0.05,
            "{row} vs {w:?}"
        );
    }
    // Bad input is one line and exit 2.
    let out = run_cmd(
        vivae()
            .arg("drive-image")
            .arg(&run)
            .arg(dir.join("poses.csv")),
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("not a PNG image"));
}

fn run_cmd(cmd: &mut std::process::Command) -> std::process::Output {
    cmd.output().unwrap()
}
