//! Reading an element's `data-*` attribute values: numbers, pairs, and the
//! error naming a bad one.

use super::ScenarioError;

/// A number attribute, or `default` when absent; `Err(())` when unusable.
pub(super) fn number(v: Option<&str>, default: f64, ok: impl Fn(f64) -> bool) -> Result<f64, ()> {
    match v {
        None => Ok(default),
        Some(t) => match t.trim().parse::<f64>() {
            Ok(x) if x.is_finite() && ok(x) => Ok(x),
            _ => Err(()),
        },
    }
}

/// `"A"` or `"AxB"` (or `"A-B"` for ranges): one or two numbers.
pub(super) fn pair(v: &str, sep: char) -> Option<(f64, f64)> {
    let mut parts = v.trim().splitn(2, sep);
    let a = parts.next()?.trim().parse::<f64>().ok()?;
    let b = match parts.next() {
        Some(t) => t.trim().parse::<f64>().ok()?,
        None => a,
    };
    (a.is_finite() && b.is_finite()).then_some((a, b))
}

/// The error of a bad attribute value.
pub(super) fn bad(source: &str, id: &str, attribute: &str, value: &str) -> ScenarioError {
    ScenarioError::Attribute {
        source_name: source.to_string(),
        id: id.to_string(),
        attribute: attribute.to_string(),
        value: value.to_string(),
    }
}
