//! One page's live simulation and the messages it exchanges with the page.
//!
//! Page → server messages are JSON objects with a `type`; anything malformed,
//! unknown or out of range gets `{"type":"error","message":…}` and changes
//! nothing. Server → page: `info` (once), `scene` (arena, substrate), `frame`
//! (robots and the selected robot's sensors and neurons), `progress` (the
//! run's history, again whenever it grows) and `error`.
//!
//! This file holds the simulation ([`Sim`]) and its handling of messages;
//! [`choice`] finds the genome a page chose to drive, [`frames`] writes the
//! `scene` and `frame` messages.

mod choice;
mod frames;

use serde::Deserialize;
use serde_json::Value;
use vivae_sim::{DVec2, Scenario, Sensor, World};

use crate::view::keys::{Keys, REAL_TIME_STEPS};
use crate::view::source::{RunSnapshot, Source};
use choice::{Choice, chosen_genome, parse_choice};
use vivae_lab::config::Config;
use vivae_lab::controller::es::RobotController;
use vivae_lab::controller::substrate::PolarGrid;
use vivae_lab::io::one_line;
use vivae_lab::search::files::Member;
use vivae_lab::tasks::driving::episode::Episode;
use vivae_lab::tasks::driving::rollout::Rollout;

/// Most simulation steps computed for one frame, whatever the speed.
const MAX_STEPS_PER_FRAME: u32 = 400;
/// Most surface sensors a page may ask for.
const MAX_SENSORS: usize = 64 * 128;
/// Most neurons a page may ask for (decoding grows with sensors × neurons).
const MAX_NEURONS: usize = 400;
/// Most steps one `step` message may ask for, at any resolution.
const MAX_STEPS_PER_MESSAGE: u32 = 10_000;
/// Work one page message may cost, in robot-steps × controller size (see
/// [`Sim::step_cost`]): about a second of one core. A step's cost grows with
/// the resolution, so at the highest one a message gets a few dozen steps,
/// not thousands (which took minutes and went on after the page closed).
const WORK_PER_MESSAGE: u64 = 600_000_000;
/// Work one frame of playing may cost (a frame is due every 16 ms).
const WORK_PER_FRAME: u64 = WORK_PER_MESSAGE / 8;

/// A message from the page.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
enum ClientMsg {
    Play,
    Pause,
    Step {
        #[serde(default)]
        n: Option<u32>,
    },
    Speed {
        value: f64,
    },
    Controller {
        which: Value,
    },
    Drive {
        robot: Option<usize>,
    },
    Keys(Keys),
    Resolution {
        sensors: String,
        neurons: String,
    },
    Select {
        robot: usize,
    },
    Drag {
        robot: usize,
        x: f64,
        y: f64,
        #[serde(default)]
        heading: Option<f64>,
    },
    Reset,
    Scenario {
        index: usize,
    },
}

/// One page's simulation.
pub(crate) struct Sim {
    config: Config,
    scenario_index: usize,
    experiment: Episode,
    world: World,
    choice: Choice,
    /// Label of the genome driving, for the page.
    driver: String,
    /// Generation of the genome driving (`None`: nobody drives, or a front
    /// member, whose generation is not recorded); a followed run's newer
    /// champion does not change it until the page asks.
    driving_generation: Option<u32>,
    /// The chosen genome's controller and the robots' side of the episode.
    driving: Option<(RobotController, Rollout)>,
    manual: Option<usize>,
    keys: Keys,
    selected: usize,
    /// Per robot, how often it was put somewhere by hand (dragged): the page
    /// starts its trail afresh when this changes, however far it moved.
    jumps: Vec<u32>,
    /// Per robot, its positions after each step since the last frame: the
    /// page draws trails through them, so that a fast robot's trail follows
    /// the road, not a chord across the grass.
    trace: Vec<Vec<DVec2>>,
    controls: Vec<[f64; 2]>,
    surface: Vec<f64>,
    /// Running or paused.
    pub playing: bool,
    speed: f64,
    /// Fraction of a step carried to the next frame.
    carry: f64,
    steps: u64,
    /// Something changed that the page has not been sent.
    pub dirty: bool,
    /// The scene changed (arena or substrate).
    pub scene_dirty: bool,
}

