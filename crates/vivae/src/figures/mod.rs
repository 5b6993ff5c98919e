//! Figures of a run: convergence, network drawing, trajectories.
//!
//! Every figure is drawn once with plotters into an SVG string (text laid out
//! with the DejaVu Sans font shipped in the repository, registered with
//! plotters' `ab_glyph` support — no system fonts), and the PNG is that SVG
//! rendered by resvg with the same font, so the two files always show the same
//! picture, anti-aliased. Functions return bytes; callers write the files
//! (except [`compare::run`], the `vivae compare` command, which reads run
//! directories and writes its figure and table itself).

/// The MAP-Elites archive heat map.
pub mod archive;
/// The figures of a predator–prey run: the CIAO matrix and both sides' curves.
pub mod compare;
mod controller;
pub mod convergence;
mod fields;
/// NSGA-II's Pareto front over two objectives.
pub mod front;
pub mod network;
mod opacity;

use std::sync::OnceLock;

use plotters::coord::CoordTranslate;
use plotters::prelude::*;
use plotters::style::{FontStyle, RGBColor};

/// DejaVu Sans, the only font figures use (shipped by the simulator).
pub(crate) use vivae_sim::draw::FONT;
/// Font family name figures ask plotters for.
pub(crate) const FAMILY: &str = "sans-serif";
/// PNG pixels per SVG unit (2 = crisp on high-density screens and in print).
pub const PNG_SCALE: f32 = 2.0;

/// A rendered figure.
#[derive(Debug, Clone)]
pub struct Figure {
    /// The figure as an SVG document.
    pub svg: String,
    /// The same figure as PNG bytes.
    pub png: Vec<u8>,
}

/// Errors while rendering a figure.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FigureError {
    /// There is nothing to draw.
    #[error("no data for the figure: {0}")]
    NoData(&'static str),
    /// Input data are inconsistent.
    #[error("invalid figure input: {0}")]
    Invalid(String),
    /// The shipped font could not be registered.
    #[error("the figure font could not be loaded")]
    Font,
    /// plotters failed while drawing.
    #[error("drawing failed: {0}")]
    Draw(String),
    /// The SVG could not be rasterised.
    #[error("rendering the PNG failed: {0}")]
    Png(String),
}

/// Registers the shipped font with plotters (once per process).
pub(crate) fn register_font() -> Result<(), FigureError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        [FontStyle::Normal, FontStyle::Bold]
            .into_iter()
            .all(|style| plotters::style::register_font(FAMILY, style, FONT).is_ok())
    });
    if ok { Ok(()) } else { Err(FigureError::Font) }
}

/// The font of axis descriptions in the plots (convergence, compare).
pub(crate) fn label_font() -> FontDesc<'static> {
    (FAMILY, 18).into_font()
}

/// The font of axis labels and legends in the plots (convergence, compare).
pub(crate) fn axis_font() -> FontDesc<'static> {
    (FAMILY, 15).into_font()
}

/// Draws `chart`'s legend of its labelled series in the lower right corner, on a white box.
pub(crate) fn draw_series_legend<'a, 'b: 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, SVGBackend<'b>, CT>,
) -> Result<(), FigureError> {
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.9))
        .border_style(RGBColor(180, 180, 180))
        .label_font(axis_font())
        .draw()
        .map_err(draw_err)
}

/// Maps any plotters error to a [`FigureError::Draw`].
pub(crate) fn draw_err(e: impl std::fmt::Display) -> FigureError {
    FigureError::Draw(e.to_string())
}

/// Renders an SVG document (as produced by the figures) to PNG bytes at [`PNG_SCALE`].
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, FigureError> {
    vivae_sim::draw::svg_to_png(&opacity::on_paint(svg), f64::from(PNG_SCALE))
        .map_err(|e| FigureError::Png(e.to_string()))
}

/// A font database holding only the shipped [`FONT`], built once.
fn fontdb() -> std::sync::Arc<usvg::fontdb::Database> {
    static DB: OnceLock<std::sync::Arc<usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(FONT.to_vec());
        db.set_sans_serif_family("DejaVu Sans");
        std::sync::Arc::new(db)
    })
    .clone()
}

/// A white canvas for a figure of `w` × `h` SVG units drawn at
/// [`PNG_SCALE`]; one past the simulator's pixel cap (or empty) is refused, not allocated.
pub(crate) fn white_canvas(w: f64, h: f64) -> Result<tiny_skia::Pixmap, FigureError> {
    let scale = f64::from(PNG_SCALE);
    let (pw, ph) = ((w * scale).ceil(), (h * scale).ceil());
    let too_large = || FigureError::Invalid(format!("a figure of {w}x{h} units is too large"));
    if pw * ph > vivae_sim::draw::MAX_PIXELS {
        return Err(too_large());
    }
    let mut base = tiny_skia::Pixmap::new(pw as u32, ph as u32).ok_or_else(too_large)?;
    base.fill(tiny_skia::Color::WHITE);
    Ok(base)
}

/// Draws an SVG document over `base` at `scale` pixels per SVG unit (as
/// [`svg_to_png`] draws it over white).
pub(crate) fn draw_svg_over(
    svg: &str,
    base: &mut tiny_skia::Pixmap,
    scale: f32,
) -> Result<(), FigureError> {
    let opt = usvg::Options {
        fontdb: fontdb(),
        font_family: "DejaVu Sans".to_string(),
        ..Default::default()
    };
    let tree = usvg::Tree::from_str(&opacity::on_paint(svg), &opt)
        .map_err(|e| FigureError::Png(e.to_string()))?;
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut base.as_mut(),
    );
    Ok(())
}

