//! `vivae view` of a predator–prey run: a hunter and a prey, each driven by
//! its own side's champion of any generation (from `hall-of-fame.jsonl`), or
//! the prey by a person with the arrow keys, meet in the run's arena.
//!
//! Page → server messages are JSON objects with a `type`: `play`, `pause`,
//! `reset`, `step {n}`, `speed {value}`, `pick {hunter, prey}` (generations),
//! `human {on}` (the keyboard drives the prey), `keys {up, down, left,
//! right}`. Anything malformed, unknown or out of range gets
//! `{"type":"error","message":…}` and changes nothing. Server → page: `info`
//! (once: the generations on offer, the champions), `scene` (the arena, which
//! robot is which), `frame` (robots, trails since the last frame, the step,
//! the catch) and `error`.

pub(super) mod server;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_json::{Value, json};
use vivae_lab::io::{one_line, read_text};
use vivae_lab::rundir::files as run_files;
use vivae_lab::tasks::predator_prey::brain::Brain;
use vivae_lab::tasks::predator_prey::run::{HallEntry, files, read_champions};
use vivae_lab::tasks::predator_prey::{Arena, INPUTS, OUTPUTS, Side};
use vivae_lab::tasks::read_config;
use vivae_lab::tasks::robot::wheels;
use vivae_lab::tasks::scenarios::load_scenario;
use vivae_neat::Genome;
use vivae_sim::World;

use super::figures::{HUNTER_COLOUR, PREY_COLOUR};
use crate::figures::convergence::hex;
use crate::report_html::SceneData;
use crate::view::keys::{Keys, REAL_TIME_STEPS};
use crate::view::{OwnPage, ViewOptions};

/// The page of a predator–prey run.
pub(crate) const PAGE: OwnPage = OwnPage {
    open,
    serve: |runtime, served| runtime.block_on(server::serve(served)),
};

/// The predator–prey run in `dir` as its page shows it: the line saying so,
/// with its generations of champions; refused in one line if it cannot be shown.
fn open(dir: &Path, options: &ViewOptions) -> vivae_lab::Result<String> {
    if options.member.is_some() || options.scenarios.is_some() {
        return Err(vivae_lab::io::bad_input(format!(
            "{}: a predator-prey run: --elite, --front and --scenarios do not apply (the page picks any generation's hunter and prey)",
            dir.display()
        )));
    }
    let generations = Hall::load(dir)?.generations();
    Ok(format!(
        "showing predator-prey run {} ({generations} generations of champions; Ctrl-C stops the server)",
        dir.display()
    ))
}

/// Most simulation steps computed for one frame, whatever the speed.
const MAX_STEPS_PER_FRAME: u32 = 400;
/// Most steps one `step` message may ask for (an episode is at most this long in the viewer).
const MAX_STEPS_PER_MESSAGE: u32 = 10_000;

/// A predator–prey run as the viewer shows it: its arena and every
/// generation's champions of both sides.
pub(crate) struct Hall {
    dir: PathBuf,
    arena: Arena,
    scene: SceneData,
    /// Per generation, its best hunter and its fitness.
    hunters: Vec<(Genome, f64)>,
    /// Per generation, its best prey and its fitness.
    prey: Vec<(Genome, f64)>,
    /// The master tournament's champions' generations (hunter, prey), once the run has stopped.
    champions: Option<(u32, u32)>,
}