/// Builds the experiment of `config` on `scenario`, using all its robots when
/// the config asks for more than it has.
fn experiment_for(config: &mut Config, scenario: &Scenario) -> Result<Episode, String> {
    if scenario.robots.len() < config.experiment.robots {
        config.experiment.robots = 0;
    }
    Episode::new(config, scenario).map_err(|e| one_line(&e.to_string()))
}

fn parse_scenario(name: &str, text: &str) -> Result<Scenario, String> {
    Scenario::from_svg(text, name, &vivae_sim::LoadOptions::default())
        .map_err(|e| one_line(&e.to_string()))
}

impl Sim {
    /// A paused simulation of the source's own scenario, driven by its best genome.
    pub fn new(source: &Source, snap: &RunSnapshot) -> Result<Sim, String> {
        let mut config = source.config.clone();
        let (name, text) = &source.scenarios[0];
        let scenario = parse_scenario(name, text)?;
        let experiment = experiment_for(&mut config, &scenario)?;
        let world = experiment.world().clone();
        let mut sim = Sim {
            config,
            scenario_index: 0,
            world,
            experiment,
            choice: Choice::None,
            driver: "nobody (drive a robot with the arrow keys)".into(),
            driving_generation: None,
            driving: None,
            manual: None,
            keys: Keys::default(),
            selected: 0,
            jumps: Vec::new(),
            trace: Vec::new(),
            controls: Vec::new(),
            surface: Vec::new(),
            playing: true,
            speed: 1.0,
            carry: 0.0,
            steps: 0,
            dirty: true,
            scene_dirty: true,
        };
        let choice = match source.start {
            Some(Member::Elite(cell)) => Choice::Elite(cell),
            Some(Member::Front(n)) => Choice::Front(n),
            None if snap.champion.is_some() => Choice::Champion,
            None => Choice::None,
        };
        sim.set_choice(choice, snap)?;
        Ok(sim)
    }

    /// Rebuilds the controller and the robots' rollout for the current choice and substrate.
    fn set_choice(&mut self, choice: Choice, snap: &RunSnapshot) -> Result<(), String> {
        let found = chosen_genome(choice, snap, &self.config)?;
        match found {
            None => {
                self.scene_dirty |= self.drives_es();
                self.driving = None;
                self.driving_generation = None;
                self.driver = "nobody (drive a robot with the arrow keys)".into();
            }
            Some((genome, label, generation)) => {
                // Decoding a large substrate takes a while: not on the async workers' time.
                let controller =
                    tokio::task::block_in_place(|| self.experiment.robot_controller(genome))
                        .map_err(|e| format!("the genome's {e}"))?;
                let rollout = self.experiment.rollout(&controller);
                // An ES network's neurons are where its CPPN put them: the
                // page gets their places in the scene, once per controller.
                self.scene_dirty |= controller.as_es().is_some() || self.drives_es();
                self.driving = Some((controller, rollout));
                self.driving_generation = generation;
                self.driver = label;
            }
        }
        self.choice = choice;
        self.resize_buffers();
        self.dirty = true;
        Ok(())
    }

    /// Whether an ES network drives (its neurons are not the dense sheet's).
    fn drives_es(&self) -> bool {
        matches!(&self.driving, Some((RobotController::Es(_), _)))
    }

    fn resize_buffers(&mut self) {
        let n = self.world.robots().len();
        self.controls = vec![[0.0; 2]; n];
        self.jumps.resize(n, 0);
        self.trace.resize_with(n, Vec::new);
        self.trace.iter_mut().for_each(Vec::clear);
        self.surface = vec![0.0; self.experiment.surface_grid().len()];
        self.selected = self.selected.min(n.saturating_sub(1));
        if self.manual.is_some_and(|m| m >= n) {
            self.manual = None;
        }
    }

    /// One simulation step: every controller (or the keyboard) moves its robot,
    /// through the same rollout loop evolution and replay use.
    fn step_once(&mut self) {
        let manual = self.manual.map(|m| (m, self.keys.controls()));
        match &mut self.driving {
            Some((controller, rollout)) => {
                rollout.step(&mut self.world, controller, manual);
                for (i, c) in self.controls.iter_mut().enumerate() {
                    *c = rollout.controls(i);
                }
            }
            None => {
                self.controls.fill([0.0, 0.0]);
                if let Some((m, wheels)) = manual
                    && let Some(c) = self.controls.get_mut(m)
                {
                    *c = wheels;
                }
                self.world.step(&self.controls);
            }
        }
        for (t, r) in self.trace.iter_mut().zip(self.world.robots()) {
            t.push(r.pos);
        }
        self.steps += 1;
        self.dirty = true;
    }

