//! Taking a controller to a robot from Python: `vivae.export` writes a run's
//! controller as ONNX, C or JSON, `vivae.drive_image` drives it with
//! pictures, and `vivae.record_episode` records what vivae's own robot read
//! and did (to check an exported controller against).

use std::path::{Path, PathBuf};

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use vivae_lab::controller::substrate::PolarGrid;
use vivae_lab::export::choose::{Chosen, Pick, choose};
use vivae_lab::export::image::{Camera, Image, ImageSensors, drive_frames};
use vivae_lab::export::{Exported, Format, write};
use vivae_lab::output_path::{check_outputs, export_outputs};
use vivae_lab::search::files::Member;
use vivae_neat::Precision;
use vivae_sim::DVec2;

use crate::errors;

/// Which genome: the champion, a generation's best, an elite or a front member.
fn pick(generation: Option<u32>, elite: Option<usize>, front: Option<usize>) -> PyResult<Pick> {
    Ok(match (generation, elite, front) {
        (None, None, None) => Pick::Champion,
        (Some(g), None, None) => Pick::Generation(g),
        (None, Some(c), None) => Pick::Member(Member::Elite(c)),
        (None, None, Some(n)) => Pick::Member(Member::Front(n)),
        _ => {
            return Err(PyValueError::new_err(
                "give at most one of generation=, elite=, front=",
            ));
        }
    })
}

/// A grid keyword (`"3x5"`) parsed.
fn grid(key: &str, text: Option<&str>) -> PyResult<Option<PolarGrid>> {
    text.map(|t| {
        t.parse::<PolarGrid>()
            .map_err(|e| PyValueError::new_err(format!("{key}={t:?}: {e}")))
    })
    .transpose()
}

/// The chosen genome of `source`, decoded.
fn chosen(
    source: &Path,
    who: (Option<u32>, Option<usize>, Option<usize>),
    (sensors, neurons): (Option<&str>, Option<&str>),
    precision: Option<&str>,
) -> PyResult<Chosen> {
    let pick = pick(who.0, who.1, who.2)?;
    let (s, n) = (grid("sensors", sensors)?, grid("neurons", neurons)?);
    let precision = (precision.map(str::parse::<Precision>).transpose())
        .map_err(|e| PyValueError::new_err(format!("precision: {e}")))?;
    choose(source, pick, s, n, precision).map_err(errors::lab)
}

/// Writes a run's controller (as `vivae export`): `format` is "onnx", "c" or
/// "json", `precision` "exact" or "fast" (default: the run's); returns the
/// files written (C: the .c file and its .h header). `out` follows the CLI's
/// `-o` rules (`vivae_lab::output_path`): its folder must exist and not be a
/// run directory, and an existing file is replaced only when it is an
/// earlier export of the format, or with `force=True`.
#[pyfunction]
#[pyo3(signature = (source, format, out, *, generation=None, elite=None, front=None, sensors=None, neurons=None, precision=None, force=false))]
#[allow(clippy::too_many_arguments)]
pub fn export(
    source: PathBuf,
    format: &str,
    out: PathBuf,
    #[pyo3(from_py_with = crate::args::opt_generation)] generation: Option<u32>,
    #[pyo3(from_py_with = crate::args::elite)] elite: Option<usize>,
    #[pyo3(from_py_with = crate::args::front)] front: Option<usize>,
    sensors: Option<&str>,
    neurons: Option<&str>,
    precision: Option<&str>,
    force: bool,
) -> PyResult<Vec<String>> {
    let format: Format = format.parse().map_err(PyValueError::new_err)?;
    let outputs = export_outputs(format, &out, "out=").map_err(errors::lab)?;
    check_outputs(&outputs, force).map_err(errors::lab)?;
    let pick = pick(generation, elite, front)?;
    let (s, n) = (grid("sensors", sensors)?, grid("neurons", neurons)?);
    let precision = (precision.map(str::parse::<Precision>).transpose())
        .map_err(|e| PyValueError::new_err(format!("precision: {e}")))?;
    let exported =
        vivae_lab::export::choose::exported(&source, pick, s, n, precision).map_err(errors::lab)?;
    let written = write(&exported, format, &out).map_err(errors::lab)?;
    Ok(written.iter().map(|p| p.display().to_string()).collect())
}

/// Records robot `robot` of a run's episode (every robot driven, as in
/// evolution; `precision` as in [`export`]): its sensor readings `[steps,
/// inputs]`, wheel commands `[steps, 2]` and poses `[steps, 3]` (x, y,
/// heading in degrees).
#[pyfunction]
#[pyo3(signature = (source, *, robot=0, steps=None, generation=None, elite=None, front=None, sensors=None, neurons=None, precision=None))]
#[allow(clippy::too_many_arguments)]
pub fn record_episode<'py>(
    py: Python<'py>,
    source: PathBuf,
    #[pyo3(from_py_with = crate::args::robot)] robot: usize,
    #[pyo3(from_py_with = crate::args::opt_steps)] steps: Option<u32>,
    #[pyo3(from_py_with = crate::args::opt_generation)] generation: Option<u32>,
    #[pyo3(from_py_with = crate::args::elite)] elite: Option<usize>,
    #[pyo3(from_py_with = crate::args::front)] front: Option<usize>,
    sensors: Option<&str>,
    neurons: Option<&str>,
    precision: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let c = chosen(
        &source,
        (generation, elite, front),
        (sensors, neurons),
        precision,
    )?;
    let steps = steps.unwrap_or(c.episode.steps());
    let rec = py
        .detach(|| vivae_lab::export::frames::record(&c.episode, &c.controller, robot, steps))
        .map_err(errors::lab)?;
    let n = rec.wheels.len();
    let shaped = |v: Vec<f64>, w: usize| Array2::from_shape_vec((n, w), v).expect("a row a step");
    let wheels: Vec<f64> = rec.wheels.iter().flatten().copied().collect();
    let poses: Vec<f64> = (rec.poses.iter())
        .flat_map(|(p, h)| [p.x, p.y, h.to_degrees()])
        .collect();
    let d = PyDict::new(py);
    d.set_item("sensors", shaped(rec.sensors, rec.inputs).into_pyarray(py))?;
    d.set_item("wheels", shaped(wheels, 2).into_pyarray(py))?;
    d.set_item("poses", shaped(poses, 3).into_pyarray(py))?;
    Ok(d)
}

