//! Arguments checked by name. pyo3's own conversions name nothing for a
//! value out of range (`OverflowError: can't convert negative int to
//! unsigned`) and say only "must be real number, not str" for a bad item of
//! a list, so sizes, counts, seeds, indices and lists of numbers are
//! converted here (`#[pyo3(from_py_with = args::seed)]` and the like), each
//! error naming the argument and what it expected: a `TypeError` for a value
//! of the wrong type, a `ValueError` with the range for one out of range.

use std::path::PathBuf;

use pyo3::exceptions::{PyOverflowError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyString};

/// Most worker threads an argument may ask for (as `run.threads` in a config).
pub const MAX_THREADS: u128 = 1024;

/// Most worlds one `DriveCore` steps (a bound on what a typo can allocate).
pub const MAX_WORLDS: usize = 1 << 16;

/// Most robots a controller may drive at once (as many as the worlds a
/// `DriveCore` may hold).
pub const MAX_ROBOTS: u128 = MAX_WORLDS as u128;

/// The integer argument `key=v` within `lo..=hi`: a `TypeError` naming `key`
/// for anything but an integer (Python's or numpy's; a bool is refused), a
/// `ValueError` naming `key` and the range for one outside it.
pub fn int_in<T: TryFrom<u128>>(
    key: &str,
    v: &Bound<'_, PyAny>,
    lo: u128,
    hi: u128,
) -> PyResult<T> {
    let out_of_range =
        || PyValueError::new_err(format!("{key}={v}: expected an integer from {lo} to {hi}"));
    if v.is_instance_of::<PyBool>() {
        return Err(wrong_type(key, "an integer", v));
    }
    let n: i128 = match v.extract() {
        Ok(n) => n,
        // An integer beyond 128 bits is out of range; anything else is no integer.
        Err(e) if e.is_instance_of::<PyOverflowError>(v.py()) => return Err(out_of_range()),
        Err(_) => return Err(wrong_type(key, "an integer", v)),
    };
    u128::try_from(n)
        .ok()
        .filter(|n| (lo..=hi).contains(n))
        .and_then(|n| T::try_from(n).ok())
        .ok_or_else(out_of_range)
}

/// A `TypeError`: `key` expected `what`, and got `v`'s type.
fn wrong_type(key: &str, what: &str, v: &Bound<'_, PyAny>) -> PyErr {
    let ty = v
        .get_type()
        .name()
        .map_or_else(|_| "?".to_string(), |n| n.to_string());
    PyTypeError::new_err(format!("{key}: expected {what}, got {ty}"))
}

/// The integer argument `key=v` in the whole range of `T`.
pub fn int<T: TryFrom<u128> + Bounded>(key: &str, v: &Bound<'_, PyAny>) -> PyResult<T> {
    let (lo, hi) = T::RANGE;
    int_in(key, v, lo, hi)
}

/// The range of an integer argument's type, for messages.
pub trait Bounded {
    /// The smallest and largest value.
    const RANGE: (u128, u128);
}

macro_rules! bounded {
    ($($t:ty),*) => {$(impl Bounded for $t {
        const RANGE: (u128, u128) = (<$t>::MIN as u128, <$t>::MAX as u128);
    })*};
}
bounded!(u32, u64, usize);

/// The text argument `key=v`: a `str`, else a `TypeError` naming `key`.
pub fn text(key: &str, v: &Bound<'_, PyAny>) -> PyResult<String> {
    if !v.is_instance_of::<PyString>() {
        return Err(wrong_type(key, "a string", v));
    }
    v.extract()
}

/// The bool argument `key=v` (Python's or numpy's), else a `TypeError` naming `key`.
pub fn boolean(key: &str, v: &Bound<'_, PyAny>) -> PyResult<bool> {
    v.extract().map_err(|_| wrong_type(key, "a bool", v))
}

