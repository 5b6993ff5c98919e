//! The driving experiment's one task: an episode on one map, at one
//! substrate resolution, scored by one fitness function.

use std::borrow::Cow;
use std::sync::Arc;

use vivae_neat::Precision;
use vivae_neat::driver::{Evaluation, Task};
use vivae_neat::hyperneat::{HyperParams, SubstrateController, SubstrateLayout, decode_genome_at};
use vivae_neat::{EvalContext, Genome, GenomeSpec};
use vivae_sim::{DVec2, Scenario, SurfaceGrid, World};

use crate::config::{Aggregate, Config};
use crate::controller::blind::NOTHING_SEEN;
use crate::controller::es::{EsSetup, RobotController, SubstrateKind};
use crate::controller::normalize::SourceScale;
use crate::controller::sensors::{SensorSheet, read_sheets, sensor_sheets};
use crate::controller::substrate::{
    PolarGrid, SubstrateSpec, WheelNeurons, cppn_outputs, layout_of,
};
use crate::search::StrategyConfig;
use crate::tasks::driving::behaviour::{Behaviour, BehaviourMeter};
use crate::tasks::driving::combined::DrivingTask;
use crate::tasks::driving::descriptors::{EpisodeSetup, METRICS, Measures, measured_episode};
use crate::tasks::driving::fitness::Fitness;
use crate::tasks::driving::placement::{placed, placement_seed};
use crate::tasks::driving::rollout::{Drive, Rollout};
use crate::tasks::driving::section::{FitnessConfig, FitnessKind};

/// Everything needed to evaluate genomes on one scenario with one config.
///
/// Built once per run; evaluation only reads it, so it is shared by all threads.
#[derive(Debug, Clone)]
pub struct Episode {
    world: World,
    /// The scenario (its robots as the experiment uses them) when its
    /// obstacles or traffic are placed per episode: every evaluation starts
    /// from its own placement, drawn from the evaluation's seed.
    varying: Option<Arc<Scenario>>,
    /// The placement this experiment was fixed to ([`Episode::with_placement_seed`]
    /// of a varying scenario).
    placement: Option<u64>,
    /// Whether the distance rays read nothing seen ([`Episode::with_blind_rays`]).
    blind_rays: bool,
    /// The robots' sensors, in controller-input order.
    sensors: Vec<SensorSheet>,
    /// The first sheet's surface sensors, typed, for pictures of what robots see.
    surface: Arc<SurfaceGrid>,
    spec: SubstrateSpec,
    layout: SubstrateLayout,
    wheels: WheelNeurons,
    hyper: HyperParams,
    /// The ES-HyperNEAT substrate, when `substrate.kind = "es-hyperneat"`.
    es: Option<EsSetup>,
    /// Factor per source node (`substrate.normalize` and its rules).
    scale: SourceScale,
    steps: u32,
    cppn_outputs: usize,
    /// What an episode scores.
    fitness: Arc<dyn Fitness>,
    /// What an evaluation measures besides fitness (`None`: fitness only).
    measures: Option<Measures>,
    /// Placements per evaluation of a varying scenario (`experiment.placements`).
    placements: u32,
    /// How the fitnesses on several placements combine.
    placements_aggregate: Aggregate,
    /// The arithmetic the dense controller steps in (`experiment.precision`).
    precision: Precision,
}

/// The outcome of one episode.
#[derive(Debug, Clone, PartialEq)]
pub struct EpisodeRecord {
    /// The experiment's fitness (by default average speed: Σ odometer /
    /// (robots × steps), px per step).
    pub fitness: f64,
    /// Fraction of robot-steps that ended with the robot's centre on a road
    /// (measured when recording: evolution does not need it).
    pub on_road: Option<f64>,
    /// Average speed, Σ odometer / (robots × steps) in px per step, whatever
    /// the fitness (measured when recording: with a progress fitness or a
    /// contact cost it differs from `fitness`).
    pub speed: Option<f64>,
    /// Every robot's path (start position first), when recorded.
    pub trajectories: Option<Vec<Vec<DVec2>>>,
    /// Collisions, turns, loops and side of the road, when recorded.
    pub behaviour: Option<Behaviour>,
}

