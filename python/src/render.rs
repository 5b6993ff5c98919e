//! A simulator world drawn for Python: an RGB image as a numpy array (what
//! every environment's `render()` returns).

use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray3};
use pyo3::prelude::*;
use vivae_sim::World;

use crate::errors;

/// `world` drawn with `opts` as an RGB image (height × width × 3, uint8),
/// the GIL released while it is drawn.
pub fn render_rgb<'py>(
    py: Python<'py>,
    world: &World,
    opts: &vivae_sim::DrawOptions,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let image = py.detach(|| -> Result<Array3<u8>, String> {
        let png = vivae_sim::render_png(world, opts).map_err(|e| e.to_string())?;
        let pixmap = tiny_skia::Pixmap::decode_png(&png).map_err(|e| e.to_string())?;
        let (w, h) = (pixmap.width() as usize, pixmap.height() as usize);
        // Drawn on white, so every pixel is opaque: premultiplied RGBA is plain RGBA.
        let rgb: Vec<u8> = pixmap
            .data()
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        Array3::from_shape_vec((h, w, 3), rgb).map_err(|e| e.to_string())
    });
    Ok(image
        .map_err(|e| errors::value(format!("rendering the world: {e}")))?
        .into_pyarray(py))
}
