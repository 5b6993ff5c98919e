//! Unique element ids for the join of roxmltree and usvg.
//!
//! The loader reads labels from the raw document and geometry from usvg, and
//! joins the two by `id`. Hand-written SVG often has elements without an id,
//! or the same id twice; without care those elements were dropped ("no usable
//! geometry") or given another element's geometry. Before usvg sees the
//! document, every element that lacks an id gets a fresh one and every repeated
//! id after its first use is renamed, so each element finds its own geometry.
//! Error messages and object names use the name the user wrote (see
//! [`UniqueIds::display`]).

use std::collections::{BTreeMap, BTreeSet};

use super::ScenarioError;

/// A document rewritten so that every element has its own id.
pub(super) struct UniqueIds {
    /// The rewritten SVG text.
    pub text: String,
    /// Name to show for each invented id.
    pub display: BTreeMap<String, String>,
    /// The invented ids that replace a repeated one (not a missing one).
    pub repeated: BTreeSet<String>,
}

/// Whether an element is one of the SVG shapes the loader reads.
pub(super) fn is_shape(name: &str) -> bool {
    matches!(
        name,
        "rect" | "circle" | "ellipse" | "line" | "polyline" | "polygon" | "path"
    )
}

/// Whether the loader looks an element up by id: shapes and containers.
fn joined(name: &str) -> bool {
    is_shape(name) || matches!(name, "g" | "a" | "switch")
}

/// Returns `None` when every element already has a unique id (the usual
/// Inkscape file: nothing is rewritten), else the rewritten text.
pub(super) fn unique_ids(
    doc: &roxmltree::Document,
    text: &str,
    source: &str,
) -> Result<Option<UniqueIds>, ScenarioError> {
    let root = doc.root_element();
    let elements: Vec<roxmltree::Node> = root
        .descendants()
        .filter(|n| n.is_element() && *n != root && joined(n.tag_name().name()))
        .collect();
    let taken: BTreeSet<&str> = elements.iter().filter_map(|n| n.attribute("id")).collect();
    let mut seen = BTreeSet::new();
    // (byte range to replace, replacement), in document order.
    let mut edits: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    let mut display = BTreeMap::new();
    let mut repeated = BTreeSet::new();
    let mut counter = 0usize;
    let mut fresh = || loop {
        counter += 1;
        let id = format!("vivae-element-{counter}");
        if !taken.contains(id.as_str()) {
            return id;
        }
    };
    for n in elements {
        let line = doc.text_pos_at(n.range().start).row;
        let tag = n.tag_name().name();
        match n
            .attributes()
            .find(|a| a.name() == "id" && a.namespace().is_none())
        {
            Some(a) if seen.insert(a.value()) => {}
            Some(a) => {
                let range = repeated_id_range(text, &a, line, source)?;
                let id = fresh();
                display.insert(
                    id.clone(),
                    format!("{} (<{tag}> on line {line})", a.value()),
                );
                repeated.insert(id.clone());
                edits.push((range, id));
            }
            None => {
                let at = id_insertion_point(text, n.range().start, tag, line, source)?;
                let id = fresh();
                display.insert(id.clone(), format!("<{tag}> on line {line}"));
                edits.push((at..at, format!(" id=\"{id}\"")));
            }
        }
    }
    if edits.is_empty() {
        return Ok(None);
    }
    Ok(Some(UniqueIds {
        text: apply_edits(text, edits),
        display,
        repeated,
    }))
}