/// `scenario` with the robots the config asks for, checked against the
/// config's fitness (a progress fitness needs a route).
fn fitted(config: &Config, scenario: &Scenario) -> Result<Scenario, EpisodeError> {
    scenario
        .require_robots()
        .map_err(|e| EpisodeError::Scenario(e.to_string()))?;
    let wanted = config.experiment.robots;
    let mut scenario = scenario.clone();
    if wanted > 0 {
        if scenario.robots.len() < wanted {
            let have = scenario.robots.len();
            return Err(EpisodeError::Scenario(format!(
                "{}: has {have} robot{}, the config asks for experiment.robots = {wanted}; \
                 use --robots {have} (or --robots 0 for all of them), or draw more robots",
                scenario.source,
                if have == 1 { "" } else { "s" }
            )));
        }
        scenario.robots.truncate(wanted);
    }
    if FitnessConfig::of(config).kind == FitnessKind::Progress && scenario.routes.is_empty() {
        return Err(EpisodeError::Scenario(format!(
            "{}: fitness.kind = \"progress\" needs a route (a path labelled Route), and the scenario has none",
            scenario.source
        )));
    }
    Ok(scenario)
}

// Defined with the library's error so that the error type needs no task.
pub use crate::error::EpisodeError;

impl Episode {
    /// Sets up the experiment of `config` on `scenario` (uses its first `robots` robots).
    pub fn new(config: &Config, scenario: &Scenario) -> Result<Episode, EpisodeError> {
        let scenario = fitted(config, scenario)?;
        // A varying scenario's own start is placement 0 (replay's default).
        let world = World::new(&placed(&scenario, 0), &config.physics)
            .map_err(|e| EpisodeError::Config(format!("physics.{e}")))?;
        let varying = scenario.varies().then(|| Arc::new(scenario));
        let distance_layout = config.distance_sensors.layout();
        let surface = &config.surface_sensors;
        let spec = SubstrateSpec {
            sensors: PolarGrid {
                rings: surface.rings,
                angles: surface.angles,
            },
            neurons: config.substrate.neurons,
            distance_rays: distance_layout.as_ref().map(|d| d.rays),
            fov: surface.fov,
            neuron_fov: 180.0,
            coords: config.substrate.coordinates,
        };
        spec.validate()
            .map_err(|e| EpisodeError::Config(format!("substrate: {e}")))?;
        let wheels = spec
            .wheels()
            .map_err(|e| EpisodeError::Config(format!("substrate: {e}")))?;
        // The layout comes from the sensors the robots really carry (the
        // registry's sheets for this config), so a sensor's input nodes sit
        // where it looks.
        let surface_grid = Arc::new(surface.grid());
        let sensors = sensor_sheets(config);
        let layout = layout_of(&sensors, &spec.neuron_nodes(), spec.coords);
        let cppn_outputs = cppn_outputs(&sensors);
        let scale = SourceScale::new(&config.substrate, &sensors, &spec.neuron_nodes());
        if !config.experiment.precision.is_exact() && config.substrate.kind != SubstrateKind::Polar
        {
            return Err(EpisodeError::Config(
                "experiment.precision = \"fast\" steps the dense polar substrate only; \
                 substrate.kind = \"es-hyperneat\" computes exactly: drop one of them"
                    .into(),
            ));
        }
        let es = match config.substrate.kind {
            SubstrateKind::Polar => None,
            SubstrateKind::EsHyperneat => Some(
                crate::controller::es::es_setup(config, &sensors, scale.factors())
                    .map_err(EpisodeError::Config)?,
            ),
        };
        Ok(Episode {
            world,
            varying,
            placement: None,
            blind_rays: false,
            sensors,
            surface: surface_grid,
            spec,
            layout,
            wheels,
            hyper: config.hyperneat,
            es,
            scale,
            steps: config.experiment.steps,
            cppn_outputs,
            fitness: crate::tasks::driving::fitness_contacts::of_config(&FitnessConfig::of(config)),
            measures: Measures::of(&StrategyConfig::of(config)),
            placements: config.experiment.placements.max(1),
            placements_aggregate: config.experiment.placements_aggregate,
            precision: config.experiment.precision,
        })
    }

    /// This experiment scored by `fitness` instead of average speed.
    pub fn with_fitness(mut self, fitness: Arc<dyn Fitness>) -> Episode {
        self.fitness = fitness;
        self
    }

