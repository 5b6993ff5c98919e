//! The limits a scenario file is checked against before and while it is
//! loaded: document size, attribute counts, path numbers, arena size, robots
//! inside the arena. A hostile file is refused in one line, never loaded
//! into unbounded time or memory.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::{Scenario, ScenarioError};

/// Options for [`Scenario::from_svg`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LoadOptions {
    /// Side of one surface-raster cell in px (default 1).
    pub cell_size: f64,
    /// Largest accepted arena width or height in px (default 20 000).
    pub max_arena_size: f64,
    /// Largest accepted arena area in px² (default 10⁸: a 100 MB surface
    /// raster at 1 px cells, the memory a run needs for it).
    pub max_arena_area: f64,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            cell_size: 1.0,
            max_arena_size: 20_000.0,
            max_arena_area: 1e8,
        }
    }
}

/// Refuses load options that are not finite and positive.
pub(super) fn check_options(opts: &LoadOptions) -> Result<(), ScenarioError> {
    if !(opts.cell_size.is_finite() && opts.cell_size > 0.0) {
        return Err(ScenarioError::Options {
            field: "cell_size",
            value: opts.cell_size,
        });
    }
    if !(opts.max_arena_area.is_finite() && opts.max_arena_area > 0.0) {
        return Err(ScenarioError::Options {
            field: "max_arena_area",
            value: opts.max_arena_area,
        });
    }
    if !(opts.max_arena_size.is_finite() && opts.max_arena_size > 0.0) {
        return Err(ScenarioError::Options {
            field: "max_arena_size",
            value: opts.max_arena_size,
        });
    }
    Ok(())
}

/// Largest magnitude of a number in path data: beyond it usvg's arc
/// conversion can run for minutes (an endpoint of 3.4e38 never finishes).
pub(super) const MAX_PATH_NUMBER: f64 = 1e9;

/// How far (in arena sizes) geometry may reach outside the arena: further out
/// it cannot matter, and flattening it could take unbounded time and memory.
pub(super) const MAX_OUTSIDE_ARENAS: f64 = 4.0;

/// Most XML nodes a scenario may have (the shipped ones have a few thousand).
pub(super) const MAX_XML_NODES: u32 = 200_000;

/// Most attributes one element may have (roxmltree's duplicate check is quadratic).
pub(super) const MAX_ATTRIBUTES: usize = 1_000;

