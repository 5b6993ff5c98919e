//! Why a scenario could not be loaded.

/// Why a scenario could not be loaded. Every variant names the source file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ScenarioError {
    /// The bytes are not UTF-8 text.
    #[error("{source_name}: not UTF-8 text")]
    NotUtf8 {
        /// File name.
        source_name: String,
    },
    /// The text is not well-formed XML.
    #[error("{source_name}: not XML: {message}")]
    Xml {
        /// File name.
        source_name: String,
        /// Parser message with position.
        message: String,
    },
    /// The XML root is not `<svg>`.
    #[error("{source_name}: not an SVG document (root element is <{root}>)")]
    NotSvg {
        /// File name.
        source_name: String,
        /// The root element's name.
        root: String,
    },
    /// The arena is zero, negative, not a number or absurdly large.
    #[error(
        "{source_name}: bad arena size {} x {}: {problem}",
        size_text(*.width),
        size_text(*.height)
    )]
    ArenaSize {
        /// File name.
        source_name: String,
        /// Width in px (0 when unreadable).
        width: f64,
        /// Height in px (0 when unreadable).
        height: f64,
        /// What is wrong.
        problem: String,
    },
    /// An element's `d` attribute cannot be parsed.
    #[error("{source_name}: element '{id}': malformed path data: {message}")]
    PathData {
        /// File name.
        source_name: String,
        /// Element id.
        id: String,
        /// Parser message.
        message: String,
    },
    /// An attribute has a value the loader cannot use.
    #[error("{source_name}: element '{id}': bad attribute {attribute}=\"{value}\"")]
    Attribute {
        /// File name.
        source_name: String,
        /// Element id.
        id: String,
        /// Attribute name.
        attribute: String,
        /// The offending value.
        value: String,
    },
    /// A route-bound obstacle region's attribute cannot work as written.
    #[error("{source_name}: element '{id}': {attribute}: {problem}")]
    RegionAttribute {
        /// File name.
        source_name: String,
        /// Element id.
        id: String,
        /// Attribute name.
        attribute: String,
        /// What is wrong.
        problem: String,
    },
    /// A robot's start position is outside the arena.
    #[error(
        "{source_name}: robot '{id}' at ({x:.1}, {y:.1}) is outside the {width} x {height} arena"
    )]
    RobotOutsideArena {
        /// File name.
        source_name: String,
        /// Element id.
        id: String,
        /// Position x.
        x: f64,
        /// Position y.
        y: f64,
        /// Arena width.
        width: f64,
        /// Arena height.
        height: f64,
    },
    /// The scenario has no robot, but the caller needs robots.
    #[error("{source_name}: no robots (label an element e.g. 'Robot' to place one)")]
    NoRobots {
        /// File name.
        source_name: String,
    },
    /// usvg rejected the document.
    #[error("{source_name}: invalid SVG: {message}")]
    Svg {
        /// File name.
        source_name: String,
        /// usvg's message.
        message: String,
    },
    /// More than 256 distinct surface materials (kind + friction override).
    #[error("{source_name}: more than 256 distinct surface frictions")]
    TooManyMaterials {
        /// File name.
        source_name: String,
    },
    /// The root's `width`, `height` or `viewBox` cannot give an arena size.
    #[error("{source_name}: bad arena {attribute}=\"{value}\": {problem}")]
    RootSize {
        /// File name.
        source_name: String,
        /// `width`, `height` or `viewBox`.
        attribute: &'static str,
        /// The value as written.
        value: String,
        /// What is wrong.
        problem: String,
    },
    /// An element's geometry reaches far outside the arena (flattening it would be unbounded work).
    #[error(
        "{source_name}: element '{id}' reaches ({min_x:.3e}, {min_y:.3e})..({max_x:.3e}, {max_y:.3e}), far outside the arena"
    )]
    FarOutside {
        /// File name.
        source_name: String,
        /// Element id.
        id: String,
        /// Smallest x reached.
        min_x: f64,
        /// Smallest y reached.
        min_y: f64,
        /// Largest x reached.
        max_x: f64,
        /// Largest y reached.
        max_y: f64,
    },
    /// An obstacle region in which no obstacle could be placed.
    #[error("{source_name}: obstacle region '{id}' {problem}")]
    Region {
        /// File name.
        source_name: String,
        /// Element id.
        id: String,
        /// What is wrong.
        problem: String,
    },
    /// A route's id is also another element's: a robot could not name it.
    #[error(
        "{source_name}: route {id}: its id is used by another element too: give each route an id of its own (robots name their route by it)"
    )]
    RepeatedRouteId {
        /// File name.
        source_name: String,
        /// The route as the user wrote it (its id and where it is).
        id: String,
    },
    /// The load options are invalid.
    #[error("invalid load option {field} = {value}")]
    Options {
        /// Field name.
        field: &'static str,
        /// Its value.
        value: f64,
    },
}

/// A size for a message: plain when moderate, scientific when huge (1e308
/// would print 309 digits).
fn size_text(v: f64) -> String {
    if v.abs() < 1e9 {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}