    /// This experiment always on placement `seed` (obstacles and traffic as
    /// an evaluation with that seed has them), e.g. one never used in
    /// training; unchanged when the scenario places nothing per episode.
    pub fn with_placement_seed(mut self, seed: u64) -> Episode {
        if let Some(sc) = self.varying.take() {
            self.world = World::new(&placed(&sc, seed), self.world.params())
                .expect("the parameters were checked when the episode was set up");
            self.placement = Some(seed);
        }
        self
    }

    /// This experiment with its distance rays blinded: every ray reads
    /// [`NOTHING_SEEN`] whatever is in front of it, the rest as it was; an
    /// error when the robots carry no distance rays.
    pub fn with_blind_rays(mut self) -> Result<Episode, EpisodeError> {
        let rays = (self.sensors.iter_mut())
            .find(|s| s.name() == "distance")
            .ok_or_else(|| {
                EpisodeError::Config(
                    "the robots carry no distance rays to blind (distance_sensors.rays is 0)"
                        .into(),
                )
            })?;
        *rays = rays.blinded(NOTHING_SEEN);
        self.blind_rays = true;
        Ok(self)
    }

    /// Whether the distance rays are blinded ([`Episode::with_blind_rays`]).
    pub fn blind_rays(&self) -> bool {
        self.blind_rays
    }

    /// The placement this experiment is fixed to: `Some` once
    /// [`Episode::with_placement_seed`] fixed a varying scenario's.
    pub fn placement(&self) -> Option<u64> {
        self.placement
    }

    /// Whether evaluations place obstacles or traffic from their seeds.
    pub fn varies(&self) -> bool {
        self.varying.is_some()
    }

    /// Episodes per evaluation: `experiment.placements` when evaluations
    /// place obstacles or traffic, else 1 (every placement would be the same episode).
    pub fn placements(&self) -> u32 {
        if self.varies() { self.placements } else { 1 }
    }