/// Refuses what would make parsing slow or huge before roxmltree sees it:
/// entity declarations (a small file can expand to gigabytes) and elements
/// with too many attributes.
pub(super) fn prescan(text: &str, source: &str) -> Result<(), ScenarioError> {
    let refuse = |message: String| ScenarioError::Svg {
        source_name: source.to_string(),
        message,
    };
    if text.contains("<!ENTITY") {
        return Err(refuse(
            "entity declarations (<!ENTITY>) are not supported".into(),
        ));
    }
    // Counts `=` outside quoted values within each tag: an upper bound on attributes.
    let (mut in_tag, mut quote, mut count) = (false, 0u8, 0usize);
    for &b in text.as_bytes() {
        if quote != 0 {
            if b == quote {
                quote = 0;
            }
            continue;
        }
        match b {
            b'<' => {
                in_tag = true;
                count = 0;
            }
            b'>' => in_tag = false,
            b'"' | b'\'' if in_tag => quote = b,
            b'=' if in_tag => {
                count += 1;
                if count > MAX_ATTRIBUTES {
                    return Err(refuse(format!(
                        "an element has more than {MAX_ATTRIBUTES} attributes"
                    )));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Reads the root's `width`, `height` and `viewBox` as written, refusing
/// values usvg would silently replace (`inf`, `100%`, an empty `viewBox`) or
/// overflow (`1e308` does not fit an f32).
pub(super) fn check_root_size(
    root: roxmltree::Node,
    source: &str,
    max: f64,
) -> Result<(), ScenarioError> {
    let bad = |attribute: &'static str, value: &str, problem: &str| ScenarioError::RootSize {
        source_name: source.to_string(),
        attribute,
        value: value.to_string(),
        problem: problem.to_string(),
    };
    let mut size = [0.0; 2];
    for (i, attribute) in ["width", "height"].into_iter().enumerate() {
        let Some(v) = root.attribute(attribute) else {
            continue;
        };
        let length: svgtypes::Length = v
            .trim()
            .parse()
            .map_err(|_| bad(attribute, v, "not a length"))?;
        if length.unit == svgtypes::LengthUnit::Percent {
            return Err(bad(attribute, v, "percentages are not supported, give px"));
        }
        if !length.number.is_finite() {
            return Err(bad(attribute, v, "not a finite number"));
        }
        size[i] = length.number;
    }
    // Units (mm, in, pt) scale by at most 96/2.54·10 px: a generous bound
    // before the f32 overflow that usvg would report as "0 x 0".
    for (i, attribute) in ["width", "height"].into_iter().enumerate() {
        let problem = if root.attribute(attribute).is_some() && size[i] <= 0.0 {
            "width and height must be positive".to_string()
        } else if size[i] > max * 100.0 {
            format!("larger than the limit of {max} px")
        } else {
            continue;
        };
        return Err(ScenarioError::ArenaSize {
            source_name: source.to_string(),
            width: size[0],
            height: size[1],
            problem,
        });
    }
    if let Some(v) = root.attribute("viewBox") {
        let nums: Vec<f64> = svgtypes::NumberListParser::from(v)
            .collect::<Result<_, _>>()
            .map_err(|_| bad("viewBox", v, "not four numbers"))?;
        match nums[..] {
            [x, y, w, h] if [x, y, w, h].iter().all(|n| n.is_finite() && n.abs() < 1e9) => {
                if w <= 0.0 || h <= 0.0 {
                    return Err(bad("viewBox", v, "width and height must be positive"));
                }
            }
            [_, _, _, _] => return Err(bad("viewBox", v, "numbers out of range")),
            _ => return Err(bad("viewBox", v, "not four numbers")),
        }
    }
    Ok(())
}

/// Refuses path data usvg would silently truncate: syntax errors and numbers
/// beyond ±[`MAX_PATH_NUMBER`].
pub(super) fn check_path_data(
    doc: &roxmltree::Document,
    display: &BTreeMap<String, String>,
    source: &str,
) -> Result<(), ScenarioError> {
    let err_src = || source.to_string();
    for n in doc
        .descendants()
        .filter(|n| n.is_element() && n.tag_name().name() == "path")
    {
        if let Some(d) = n.attribute("d") {
            for seg in svgtypes::PathParser::from(d) {
                let message = match seg {
                    Err(e) => e.to_string(),
                    Ok(seg) if !path_numbers_in_range(&seg) => {
                        format!("a number is beyond ±{MAX_PATH_NUMBER:e} (or not finite)")
                    }
                    Ok(_) => continue,
                };
                return Err(ScenarioError::PathData {
                    source_name: err_src(),
                    id: n
                        .attribute("id")
                        .map(|id| display.get(id).map_or(id, |d| d.as_str()))
                        .unwrap_or("(no id)")
                        .to_string(),
                    message,
                });
            }
        }
    }
    Ok(())
}

/// Refuses an arena smaller than 1 px, or beyond the options' size or area.
pub(super) fn check_arena_size(
    width: f64,
    height: f64,
    opts: &LoadOptions,
    source: &str,
) -> Result<(), ScenarioError> {
    let err_src = || source.to_string();
    if !(width.is_finite() && height.is_finite() && width >= 1.0 && height >= 1.0) {
        return Err(ScenarioError::ArenaSize {
            source_name: err_src(),
            width,
            height,
            problem: "must be at least 1 px each way".into(),
        });
    }
    if width > opts.max_arena_size || height > opts.max_arena_size {
        return Err(ScenarioError::ArenaSize {
            source_name: err_src(),
            width,
            height,
            problem: format!("larger than the limit of {} px", opts.max_arena_size),
        });
    }
    if width * height > opts.max_arena_area {
        return Err(ScenarioError::ArenaSize {
            source_name: err_src(),
            width,
            height,
            problem: format!(
                "larger than the limit of {:e} px² in area (its surface raster would take {:.0} MB)",
                opts.max_arena_area,
                width * height / (opts.cell_size * opts.cell_size) / 1e6
            ),
        });
    }
    Ok(())
}

/// Refuses a robot that starts outside the arena.
pub(super) fn check_robots_inside(sc: &Scenario, source: &str) -> Result<(), ScenarioError> {
    let (width, height) = (sc.width, sc.height);
    for r in &sc.robots {
        if !(r.pos.x >= 0.0 && r.pos.y >= 0.0 && r.pos.x <= width && r.pos.y <= height) {
            return Err(ScenarioError::RobotOutsideArena {
                source_name: source.to_string(),
                id: r.id.clone(),
                x: r.pos.x,
                y: r.pos.y,
                width,
                height,
            });
        }
    }
    Ok(())
}

/// Whether every number of a path segment is finite and within ±[`MAX_PATH_NUMBER`].
pub(super) fn path_numbers_in_range(seg: &svgtypes::PathSegment) -> bool {
    use svgtypes::PathSegment as S;
    let nums: &[f64] = match *seg {
        S::MoveTo { x, y, .. } | S::LineTo { x, y, .. } | S::SmoothQuadratic { x, y, .. } => {
            &[x, y]
        }
        S::HorizontalLineTo { x, .. } => &[x],
        S::VerticalLineTo { y, .. } => &[y],
        S::CurveTo {
            x1,
            y1,
            x2,
            y2,
            x,
            y,
            ..
        } => &[x1, y1, x2, y2, x, y],
        S::SmoothCurveTo { x2, y2, x, y, .. }
        | S::Quadratic {
            x1: x2,
            y1: y2,
            x,
            y,
            ..
        } => &[x2, y2, x, y],
        S::EllipticalArc {
            rx,
            ry,
            x_axis_rotation,
            x,
            y,
            ..
        } => &[rx, ry, x_axis_rotation, x, y],
        S::ClosePath { .. } => &[],
    };
    nums.iter()
        .all(|v| v.is_finite() && v.abs() <= MAX_PATH_NUMBER)
}
