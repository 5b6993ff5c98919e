//! Where things go in the receptive-field figure: the panels' grid, the bands
//! of further input sheets, and which sensor's wedge each pixel of a panel is.

use std::f64::consts::FRAC_PI_2;

use vivae_lab::controller::substrate::PolarNode;

use crate::figures::PNG_SCALE;
use crate::figures::controller::{FigureSheet, NetworkOptions};

/// The receptive-field figure is this much larger than the link figure (more to show).
const ENLARGE: f64 = 1.6;
/// Inner and outer radius (sheet radius = 1) of the first band outside the
/// panel: the second input sheet's (e.g. the distance rays').
const BAND: (f64, f64) = (1.06, 1.22);
/// How much further out each further band is.
const BAND_STEP: f64 = 0.22;

/// Inner and outer radius of input sheet `band`'s band (1 = the second sheet).
fn band_radii(band: usize) -> (f64, f64) {
    let shift = BAND_STEP * (band - 1) as f64;
    (BAND.0 + shift, BAND.1 + shift)
}

/// Outer radius of a panel with `sheets` input sheets (1 = no band).
pub(super) fn outer_radius(sheets: usize) -> f64 {
    if sheets > 1 {
        band_radii(sheets - 1).1
    } else {
        1.0
    }
}
/// Marks a pixel outside every sensor's wedge.
pub(super) const OUTSIDE: u32 = u32::MAX;

/// Boundaries between the wedges of nodes at angles `phis` (ascending): midway
/// between neighbours, half a spacing beyond the ends (`half_fov` for one node).
fn wedge_bounds(phis: &[f64], half_fov: f64) -> Vec<f64> {
    match phis {
        [] => Vec::new(),
        [only] => vec![only - half_fov, only + half_fov],
        _ => {
            let first = phis[0] - (phis[1] - phis[0]) / 2.0;
            let last = phis[phis.len() - 1] + (phis[phis.len() - 1] - phis[phis.len() - 2]) / 2.0;
            std::iter::once(first)
                .chain(phis.windows(2).map(|p| (p[0] + p[1]) / 2.0))
                .chain(std::iter::once(last))
                .collect()
        }
    }
}

/// Index of the wedge holding angle `phi`.
fn wedge(bounds: &[f64], phi: f64) -> Option<usize> {
    if bounds.len() < 2 || !(phi >= bounds[0] && phi < bounds[bounds.len() - 1]) {
        return None;
    }
    Some(bounds.partition_point(|&b| b <= phi) - 1)
}

/// Which input feeds each pixel of a panel: the same for every panel, so
/// computed once. `radius` is the sheet radius in pixels; the panel's box
/// spans `x0..x0+width`, `y0..y0+height` pixels around the centre.
pub(super) struct Stencil {
    pub(super) x0: i32,
    pub(super) y0: i32,
    pub(super) width: u32,
    /// Input index per pixel, row-major, [`OUTSIDE`] where there is none.
    pub(super) input: Vec<u32>,
}

/// Which input of one sheet feeds a point of a panel: the sheet's nodes by
/// ring (radial slices of `r0..r1`) and wedge (angle).
struct Placement {
    /// Radial extent in sheet radii: `0..1` for the panel, a band outside it.
    r0: f64,
    r1: f64,
    rings: usize,
    angles: usize,
    /// Input index (over all sheets) by `ring * angles + angle_index`.
    by_place: Vec<u32>,
    bounds: Vec<f64>,
}

impl Placement {
    fn new(nodes: &[PolarNode], first_input: usize, (r0, r1): (f64, f64), half: f64) -> Self {
        let rings = nodes.iter().map(|n| n.ring + 1).max().unwrap_or(1);
        let angles = nodes.iter().map(|n| n.angle_index + 1).max().unwrap_or(1);
        // Input index by (ring, angle): the sheet need not list them in grid order.
        let mut by_place = vec![OUTSIDE; rings * angles];
        let mut phis = vec![0.0; angles];
        for (i, n) in nodes.iter().enumerate() {
            by_place[n.ring * angles + n.angle_index] = (first_input + i) as u32;
            phis[n.angle_index] = n.phi;
        }
        Placement {
            r0,
            r1,
            rings,
            angles,
            by_place,
            bounds: wedge_bounds(&phis, half),
        }
    }