impl Hall {
    /// Reads the run in `dir`; a last line of `hall-of-fame.jsonl` that a
    /// running run is still writing is left out.
    pub(crate) fn load(dir: &Path) -> vivae_lab::Result<Hall> {
        let config = read_config(&dir.join(run_files::CONFIG))?;
        let loaded = load_scenario(Some(&dir.join(run_files::SCENARIO)))?;
        let arena = Arena::of_config(&loaded.scenario, &config)
            .map_err(|e| vivae_lab::io::bad_input(e.to_string()))?;
        let scene = SceneData::new(&loaded.scenario, arena.world());
        let path = dir.join(files::HALL);
        let text = read_text(&path)?;
        let (mut hunters, mut prey) = (Vec::new(), Vec::new());
        let lines: Vec<&str> = text.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let entry: HallEntry = match serde_json::from_str(line) {
                Ok(e) => e,
                Err(_) if i + 1 == lines.len() && !text.ends_with('\n') => break,
                Err(e) => {
                    return Err(vivae_lab::Error::RunFile {
                        path,
                        reason: format!("line {}: {}", i + 1, one_line(&e.to_string())),
                    });
                }
            };
            let side = if entry.side == Side::Hunter.name() {
                &mut hunters
            } else {
                &mut prey
            };
            if entry.generation as usize == side.len() {
                side.push((entry.genome, entry.fitness));
            }
        }
        let n = hunters.len().min(prey.len());
        hunters.truncate(n);
        prey.truncate(n);
        let champions = (dir.join(files::CHAMPIONS).is_file())
            .then(|| read_champions(dir).ok())
            .flatten()
            .map(|c| (c.hunter.generation, c.prey.generation))
            .filter(|&(h, p)| (h as usize) < n && (p as usize) < n);
        Ok(Hall {
            dir: dir.to_path_buf(),
            arena,
            scene,
            hunters,
            prey,
            champions,
        })
    }

    /// Generations of champions on offer.
    pub(crate) fn generations(&self) -> usize {
        self.hunters.len()
    }

    /// The `info` message: the run, each generation's champions' fitness, the master tournament's champions.
    pub(crate) fn info(&self) -> String {
        let fit = |side: &[(Genome, f64)]| side.iter().map(|g| g.1).collect::<Vec<_>>();
        json!({
            "type": "info",
            "source": format!("showing predator-prey run {}", self.dir.display()),
            "generations": self.generations(),
            "hunter_fitness": fit(&self.hunters),
            "prey_fitness": fit(&self.prey),
            "champions": self.champions.map(|(h, p)| json!({"hunter": h, "prey": p})),
            "real_time_steps": REAL_TIME_STEPS,
        })
        .to_string()
    }
}

/// A message from the page.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
enum ClientMsg {
    Play,
    Pause,
    Reset,
    Step { n: u32 },
    Speed { value: f64 },
    Pick { hunter: u32, prey: u32 },
    Human { on: bool },
    Keys(Keys),
}

/// One page's game: the hunter and the prey of the chosen generations.
pub(crate) struct Game {
    world: World,
    picked: (u32, u32),
    hunter: Brain,
    prey: Brain,
    /// The keyboard drives the prey.
    human: bool,
    keys: Keys,
    step: u32,
    /// The step of the catch, once it happened.
    caught: Option<u32>,
    /// Per robot, its positions since the last frame (the page's trails).
    trace: Vec<Vec<[f64; 2]>>,
    pub playing: bool,
    speed: f64,
    carry: f64,
    /// Something changed that the page has not been sent.
    pub dirty: bool,
}

impl Game {
    /// The master tournament's champions (or the last generation's) meeting, playing.
    pub(crate) fn new(hall: &Hall) -> Result<Game, String> {
        let last = hall.generations().checked_sub(1).ok_or_else(|| {
            "the run has no generation yet: wait for its first one and reload".to_string()
        })? as u32;
        let picked = hall.champions.unwrap_or((last, last));
        let mut game = Game {
            world: hall.arena.world().clone(),
            picked,
            hunter: hall
                .arena
                .brain(Side::Hunter, &hall.hunters[picked.0 as usize].0),
            prey: hall
                .arena
                .brain(Side::Prey, &hall.prey[picked.1 as usize].0),
            human: false,
            keys: Keys::default(),
            step: 0,
            caught: None,
            trace: vec![Vec::new(); hall.arena.world().robots().len()],
            playing: true,
            speed: 1.0,
            carry: 0.0,
            dirty: true,
        };
        game.reset(hall);
        Ok(game)
    }

    /// The `scene` message: the arena and which robot is which, in which colour.
    pub(crate) fn scene_msg(hall: &Hall) -> String {
        let (h, p) = (hall.arena.robot(Side::Hunter), hall.arena.robot(Side::Prey));
        json!({
            "type": "scene",
            "scene": hall.scene,
            "hunter": h,
            "prey": p,
            "colours": [hex(HUNTER_COLOUR), hex(PREY_COLOUR)],
            "max_steps": hall.arena.steps(),
        })
        .to_string()
    }

