//! The polar substrate layout of the driving controller (DESIGN §7).
//!
//! Every sheet is a polar grid of `rings × angles` nodes. Ring `k` (0 =
//! innermost) has radius `ρ = (k+1)/rings`; angles are spread evenly over the
//! sheet's field of view, 0 straight ahead, negative to the left (one angle:
//! 0). Nodes are numbered ring-major, left to right — the order in which
//! `vivae_sim::SurfaceSensors` reads its sensors. A node's CPPN coordinates
//! are `(ρ·sin φ, ρ·cos φ)` (x to the right, y ahead) or, as an option, the
//! raw `(ρ, φ/π)`.
//!
//! Sheets and the CPPN outputs that paint their links:
//!
//! | sheet                                | CPPN output |
//! |--------------------------------------|-------------|
//! | surface sensors → neurons            | 0           |
//! | neuron biases (`x2 = y2 = 0`)        | 1           |
//! | neurons → neurons                    | 2           |
//! | distance sensors → neurons (optional)| 3           |
//!
//! Distance sensors are rays, one per angle, placed on a single ring at
//! `ρ = 1`; with them the CPPN has 4 outputs instead of DESIGN's 3.
//!
//! Wheel neurons: the leftmost angle is L, the rightmost is R, on the ring
//! nearest to `ρ = 2/3` ([`WHEEL_RADIUS`]). That is the middle ring of the
//! paper's 3-ring sheet (and of 1- and 5-ring sheets), and it is exactly
//! `ρ = 2/3` whenever `rings` is a multiple of 3, so re-sampling 3×3 → 9×9
//! keeps the wheels at the same CPPN coordinates — the point of HyperNEAT's
//! re-sampling. (The literal middle ring `rings/2` would move them: for 9
//! rings it has `ρ = 5/9`.) For an even number of rings there is no middle
//! ring; the same rule gives 2 rings → ρ = 1/2, 4 rings → ρ = 3/4,
//! 6 rings → ρ = 4/6. (Distances to 2/3 never tie.)

use crate::config::Config;
use crate::controller::sensors::{SensorSheet, sensor_sheets};
use serde::{Deserialize, Serialize};
use vivae_neat::hyperneat::{InputSheet, SubstrateLayout};

// The sheets' geometry has its own module, which the sensors use too.
pub use crate::controller::polar::{
    BIAS_OUTPUT, CoordMode, DISTANCE_OUTPUT, MAX_GRID_SIDE, PolarGrid, PolarNode, RECURRENT_OUTPUT,
    SURFACE_OUTPUT, SubstrateError, WHEEL_RADIUS, WheelNeurons,
};

/// Everything that fixes the substrate geometry of a run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SubstrateSpec {
    /// Surface sensor sheet (the paper's 3×5).
    pub sensors: PolarGrid,
    /// Neuron (output) sheet (the paper's 3×3).
    pub neurons: PolarGrid,
    /// Number of distance-sensor rays; `None` = no distance sheet (the paper).
    pub distance_rays: Option<usize>,
    /// Angular span of the input sheets in degrees (the sensors' field of view, 180).
    pub fov: f64,
    /// Angular span of the neuron sheet in degrees (180).
    pub neuron_fov: f64,
    /// How node positions are given to the CPPN.
    pub coords: CoordMode,
}

impl Default for SubstrateSpec {
    fn default() -> Self {
        SubstrateSpec {
            sensors: PolarGrid {
                rings: 3,
                angles: 5,
            },
            neurons: PolarGrid {
                rings: 3,
                angles: 3,
            },
            distance_rays: None,
            fov: 180.0,
            neuron_fov: 180.0,
            coords: CoordMode::Cartesian,
        }
    }
}

impl SubstrateSpec {
    /// Checks grids, fields of view and ray count.
    pub fn validate(&self) -> Result<(), SubstrateError> {
        PolarGrid::new(self.sensors.rings, self.sensors.angles)?;
        PolarGrid::new(self.neurons.rings, self.neurons.angles)?;
        self.neurons.wheel_neurons()?;
        if !(self.fov > 0.0 && self.fov <= 360.0) {
            return Err(SubstrateError::Fov {
                field: "fov",
                value: self.fov,
                reason: "must be in (0, 360]",
            });
        }
        // At 360° the leftmost and rightmost neurons would coincide: L = R.
        if !(self.neuron_fov > 0.0 && self.neuron_fov < 360.0) {
            return Err(SubstrateError::Fov {
                field: "neuron_fov",
                value: self.neuron_fov,
                reason: "must be in (0, 360) so that L and R differ",
            });
        }
        match self.distance_rays {
            Some(0) => Err(SubstrateError::NoRays),
            Some(r) if r > MAX_GRID_SIDE => Err(SubstrateError::GridSize {
                rings: 1,
                angles: r,
            }),
            _ => Ok(()),
        }
    }

