//! The sensors a run's robots carry, each with its input sheet on the substrate.
//!
//! This file is the one place that maps the config's sensor sections to
//! simulator sensors: adding a sensor type means a new file in
//! `vivae_sim::sensors`, its config section, and one entry in
//! [`sensor_sheets`]. The substrate, the experiment and the figures then
//! handle it with no further edits: its input nodes come from the sensor's
//! own places ([`SensorSheet::nodes`]).

use std::sync::Arc;

use vivae_sim::{DistanceSensors, Sensor, SurfaceGrid, SurfaceSensors, World};

use crate::polar::{DISTANCE_OUTPUT, PolarNode, SURFACE_OUTPUT};

/// One sensor and the input sheet that stands for it on the substrate.
#[derive(Debug, Clone)]
pub struct SensorSheet {
    /// The compiled sensor the simulator reads.
    pub sensor: Arc<dyn Sensor>,
    /// The CPPN output that paints this sheet's links to the neurons.
    pub cppn_output: usize,
    /// Readings of this sensor in its reference layout (the paper's 3×5 for
    /// surface sensors): `substrate.normalize` scales the sheet's weights by
    /// `reference_len / len`.
    pub reference_len: usize,
}

impl SensorSheet {
    /// Number of readings (= input nodes of the sheet).
    pub fn len(&self) -> usize {
        self.sensor.len()
    }

    /// Whether the sheet has no node.
    pub fn is_empty(&self) -> bool {
        self.sensor.is_empty()
    }

    /// The sheet's nodes in reading order: ring `k` of `rings` at radius
    /// `(k+1)/rings`, at the angle the sensor looks.
    pub fn nodes(&self) -> Vec<PolarNode> {
        let rings = self.sensor.rings().max(1);
        self.sensor
            .places()
            .iter()
            .map(|p| PolarNode {
                ring: p.ring,
                angle_index: p.angle_index,
                rho: (p.ring + 1) as f64 / rings as f64,
                phi: p.angle,
            })
            .collect()
    }
}

/// Reads robot `robot`'s sensors in `world` into `inputs`, sheet after
/// sheet: the controller's input vector. Allocation-free.
#[inline]
pub fn read_sheets(sheets: &[SensorSheet], world: &World, robot: usize, inputs: &mut [f64]) {
    let mut rest = inputs;
    for sheet in sheets {
        let (mine, others) = rest.split_at_mut(sheet.len());
        sheet.sensor.read(world, robot, mine);
        rest = others;
    }
}

/// The input sheets, in controller-input order, for surface sensors and
/// optional distance sensors.
pub fn sensor_sheets(
    surface: &SurfaceSensors,
    distance: Option<&DistanceSensors>,
) -> Vec<SensorSheet> {
    sheets_with_surface(Arc::new(surface.grid()), distance)
}

/// As [`sensor_sheets`], with the surface sensors already compiled (so a
/// caller that also draws them shares the one grid).
pub fn sheets_with_surface(
    surface: Arc<SurfaceGrid>,
    distance: Option<&DistanceSensors>,
) -> Vec<SensorSheet> {
    let mut sheets = vec![SensorSheet {
        sensor: surface,
        cppn_output: SURFACE_OUTPUT,
        reference_len: SurfaceSensors::default().len(),
    }];
    if let Some(d) = distance {
        sheets.push(SensorSheet {
            sensor: Arc::new(d.grid()),
            cppn_output: DISTANCE_OUTPUT,
            reference_len: DistanceSensors::default().rays,
        });
    }
    sheets
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_sheet_nodes_match_the_polar_grid() {
        let sheets = sensor_sheets(
            &SurfaceSensors {
                rings: 4,
                angles: 7,
                ..SurfaceSensors::default()
            },
            None,
        );
        assert_eq!(sheets.len(), 1);
        let grid = crate::substrate::PolarGrid::new(4, 7).unwrap();
        assert_eq!(sheets[0].nodes(), grid.nodes(180.0));
    }

    #[test]
    fn distance_rays_sit_on_the_outer_ring() {
        let rays = DistanceSensors {
            rays: 6,
            ..DistanceSensors::default()
        };
        let sheets = sensor_sheets(&SurfaceSensors::default(), Some(&rays));
        assert_eq!(sheets.len(), 2);
        assert_eq!(sheets[1].cppn_output, DISTANCE_OUTPUT);
        let nodes = sheets[1].nodes();
        assert_eq!(nodes.len(), 6);
        assert!(nodes.iter().all(|n| n.rho == 1.0 && n.ring == 0));
        assert_eq!(
            nodes,
            crate::substrate::PolarGrid::new(1, 6).unwrap().nodes(180.0)
        );
    }
}