    /// The input at radius `rho` (in `r0..r1`) and angle `phi`.
    fn input(&self, rho: f64, phi: f64) -> u32 {
        let ring = (((rho - self.r0) / (self.r1 - self.r0) * self.rings as f64) as usize)
            .min(self.rings - 1);
        wedge(&self.bounds, phi).map_or(OUTSIDE, |a| self.by_place[ring * self.angles + a])
    }
}

impl Stencil {
    pub(super) fn new(radius: f64, half: f64, sheets: &[FigureSheet]) -> Stencil {
        let mut first_input = 0;
        let placements: Vec<Placement> = sheets
            .iter()
            .enumerate()
            .map(|(k, sheet)| {
                let radii = if k == 0 { (0.0, 1.0) } else { band_radii(k) };
                let p = Placement::new(&sheet.nodes, first_input, radii, half);
                first_input += sheet.nodes.len();
                p
            })
            .collect();
        let outer = outer_radius(sheets.len());
        let side = outer * half.min(FRAC_PI_2).sin().max(0.05);
        let below = if half > FRAC_PI_2 { -half.cos() } else { 0.0 };
        let x0 = -(side * radius).ceil() as i32 - 1;
        let y0 = -(outer * radius).ceil() as i32 - 1;
        let width = (2 * -x0) as u32;
        let height = (-y0 + (below * outer * radius).ceil() as i32 + 1) as u32;
        let mut input = Vec::with_capacity(width as usize * height as usize);
        for y in 0..height as i32 {
            for x in 0..width as i32 {
                let (dx, dy) = (f64::from(x0 + x) + 0.5, f64::from(y0 + y) + 0.5);
                let rho = dx.hypot(dy) / radius;
                // Angle from straight ahead (up), positive to the right.
                let phi = dx.atan2(-dy);
                let index = placements
                    .iter()
                    .find(|p| rho < p.r1 && (p.r0 == 0.0 || rho >= p.r0))
                    .map_or(OUTSIDE, |p| p.input(rho, phi));
                input.push(index);
            }
        }
        Stencil {
            x0,
            y0,
            width,
            input,
        }
    }
}

/// Where the blocks go, in SVG units.
pub(super) struct Layout {
    pub(super) w: f64,
    pub(super) h: f64,
    /// Panel grid: left, top, cell width, cell height.
    pub(super) grid: (f64, f64, f64, f64),
    /// Sheet radius of a panel.
    pub(super) radius: f64,
    /// Recurrent matrix: left, top, side.
    pub(super) matrix: (f64, f64, f64),
    /// Bias row: top and height (left and width are the matrix's).
    pub(super) bias: (f64, f64),
}

impl Layout {
    pub(super) fn new(
        opts: &NetworkOptions,
        rows: usize,
        cols: usize,
        half: f64,
        outer: f64,
    ) -> Layout {
        let (w, h) = (
            (f64::from(opts.width) * ENLARGE).round(),
            (f64::from(opts.height) * ENLARGE).round(),
        );
        let (left, top) = (w * 0.07, 130.0);
        let (right, bottom) = (w * 0.63, h - 150.0);
        let (cw, ch) = ((right - left) / cols as f64, (bottom - top) / rows as f64);
        let fan_w = 2.0 * outer * half.min(FRAC_PI_2).sin().max(0.05);
        let fan_h = outer * (1.0 + if half > FRAC_PI_2 { -half.cos() } else { 0.0 });
        let radius = (cw * 0.9 / fan_w).min(ch * 0.86 / fan_h);
        let mx = w * 0.68;
        let side = (w - 40.0 - mx).min(h - 330.0 - top);
        Layout {
            w,
            h,
            grid: (left, top, cw, ch),
            radius,
            matrix: (mx, top + 20.0, side),
            bias: (top + 20.0 + side + 46.0, 24.0),
        }
    }