    /// The world an evaluation with seed `seed` starts from.
    pub fn start(&self, seed: u64) -> Cow<'_, World> {
        match &self.varying {
            None => Cow::Borrowed(&self.world),
            Some(sc) => Cow::Owned(
                World::new(&placed(sc, seed), self.world.params())
                    .expect("the parameters were checked when the episode was set up"),
            ),
        }
    }

    /// The fitness function episodes are scored by.
    pub fn fitness_function(&self) -> &dyn Fitness {
        &*self.fitness
    }

    /// The shape of the CPPN genomes this experiment evolves.
    pub fn cppn_spec(&self) -> GenomeSpec {
        GenomeSpec {
            outputs: self.cppn_outputs,
            ..GenomeSpec::cppn()
        }
    }

    /// The substrate's polar geometry.
    pub fn substrate_spec(&self) -> &SubstrateSpec {
        &self.spec
    }

    /// The substrate geometry as the decoder sees it.
    pub fn layout(&self) -> &SubstrateLayout {
        &self.layout
    }

    /// Indices of the wheel neurons among the controller's outputs.
    pub fn wheels(&self) -> WheelNeurons {
        self.wheels
    }

    /// The world at the start of an episode.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The robots' sensors with their input sheets, in controller-input order.
    pub fn sensors(&self) -> &[SensorSheet] {
        &self.sensors
    }

    /// The surface sensors (the first sheet), for drawing what a robot sees.
    pub fn surface_grid(&self) -> &SurfaceGrid {
        &self.surface
    }

    /// Reads robot `robot`'s sensors in `world` into `inputs`, sheet after
    /// sheet: the controller's input vector. Allocation-free.
    #[inline]
    pub fn read_inputs(&self, world: &World, robot: usize, inputs: &mut [f64]) {
        read_sheets(&self.sensors, world, robot, inputs);
    }

    /// Simulation steps per episode.
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// Number of robots per episode.
    pub fn robots(&self) -> usize {
        self.world.robots().len()
    }

    /// The ES-HyperNEAT substrate, when the experiment decodes into one.
    pub fn es_setup(&self) -> Option<&EsSetup> {
        self.es.as_ref()
    }

    /// Decodes `genome` into this experiment's controller, dense or ES.
    pub fn robot_controller(&self, genome: &Genome) -> Result<RobotController, EpisodeError> {
        match &self.es {
            None => self.controller(genome).map(RobotController::Polar),
            Some(es) => {
                self.check_genome(genome)?;
                let c = es
                    .decode(genome)
                    .map_err(|e| EpisodeError::Genome(e.to_string()))?;
                Ok(RobotController::Es(c))
            }
        }
    }

    /// An error if `genome`'s CPPN has the wrong number of inputs or outputs.
    fn check_genome(&self, genome: &Genome) -> Result<(), EpisodeError> {
        let want = self.cppn_spec();
        let (inputs, outputs) = (genome.num_inputs(), genome.num_outputs());
        if inputs != want.inputs || outputs != want.outputs {
            return Err(EpisodeError::Genome(format!(
                "CPPN has {inputs} inputs and {outputs} outputs, this substrate needs {} and {}",
                want.inputs, want.outputs
            )));
        }
        Ok(())
    }

    /// Decodes `genome` (a CPPN) into the dense polar controller; an error if
    /// its CPPN has the wrong number of inputs or outputs, or if the
    /// experiment's substrate is ES-HyperNEAT (see [`Episode::robot_controller`]).
    pub fn controller(&self, genome: &Genome) -> Result<SubstrateController, EpisodeError> {
        if self.es.is_some() {
            return Err(EpisodeError::Config(
                "substrate.kind = \"es-hyperneat\" has no dense polar sheet".into(),
            ));
        }
        self.check_genome(genome)?;
        let mut controller = decode_genome_at(genome, &self.layout, &self.hyper, self.precision)
            .map_err(|e| EpisodeError::Genome(e.to_string()))?;
        self.scale.apply(&mut controller);
        Ok(controller)
    }

    /// The fitness of `genome`'s controller (average speed by default); 0 for
    /// a genome that does not fit the substrate (evolution never makes one).
    pub fn fitness(&self, genome: &Genome) -> f64 {
        self.fitness_from(&self.world, genome)
    }

    /// [`Episode::fitness`] of an episode starting from `start`.
    fn fitness_from(&self, start: &World, genome: &Genome) -> f64 {
        match self.robot_controller(genome) {
            Ok(c) => self.run_from(start, &c, false).0.fitness,
            Err(_) => 0.0,
        }
    }

    /// Runs one episode, every robot driven by `controller` (each with its own
    /// neuron states); `record` also keeps the trajectories and measures the
    /// time on road.
    pub fn run(&self, controller: &(impl Drive + ?Sized), record: bool) -> EpisodeRecord {
        self.run_world(controller, record).0
    }

    /// The controller side of an episode of this experiment driven by
    /// `controller` (the world starts as [`Episode::world`]).
    pub fn rollout(&self, controller: &(impl Drive + ?Sized)) -> Rollout {
        Rollout::new(self.robots(), self.sensors.clone(), self.wheels, controller)
    }

    /// The start, length and fitness of this experiment's episodes.
    pub fn setup(&self) -> EpisodeSetup<'_> {
        self.setup_from(&self.world)
    }

    /// [`Episode::setup`] starting from `start`.
    fn setup_from<'a>(&'a self, start: &'a World) -> EpisodeSetup<'a> {
        EpisodeSetup {
            start,
            steps: self.steps,
            fitness: &*self.fitness,
        }
    }

    /// Runs one episode and also returns the final world (for drawing).
    pub fn run_world(
        &self,
        controller: &(impl Drive + ?Sized),
        record: bool,
    ) -> (EpisodeRecord, World) {
        self.run_from(&self.world, controller, record)
    }

    /// [`Episode::run_world`] starting from `start`.
    fn run_from(
        &self,
        start: &World,
        controller: &(impl Drive + ?Sized),
        record: bool,
    ) -> (EpisodeRecord, World) {
        let n = self.robots();
        let mut world = start.clone();
        if record {
            world.record_trajectories(self.steps as usize);
        }
        let mut meter = self.fitness.meter(&world);
        let observe = self.fitness.observes_steps();
        let mut rollout = self.rollout(controller);
        let mut on_road = 0u64;
        let mut behaviour = record.then(|| BehaviourMeter::new(&world, self.steps as usize));
        for _ in 0..self.steps {
            rollout.step(&mut world, controller, None);
            if observe {
                meter.observe(&world);
            }
            if let Some(b) = &mut behaviour {
                on_road += (0..n).filter(|&i| world.on_road(i)).count() as u64;
                b.observe(&world);
            }
        }
        let robot_steps = (n as f64) * f64::from(self.steps);
        let episode = EpisodeRecord {
            fitness: meter.score(&world, robot_steps),
            on_road: record.then_some(on_road as f64 / robot_steps),
            speed: record
                .then(|| world.robots().iter().map(|r| r.odometer).sum::<f64>() / robot_steps),
            trajectories: world.trajectories().map(|t| t.to_vec()),
            behaviour: behaviour.map(|m| m.finish()),
        };
        (episode, world)
    }
}