/// `None` for Python's `None`, else `convert(key, v)`.
fn opt<T>(
    key: &str,
    v: &Bound<'_, PyAny>,
    convert: impl Fn(&str, &Bound<'_, PyAny>) -> PyResult<T>,
) -> PyResult<Option<T>> {
    if v.is_none() {
        Ok(None)
    } else {
        convert(key, v).map(Some)
    }
}

/// The items of the sequence argument `key` (a list, tuple or array; not a
/// string), each converted by `item(name, value)` with `name` = `key[i]`.
pub fn items<T>(
    key: &str,
    what: &str,
    v: &Bound<'_, PyAny>,
    item: impl Fn(&str, &Bound<'_, PyAny>) -> PyResult<T>,
) -> PyResult<Vec<T>> {
    let expected = format!("a list of {what}");
    if v.is_instance_of::<PyString>() {
        return Err(wrong_type(key, &expected, v));
    }
    let iter = v.try_iter().map_err(|_| wrong_type(key, &expected, v))?;
    let mut out = Vec::new();
    for (i, x) in iter.enumerate() {
        out.push(item(&format!("{key}[{i}]"), &x?)?);
    }
    Ok(out)
}

/// A real number `key=v`: an int or a float of any width (numpy's too); a
/// bool, a string or anything else is a `TypeError` naming `key`.
pub fn real(key: &str, v: &Bound<'_, PyAny>) -> PyResult<f64> {
    if v.is_instance_of::<PyBool>() || v.is_instance_of::<PyString>() {
        return Err(wrong_type(key, "a real number", v));
    }
    v.extract::<f64>()
        .map_err(|_| wrong_type(key, "a real number", v))
}

/// A list of real numbers `key=v`.
pub fn reals(key: &str, v: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    items(key, "real numbers", v, real)
}

/// One list of real numbers per genome (`key=v`).
pub fn rows(key: &str, v: &Bound<'_, PyAny>) -> PyResult<Vec<Vec<f64>>> {
    items(key, "lists of real numbers", v, reals)
}

/// Converters for `#[pyo3(from_py_with = ...)]`, one per argument name and type.
macro_rules! named {
    ($($f:ident: $t:ty = $key:literal, $conv:expr;)*) => {$(
        #[doc = concat!("The argument `", $key, "` (`", stringify!($t), "`), checked by name.")]
        pub fn $f(v: &Bound<'_, PyAny>) -> PyResult<$t> {
            $conv($key, v)
        }
    )*};
}

named! {
    inputs: usize = "inputs", int;
    outputs: usize = "outputs", int;
    seed: u64 = "seed", int;
    opt_seed: Option<u64> = "seed", |k, v| opt(k, v, int);
    size: Option<usize> = "size", |k, v| opt(k, v, int);
    size_given: usize = "size", int;
    runs: Option<usize> = "runs", |k, v| opt(k, v, int);
    evaluations: Option<u64> = "evaluations", |k, v| opt(k, v, int);
    generation: u32 = "generation", int;
    generations: Option<u32> = "generations", |k, v| opt(k, v, int);
    opt_generation: Option<u32> = "generation", |k, v| opt(k, v, int);
    elite: Option<usize> = "elite", |k, v| opt(k, v, int);
    front: Option<usize> = "front", |k, v| opt(k, v, int);
    robot: usize = "robot", int;
    opt_steps: Option<u32> = "steps", |k, v| opt(k, v, int);
    threads: usize = "threads", |k, v| int_in(k, v, 0, MAX_THREADS);
    opt_threads: Option<usize> = "threads", |k, v| opt(k, v, |k, v| int_in(k, v, 0, MAX_THREADS));
    num_worlds: usize = "num_worlds", int;
    robots: usize = "robots", |k, v| int_in(k, v, 1, MAX_ROBOTS);
    index: usize = "index", int;
    steps: u32 = "steps", int;
    cvt_cells: Option<usize> = "cvt_cells", |k, v| opt(k, v, int);
    cvt_samples: usize = "cvt_samples", int;
    cvt_iterations: usize = "cvt_iterations", int;
    bins: Option<Vec<usize>> = "bins", |k, v| opt(k, v, |k, v| items(k, "integers", v, int));
    lower: Vec<f64> = "lower", reals;
    upper: Vec<f64> = "upper", reals;
    behaviour: Vec<f64> = "behaviour", reals;
    fitnesses: Vec<f64> = "fitnesses", reals;
    behaviours: Option<Vec<Vec<f64>>> = "behaviours", |k, v| opt(k, v, rows);
    metrics: Option<Vec<Vec<f64>>> = "metrics", |k, v| opt(k, v, rows);
}

/// The run directory `out=` names (the default run directory when not
/// given): a `ValueError` for an empty name, which names no folder.
pub fn run_dir(out: Option<PathBuf>) -> PyResult<PathBuf> {
    match out {
        Some(p) if p.as_os_str().is_empty() => Err(PyValueError::new_err(
            "out=\"\": the run directory's name is empty (name a folder, or leave out for the default)",
        )),
        Some(p) => Ok(p),
        None => Ok(vivae_lab::io::default_run_dir()),
    }
}