    /// Advances by one frame of `seconds` at the current speed (if playing).
    pub fn advance(&mut self, seconds: f64) {
        if !self.playing {
            return;
        }
        self.carry += self.speed * REAL_TIME_STEPS * seconds;
        let n = (self.carry.floor() as u32)
            .min(MAX_STEPS_PER_FRAME)
            .min(self.steps_within(WORK_PER_FRAME));
        self.carry = (self.carry - f64::from(n)).min(1.0);
        tokio::task::block_in_place(|| {
            for _ in 0..n {
                self.step_once();
            }
        });
    }

    /// Puts every robot back at its start and clears the controllers' state.
    fn reset(&mut self) {
        self.world = self.experiment.world().clone();
        self.trace.iter_mut().for_each(Vec::clear);
        if let Some((controller, rollout)) = &mut self.driving {
            rollout.reset(controller);
        }
        self.steps = 0;
        self.carry = 0.0;
        self.dirty = true;
        self.scene_dirty = true;
    }

    /// Rebuilds the experiment (new scenario or resolution), keeping the genome choice.
    fn rebuild(
        &mut self,
        mut config: Config,
        index: usize,
        source: &Source,
        snap: &RunSnapshot,
    ) -> Result<(), String> {
        vivae_lab::tasks::check(&config).map_err(|e| one_line(&e.to_string()))?;
        let (name, text) = source
            .scenarios
            .get(index)
            .ok_or_else(|| format!("no scenario {index}"))?;
        if let Some(Some(why)) = source.unusable.get(index) {
            return Err(format!("scenario {name} cannot be driven: {why}"));
        }
        let scenario = parse_scenario(name, text)?;
        let experiment = experiment_for(&mut config, &scenario)?;
        let old = (
            std::mem::replace(&mut self.experiment, experiment),
            std::mem::replace(&mut self.config, config),
            self.scenario_index,
        );
        self.scenario_index = index;
        let scenario_changed = old.2 != index;
        if scenario_changed {
            self.world = self.experiment.world().clone();
            self.steps = 0;
        }
        if let Err(e) = self.set_choice(self.choice, snap) {
            // Keep the page's simulation as it was.
            self.experiment = old.0;
            self.config = old.1;
            self.scenario_index = old.2;
            if scenario_changed {
                self.world = self.experiment.world().clone();
            }
            self.set_choice(self.choice, snap)?;
            return Err(e);
        }
        self.scene_dirty = true;
        Ok(())
    }

    /// Handles one text message from the page; `Err` is sent back as an error.
    pub fn handle(
        &mut self,
        text: &str,
        source: &Source,
        snap: &RunSnapshot,
    ) -> Result<(), String> {
        let msg: ClientMsg = serde_json::from_str(text).map_err(|e| format!("bad message: {e}"))?;
        match msg {
            ClientMsg::Play => self.playing = true,
            ClientMsg::Pause => self.playing = false,
            ClientMsg::Step { n } => self.step_paused(n.unwrap_or(1))?,
            ClientMsg::Speed { value } => {
                if !(value.is_finite() && (0.05..=200.0).contains(&value)) {
                    return Err(format!("speed {value}: must be 0.05 to 200"));
                }
                self.speed = value;
            }
            ClientMsg::Controller { which } => self.set_choice(parse_choice(&which)?, snap)?,
            ClientMsg::Drive { robot } => {
                if let Some(i) = robot {
                    self.check_robot(i)?;
                    self.selected = i;
                }
                self.manual = robot;
                self.keys = Keys::default();
            }
            ClientMsg::Keys(keys) => self.keys = keys,
            ClientMsg::Resolution { sensors, neurons } => {
                self.set_resolution(&sensors, &neurons, source, snap)?;
            }
            ClientMsg::Select { robot } => {
                self.check_robot(robot)?;
                self.selected = robot;
                self.dirty = true;
            }
            ClientMsg::Drag {
                robot,
                x,
                y,
                heading,
            } => self.drag(robot, (x, y), heading)?,
            ClientMsg::Reset => self.reset(),
            ClientMsg::Scenario { index } => {
                self.rebuild(self.config.clone(), index, source, snap)?;
            }
        }
        self.dirty = true;
        Ok(())
    }