/// One frame: a PNG file's name or an `[height, width, 3|4]` uint8 array.
fn frame(f: &Bound<'_, PyAny>) -> PyResult<Image> {
    if let Ok(path) = f.extract::<PathBuf>() {
        let bytes = vivae_lab::io::read_regular(&path, 1 << 30).map_err(|e| {
            errors::lab(vivae_lab::io::bad_input(format!(
                "{}: {}",
                path.display(),
                vivae_lab::io::io_reason(&e)
            )))
        })?;
        return Image::from_png(&bytes, &path.display().to_string()).map_err(errors::lab);
    }
    let a: PyReadonlyArray3<u8> = f.extract().map_err(|_| {
        PyValueError::new_err("a frame is a PNG file name or a [height, width, 3|4] uint8 array")
    })?;
    let [h, w, ch] = [a.shape()[0], a.shape()[1], a.shape()[2]];
    if !(ch == 3 || ch == 4) {
        return Err(PyValueError::new_err(format!(
            "a frame has 3 or 4 channels, not {ch}"
        )));
    }
    let view = a.as_array();
    let mut rgba = Vec::with_capacity(w * h * 4);
    for y in 0..h {
        for x in 0..w {
            let alpha = if ch == 4 { view[[y, x, 3]] } else { 255 };
            rgba.extend_from_slice(&[view[[y, x, 0]], view[[y, x, 1]], view[[y, x, 2]], alpha]);
        }
    }
    Ok(Image {
        width: w,
        height: h,
        rgba,
    })
}

/// Drives a run's controller with pictures (as `vivae drive-image`):
/// robot-centred `frames` (file names or uint8 arrays) seen through one
/// camera, or with `poses` (rows x, y, heading in degrees) one top-down
/// `frames[0]` map; returns the wheel commands `(left, right)` of every frame.
#[pyfunction]
#[pyo3(signature = (source, frames, *, poses=None, centre=None, scale=1.0, heading=0.0, radius=None, generation=None, elite=None, front=None, sensors=None, neurons=None, precision=None))]
#[allow(clippy::too_many_arguments)]
pub fn drive_image(
    py: Python<'_>,
    source: PathBuf,
    frames: Vec<Bound<'_, PyAny>>,
    poses: Option<Vec<(f64, f64, f64)>>,
    centre: Option<(f64, f64)>,
    scale: f64,
    heading: f64,
    radius: Option<f64>,
    #[pyo3(from_py_with = crate::args::opt_generation)] generation: Option<u32>,
    #[pyo3(from_py_with = crate::args::elite)] elite: Option<usize>,
    #[pyo3(from_py_with = crate::args::front)] front: Option<usize>,
    sensors: Option<&str>,
    neurons: Option<&str>,
    precision: Option<&str>,
) -> PyResult<Vec<(f64, f64)>> {
    if !Camera::usable(scale, radius) {
        return Err(PyValueError::new_err(
            "scale= and radius= must be positive numbers",
        ));
    }
    let c = chosen(
        &source,
        (generation, elite, front),
        (sensors, neurons),
        precision,
    )?;
    let images: Vec<Image> = frames.iter().map(frame).collect::<PyResult<_>>()?;
    let image_sensors = ImageSensors::new(&c.episode, None).map_err(errors::lab)?;
    let net = Exported::new(&c.episode, &c.controller, "").net;
    let cameras: Vec<(&Image, Camera)> = match &poses {
        Some(poses) => {
            let [map] = &images[..] else {
                return Err(PyValueError::new_err(
                    "poses= takes exactly one frame: the map",
                ));
            };
            (poses.iter())
                .map(|&(x, y, h)| {
                    let mut cam = Camera::on_map(DVec2::new(x, y), h.to_radians(), scale);
                    cam.radius = radius;
                    (map, cam)
                })
                .collect()
        }
        None => (images.iter())
            .map(|im| {
                let (cx, cy) = centre.unwrap_or((im.width as f64 / 2.0, im.height as f64 / 2.0));
                let cam = Camera {
                    centre: [cx, cy],
                    scale,
                    heading: heading.to_radians(),
                    radius,
                };
                (im, cam)
            })
            .collect(),
    };
    let wheels = py
        .detach(|| drive_frames(&net, &image_sensors, cameras))
        .map_err(errors::lab)?;
    Ok(wheels.into_iter().map(|[l, r]| (l, r)).collect())
}