/// Encodes `pixmap` as PNG with fast compression.
pub(crate) fn encode_png_fast(pixmap: &tiny_skia::Pixmap) -> Result<Vec<u8>, FigureError> {
    vivae_sim::draw::encode_png(pixmap).map_err(|e| FigureError::Png(e.to_string()))
}

/// Standard base64 (RFC 4648, with padding), for images embedded in SVG.
pub(crate) fn base64(bytes: &[u8]) -> String {
    const ABC: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = u32::from(b[0]) << 16 | u32::from(b[1]) << 8 | u32::from(b[2]);
        for (i, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if i <= chunk.len() {
                out.push(char::from(ABC[(n >> shift & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Colour for positive weights (blue).
pub(crate) const POSITIVE: RGBColor = RGBColor(33, 102, 172);
/// Colour for negative weights (orange).
pub(crate) const NEGATIVE: RGBColor = RGBColor(230, 97, 1);

/// The viridis colour map at `t ∈ [0, 1]` (perceptually uniform, colour-blind safe).
pub(crate) fn viridis(t: f64) -> RGBColor {
    // Eleven evenly spaced samples of matplotlib's viridis.
    const STOPS: [(f64, f64, f64); 11] = [
        (68.0, 1.0, 84.0),
        (72.0, 36.0, 117.0),
        (65.0, 68.0, 135.0),
        (53.0, 95.0, 141.0),
        (42.0, 120.0, 142.0),
        (33.0, 145.0, 140.0),
        (34.0, 168.0, 132.0),
        (68.0, 191.0, 112.0),
        (122.0, 209.0, 81.0),
        (189.0, 223.0, 38.0),
        (253.0, 231.0, 37.0),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (STOPS.len() - 1) as f64;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let mix = |p: f64, q: f64| (p + (q - p) * f).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

#[cfg(test)]
pub(crate) mod test_util {
    /// Width and height from a PNG's IHDR chunk, after checking the signature.
    pub fn png_size(png: &[u8]) -> (u32, u32) {
        assert!(png.len() > 33, "PNG too short");
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
        assert_eq!(&png[12..16], b"IHDR");
        let w = u32::from_be_bytes(png[16..20].try_into().unwrap());
        let h = u32::from_be_bytes(png[20..24].try_into().unwrap());
        (w, h)
    }

    /// Decodes a PNG and returns the number of distinct colours (a "not blank" check).
    pub fn distinct_colours(png: &[u8]) -> usize {
        let pixmap = tiny_skia::Pixmap::decode_png(png).expect("valid PNG");
        let mut colours: Vec<u32> = pixmap
            .pixels()
            .iter()
            .map(|p| u32::from_be_bytes([p.red(), p.green(), p.blue(), p.alpha()]))
            .collect();
        colours.sort_unstable();
        colours.dedup();
        colours.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn white_canvas_is_scaled_and_refused_past_the_pixel_cap() {
        let c = white_canvas(10.5, 3.0).unwrap();
        assert_eq!((c.width(), c.height()), (21, 6));
        assert!(
            c.pixels()
                .iter()
                .all(|p| p.red() == 255 && p.alpha() == 255)
        );
        // 10⁵ × 10⁵ units would be 4·10¹⁰ pixels (160 GB): an error, not an allocation.
        let e = white_canvas(1e5, 1e5).unwrap_err();
        assert!(e.to_string().contains("too large"), "{e}");
        assert!(white_canvas(0.0, 5.0).is_err());
    }

    #[test]
    fn viridis_ends_and_middle() {
        assert_eq!(viridis(0.0), RGBColor(68, 1, 84));
        assert_eq!(viridis(1.0), RGBColor(253, 231, 37));
        assert_eq!(viridis(0.5), RGBColor(33, 145, 140));
        assert_eq!(viridis(f64::NAN), viridis(0.0));
        assert_eq!(viridis(7.0), viridis(1.0));
    }

    #[test]
    fn fast_png_decodes_to_the_same_pixels() {
        let mut pixmap = tiny_skia::Pixmap::new(7, 3).unwrap();
        pixmap.fill(tiny_skia::Color::from_rgba8(10, 200, 30, 255));
        pixmap.pixels_mut()[4] = tiny_skia::PremultipliedColorU8::TRANSPARENT;
        let back = tiny_skia::Pixmap::decode_png(&encode_png_fast(&pixmap).unwrap()).unwrap();
        assert_eq!(back.data(), pixmap.data());
        // Half-transparent pixels are written with straight alpha.
        pixmap.pixels_mut()[5] =
            tiny_skia::PremultipliedColorU8::from_rgba(50, 60, 70, 128).unwrap();
        let back = tiny_skia::Pixmap::decode_png(&encode_png_fast(&pixmap).unwrap()).unwrap();
        assert_eq!(back.pixels()[5].alpha(), 128);
        assert!(back.pixels()[5].red().abs_diff(50) <= 1);
        assert_eq!(back.pixels()[6], pixmap.pixels()[6]);
    }

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded);
        }
        assert_eq!(base64(&[0xff, 0xfe, 0xfd]), "//79");
    }

    #[test]
    fn svg_text_renders_with_the_shipped_font() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="60" height="20">
            <text x="2" y="15" font-family="sans-serif" font-size="14">Ag</text></svg>"#;
        let png = svg_to_png(svg).unwrap();
        assert_eq!(test_util::png_size(&png), (120, 40));
        // White background plus anti-aliased glyph pixels.
        assert!(test_util::distinct_colours(&png) > 5);
        assert!(svg_to_png("<svg").is_err());
    }
}
