//! Element opacity moved onto the element's one paint, before rasterising.
//!
//! plotters writes a translucent colour as `opacity="a"` on the shape. resvg
//! draws every element with `opacity` below 1 into a layer of its own and
//! composites the layer: in the network figure, whose ~200 links are each
//! translucent, that was most of the figure's time. A shape painted only by
//! its stroke (`fill="none"`) or only by its fill (`stroke="none"`, or no
//! stroke) looks the same with the opacity on that paint instead
//! (`stroke-opacity`, `fill-opacity`), and is then drawn straight onto the
//! canvas. Shapes with both paints, and everything else, are left alone.

use std::borrow::Cow;

/// The shape elements whose opacity may move onto their paint.
const SHAPES: [&str; 6] = [
    "<polyline ",
    "<polygon ",
    "<path ",
    "<circle ",
    "<rect ",
    "<line ",
];

/// `svg` with each single-paint shape's `opacity="a"` (a < 1) written as
/// `stroke-opacity="a"` or `fill-opacity="a"`: the same picture, drawn without layers.
pub(crate) fn on_paint(svg: &str) -> Cow<'_, str> {
    if !svg.contains(" opacity=\"") {
        return Cow::Borrowed(svg);
    }
    let mut out = String::with_capacity(svg.len());
    let mut rest = svg;
    while let Some(start) = rest.find('<') {
        out.push_str(&rest[..start]);
        rest = &rest[start..];
        let end = tag_end(rest);
        let tag = &rest[..end];
        match SHAPES
            .iter()
            .any(|s| tag.starts_with(s))
            .then(|| moved(tag))
        {
            Some(Some(tag)) => out.push_str(&tag),
            _ => out.push_str(tag),
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    Cow::Owned(out)
}

/// The length of the markup `s` starts with, up to its `>` outside quotes
/// (an attribute value may hold a `>`), or all of `s`.
fn tag_end(s: &str) -> usize {
    let mut quote = None;
    for (i, b) in s.bytes().enumerate() {
        match (quote, b) {
            (None, b'"' | b'\'') => quote = Some(b),
            (Some(q), _) if b == q => quote = None,
            (None, b'>') => return i + 1,
            _ => {}
        }
    }
    s.len()
}

/// The start tag `tag` with its opacity on its one paint, if it qualifies.
fn moved(tag: &str) -> Option<String> {
    let opacity = attribute(tag, "opacity")?;
    if opacity.parse::<f64>().ok()? >= 1.0
        || attribute(tag, "fill-opacity").is_some()
        || attribute(tag, "stroke-opacity").is_some()
    {
        return None;
    }
    let fill = attribute(tag, "fill");
    let stroke = attribute(tag, "stroke").filter(|s| *s != "none");
    let paint = match (fill, stroke) {
        // An absent fill is black: a stroked shape without one has two paints.
        (Some("none"), Some(_)) => "stroke-opacity",
        (Some(f), None) if f != "none" => "fill-opacity",
        (None, None) => "fill-opacity",
        _ => return None,
    };
    let from = format!(" opacity=\"{opacity}\"");
    Some(tag.replacen(&from, &format!(" {paint}=\"{opacity}\""), 1))
}

/// The value of attribute `name` in the start tag `tag`.
fn attribute<'t>(tag: &'t str, name: &str) -> Option<&'t str> {
    let key = format!(" {name}=\"");
    let from = tag.find(&key)? + key.len();
    let len = tag[from..].find('"')?;
    Some(&tag[from..from + len])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_translucent_stroke_only_shape_gets_stroke_opacity() {
        let svg = r##"<svg><polyline fill="none" opacity="0.5" stroke="#1F77B4" points="0,0 1,1"/></svg>"##;
        assert_eq!(
            on_paint(svg),
            r##"<svg><polyline fill="none" stroke-opacity="0.5" stroke="#1F77B4" points="0,0 1,1"/></svg>"##
        );
    }

    #[test]
    fn a_translucent_fill_only_shape_gets_fill_opacity() {
        let svg = r##"<circle cx="1" cy="1" r="2" opacity="0.25" fill="#FF0000" stroke="none"/>"##;
        assert_eq!(
            on_paint(svg),
            r##"<circle cx="1" cy="1" r="2" fill-opacity="0.25" fill="#FF0000" stroke="none"/>"##
        );
        let no_stroke = r##"<polygon opacity="0.25" fill="#00FF00" points="0,0 1,0 1,1"/>"##;
        assert!(on_paint(no_stroke).contains(r#" fill-opacity="0.25""#));
    }

    #[test]
    fn a_greater_than_sign_in_an_attribute_does_not_end_the_tag() {
        let svg = r##"<svg><polyline data-note="a>b" fill="none" opacity="0.5" stroke="#000000" points="0,0 1,1"/><text>x > y</text></svg>"##;
        assert_eq!(
            on_paint(svg),
            r##"<svg><polyline data-note="a>b" fill="none" stroke-opacity="0.5" stroke="#000000" points="0,0 1,1"/><text>x > y</text></svg>"##
        );
        // Its fill and stroke after the `>` are read: two paints, left alone.
        let two = r##"<rect data-note="a>b" opacity="0.5" fill="#FFFFFF" stroke="#000000"/>"##;
        assert_eq!(on_paint(two), two);
    }

    #[test]
    fn shapes_with_two_paints_opaque_shapes_and_text_are_left_alone() {
        for svg in [
            r##"<rect x="0" y="0" width="1" height="1" opacity="0.5" fill="#FFFFFF" stroke="#000000"/>"##,
            r##"<polyline opacity="0.5" stroke="#000000" points="0,0 1,1"/>"##,
            r##"<rect x="0" y="0" width="1" height="1" opacity="1" fill="#FFFFFF" stroke="none"/>"##,
            r##"<text x="0" y="0" opacity="0.5" fill="#000000">a</text>"##,
            r##"<polyline fill="none" opacity="0.5" stroke-opacity="0.5" stroke="#000000" points="0,0"/>"##,
        ] {
            assert_eq!(on_paint(svg), svg);
        }
    }

    #[test]
    fn the_network_figure_renders_the_same_with_its_opacity_on_the_paint() {
        // Translucent links crossing one another over a filled shape: the
        // layered and the unlayered drawings differ at most by rounding (a
        // layer rounds each 8-bit channel once more, and links overlap).
        let mut svg = String::from(
            r##"<svg width="60" height="40" viewBox="0 0 60 40" xmlns="http://www.w3.org/2000/svg"><rect x="0" y="0" width="60" height="40" opacity="1" fill="#FFFFFF" stroke="none"/><polygon opacity="0.6" fill="#F6F6F6" points="5,35 55,35 30,5"/>"##,
        );
        for k in 0..12 {
            svg += &format!(
                r##"<polyline fill="none" opacity="0.{}" stroke="#D62728" stroke-width="{}" points="{},4 {},36 56,{}"/>"##,
                k % 9 + 1,
                1 + k % 3,
                4 + 4 * k,
                56 - 4 * k,
                4 + 2 * k
            );
        }
        svg += "</svg>";
        let moved = on_paint(&svg);
        assert_ne!(moved, svg);
        let decode = |svg: &str| {
            let png = vivae_sim::draw::svg_to_png(svg, 2.0).unwrap();
            tiny_skia::Pixmap::decode_png(&png).unwrap()
        };
        let (a, b) = (decode(&svg), decode(&moved));
        let worst = (a.data().iter().zip(b.data()))
            .map(|(x, y)| x.abs_diff(*y))
            .max()
            .unwrap();
        assert!(worst <= 4, "a channel differs by {worst}");
    }
}