    /// Back to the start: the world, the networks' state, the clock.
    fn reset(&mut self, hall: &Hall) {
        self.world = hall.arena.world().clone();
        self.hunter = (hall.arena).brain(Side::Hunter, &hall.hunters[self.picked.0 as usize].0);
        self.prey = (hall.arena).brain(Side::Prey, &hall.prey[self.picked.1 as usize].0);
        self.step = 0;
        self.caught = None;
        self.carry = 0.0;
        self.trace.iter_mut().for_each(Vec::clear);
        for (t, r) in self.trace.iter_mut().zip(self.world.robots()) {
            t.push([r.pos.x, r.pos.y]);
        }
        self.dirty = true;
    }

    /// Whether the episode is over (a catch, or its last step).
    fn over(&self, hall: &Hall) -> bool {
        self.caught.is_some() || self.step >= hall.arena.steps()
    }

    /// One step, as [`Arena::play`] takes it: both read their sensors, their
    /// networks (or the keys, for the prey) set the wheels, the world moves.
    fn step_once(&mut self, hall: &Hall) {
        if self.over(hall) {
            self.playing = false;
            return;
        }
        let arena = &hall.arena;
        let (mut inputs, mut outputs) = ([0.0; INPUTS], [0.0; OUTPUTS]);
        let mut controls = vec![[0.0; 2]; self.world.robots().len()];
        arena.inputs(&self.world, Side::Hunter, &mut inputs);
        self.hunter.act(&inputs, &mut outputs);
        controls[arena.robot(Side::Hunter)] = wheels(outputs[0], outputs[1]);
        arena.inputs(&self.world, Side::Prey, &mut inputs);
        self.prey.act(&inputs, &mut outputs);
        controls[arena.robot(Side::Prey)] = if self.human {
            self.keys.controls()
        } else {
            wheels(outputs[0], outputs[1])
        };
        self.world.step(&controls);
        self.step += 1;
        if arena.caught(&self.world) {
            self.caught = Some(self.step);
        }
        for (t, r) in self.trace.iter_mut().zip(self.world.robots()) {
            t.push([r.pos.x, r.pos.y]);
        }
        self.dirty = true;
    }

    /// Advances by one frame of `seconds` at the current speed (if playing).
    pub(crate) fn advance(&mut self, hall: &Hall, seconds: f64) {
        if !self.playing {
            return;
        }
        self.carry += self.speed * REAL_TIME_STEPS * seconds;
        let n = (self.carry.floor() as u32).min(MAX_STEPS_PER_FRAME);
        self.carry = (self.carry - f64::from(n)).min(1.0);
        for _ in 0..n {
            self.step_once(hall);
        }
    }

    /// Handles one text message from the page; `Err` is sent back as an error.
    pub(crate) fn handle(&mut self, text: &str, hall: &Hall) -> Result<(), String> {
        let msg: ClientMsg = serde_json::from_str(text)
            .map_err(|e| format!("bad message: {}", one_line(&e.to_string())))?;
        match msg {
            ClientMsg::Play => {
                if self.over(hall) {
                    self.reset(hall);
                }
                self.playing = true;
            }
            ClientMsg::Pause => self.playing = false,
            ClientMsg::Reset => self.reset(hall),
            ClientMsg::Step { n } => {
                if n == 0 || n > MAX_STEPS_PER_MESSAGE {
                    return Err(format!("step {n}: must be 1 to {MAX_STEPS_PER_MESSAGE}"));
                }
                self.playing = false;
                for _ in 0..n {
                    self.step_once(hall);
                }
            }
            ClientMsg::Speed { value } => {
                if !(value.is_finite() && (0.05..=200.0).contains(&value)) {
                    return Err(format!("speed {value}: must be 0.05 to 200"));
                }
                self.speed = value;
            }
            ClientMsg::Pick { hunter, prey } => {
                let n = hall.generations();
                for (side, g) in [("hunter", hunter), ("prey", prey)] {
                    if g as usize >= n {
                        return Err(format!(
                            "no {side} of generation {g}: the run has generations 0 to {}",
                            n - 1
                        ));
                    }
                }
                self.picked = (hunter, prey);
                self.reset(hall);
                self.playing = true;
            }
            ClientMsg::Human { on } => {
                self.human = on;
                self.keys = Keys::default();
                self.reset(hall);
                self.playing = true;
            }
            ClientMsg::Keys(keys) => self.keys = keys,
        }
        self.dirty = true;
        Ok(())
    }