impl Episode {
    /// An evaluation on [`Episode::placements`] placements, drawn from
    /// [`placement_seed`]`(seed, k)`: the fitness combined by
    /// `experiment.placements_aggregate`, metrics and behaviour the mean over
    /// the placements, coordinate by coordinate.
    fn evaluate_placements(&self, genome: &Genome, seed: u64) -> Evaluation {
        let controller = match self.robot_controller(genome) {
            Ok(c) => c,
            Err(_) => {
                return match self.measures {
                    None => Evaluation::fitness(0.0),
                    Some(m) => crate::tasks::driving::descriptors::unfit(m, self.robots()),
                };
            }
        };
        let parts: Vec<Evaluation> = (0..self.placements())
            .map(|k| {
                let start = self.start(placement_seed(seed, k));
                match self.measures {
                    None => {
                        Evaluation::fitness(self.run_from(&start, &controller, false).0.fitness)
                    }
                    Some(m) => measured_episode(
                        self.setup_from(&start),
                        self.rollout(&controller),
                        &controller,
                        m,
                    ),
                }
            })
            .collect();
        let fitnesses: Vec<f64> = parts.iter().map(|e| e.fitness).collect();
        let metrics: Vec<&[f64]> = parts.iter().map(|e| &e.metrics[..]).collect();
        let behaviours: Vec<&[f64]> = parts.iter().map(|e| &e.behaviour[..]).collect();
        Evaluation {
            fitness: self.placements_aggregate.combine(&fitnesses),
            metrics: crate::tasks::driving::descriptors::mean_of(&metrics),
            behaviour: crate::tasks::driving::descriptors::mean_of(&behaviours),
        }
    }
}

/// The driving experiment as a NEAT task: a genome's fitness is its
/// controller's episode score (deterministic: the only randomness, a varying
/// scenario's placement, comes from `ctx.seed`), with the behaviour and
/// metrics the run's strategy needs ([`crate::tasks::driving::descriptors`]).
impl Task for Episode {
    fn evaluate(&self, genome: &Genome, ctx: &EvalContext) -> Evaluation {
        if self.placements() > 1 {
            return self.evaluate_placements(genome, ctx.seed);
        }
        let start = self.start(ctx.seed);
        let Some(measures) = self.measures else {
            return Evaluation::fitness(self.fitness_from(&start, genome));
        };
        match self.robot_controller(genome) {
            Ok(c) => measured_episode(self.setup_from(&start), self.rollout(&c), &c, measures),
            Err(_) => crate::tasks::driving::descriptors::unfit(measures, self.robots()),
        }
    }

    fn metric_names(&self) -> &[&str] {
        match self.measures {
            Some(m) if m.metrics => &METRICS,
            _ => &[],
        }
    }

    /// The context's seed only places a varying scenario's obstacles and traffic.
    fn context_free(&self) -> bool {
        !self.varies()
    }
}

impl DrivingTask for Episode {
    fn robot_steps(&self) -> u64 {
        self.robots() as u64 * u64::from(self.steps) * u64::from(self.placements())
    }

    fn cppn_spec(&self) -> GenomeSpec {
        Episode::cppn_spec(self)
    }
}