    /// `Err` unless robot `i` exists.
    fn check_robot(&self, i: usize) -> Result<(), String> {
        let robots = self.world.robots().len();
        if i < robots {
            Ok(())
        } else {
            Err(format!("no robot {i} (there are {robots})"))
        }
    }

    /// The work of one simulation step, in the units of [`WORK_PER_MESSAGE`]:
    /// per robot, sensing every surface sensor and running the controller
    /// (each neuron reads every sensor and neuron).
    fn step_cost(&self) -> u64 {
        let spec = self.experiment.substrate_spec();
        let sensors = (spec.sensors.rings as u64).saturating_mul(spec.sensors.angles as u64);
        let neurons = (spec.neurons.rings as u64).saturating_mul(spec.neurons.angles as u64);
        let robots = self.world.robots().len().max(1) as u64;
        let per_robot = sensors.saturating_add(
            neurons.saturating_mul(sensors.saturating_add(neurons).saturating_add(2)),
        );
        robots.saturating_mul(per_robot.max(1))
    }

    /// Most steps (at least 1) whose work fits in `budget` at the current resolution.
    fn steps_within(&self, budget: u64) -> u32 {
        let n = (budget / self.step_cost()).clamp(1, u64::from(MAX_STEPS_PER_MESSAGE));
        n as u32
    }

    /// Pauses and advances `n` steps: 1 to 10000, and no more than about a
    /// second of work at the current resolution.
    fn step_paused(&mut self, n: u32) -> Result<(), String> {
        if n == 0 || n > MAX_STEPS_PER_MESSAGE {
            return Err(format!("step {n}: must be 1 to {MAX_STEPS_PER_MESSAGE}"));
        }
        let most = self.steps_within(WORK_PER_MESSAGE);
        if n > most {
            let spec = self.experiment.substrate_spec();
            return Err(format!(
                "step {n}: at most {most} steps per message at this resolution \
                 (sensors {}x{}, neurons {}x{}); send several messages",
                spec.sensors.rings, spec.sensors.angles, spec.neurons.rings, spec.neurons.angles
            ));
        }
        self.playing = false;
        tokio::task::block_in_place(|| {
            for _ in 0..n {
                self.step_once();
            }
        });
        Ok(())
    }

    /// Re-samples the substrate at `sensors` and `neurons` (RINGSxANGLES).
    fn set_resolution(
        &mut self,
        sensors: &str,
        neurons: &str,
        source: &Source,
        snap: &RunSnapshot,
    ) -> Result<(), String> {
        let parse = |what: &str, s: &str, max: usize| -> Result<PolarGrid, String> {
            let g: PolarGrid = s
                .parse()
                .map_err(|e| format!("{what} {s:?}: {}", one_line(&format!("{e}"))))?;
            if g.rings.saturating_mul(g.angles) > max {
                return Err(format!("{what} {s}: at most {max} in the viewer"));
            }
            Ok(g)
        };
        let s = parse("sensors", sensors, MAX_SENSORS)?;
        let n = parse("neurons", neurons, MAX_NEURONS)?;
        let mut config = self.config.clone();
        config.surface_sensors.rings = s.rings;
        config.surface_sensors.angles = s.angles;
        config.substrate.neurons = n;
        self.rebuild(config, self.scenario_index, source, snap)
    }