    /// The sensor sheets this spec describes (surface, then distance if
    /// any), built by the registry `sensors::SENSORS` from a default config
    /// with this spec's sheets: the ranges do not move the substrate's nodes.
    pub fn sheets(&self) -> Vec<SensorSheet> {
        let mut config = Config::default();
        config.surface_sensors.rings = self.sensors.rings;
        config.surface_sensors.angles = self.sensors.angles;
        config.surface_sensors.fov = self.fov;
        config.distance_sensors.rays = self.distance_rays.unwrap_or(0);
        config.distance_sensors.fov = self.fov;
        sensor_sheets(&config)
    }

    /// Number of CPPN outputs this substrate needs: 3, or 4 with distance sensors.
    pub fn cppn_outputs(&self) -> usize {
        cppn_outputs(&self.sheets())
    }

    /// Surface sensor nodes (the first sheet's) in controller-input order.
    pub fn sensor_nodes(&self) -> Vec<PolarNode> {
        self.sheets()[0].nodes()
    }

    /// Neuron nodes in controller-output order.
    pub fn neuron_nodes(&self) -> Vec<PolarNode> {
        self.neurons.nodes(self.neuron_fov)
    }

    /// The wheel neurons.
    pub fn wheels(&self) -> Result<WheelNeurons, SubstrateError> {
        self.neurons.wheel_neurons()
    }

    /// The geometry-agnostic layout `vivae_neat::hyperneat::decode` takes.
    pub fn layout(&self) -> Result<SubstrateLayout, SubstrateError> {
        self.validate()?;
        Ok(layout_of(&self.sheets(), &self.neuron_nodes(), self.coords))
    }
}

/// The decoder's layout for input `sheets` (in controller-input order) and
/// `neurons`: the one place sheets become CPPN coordinates.
pub fn layout_of(
    sheets: &[SensorSheet],
    neurons: &[PolarNode],
    mode: CoordMode,
) -> SubstrateLayout {
    let coords =
        |nodes: &[PolarNode]| -> Vec<[f64; 2]> { nodes.iter().map(|n| n.coords(mode)).collect() };
    SubstrateLayout {
        inputs: sheets
            .iter()
            .map(|s| InputSheet {
                coords: coords(&s.nodes()),
                cppn_output: s.cppn_output,
            })
            .collect(),
        neurons: coords(neurons),
        bias_output: BIAS_OUTPUT,
        recurrent_output: RECURRENT_OUTPUT,
    }
}

/// CPPN outputs a substrate with `sheets` needs: one more than the highest
/// output any sheet, the bias or the recurrent links read.
pub fn cppn_outputs(sheets: &[SensorSheet]) -> usize {
    sheets
        .iter()
        .map(|s| s.cppn_output)
        .chain([BIAS_OUTPUT, RECURRENT_OUTPUT])
        .max()
        .unwrap_or(0)
        + 1
}

