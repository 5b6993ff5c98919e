//! The messages a page's simulation sends: `scene` (arena and substrate
//! geometry, the ES network's places) and `frame` (robots and the selected
//! robot's sensors and neurons).

use std::fmt::Write as _;

use serde_json::{Value, json};

use super::Sim;
use crate::report_html::SceneData;
use crate::view::source::Source;
use vivae_lab::controller::es::RobotController;
use vivae_lab::tasks::driving::rollout::Drive;
use vivae_sim::Sensor;

/// Most in-between positions per robot a frame carries for the page's trails.
pub(super) const TRACE_POINTS: usize = 24;

impl Sim {
    /// The scene's `network`: for an ES network, the sensors' and then the
    /// wheel and hidden neurons' places in the CPPN plane `[−1, 1]²` (x right,
    /// y ahead), in the order of the frames' `neurons`; `null` otherwise.
    fn network_json(&self) -> Value {
        let (Some((RobotController::Es(es), _)), Some(setup)) =
            (&self.driving, self.experiment.es_setup())
        else {
            return Value::Null;
        };
        let net = es.network();
        let nodes: Vec<[f64; 2]> = setup
            .layout
            .outputs
            .iter()
            .chain(net.hidden())
            .copied()
            .collect();
        json!({
            "kind": "es-hyperneat",
            "sensors": setup.layout.inputs,
            "nodes": nodes,
            "hidden": es.hidden_neurons(),
            "links": es.expressed_links(),
        })
    }

    /// The `scene` message: arena picture and substrate geometry.
    pub fn scene_msg(&self, source: &Source) -> String {
        let spec = self.experiment.substrate_spec();
        let polar = |nodes: Vec<vivae_lab::controller::substrate::PolarNode>| -> Vec<[f64; 2]> {
            nodes.iter().map(|n| [n.rho, n.phi]).collect()
        };
        let wheels = self.experiment.wheels();
        json!({
            "type": "scene",
            "scene": SceneData::new(self.world.scenario(), &self.world),
            "scenario_index": self.scenario_index,
            "scenario_name": source.scenarios[self.scenario_index].0,
            "sensors": format!("{}x{}", spec.sensors.rings, spec.sensors.angles),
            "neurons": format!("{}x{}", spec.neurons.rings, spec.neurons.angles),
            "sensor_nodes": polar(spec.sensor_nodes()),
            "neuron_nodes": polar(spec.neuron_nodes()),
            "wheels": [wheels.left, wheels.right],
            "robots": self.world.robots().len(),
            "network": self.network_json(),
        })
        .to_string()
    }

    /// The `frame` message: every robot's pose and the selected robot's insides.
    ///
    /// Written by hand: it goes out up to 60 times a second per page.
    pub fn frame_msg(&mut self) -> String {
        let mut s = String::with_capacity(256 + 24 * self.surface.len());
        let _ = write!(
            s,
            r#"{{"type":"frame","step":{},"choice":{},"generation":{},"playing":{},"speed":{},"selected":{},"manual":{},"driver":{},"robots":["#,
            self.steps,
            serde_json::to_string(&self.choice.page_value()).unwrap_or_default(),
            self.driving_generation
                .map_or("null".to_string(), |g| g.to_string()),
            self.playing,
            self.speed,
            self.selected,
            self.manual.map_or("null".to_string(), |m| m.to_string()),
            serde_json::to_string(&self.driver).unwrap_or_default(),
        );
        for (i, r) in self.world.robots().iter().enumerate() {
            let _ = write!(
                s,
                r#"{}{{"x":{:.2},"y":{:.2},"h":{:.4},"v":{:.3},"odo":{:.1},"j":{},"p":["#,
                if i > 0 { "," } else { "" },
                r.pos.x,
                r.pos.y,
                r.heading,
                r.speed,
                r.odometer,
                self.jumps.get(i).copied().unwrap_or(0)
            );
            if let Some(t) = self.trace.get_mut(i) {
                // Evenly spaced positions before the last (which is `x`, `y`).
                let before = t.len().saturating_sub(1);
                let every = before.div_ceil(TRACE_POINTS).max(1);
                for (k, p) in t[..before].iter().rev().step_by(every).rev().enumerate() {
                    let _ = write!(s, "{}{:.1},{:.1}", if k > 0 { "," } else { "" }, p.x, p.y);
                }
                t.clear();
            }
            s.push_str("]}");
        }
        s.push(']');
        if let Some(i) = (self.selected < self.world.robots().len()).then_some(self.selected) {
            let grid = self.experiment.surface_grid();
            grid.read(&self.world, i, &mut self.surface);
            let places = grid.positions(&self.world, i);
            s.push_str(r#","sensors":["#);
            for (k, (p, v)) in places.iter().zip(&self.surface).enumerate() {
                let _ = write!(
                    s,
                    "{}{:.1},{:.1},{:.3}",
                    if k > 0 { "," } else { "" },
                    p.x,
                    p.y,
                    v
                );
            }
            s.push_str(r#"],"neurons":["#);
            // The dense sheet's neurons; an ES network's wheel then hidden
            // neurons, in the order of the scene's `network.nodes`.
            let neurons = match &self.driving {
                Some((RobotController::Polar(_), rollout)) => Some(rollout.outputs(i)),
                Some((RobotController::Es(es), rollout)) => rollout
                    .node_values(i)
                    .and_then(|v| v.get(Drive::num_inputs(es)..)),
                None => None,
            };
            for (k, v) in neurons.unwrap_or_default().iter().enumerate() {
                let _ = write!(s, "{}{:.4}", if k > 0 { "," } else { "" }, v);
            }
            let c = self.controls.get(i).copied().unwrap_or_default();
            let _ = write!(s, r#"],"wheels":[{:.4},{:.4}]"#, c[0], c[1]);
        }
        s.push('}');
        self.dirty = false;
        s
    }
}