    /// Centre of the panel at `row`, `col`, rounded to whole PNG pixels so
    /// every panel shares one [`Stencil`].
    pub(super) fn centre(&self, row: usize, col: usize, half: f64, outer: f64) -> (f64, f64) {
        let (left, top, cw, ch) = self.grid;
        let fan_h = outer * (1.0 + if half > FRAC_PI_2 { -half.cos() } else { 0.0 });
        let cx = left + cw * (col as f64 + 0.5);
        let cy = top + ch * row as f64 + (ch - fan_h * self.radius) / 2.0 + outer * self.radius;
        let s = f64::from(PNG_SCALE);
        ((cx * s).round() / s, (cy * s).round() / s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vivae_lab::controller::substrate::SubstrateSpec;

    #[test]
    fn wedges_split_halfway_between_nodes() {
        let b = wedge_bounds(&[-1.0, 0.0, 1.0], 1.0);
        assert_eq!(b, vec![-1.5, -0.5, 0.5, 1.5]);
        assert_eq!(wedge(&b, -1.5), Some(0));
        assert_eq!(wedge(&b, 0.0), Some(1));
        assert_eq!(wedge(&b, 1.49), Some(2));
        assert_eq!(wedge(&b, 1.5), None);
        assert_eq!(wedge(&b, f64::NAN), None);
        assert_eq!(wedge_bounds(&[0.0], 0.5), vec![-0.5, 0.5]);
        assert_eq!(wedge_bounds(&[], 0.5), Vec::<f64>::new());
    }

    #[test]
    fn outer_sensors_and_distance_rays_get_their_own_pixels() {
        use vivae_lab::controller::substrate::PolarGrid;
        let spec = SubstrateSpec {
            sensors: PolarGrid::new(32, 96).unwrap(),
            distance_rays: Some(7),
            ..SubstrateSpec::default()
        };
        let sheets = FigureSheet::all(&spec.sheets());
        let (sensors, distance) = (&sheets[0].nodes, &sheets[1].nodes);
        let half = spec.fov.to_radians() / 2.0;
        // A panel as large as the 9×9 figure draws it (radius ≈ 90 pixels).
        let stencil = Stencil::new(90.0, half, &sheets);
        let mut seen = vec![0usize; sensors.len() + distance.len()];
        for &i in stencil.input.iter().filter(|&&i| i != OUTSIDE) {
            seen[i as usize] += 1;
        }
        // Wedges of inner rings are narrower than a pixel (true to the geometry:
        // they are that close together); every sensor of the outer half of the
        // rings and every distance ray has pixels of its own.
        let outer_half = sensors.iter().enumerate().filter(|(_, n)| n.ring >= 16);
        assert!(outer_half.clone().count() == 16 * 96);
        assert!(outer_half.into_iter().all(|(i, _)| seen[i] > 0));
        assert!(
            seen[sensors.len()..].iter().all(|&n| n > 0),
            "a ray has no pixel"
        );
        // The left-most outer sensor is drawn left of the centre, the right-most right of it.
        let column_of = |input: u32| {
            let at = stencil.input.iter().position(|&i| i == input).unwrap();
            at as i32 % stencil.width as i32 + stencil.x0
        };
        let outer_left = (31 * 96) as u32;
        assert!(column_of(outer_left) < 0 && column_of(outer_left + 95) > 0);
    }

    #[test]
    fn every_further_sheet_is_a_band_of_its_own() {
        let spec = SubstrateSpec {
            distance_rays: Some(5),
            ..SubstrateSpec::default()
        };
        let mut sheets = FigureSheet::all(&spec.sheets());
        let ahead = PolarNode {
            ring: 0,
            angle_index: 0,
            rho: 1.0,
            phi: 0.0,
        };
        sheets.push(FigureSheet {
            name: "speed",
            label: "speedometer",
            nodes: vec![ahead],
        });
        let radius = 90.0;
        let stencil = Stencil::new(radius, FRAC_PI_2, &sheets);
        let inputs = 15 + 5 + 1;
        let mut seen = vec![0usize; inputs];
        for &i in stencil.input.iter().filter(|&&i| i != OUTSIDE) {
            seen[i as usize] += 1;
        }
        assert!(seen.iter().all(|&n| n > 0), "{seen:?}");
        // The speedometer fills the third band, the whole half ring.
        let (r0, r1) = band_radii(2);
        assert!(r0 > band_radii(1).1);
        let row = |input: u32| {
            let at = stencil.input.iter().position(|&i| i == input).unwrap();
            at as i32 / stencil.width as i32 + stencil.y0
        };
        let top = -f64::from(row(20));
        assert!(top > r0 * radius - 2.0 && top <= r1 * radius + 1.0, "{top}");
        assert_eq!(outer_radius(sheets.len()), r1);
    }
}