/// Builds the layout and wheel neurons from the parts of a [`SubstrateSpec`]
/// (input sheets and neuron sheet over 180°).
pub fn build_layout(
    sensors: PolarGrid,
    neurons: PolarGrid,
    distance_rays: Option<usize>,
    coords: CoordMode,
) -> Result<(SubstrateLayout, WheelNeurons), SubstrateError> {
    let spec = SubstrateSpec {
        sensors,
        neurons,
        distance_rays,
        coords,
        ..SubstrateSpec::default()
    };
    Ok((spec.layout()?, spec.wheels()?))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(s: &str) -> PolarGrid {
        s.parse().unwrap()
    }

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12
    }

    #[test]
    fn parses_and_prints_grids() {
        assert_eq!(
            grid("3x5"),
            PolarGrid {
                rings: 3,
                angles: 5
            }
        );
        assert_eq!(
            grid(" 9X9 "),
            PolarGrid {
                rings: 9,
                angles: 9
            }
        );
        assert_eq!(
            grid("3×6"),
            PolarGrid {
                rings: 3,
                angles: 6
            }
        );
        assert_eq!(grid("20x60").to_string(), "20x60");
        for (bad, needle) in [
            ("3", "exactly one 'x'"),
            ("3x5x2", "exactly one 'x'"),
            ("x5", "rings is missing"),
            ("3x", "angles is missing"),
            ("3xfive", "\"five\" is not a whole number"),
            ("-3x5", "not a whole number"),
            ("0x5", "must be in 1..=10000"),
            ("3x0", "must be in 1..=10000"),
            ("3x100000", "must be in 1..=10000"),
        ] {
            let e = bad.parse::<PolarGrid>().unwrap_err().to_string();
            assert!(e.contains(needle), "{bad}: {e}");
        }
    }

    #[test]
    fn grid_serde_is_the_rxa_string() {
        let spec = SubstrateSpec::default();
        let json = serde_json::to_string(&spec).unwrap();
        assert!(json.contains(r#""sensors":"3x5""#), "{json}");
        assert!(json.contains(r#""neurons":"3x3""#), "{json}");
        let back: SubstrateSpec = serde_json::from_str(&json).unwrap();
        assert_eq!(back, spec);
        let e = serde_json::from_str::<SubstrateSpec>(r#"{"sensors":"3y5"}"#).unwrap_err();
        assert!(e.to_string().contains("3y5"), "{e}");
        assert!(serde_json::from_str::<SubstrateSpec>(r#"{"sensor":"3x5"}"#).is_err());
        let partial: SubstrateSpec = serde_json::from_str(r#"{"neurons":"9x9"}"#).unwrap();
        assert_eq!(partial.neurons, grid("9x9"));
        assert_eq!(partial.sensors, grid("3x5"));
    }

    #[test]
    fn nodes_are_ring_major_left_to_right() {
        let nodes = grid("3x5").nodes(180.0);
        assert_eq!(nodes.len(), 15);
        let deg: Vec<f64> = nodes[..5].iter().map(|n| n.phi.to_degrees()).collect();
        for (d, e) in deg.iter().zip([-90.0, -45.0, 0.0, 45.0, 90.0]) {
            assert!((d - e).abs() < 1e-9, "{deg:?}");
        }
        let rho: Vec<f64> = nodes.iter().step_by(5).map(|n| n.rho).collect();
        assert_eq!(rho, vec![1.0 / 3.0, 2.0 / 3.0, 1.0]);
        assert_eq!(nodes[7].ring, 1);
        assert_eq!(nodes[7].angle_index, 2);
        // Leftmost node of the outer ring is at x = −1, straight ahead at y = ρ.
        assert!(close(nodes[10].cartesian(), [-1.0, 0.0]));
        assert!(close(nodes[12].cartesian(), [0.0, 1.0]));
        assert!(close(nodes[14].coords(CoordMode::Polar), [1.0, 0.5]));
        // One angle points straight ahead.
        assert_eq!(grid("2x1").nodes(180.0)[1].phi, 0.0);
    }

    #[test]
    fn paper_wheels_are_the_outer_angles_of_the_middle_ring() {
        let w = grid("3x3").wheel_neurons().unwrap();
        assert_eq!(w, WheelNeurons { left: 3, right: 5 });
        let nodes = grid("3x3").nodes(180.0);
        assert!(close(nodes[w.left].cartesian(), [-2.0 / 3.0, 0.0]));
        assert!(close(nodes[w.right].cartesian(), [2.0 / 3.0, 0.0]));
        assert_eq!(grid("5x4").wheel_neurons().unwrap().left, 2 * 4);
        assert_eq!(
            grid("1x2").wheel_neurons().unwrap(),
            WheelNeurons { left: 0, right: 1 }
        );
        assert!(matches!(
            grid("3x1").wheel_neurons(),
            Err(SubstrateError::OneAngle(_))
        ));
    }

    #[test]
    fn wheel_neurons_keep_their_place_when_resampled() {
        let place = |s: &str| {
            let g = grid(s);
            let w = g.wheel_neurons().unwrap();
            let nodes = g.nodes(180.0);
            (
                nodes[w.left].coords(CoordMode::Cartesian),
                nodes[w.right].coords(CoordMode::Cartesian),
            )
        };
        let (l3, r3) = place("3x3");
        for other in ["9x9", "6x5", "3x7", "12x3", "9x17"] {
            let (l, r) = place(other);
            assert!(close(l, l3) && close(r, r3), "{other}: {l:?} {r:?}");
        }
        // Any resolution: L is left of R, mirrored, and on the ring nearest 2/3.
        for rings in 1..=12 {
            for angles in 2..=7 {
                let g = PolarGrid::new(rings, angles).unwrap();
                let w = g.wheel_neurons().unwrap();
                let nodes = g.nodes(180.0);
                let (l, r) = (nodes[w.left], nodes[w.right]);
                assert_eq!(l.ring, r.ring);
                assert!(l.cartesian()[0] < 0.0 && r.cartesian()[0] > 0.0);
                for ring in 0..rings {
                    assert!((l.rho - WHEEL_RADIUS).abs() <= (g.radius(ring) - WHEEL_RADIUS).abs());
                }
            }
        }
    }

    #[test]
    fn layout_of_the_paper_substrate() {
        let spec = SubstrateSpec::default();
        let l = spec.layout().unwrap();
        assert_eq!(l.inputs.len(), 1);
        assert_eq!(l.inputs[0].coords.len(), 15);
        assert_eq!(l.inputs[0].cppn_output, SURFACE_OUTPUT);
        assert_eq!(l.neurons.len(), 9);
        assert_eq!((l.bias_output, l.recurrent_output), (1, 2));
        assert_eq!(spec.cppn_outputs(), 3);
        assert_eq!(l.num_queries(), 9 * (15 + 9 + 1));
    }

    #[test]
    fn distance_sensors_add_a_second_sheet_on_output_three() {
        let (l, w) = build_layout(grid("3x5"), grid("3x3"), Some(7), CoordMode::Polar).unwrap();
        assert_eq!(l.inputs.len(), 2);
        assert_eq!(l.inputs[1].cppn_output, DISTANCE_OUTPUT);
        assert_eq!(l.inputs[1].coords.len(), 7);
        assert!(close(l.inputs[1].coords[0], [1.0, -0.5]));
        assert!(close(l.inputs[1].coords[6], [1.0, 0.5]));
        assert_eq!(w, WheelNeurons { left: 3, right: 5 });
        let spec = SubstrateSpec {
            distance_rays: Some(7),
            ..SubstrateSpec::default()
        };
        assert_eq!(spec.cppn_outputs(), 4);
        let spec = SubstrateSpec {
            distance_rays: Some(0),
            ..SubstrateSpec::default()
        };
        assert_eq!(spec.layout().unwrap_err(), SubstrateError::NoRays);
    }

    #[test]
    fn bad_specs_are_errors() {
        let spec = SubstrateSpec {
            neuron_fov: 360.0,
            ..SubstrateSpec::default()
        };
        assert!(
            spec.validate()
                .unwrap_err()
                .to_string()
                .contains("neuron_fov")
        );
        let spec = SubstrateSpec {
            fov: f64::NAN,
            ..SubstrateSpec::default()
        };
        assert!(spec.validate().is_err());
        let spec = SubstrateSpec {
            neurons: PolarGrid {
                rings: 0,
                angles: 3,
            },
            ..SubstrateSpec::default()
        };
        assert!(matches!(
            spec.layout(),
            Err(SubstrateError::GridSize { .. })
        ));
        assert!(build_layout(grid("3x5"), grid("4x1"), None, CoordMode::Cartesian).is_err());
    }

    #[test]
    fn node_order_matches_the_simulators_sensors() {
        let spec = SubstrateSpec {
            sensors: grid("4x7"),
            distance_rays: Some(6),
            ..SubstrateSpec::default()
        };
        let surface = vivae_sim::SurfaceSensors {
            rings: 4,
            angles: 7,
            ..vivae_sim::SurfaceSensors::default()
        };
        let places = surface.places();
        let nodes = spec.sensor_nodes();
        assert_eq!(places.len(), nodes.len());
        for (p, n) in places.iter().zip(&nodes) {
            assert_eq!((p.ring, p.angle_index), (n.ring, n.angle_index));
            assert!((p.angle - n.phi).abs() < 1e-12);
        }
        let rays = vivae_sim::DistanceSensors {
            rays: 6,
            ..vivae_sim::DistanceSensors::default()
        };
        let angles = rays.angles();
        let nodes = spec.sheets()[1].nodes();
        assert_eq!(angles.len(), nodes.len());
        for (a, n) in angles.iter().zip(&nodes) {
            assert!((a - n.phi).abs() < 1e-12);
        }
    }
}
