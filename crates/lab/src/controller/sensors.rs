//! The sensors a run's robots carry, each with its input sheet on the substrate.
//!
//! [`SENSORS`] is the registry: the one table of the sensor kinds a config
//! can build. A new sensor is a file in `vivae_sim::sensors` implementing
//! `vivae_sim::Sensor`, its config section, and one [`SensorKind`] entry here
//! (how to build it from the config, its CPPN output, its reference length
//! and its label). [`sensor_sheets`], `SubstrateSpec::sheets`, the
//! experiment and the figures then handle it with no further edits: its
//! input nodes come from the sensor's own places ([`SensorSheet::nodes`]),
//! and the figures draw any list of sheets by name and label.

use std::sync::Arc;

use vivae_sim::{DistanceSensors, Sensor, SurfaceSensors, World};

use crate::config::Config;
use crate::controller::polar::{DISTANCE_OUTPUT, OPPONENT_OUTPUT, PolarNode, SURFACE_OUTPUT};

/// One sensor kind the config can build: an entry of [`SENSORS`].
#[derive(Debug, Clone, Copy)]
pub struct SensorKind {
    /// Short name, the `Sensor::name` of what it builds (e.g. `"surface"`).
    pub name: &'static str,
    /// What its readings are called in figures, plural (e.g. `"distance rays"`).
    pub label: &'static str,
    /// The CPPN output that paints its sheet's links to the neurons.
    pub cppn_output: usize,
    /// Readings in its reference layout (see [`SensorSheet::reference_len`]).
    pub reference_len: fn() -> usize,
    /// The compiled sensor the config asks for, `None` when it is switched off.
    pub build: fn(&Config) -> Option<Arc<dyn Sensor>>,
}

impl SensorKind {
    /// This kind's sheet for `config`, `None` when the config switches it off.
    pub fn sheet(&self, config: &Config) -> Option<SensorSheet> {
        (self.build)(config).map(|sensor| SensorSheet {
            sensor,
            cppn_output: self.cppn_output,
            reference_len: (self.reference_len)(),
            label: self.label,
        })
    }
}

/// The registry: every sensor kind the config can build, in controller-input
/// order (the surface sensors first: they are always there).
pub static SENSORS: [SensorKind; 3] = [
    SensorKind {
        name: "surface",
        label: "surface sensors",
        cppn_output: SURFACE_OUTPUT,
        // The paper's 3×5.
        reference_len: || SurfaceSensors::default().len(),
        build: |c| Some(Arc::new(c.surface_sensors.grid())),
    },
    SensorKind {
        name: "distance",
        label: "distance rays",
        cppn_output: DISTANCE_OUTPUT,
        reference_len: || DistanceSensors::default().rays,
        build: |c| {
            c.distance_sensors
                .layout()
                .map(|d| Arc::new(d.grid()) as Arc<dyn Sensor>)
        },
    },
    SensorKind {
        name: "opponent",
        label: "opponent radar",
        cppn_output: OPPONENT_OUTPUT,
        // The maze radar's four slices.
        reference_len: || 4,
        build: |c| {
            c.opponent_sensors
                .radar()
                .map(|r| Arc::new(r) as Arc<dyn Sensor>)
        },
    },
];

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
    /// What its readings are called in figures, plural: `"surface sensors"`,
    /// `"distance rays"`.
    pub label: &'static str,
}

impl SensorSheet {
    /// The sensor's short name (`Sensor::name`), e.g. `"distance"`.
    pub fn name(&self) -> &'static str {
        self.sensor.name()
    }

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

/// [`read_sheets`] in single precision, for controllers that step in f32:
/// each sheet's `Sensor::read_f32` (the surface sensors compute in f32;
/// the others read in f64 into `scratch`, at least as long as the longest
/// sheet, and round). Allocation-free.
#[inline]
pub fn read_sheets_single(
    sheets: &[SensorSheet],
    world: &World,
    robot: usize,
    inputs: &mut [f32],
    scratch: &mut [f64],
) {
    let mut rest = inputs;
    for sheet in sheets {
        let (mine, others) = rest.split_at_mut(sheet.len());
        sheet.sensor.read_f32(world, robot, mine, scratch);
        rest = others;
    }
}