    /// Puts `robot` at `(x, y)` (inside the arena), facing `heading` (default: as it was), and selects it.
    fn drag(
        &mut self,
        robot: usize,
        (x, y): (f64, f64),
        heading: Option<f64>,
    ) -> Result<(), String> {
        self.check_robot(robot)?;
        let sc = self.world.scenario();
        let inside = x.is_finite()
            && y.is_finite()
            && (0.0..=sc.width()).contains(&x)
            && (0.0..=sc.height()).contains(&y);
        if !inside {
            return Err(format!("drag to ({x}, {y}): outside the arena"));
        }
        let heading = heading.unwrap_or(self.world.robots()[robot].heading);
        if !heading.is_finite() {
            return Err("drag: heading must be a number".into());
        }
        self.world.set_pose(robot, DVec2::new(x, y), heading);
        if let Some(j) = self.jumps.get_mut(robot) {
            *j = j.wrapping_add(1);
        }
        if let Some(t) = self.trace.get_mut(robot) {
            t.clear();
        }
        self.selected = robot;
        self.dirty = true;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::frames::TRACE_POINTS;
    use super::*;

    /// Runs `f` on a fresh simulation of the default source, inside a Tokio
    /// runtime (decoding uses `block_in_place`).
    fn with_sim(f: impl FnOnce(&mut Sim, &Source, &RunSnapshot)) {
        with_sim_of(&Source::load(None, None).unwrap(), f);
    }

    /// [`with_sim`] on `source`.
    fn with_sim_of(source: &Source, f: impl FnOnce(&mut Sim, &Source, &RunSnapshot)) {
        let snap = source.snapshot();
        let rt = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .build()
            .unwrap();
        rt.block_on(async {
            let mut sim = Sim::new(source, &snap).unwrap();
            f(&mut sim, source, &snap);
        });
    }

    /// The paper's champion (tests/data) as a genome file recording an ES-HyperNEAT config.
    fn es_champion_source() -> Source {
        let mut config = Config::default();
        config.substrate.kind = vivae_lab::controller::es::SubstrateKind::EsHyperneat;
        champion_source("es", &config)
    }

    /// The paper's champion (tests/data) as a genome file recording `config`.
    fn champion_source(name: &str, config: &Config) -> Source {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(root.join("tests/data/paper-champion.json")).unwrap();
        let mut champion: Value = serde_json::from_str(&text).unwrap();
        champion["config"] = serde_json::to_value(config).unwrap();
        let dir = std::env::temp_dir().join(format!("vivae-view-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(format!("{name}-champion.json"));
        std::fs::write(&path, champion.to_string()).unwrap();
        let source = Source::load(Some(&path), None).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        source
    }

    #[test]
    fn a_360_degree_sheet_drives_and_resamples_in_the_viewer() {
        let mut config = Config::default();
        config.surface_sensors.fov = 360.0;
        config.surface_sensors.angles = 8;
        with_sim_of(&champion_source("omni", &config), |sim, source, snap| {
            for (resolution, n) in [("3x8", 24), ("4x24", 96), ("2x5", 10)] {
                if resolution != "3x8" {
                    let msg = format!(
                        r#"{{"type":"resolution","sensors":"{resolution}","neurons":"5x5"}}"#
                    );
                    sim.handle(&msg, source, snap).unwrap();
                }
                let scene: Value = serde_json::from_str(&sim.scene_msg(source)).unwrap();
                assert_eq!(scene["sensors"], resolution);
                let nodes: Vec<[f64; 2]> =
                    serde_json::from_value(scene["sensor_nodes"].clone()).unwrap();
                assert_eq!(nodes.len(), n);
                // The sheet looks all round: its angles reach behind the robot on both sides.
                let (lo, hi) = (nodes.iter().map(|p| p[1]))
                    .fold((0.0f64, 0.0f64), |(lo, hi), a| (lo.min(a), hi.max(a)));
                assert!(lo < -3.1 && hi > 3.1, "{lo} {hi}");
                sim.handle(r#"{"type":"step","n":30}"#, source, snap)
                    .unwrap();
                let frame: Value = serde_json::from_str(&sim.frame_msg()).unwrap();
                let sensors: Vec<f64> = serde_json::from_value(frame["sensors"].clone()).unwrap();
                assert_eq!(sensors.len(), 3 * n, "x, y and value of each sensor");
                assert!(sensors.iter().all(|v| v.is_finite()));
            }
        });
    }

    #[test]
    fn an_es_network_is_sent_where_its_neurons_are_and_how_active() {
        with_sim_of(&es_champion_source(), |sim, source, snap| {
            let es = sim.driving.as_ref().unwrap().0.as_es().unwrap().clone();
            let hidden = es.hidden_neurons();
            assert!(hidden > 0);
            let scene: Value = serde_json::from_str(&sim.scene_msg(source)).unwrap();
            let net = &scene["network"];
            assert_eq!(net["hidden"], hidden);
            assert_eq!(net["links"], es.expressed_links());
            assert_eq!(net["sensors"].as_array().unwrap().len(), 15);
            let nodes: Vec<[f64; 2]> = serde_json::from_value(net["nodes"].clone()).unwrap();
            assert_eq!(nodes.len(), 2 + hidden);
            assert_eq!(&nodes[2..], es.network().hidden());
            sim.handle(r#"{"type":"step","n":20}"#, source, snap)
                .unwrap();
            let frame: Value = serde_json::from_str(&sim.frame_msg()).unwrap();
            let values: Vec<f64> = serde_json::from_value(frame["neurons"].clone()).unwrap();
            assert_eq!(values.len(), 2 + hidden);
            assert!(values.iter().all(|v| v.abs() <= 1.0), "{values:?}");
            assert!(values[2..].iter().any(|&v| v != 0.0), "{values:?}");
            // The places go out again when the controller changes, not every frame.
            sim.scene_dirty = false;
            sim.handle(r#"{"type":"step","n":1}"#, source, snap)
                .unwrap();
            assert!(!sim.scene_dirty);
            sim.handle(r#"{"type":"controller","which":"none"}"#, source, snap)
                .unwrap();
            assert!(sim.scene_dirty);
            assert!(sim.scene_msg(source).contains(r#""network":null"#));
            let frame: Value = serde_json::from_str(&sim.frame_msg()).unwrap();
            assert_eq!(frame["neurons"], serde_json::json!([]));
        });
    }

    #[test]
    fn arrow_keys_turn_the_right_way() {
        let k = |up, down, left, right| {
            Keys {
                up,
                down,
                left,
                right,
            }
            .controls()
        };
        assert_eq!(k(false, false, false, false), [0.0, 0.0]);
        let fwd = k(true, false, false, false);
        assert!(fwd[0] > 0.0 && fwd[0] == fwd[1]);
        let l = k(true, false, true, false);
        assert!(l[0] < l[1], "turning left slows the left wheel");
        let spin = k(false, false, false, true);
        assert!(spin[0] > 0.0 && spin[1] < 0.0);
        assert!(k(false, true, false, false)[0] < 0.0);
    }

    #[test]
    fn hostile_messages_are_refused_and_change_nothing() {
        with_sim(|sim, source, snap| {
            let before = sim.frame_msg();
            for bad in [
                "",
                "null",
                "{}",
                "[1,2]",
                r#"{"type":"nope"}"#,
                r#"{"type":"speed","value":1e308}"#,
                r#"{"type":"speed","value":-1}"#,
                r#"{"type":"step","n":4000000000}"#,
                r#"{"type":"select","robot":99}"#,
                r#"{"type":"drag","robot":0,"x":-5,"y":3}"#,
                r#"{"type":"drag","robot":7,"x":5,"y":3}"#,
                r#"{"type":"resolution","sensors":"100000x100000","neurons":"3x3"}"#,
                r#"{"type":"resolution","sensors":"3x5","neurons":"0x3"}"#,
                r#"{"type":"resolution","sensors":"3x5","neurons":"../../etc"}"#,
                r#"{"type":"scenario","index":12345}"#,
                r#"{"type":"controller","which":"champion"}"#,
                r#"{"type":"controller","which":-3}"#,
                r#"{"type":"controller","which":7}"#,
                r#"{"type":"controller","which":{"elite":0}}"#,
                r#"{"type":"controller","which":{"front":0}}"#,
                r#"{"type":"controller","which":{}}"#,
                r#"{"type":"controller","which":[1]}"#,
                r#"{"type":"controller","which":{"elite":-1}}"#,
                r#"{"type":"controller","which":{"elite":1.5}}"#,
                r#"{"type":"controller","which":{"elite":"3"}}"#,
                r#"{"type":"controller","which":{"elite":1e30}}"#,
                r#"{"type":"controller","which":{"elite":18446744073709551615}}"#,
                r#"{"type":"controller","which":{"elite":1,"front":2}}"#,
                r#"{"type":"controller","which":{"champion":1}}"#,
                r#"{"type":"controller","which":"elite:3"}"#,
            ] {
                assert!(sim.handle(bad, source, snap).is_err(), "accepted {bad:?}");
            }
            assert_eq!(sim.frame_msg(), before);
        });
    }

    #[test]
    fn a_scenario_without_robots_is_refused_with_its_reason_and_changes_nothing() {
        let mut source = Source::load(None, None).unwrap();
        let bare: String = vivae_sim::ROADS_SVG
            .lines()
            .filter(|l| !l.contains("ControlledRobot"))
            .collect::<Vec<_>>()
            .join("\n");
        source.scenarios.push(("bare.svg".into(), bare));
        source.unusable = source
            .scenarios
            .iter()
            .map(|(n, t)| crate::view::source::unusable(n, t))
            .collect();
        assert_eq!(source.unusable, [None, Some("no robots".to_string())]);
        assert!(source.unusable_note().unwrap().contains("bare.svg"));
        with_sim_of(&source, |sim, source, snap| {
            let scene = sim.scene_msg(source);
            let err = sim
                .handle(r#"{"type":"scenario","index":1}"#, source, snap)
                .unwrap_err();
            assert_eq!(err, "scenario bare.svg cannot be driven: no robots");
            assert_eq!(sim.scene_msg(source), scene);
        });
    }

    /// The default source with a made-up archive (cells 3 and 8) and front
    /// (members 0 and 1) of a first generation's genomes.
    fn source_with_members() -> (Source, RunSnapshot) {
        use vivae_lab::search::files::{ArchiveLine, FrontLine};
        let source = Source::load(None, None).unwrap();
        let scenario = vivae_lab::tasks::scenarios::load_scenario(None)
            .unwrap()
            .scenario;
        let spec = Episode::new(&source.config, &scenario).unwrap().cppn_spec();
        let population = vivae_neat::Population::new(source.config.neat.clone(), spec, 3).unwrap();
        let g = |i: usize| population.genomes()[i].clone();
        let mut snap = source.snapshot();
        snap.elites = [(3, 1.25, 2), (8, 2.5, 4)]
            .into_iter()
            .enumerate()
            .map(|(i, (cell, fitness, generation))| ArchiveLine {
                cell,
                fitness,
                generation,
                behaviour: vec![0.125 * i as f64, 0.5],
                genome: g(i),
            })
            .collect();
        snap.front = (0..2)
            .map(|member| FrontLine {
                member,
                fitness: 3.0 - member as f64,
                objectives: vec![3.0 - member as f64, 0.25 * member as f64],
                genome: g(2 + member),
            })
            .collect();
        (source, snap)
    }

    #[test]
    fn an_elite_or_a_front_member_drives_when_chosen_and_the_frame_says_which() {
        let (source, snap) = source_with_members();
        let rt = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .build()
            .unwrap();
        rt.block_on(async {
            let mut sim = Sim::new(&source, &snap).unwrap();
            let frame =
                |sim: &mut Sim| -> Value { serde_json::from_str(&sim.frame_msg()).unwrap() };
            let send = |sim: &mut Sim, message: &str| sim.handle(message, &source, &snap);
            assert_eq!(frame(&mut sim)["choice"], "none");
            send(&mut sim, r#"{"type":"controller","which":{"elite":8}}"#).unwrap();
            let f = frame(&mut sim);
            assert_eq!(f["choice"], "elite:8");
            assert_eq!(f["generation"], 4);
            assert_eq!(
                f["driver"],
                "elite of cell 8 (generation 4, fitness 2.500; x 0.12, y 0.50)"
            );
            send(&mut sim, r#"{"type":"controller","which":{"front":1}}"#).unwrap();
            let f = frame(&mut sim);
            assert_eq!(f["choice"], "front:1");
            assert_eq!(
                f["generation"],
                Value::Null,
                "a front member's generation is not recorded"
            );
            assert_eq!(
                f["driver"],
                "front member 1 (fitness 2.000; fitness 2.00, contacts 0.25)"
            );
            // Cells and members that are not there are refused, naming what there is.
            let before = sim.frame_msg();
            let err = send(&mut sim, r#"{"type":"controller","which":{"elite":4}}"#).unwrap_err();
            assert_eq!(err, "no elite in cell 4 (the run has 2 elites)");
            let err = send(&mut sim, r#"{"type":"controller","which":{"front":2}}"#).unwrap_err();
            assert_eq!(err, "no front member 2 (the run has 2 members)");
            assert_eq!(sim.frame_msg(), before);
            // The choice survives a re-sampled substrate.
            send(
                &mut sim,
                r#"{"type":"resolution","sensors":"9x9","neurons":"9x9"}"#,
            )
            .unwrap();
            assert_eq!(frame(&mut sim)["choice"], "front:1");
        });
        // `--elite 3` starts a page on that elite.
        let mut started = source.clone();
        started.start = Some(Member::Elite(3));
        rt.block_on(async {
            let mut sim = Sim::new(&started, &snap).unwrap();
            let f: Value = serde_json::from_str(&sim.frame_msg()).unwrap();
            assert_eq!(f["choice"], "elite:3");
        });
    }

    /// Robot 0 taken over by hand, with the forward key held.
    fn drive_forward(sim: &mut Sim, source: &Source, snap: &RunSnapshot) {
        sim.handle(r#"{"type":"drive","robot":0}"#, source, snap)
            .unwrap();
        sim.handle(
            r#"{"type":"keys","up":true,"down":false,"left":false,"right":false}"#,
            source,
            snap,
        )
        .unwrap();
    }

    #[test]
    fn a_frame_carries_the_positions_since_the_last_one() {
        with_sim(|sim, source, snap| {
            sim.frame_msg();
            drive_forward(sim, source, snap);
            let path = |sim: &mut Sim| -> Vec<f64> {
                let frame: serde_json::Value = serde_json::from_str(&sim.frame_msg()).unwrap();
                serde_json::from_value(frame["robots"][0]["p"].clone()).unwrap()
            };
            sim.handle(r#"{"type":"step","n":10}"#, source, snap)
                .unwrap();
            // Nine positions before the one the frame ends on, in order.
            let p = path(sim);
            assert_eq!(p.len(), 18, "{p:?}");
            let x = sim.world.robots()[0].pos.x;
            assert!(p.chunks(2).all(|q| q[0] < x), "{p:?} then {x}");
            assert!(p.windows(4).step_by(2).all(|w| w[0] < w[2]), "{p:?}");
            // Many steps: at most TRACE_POINTS of them, the last close to the end.
            sim.handle(r#"{"type":"step","n":200}"#, source, snap)
                .unwrap();
            let p = path(sim);
            assert!(
                p.len() <= 2 * TRACE_POINTS && p.len() >= TRACE_POINTS,
                "{}",
                p.len()
            );
            assert_eq!(path(sim), Vec::<f64>::new());
        });
    }

    #[test]
    fn keyboard_driving_moves_the_robot_forward() {
        with_sim(|sim, source, snap| {
            let start = sim.world.robots()[0].pos;
            drive_forward(sim, source, snap);
            sim.handle(r#"{"type":"step","n":40}"#, source, snap)
                .unwrap();
            let r = &sim.world.robots()[0];
            assert!(
                r.pos.distance(start) > 20.0,
                "moved {}",
                r.pos.distance(start)
            );
            // Reset puts it back.
            sim.handle(r#"{"type":"reset"}"#, source, snap).unwrap();
            assert_eq!(sim.world.robots()[0].pos, start);
        });
    }

    #[test]
    fn dragging_places_a_robot_and_scenarios_switch_by_index() {
        with_sim(|sim, source, snap| {
            sim.handle(
                r#"{"type":"drag","robot":2,"x":100.5,"y":200.25,"heading":1.0}"#,
                source,
                snap,
            )
            .unwrap();
            let r = &sim.world.robots()[2];
            assert_eq!((r.pos.x, r.pos.y), (100.5, 200.25));
            assert_eq!(sim.selected, 2);
            // The page starts robot 3's trail afresh: its jump count changed, no other's.
            let frame: serde_json::Value = serde_json::from_str(&sim.frame_msg()).unwrap();
            assert_eq!(frame["selected"], 2);
            let jumps: Vec<u64> = (0..5)
                .map(|i| frame["robots"][i]["j"].as_u64().unwrap())
                .collect();
            assert_eq!(jumps, [0, 0, 1, 0, 0]);
            sim.handle(r#"{"type":"scenario","index":0}"#, source, snap)
                .unwrap();
            assert!(sim.scene_msg(source).contains(r#""scenario_index":0"#));
            // Re-sampling keeps the scenario and changes the substrate the page is sent.
            sim.handle(
                r#"{"type":"resolution","sensors":"32x96","neurons":"9x9"}"#,
                source,
                snap,
            )
            .unwrap();
            let scene: serde_json::Value = serde_json::from_str(&sim.scene_msg(source)).unwrap();
            assert_eq!(scene["sensor_nodes"].as_array().unwrap().len(), 32 * 96);
            assert_eq!(scene["neuron_nodes"].as_array().unwrap().len(), 81);
        });
    }
}