// Tests of the modules an episode is built from that need an episode to
// run: those modules cannot import `Episode` without importing their user.
#[cfg(test)]
mod es_controllers;
#[cfg(test)]
mod measures;
#[cfg(test)]
mod normalized_controllers;
#[cfg(test)]
mod rollouts;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::scenarios::load_scenario;
    use vivae_neat::Population;

    fn paper_experiment(config: &Config) -> Episode {
        Episode::new(config, &load_scenario(None).unwrap().scenario).unwrap()
    }

    #[test]
    fn recording_does_not_change_the_episode() {
        let config = Config::default();
        let exp = paper_experiment(&config);
        let pop = Population::new(config.neat.clone(), exp.cppn_spec(), 11).unwrap();
        for g in pop.genomes().iter().take(5) {
            let c = exp.controller(g).unwrap();
            let plain = exp.run(&c, false);
            let recorded = exp.run(&c, true);
            assert_eq!(plain.fitness, recorded.fitness);
            assert_eq!(plain.fitness, exp.fitness(g));
            assert!(plain.on_road.is_none() && plain.trajectories.is_none());
            assert!(plain.speed.is_none());
            // The paper's fitness is the average speed the record measures.
            assert_eq!(recorded.speed, Some(recorded.fitness));
            let on_road = recorded.on_road.unwrap();
            assert!((0.0..=1.0).contains(&on_road));
            let t = recorded.trajectories.unwrap();
            assert_eq!(t.len(), exp.robots());
            assert!(t.iter().all(|p| p.len() == exp.steps() as usize + 1));
        }
    }

    #[test]
    fn a_strategy_measures_es_hyperneat_controllers_too() {
        let mut config = Config::default();
        config.experiment.steps = 100;
        config.substrate.kind = SubstrateKind::EsHyperneat;
        // A strategy that selects on the task's metrics.
        let metrics = crate::search::entries()
            .into_iter()
            .find(|e| e.needs.metrics);
        let kind = metrics.expect("a strategy selects on metrics").kind;
        StrategyConfig::update(&mut config, |s| s.kind = kind.into());
        let exp = paper_experiment(&config);
        let pop = Population::new(config.neat.clone(), exp.cppn_spec(), 5).unwrap();
        let ctx = EvalContext {
            generation: 0,
            index: 0,
            seed: 0,
        };
        let mut moved = 0;
        for g in pop.genomes().iter().take(10) {
            let e = exp.evaluate(g, &ctx);
            // The measured episode is the plain one: same fitness, plus metrics.
            assert_eq!(e.fitness, exp.fitness(g));
            assert_eq!(e.metrics.len(), exp.metric_names().len());
            moved += usize::from(e.fitness > 0.0);
        }
        assert!(moved > 0, "no ES controller drove: were they decoded?");
    }

    #[test]
    fn several_placements_score_the_mean_or_the_worst_of_their_episodes() {
        let mut config = Config::default();
        config.experiment.steps = 60;
        let sc = crate::tasks::scenarios::find("obstacles-random").unwrap();
        let scenario = Scenario::from_svg(sc.svg, "obstacles-random", &Default::default()).unwrap();
        let one = Episode::new(&config, &scenario).unwrap();
        config.experiment.placements = 3;
        let three = Episode::new(&config, &scenario).unwrap();
        config.experiment.placements_aggregate = Aggregate::Min;
        let worst = Episode::new(&config, &scenario).unwrap();
        assert_eq!((one.placements(), three.placements()), (1, 3));
        let pop = Population::new(config.neat.clone(), one.cppn_spec(), 3).unwrap();
        let ctx = EvalContext {
            generation: 2,
            index: 1,
            seed: 99,
        };
        let mut differ = 0;
        for g in pop.genomes().iter().take(8) {
            let parts: Vec<f64> = (0..3)
                .map(|k| {
                    one.evaluate(
                        g,
                        &EvalContext {
                            seed: placement_seed(99, k),
                            ..ctx
                        },
                    )
                    .fitness
                })
                .collect();
            assert_eq!(
                parts[0],
                one.evaluate(g, &ctx).fitness,
                "placement 0 is the seed's"
            );
            assert_eq!(
                three.evaluate(g, &ctx).fitness,
                Aggregate::Mean.combine(&parts)
            );
            assert_eq!(
                worst.evaluate(g, &ctx).fitness,
                Aggregate::Min.combine(&parts)
            );
            differ += usize::from(parts[0] != parts[1] || parts[1] != parts[2]);
        }
        assert!(differ > 0, "the placements gave one episode");
        // A scenario that places nothing is run once.
        let plain = paper_experiment(&config);
        assert_eq!(plain.placements(), 1);
    }

    /// Records, for every evaluation a run reused, whether a fresh one in
    /// another context has the same bits.
    struct CheckReused<'a> {
        exp: &'a Episode,
        reused: usize,
    }

    impl vivae_neat::driver::Observer for CheckReused<'_> {
        fn on_generation(
            &mut self,
            report: &vivae_neat::driver::GenerationReport<'_>,
        ) -> Result<(), vivae_neat::driver::HookError> {
            for &i in report.reused {
                let genome = &report.strategy.genomes()[i];
                let fresh = self.exp.evaluate(
                    genome,
                    &EvalContext {
                        generation: 999,
                        index: 1000 + i,
                        seed: 12345,
                    },
                );
                assert_eq!(
                    fresh, report.evaluations[i],
                    "generation {}",
                    report.generation
                );
                assert_eq!(
                    fresh.fitness.to_bits(),
                    report.evaluations[i].fitness.to_bits()
                );
                self.reused += 1;
            }
            Ok(())
        }
    }

    #[test]
    fn a_reused_driving_evaluation_has_the_bits_of_a_fresh_one() {
        use vivae_neat::driver::{
            Evolution, NoCheckpoints, ParallelEvaluator, Reusing, StopCriteria,
        };
        let mut config = Config::default();
        config.experiment.steps = 150;
        config.neat.population_size = 30;
        let exp = paper_experiment(&config);
        assert!(exp.context_free(), "the paper's scenario places nothing");
        let pop = Population::new(config.neat.clone(), exp.cppn_spec(), 5).unwrap();
        let evaluator = Reusing::new(ParallelEvaluator::new(exp.clone()), exp.context_free());
        let mut evolution = Evolution::new(pop, evaluator);
        let mut check = CheckReused {
            exp: &exp,
            reused: 0,
        };
        evolution
            .run(
                &StopCriteria::generations(6),
                &mut check,
                &mut NoCheckpoints,
            )
            .unwrap();
        // Elites alone are copied every generation after the first.
        assert!(
            check.reused >= 5,
            "only {} evaluations reused",
            check.reused
        );
    }

    #[test]
    fn an_episode_that_places_from_its_seed_is_not_context_free() {
        let config = Config::default();
        let sc = crate::tasks::scenarios::find("obstacles-random").unwrap();
        let scenario = Scenario::from_svg(sc.svg, "obstacles-random", &Default::default()).unwrap();
        assert!(!Episode::new(&config, &scenario).unwrap().context_free());
    }

    #[test]
    fn blind_rays_read_nothing_seen_and_change_what_a_rays_controller_does() {
        let mut config = Config::default();
        config.experiment.steps = 200;
        config.distance_sensors.rays = 5;
        let sc = crate::tasks::scenarios::find("corridor").unwrap();
        let scenario = Scenario::from_svg(sc.svg, "corridor", &Default::default()).unwrap();
        let seeing = Episode::new(&config, &scenario)
            .unwrap()
            .with_placement_seed(3);
        let blind = seeing.clone().with_blind_rays().unwrap();
        assert!(blind.blind_rays() && !seeing.blind_rays());
        let n = seeing.sensors().iter().map(|s| s.len()).sum::<usize>();
        let rays = seeing.sensors()[0].len()..n;
        assert_eq!(rays.len(), 5);
        let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
        seeing.read_inputs(seeing.world(), 0, &mut a);
        blind.read_inputs(blind.world(), 0, &mut b);
        // The corridor's kerbs are in reach: the seeing rays read them.
        assert_eq!(a[..rays.start], b[..rays.start]);
        assert!(a[rays.clone()].iter().any(|&v| v > 0.0), "{a:?}");
        assert!(b[rays].iter().all(|&v| v == NOTHING_SEEN), "{b:?}");
        let pop = Population::new(config.neat.clone(), seeing.cppn_spec(), 4).unwrap();
        let differ = (pop.genomes().iter().take(8))
            .filter(|g| {
                let c = seeing.controller(g).unwrap();
                seeing.run(&c, true).trajectories != blind.run(&c, true).trajectories
            })
            .count();
        assert!(differ > 0, "no controller drove otherwise blind");
        // Robots without rays have none to blind.
        config.distance_sensors.rays = 0;
        let e = Episode::new(&config, &scenario).unwrap().with_blind_rays();
        assert!(e.unwrap_err().to_string().contains("no distance rays"));
    }

    #[test]
    fn robots_never_move_faster_than_v_max() {
        let config = Config {
            experiment: crate::config::ExperimentConfig {
                steps: 300,
                ..Default::default()
            },
            ..Config::default()
        };
        let exp = paper_experiment(&config);
        let pop = Population::new(config.neat.clone(), exp.cppn_spec(), 3).unwrap();
        for g in pop.genomes().iter().take(30) {
            let episode = exp.run(&exp.controller(g).unwrap(), true);
            for t in episode.trajectories.unwrap() {
                for w in t.windows(2) {
                    let d = w[0].distance(w[1]);
                    assert!(
                        d <= config.physics.v_max + 1e-9,
                        "jump of {d} px in one step"
                    );
                }
            }
        }
    }
}