/// The byte range of a repeated id's value, to rename it. roxmltree's value
/// range is exact unless more than 255 spaces surround the `=`: then the
/// quotes are not where it says, and the duplicate is refused rather than
/// guessed at.
fn repeated_id_range(
    text: &str,
    a: &roxmltree::Attribute,
    line: u32,
    source: &str,
) -> Result<std::ops::Range<usize>, ScenarioError> {
    let range = a.range_value();
    let quoted = |i: usize| matches!(text.as_bytes().get(i), Some(b'"' | b'\''));
    if range.start == 0
        || !quoted(range.start - 1)
        || !quoted(range.end)
        || text.get(range.clone()).is_none()
    {
        return Err(ScenarioError::Xml {
            source_name: source.to_string(),
            message: format!(
                "id '{}' is used twice (again on line {line}) and cannot be renamed: too many spaces around its '='",
                a.value()
            ),
        });
    }
    Ok(range)
}

/// Where to insert an id into the element whose `<` is at byte `start`:
/// after the tag's qualified name (`<svg:path` → `<svg:path id="…"`).
fn id_insertion_point(
    text: &str,
    start: usize,
    tag: &str,
    line: u32,
    source: &str,
) -> Result<usize, ScenarioError> {
    let name_len = text
        .get(start + 1..)
        .and_then(|rest| rest.find(|c: char| c.is_whitespace() || c == '/' || c == '>'))
        .ok_or_else(|| ScenarioError::Xml {
            source_name: source.to_string(),
            message: format!("cannot find the end of <{tag}> on line {line}"),
        })?;
    Ok(start + 1 + name_len)
}

/// `text` with each `(byte range, replacement)` edit applied.
fn apply_edits(text: &str, mut edits: Vec<(std::ops::Range<usize>, String)>) -> String {
    edits.sort_by_key(|(r, _)| r.start);
    let mut out = String::with_capacity(text.len() + edits.len() * 28);
    let mut at = 0;
    for (range, with) in edits {
        out.push_str(&text[at..range.start]);
        out.push_str(&with);
        at = range.end;
    }
    out.push_str(&text[at..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rewrite(svg: &str) -> Option<UniqueIds> {
        let doc = roxmltree::Document::parse(svg).unwrap();
        unique_ids(&doc, svg, "t.svg").unwrap()
    }

    #[test]
    fn unique_ids_are_left_alone() {
        assert!(rewrite(r#"<svg><g id="a"><path id="b" d="M0 0"/></g></svg>"#).is_none());
    }

    #[test]
    fn missing_and_repeated_ids_become_unique() {
        let svg = "<svg>\n<path d=\"M0 0\"/>\n<rect id=\"r\"/>\n<svg:rect xmlns:svg=\"x\" id='r' />\n</svg>";
        let u = rewrite(svg).unwrap();
        let doc = roxmltree::Document::parse(&u.text).unwrap();
        let ids: Vec<&str> = doc
            .descendants()
            .filter(|n| n.is_element() && n.tag_name().name() != "svg")
            .map(|n| n.attribute("id").unwrap())
            .collect();
        assert_eq!(ids, ["vivae-element-1", "r", "vivae-element-2"]);
        assert_eq!(u.display["vivae-element-1"], "<path> on line 2");
        assert_eq!(u.display["vivae-element-2"], "r (<rect> on line 4)");
    }

    #[test]
    fn a_repeated_id_written_with_a_character_reference_is_renamed() {
        let u = rewrite(r#"<svg><path id="a"/><path id="&#97;"/></svg>"#).unwrap();
        assert!(
            u.text.contains(r#"<path id="vivae-element-1"/>"#),
            "{}",
            u.text
        );
    }

    #[test]
    fn a_repeated_id_whose_position_is_unknown_is_refused() {
        let svg = format!(
            r#"<svg><path id="a"/><path id{}="a"/></svg>"#,
            " ".repeat(300)
        );
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let e = unique_ids(&doc, &svg, "t.svg").err().expect("refused");
        assert!(e.to_string().contains("used twice"), "{e}");
    }

    #[test]
    fn invented_ids_avoid_ids_in_use() {
        let u = rewrite(r#"<svg><path id="vivae-element-1"/><path/></svg>"#).unwrap();
        assert!(
            u.text.contains(r#"<path id="vivae-element-2"/>"#),
            "{}",
            u.text
        );
    }
}
