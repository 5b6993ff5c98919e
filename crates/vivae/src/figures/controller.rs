//! What both forms of the controller figure share: its options, the check
//! of a controller against its substrate, colours and pixel helpers. The
//! line-per-link form is [`super::network`], the receptive-field form
//! `super::fields`; both import from here, and `network` chooses between them.

use plotters::prelude::*;
use vivae_neat::hyperneat::SubstrateController;

use super::FigureError;
use vivae_lab::controller::sensors::SensorSheet;
use vivae_lab::controller::substrate::{PolarGrid, PolarNode, SubstrateSpec, WheelNeurons};

/// Wheel neurons' colour.
pub(super) const WHEEL: RGBColor = RGBColor(214, 39, 40);
/// Guide lines (rings, baseline).
pub(super) const GUIDE: RGBColor = RGBColor(200, 200, 200);

/// What the network figure shows and how large it is.
#[derive(Debug, Clone, PartialEq)]
pub struct NetworkOptions {
    /// Figure title.
    pub title: String,
    /// |weight| drawn at full width and opacity (the HyperNEAT amplitude, 3.0).
    pub weight_scale: f64,
    /// Width in SVG units (the PNG is `PNG_SCALE` times larger).
    pub width: u32,
    /// Height in SVG units.
    pub height: u32,
    /// Most expressed links drawn one line each; a larger controller is drawn
    /// as receptive fields (heat maps), whose cost does not grow with its links.
    pub max_links: usize,
}

impl Default for NetworkOptions {
    fn default() -> Self {
        NetworkOptions {
            title: "Controller network".to_string(),
            weight_scale: 3.0,
            width: 1000,
            height: 720,
            max_links: 400,
        }
    }
}

/// One input sheet as the controller figures draw it: the first sheet is the
/// inner panel, every further one a band outside it.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureSheet {
    /// Short name of its sensor (`Sensor::name`), e.g. `"distance"`.
    pub name: &'static str,
    /// What its readings are called, plural: `"surface sensors"`, `"distance rays"`.
    pub label: &'static str,
    /// Its nodes in controller-input order.
    pub nodes: Vec<PolarNode>,
}

impl FigureSheet {
    /// The figure's view of `sheet`.
    pub fn of(sheet: &SensorSheet) -> FigureSheet {
        FigureSheet {
            name: sheet.name(),
            label: sheet.label,
            nodes: sheet.nodes(),
        }
    }

    /// The figure's view of every sheet, in controller-input order.
    pub fn all(sheets: &[SensorSheet]) -> Vec<FigureSheet> {
        sheets.iter().map(FigureSheet::of).collect()
    }

    /// Rings and angles of the grid its nodes fill.
    pub fn grid(&self) -> PolarGrid {
        PolarGrid {
            rings: self.nodes.iter().map(|n| n.ring + 1).max().unwrap_or(1),
            angles: self
                .nodes
                .iter()
                .map(|n| n.angle_index + 1)
                .max()
                .unwrap_or(1),
        }
    }
}

/// The sheets' nodes and wheel neurons, once `spec`, `controller` and `opts` are checked.
pub(super) struct Checked {
    /// The input sheets, at least one.
    pub inputs: Vec<FigureSheet>,
    pub neurons: Vec<PolarNode>,
    pub wheels: WheelNeurons,
}

/// Checks that `controller` was decoded on the input `sheets` and `spec`'s
/// neuron sheet, and that `opts` are usable.
pub(super) fn check(
    spec: &SubstrateSpec,
    sheets: &[FigureSheet],
    controller: &SubstrateController,
    opts: &NetworkOptions,
) -> Result<Checked, FigureError> {
    spec.validate()
        .map_err(|e| FigureError::Invalid(e.to_string()))?;
    let neurons = spec.neuron_nodes();
    let wheels = spec
        .wheels()
        .map_err(|e| FigureError::Invalid(e.to_string()))?;
    let expected_sheets: Vec<usize> = sheets.iter().map(|s| s.nodes.len()).collect();
    if sheets.is_empty()
        || controller.sheet_sizes() != expected_sheets.as_slice()
        || controller.num_neurons() != neurons.len()
    {
        return Err(FigureError::Invalid(format!(
            "controller with input sheets {:?} and {} neurons does not match substrate {:?} → {}",
            controller.sheet_sizes(),
            controller.num_neurons(),
            expected_sheets,
            spec.neurons
        )));
    }
    if !(opts.weight_scale.is_finite() && opts.weight_scale > 0.0) {
        return Err(FigureError::Invalid(format!(
            "weight_scale {} must be finite and positive",
            opts.weight_scale
        )));
    }
    if opts.width < 400 || opts.height < 300 {
        return Err(FigureError::Invalid(format!(
            "figure size {}x{} is too small (at least 400x300)",
            opts.width, opts.height
        )));
    }
    Ok(Checked {
        inputs: sheets.to_vec(),
        neurons,
        wheels,
    })
}

impl Checked {
    /// The first input sheet, drawn as the inner panel.
    pub fn first(&self) -> &FigureSheet {
        &self.inputs[0]
    }

    /// The sheets drawn as bands outside the first, with their band number (1, 2, …).
    pub fn bands(&self) -> impl Iterator<Item = (usize, &FigureSheet)> {
        self.inputs.iter().enumerate().skip(1)
    }

    /// Number of input nodes over all sheets.
    pub fn num_inputs(&self) -> usize {
        self.inputs.iter().map(|s| s.nodes.len()).sum()
    }

    /// `" + 7 distance rays"` for every sheet after the first.
    pub fn bands_caption(&self) -> String {
        self.bands()
            .map(|(_, s)| format!(" + {} {}", s.nodes.len(), s.label))
            .collect()
    }
}

/// Rounds a pixel position for plotters.
pub(super) fn px((x, y): (f64, f64)) -> (i32, i32) {
    (x.round() as i32, y.round() as i32)
}

/// Mixes `c` with white: `m = 0` white, `m = 1` the colour.
pub(super) fn blend(c: RGBColor, m: f64) -> RGBColor {
    let f = |v: u8| (255.0 + (f64::from(v) - 255.0) * m).round() as u8;
    RGBColor(f(c.0), f(c.1), f(c.2))
}