/// [`read_sheets`] of robots `0..robots` at once, robot `r`'s input vector
/// at `inputs[r · ni..][..ni]` (`ni` = `inputs.len() / robots`): each sheet
/// reads every robot in one call ([`vivae_sim::Sensor::read_robots`]), the
/// same bits. Allocation-free.
#[inline]
pub fn read_sheets_all(sheets: &[SensorSheet], world: &World, robots: usize, inputs: &mut [f64]) {
    let ni = inputs.len() / robots.max(1);
    let mut at = 0;
    for sheet in sheets {
        sheet
            .sensor
            .read_robots(world, robots, &mut inputs[at..], ni);
        at += sheet.len();
    }
}

/// [`read_sheets_all`] in single precision (each sheet's
/// [`vivae_sim::Sensor::read_robots_f32`]; `scratch` as in
/// [`read_sheets_single`]). Allocation-free.
#[inline]
pub fn read_sheets_single_all(
    sheets: &[SensorSheet],
    world: &World,
    robots: usize,
    inputs: &mut [f32],
    scratch: &mut [f64],
) {
    let ni = inputs.len() / robots.max(1);
    let mut at = 0;
    for sheet in sheets {
        sheet
            .sensor
            .read_robots_f32(world, robots, &mut inputs[at..], ni, scratch);
        at += sheet.len();
    }
}

/// The input sheets `config` asks for, in controller-input order: every
/// kind of the registry [`SENSORS`] the config switches on.
pub fn sensor_sheets(config: &Config) -> Vec<SensorSheet> {
    SENSORS.iter().filter_map(|k| k.sheet(config)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_sheet_nodes_match_the_polar_grid() {
        let mut config = Config::default();
        config.surface_sensors.rings = 4;
        config.surface_sensors.angles = 7;
        let sheets = sensor_sheets(&config);
        assert_eq!(sheets.len(), 1);
        assert_eq!(
            (sheets[0].name(), sheets[0].label),
            ("surface", "surface sensors")
        );
        let grid = crate::controller::substrate::PolarGrid::new(4, 7).unwrap();
        assert_eq!(sheets[0].nodes(), grid.nodes(180.0));
    }

    #[test]
    fn distance_rays_sit_on_the_outer_ring() {
        let mut config = Config::default();
        config.distance_sensors.rays = 6;
        let sheets = sensor_sheets(&config);
        assert_eq!(sheets.len(), 2);
        assert_eq!(
            (sheets[1].name(), sheets[1].label),
            ("distance", "distance rays")
        );
        assert_eq!(sheets[1].cppn_output, DISTANCE_OUTPUT);
        let nodes = sheets[1].nodes();
        assert_eq!(nodes.len(), 6);
        assert!(nodes.iter().all(|n| n.rho == 1.0 && n.ring == 0));
        assert_eq!(
            nodes,
            crate::controller::substrate::PolarGrid::new(1, 6)
                .unwrap()
                .nodes(180.0)
        );
    }

    #[test]
    fn every_kind_builds_the_sensor_it_names() {
        let mut config = Config::default();
        config.distance_sensors.rays = 3;
        config.opponent_sensors.slices = 4;
        for kind in &SENSORS {
            let sheet = kind.sheet(&config).unwrap();
            assert_eq!(sheet.name(), kind.name);
            assert_eq!(sheet.cppn_output, kind.cppn_output);
        }
    }

    #[test]
    fn the_opponent_radar_is_a_sheet_of_its_own_output() {
        let mut config = Config::default();
        assert_eq!(sensor_sheets(&config).len(), 1, "off by default");
        config.opponent_sensors.slices = 6;
        let sheets = sensor_sheets(&config);
        let radar = &sheets[1];
        assert_eq!((radar.name(), radar.len()), ("opponent", 6));
        assert_eq!(radar.cppn_output, OPPONENT_OUTPUT);
        assert!(radar.nodes().iter().all(|n| n.rho == 1.0));
        assert_eq!(crate::controller::substrate::cppn_outputs(&sheets), 5);
        // A driving config may switch it on; a bad range is refused by key.
        config.experiment.steps = 20;
        crate::tasks::check(&config).unwrap();
        config.opponent_sensors.range = -1.0;
        let err = crate::tasks::check(&config).unwrap_err().to_string();
        assert!(err.contains("opponent_sensors.range"), "{err}");
    }
}