    /// The `frame` message; clears the trails sent.
    pub(crate) fn frame_msg(&mut self, hall: &Hall) -> String {
        #[derive(Serialize)]
        struct Frame<'a> {
            r#type: &'static str,
            robots: Vec<[f64; 3]>,
            trace: &'a [Vec<[f64; 2]>],
            step: u32,
            max_steps: u32,
            caught: Option<u32>,
            hunter: u32,
            prey: u32,
            human: bool,
            playing: bool,
        }
        let robots = (self.world.robots().iter())
            .map(|r| [r.pos.x, r.pos.y, r.heading])
            .collect();
        let text = serde_json::to_string(&Frame {
            r#type: "frame",
            robots,
            trace: &self.trace,
            step: self.step,
            max_steps: hall.arena.steps(),
            caught: self.caught,
            hunter: self.picked.0,
            prey: self.picked.1,
            human: self.human,
            playing: self.playing,
        })
        .unwrap_or_else(|_| Value::Null.to_string());
        self.trace.iter_mut().for_each(Vec::clear);
        self.dirty = false;
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small run's hall in a folder of its own (`name`: the test's, as
    /// tests run in parallel).
    fn hall(name: &str) -> (Hall, PathBuf) {
        let dir =
            std::env::temp_dir().join(format!("vivae-coevo-view-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut config = vivae_lab::config::Config::predator_prey();
        config.experiment.generations = 2;
        config.neat.population_size = 10;
        config.experiment.steps = 200;
        config.run.threads = 1;
        let quiet = |_: &str| {};
        let stop = std::sync::atomic::AtomicBool::new(false);
        let session = vivae_lab::tasks::Session {
            interrupted: &stop,
            say: &quiet,
            players: None,
        };
        let driver = vivae_lab::tasks::predator_prey::TASK.own_driver.unwrap();
        (driver.evolve)(&dir, config, false, &session).unwrap();
        (Hall::load(&dir).unwrap(), dir)
    }

    #[test]
    fn the_viewers_game_is_the_evaluations_episode_and_refuses_bad_messages() {
        let (hall, dir) = hall("episode");
        assert_eq!(hall.generations(), 2);
        let mut game = Game::new(&hall).unwrap();
        for (h, p) in [(0, 1), (1, 0), (1, 1)] {
            game.handle(
                &format!(r#"{{"type":"pick","hunter":{h},"prey":{p}}}"#),
                &hall,
            )
            .unwrap();
            game.handle(r#"{"type":"step","n":10000}"#, &hall).unwrap();
            let out = hall.arena.play_genomes(&hall.hunters[h].0, &hall.prey[p].0);
            assert_eq!(game.caught, out.caught.then_some(out.steps), "({h}, {p})");
            assert_eq!(game.step, out.steps);
        }
        game.frame_msg(&hall);
        let before = game.frame_msg(&hall);
        for bad in [
            r#"{"type":"pick","hunter":2,"prey":0}"#,
            r#"{"type":"pick","hunter":-1,"prey":0}"#,
            r#"{"type":"speed","value":1e308}"#,
            r#"{"type":"step","n":0}"#,
            r#"{"type":"keys","up":1}"#,
            r#"{"type":"keys","up":true,"down":false,"left":false,"right":false,"fire":true}"#,
            r#"{"type":"launch"}"#,
            "[]",
            "\u{0}",
        ] {
            assert!(game.handle(bad, &hall).is_err(), "{bad}");
        }
        assert_eq!(
            game.frame_msg(&hall),
            before,
            "a refused message changed nothing"
        );
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn the_keyboard_drives_the_prey() {
        let (hall, dir) = hall("keyboard");
        let mut game = Game::new(&hall).unwrap();
        game.handle(r#"{"type":"human","on":true}"#, &hall).unwrap();
        let prey = hall.arena.robot(Side::Prey);
        let start = game.world.robots()[prey].pos;
        game.handle(
            r#"{"type":"keys","up":true,"down":false,"left":false,"right":false}"#,
            &hall,
        )
        .unwrap();
        game.handle(r#"{"type":"step","n":10}"#, &hall).unwrap();
        let moved = game.world.robots()[prey].pos.distance(start);
        assert!(game.caught.is_some() || moved > 5.0, "moved {moved}");
        let _ = std::fs::remove_dir_all(dir);
    }
}
