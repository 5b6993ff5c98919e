//! What the classic-control tasks (Gymnasium's CartPole, Acrobot, the two
//! MountainCars and Pendulum) share: the start's uniform draws from the
//! evaluation's seed, the episode loop a network plays (observations rounded
//! to float32 as Gymnasium returns them, a bias input, fitness = the mean
//! return), and an episode stepped from a given state under given actions,
//! which each of them declares as its [`super::TaskEntry::stepped`] (the
//! Python package exposes it through [`super::gymnasium`]) so a test can
//! compare every step with Gymnasium's.

use vivae_neat::driver::Evaluation;
use vivae_neat::eval::splitmix64;
use vivae_neat::{FeedForwardNetwork, Network};

use super::plain::{Described, Plain, Trace, Validation};
use super::sketch::Sketch;
use super::{Step, Stepped, Threshold};
use crate::config::Config;

/// The most inputs or outputs a classic-control network has.
const MOST: usize = 8;

/// A Gymnasium classic-control environment: its dynamics (what it is is
/// [`Described`]; its inputs are the observation's values and a bias).
/// Every such environment is a [`Plain`] task by the one implementation
/// below (its evaluation, lanes, validation and check are this module's), so
/// a task's file states only these.
pub trait Classic: Described + Send + Sync + 'static {
    /// Names of its behaviour descriptor's two coordinates ([`Classic::place`]).
    const BEHAVIOUR: &'static [&'static str];
    /// The mean return that solves it: a training evaluation reaching it
    /// stops the run (once the check holds it, by three standard errors:
    /// [`super::plain::Validation::lower_bound`]), a validation reaching it
    /// solves the run.
    const THRESHOLD: f64;
    /// Where [`Classic::THRESHOLD`] comes from (a table's source column).
    const THRESHOLD_SOURCE: &'static str = GYMNASIUM_THRESHOLD;
    /// Whether its feed-forward evaluation steps its episodes side by side
    /// ([`evaluate_lanes`]); false where that was measured no faster.
    const LANES: bool = true;
    /// What the environment holds between steps.
    type State: Values;
    /// What a step takes.
    type Action: ActionValue;
    /// Episodes per evaluation.
    const EPISODES: u32 = 5;
    /// Generations of its default run (`experiment.generations`).
    const GENERATIONS: u32 = 100;
    /// Steps after which an episode is truncated (its `max_episode_steps`).
    const MAX_STEPS: u32;
    /// Episode `k`'s start, drawn as Gymnasium's `reset` draws it (its uniform ranges).
    fn start(draws: &mut Draws) -> Self::State;
    /// The observation in float64, before Gymnasium's float32 rounding
    /// (`INPUTS − 1` values): by default the state's values as they are.
    fn observe(s: &Self::State, obs: &mut [f64]) {
        s.write(obs);
    }
    /// The action the network's outputs choose.
    fn act(outputs: &[f64]) -> Self::Action;
    /// One step: the next state, the reward, whether it terminated.
    fn step(s: Self::State, a: Self::Action) -> (Self::State, f64, bool);
    /// A step's share of the behaviour descriptor, each coordinate in [0, 1],
    /// from the (float32) observation; the descriptor is its mean over steps.
    fn place(obs: &[f64]) -> [f64; 2];
    /// How a step of its episodes looks (report.html animates the champion's
    /// replay); `None`: not drawn.
    fn sketch() -> Option<Sketch> {
        None
    }
}

/// A classic-control state as Gymnasium's `env.unwrapped.state` holds it:
/// its values.
pub trait Values: Copy {
    /// The state these values are (`None`: not a state).
    fn of(values: &[f64]) -> Option<Self>;
    /// Its values.
    fn values(&self) -> Vec<f64>;
    /// Its values written into `out` (as many), allocating nothing.
    fn write(&self, out: &mut [f64]);
}

impl<const N: usize> Values for [f64; N] {
    fn of(values: &[f64]) -> Option<Self> {
        values.try_into().ok()
    }

    fn values(&self) -> Vec<f64> {
        self.to_vec()
    }

    fn write(&self, out: &mut [f64]) {
        out.copy_from_slice(self);
    }
}

/// A classic-control action as Gymnasium's `env.step` is given it: a number.
pub trait ActionValue: Copy {
    /// The action `value` is (`None`: not an action) when the network's
    /// `outputs` choose among that many (a discrete action is its argmax).
    fn of(value: f64, outputs: usize) -> Option<Self>;
}

/// A discrete action: its number.
impl ActionValue for usize {
    fn of(value: f64, outputs: usize) -> Option<usize> {
        let whole = value >= 0.0 && value < outputs as f64 && value.fract() == 0.0;
        whole.then_some(value as usize)
    }
}

/// One of two actions: 1 is true.
impl ActionValue for bool {
    fn of(value: f64, _outputs: usize) -> Option<bool> {
        usize::of(value, 2).map(|a| a == 1)
    }
}

/// A continuous action: any number, as float32 (as Gymnasium's action
/// spaces hold it).
impl ActionValue for f32 {
    fn of(value: f64, _outputs: usize) -> Option<f32> {
        Some(value as f32)
    }
}

/// [`Classic::THRESHOLD_SOURCE`] of an environment whose threshold is Gymnasium's.
pub const GYMNASIUM_THRESHOLD: &str =
    "Gymnasium 1.x's reward_threshold (gymnasium/envs/__init__.py)";

/// A classic-control environment as a plain task: its episodes played by
/// this module, its runs stopped by the check and solved by the validation.
impl<T: Classic> Plain for T {
    const METRICS: &'static [&'static str] = &["worst", "steps"];
    const BEHAVIOUR: &'static [&'static str] = <T as Classic>::BEHAVIOUR;
    const STEPS: u64 = T::EPISODES as u64 * T::MAX_STEPS as u64;
    const TARGET: Option<f64> = Some(T::THRESHOLD);
    const REWARD_THRESHOLD: Option<Threshold> = Some(Threshold {
        value: T::THRESHOLD,
        source: T::THRESHOLD_SOURCE,
    });
    const CHECK_EPISODES: u32 = CHECK_EPISODES;
    const TRACES: bool = true;
    const STEPPED: Option<Stepped> = Some(episode::<T>);

    fn defaults(config: &mut Config) {
        config.experiment.generations = T::GENERATIONS;
    }

    fn evaluate(net: &mut dyn Network, seed: u64, trace: Option<&mut Trace>) -> Evaluation {
        evaluate::<T>(net, seed, trace)
    }

    fn validate(net: &mut dyn Network, run_seed: u64) -> Option<Validation> {
        Some(validate::<T>(net, run_seed))
    }

    fn check(net: &mut dyn Network, run_seed: u64) -> Option<(Validation, u64)> {
        Some(check::<T>(net, run_seed))
    }

    fn evaluate_feed_forward(net: &FeedForwardNetwork, seed: u64) -> Option<Evaluation> {
        T::LANES.then(|| evaluate_lanes::<T>(net, seed))
    }

    fn sketch() -> Option<Sketch> {
        <T as Classic>::sketch()
    }
}

/// Uniform draws from the evaluation's seed and the episode's number.
#[derive(Debug, Clone)]
pub struct Draws(u64);

impl Draws {
    /// The draws of episode `k` of the evaluation of `seed`.
    pub fn new(seed: u64, k: u32) -> Draws {
        Draws(splitmix64(seed ^ u64::from(k)))
    }

    /// The next draw, uniform in [`low`, `high`).
    pub fn uniform(&mut self, low: f64, high: f64) -> f64 {
        self.0 = splitmix64(self.0);
        low + (high - low) * ((self.0 >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// The index of the largest output, the first on a tie: a discrete action.
pub fn argmax(outputs: &[f64]) -> usize {
    let mut best = 0;
    for (i, v) in outputs.iter().enumerate() {
        if *v > outputs[best] {
            best = i;
        }
    }
    best
}

/// `x` clipped to [`low`, `high`] as NumPy's `clip` does (NaN stays NaN).
pub fn clip(x: f64, low: f64, high: f64) -> f64 {
    if x < low {
        low
    } else if x > high {
        high
    } else {
        x
    }
}

/// Rounded to float32 as Gymnasium's observations are, read back as float64.
fn single(x: f64) -> f64 {
    f64::from(x as f32)
}

/// Episodes a champion is validated on ([`validate`]).
pub const VALIDATION_EPISODES: u32 = 100;

/// The tag of the validation stream: "validate" in ASCII.
pub const VALIDATION_TAG: u64 = 0x7661_6c69_6461_7465;

/// The seed whose episodes 0…99 validate the champions of the run seeded
/// `run_seed`. Training evaluations are seeded `eval_seed(run_seed,
/// generation, index)`, three splitmix64 rounds deep; this is one round of
/// the run seed with a tag, a different stream, so its starts are not the
/// training's (bar a 64-bit hash collision).
pub fn validation_seed(run_seed: u64) -> u64 {
    splitmix64(run_seed ^ VALIDATION_TAG)
}

/// Episodes a genome that reaches the threshold in training is checked on
/// before its run stops ([`check`]).
pub const CHECK_EPISODES: u32 = 100;

/// The tag of the check stream: "checking" in ASCII.
pub const CHECK_TAG: u64 = 0x6368_6563_6b69_6e67;

/// The seed whose episodes 0…99 check the training solvers of the run
/// seeded `run_seed`: one splitmix64 round of the run seed with its own tag,
/// a stream apart from the training's (three rounds deep) and from
/// [`validation_seed`]'s (another tag), so the run never stops on episodes
/// its champion is validated on.
pub fn check_seed(run_seed: u64) -> u64 {
    splitmix64(run_seed ^ CHECK_TAG)
}

/// Scores `net` on [`Classic::EPISODES`] episodes of `T` started from
/// `seed`: fitness = the mean return; metrics the worst return and the steps
/// taken; behaviour the mean of [`Classic::place`] over every step.
pub fn evaluate<T: Classic>(
    net: &mut dyn Network,
    seed: u64,
    trace: Option<&mut Trace>,
) -> Evaluation {
    let p = play::<T>(net, seed, T::EPISODES, trace);
    Evaluation {
        fitness: p.total / f64::from(T::EPISODES),
        metrics: vec![p.worst, p.steps],
        behaviour: p.place.map(|x| x / p.steps).to_vec(),
    }
}

/// `net` validated for the run seeded `run_seed`: its mean and worst return
/// over the [`VALIDATION_EPISODES`] episodes of [`validation_seed`], each
/// started as a training episode is.
pub fn validate<T: Classic>(net: &mut dyn Network, run_seed: u64) -> Validation {
    let seed = validation_seed(run_seed);
    play::<T>(net, seed, VALIDATION_EPISODES, None).validation(seed, VALIDATION_EPISODES)
}

/// `net`, which reached the threshold in training, checked for the run
/// seeded `run_seed`: its returns on the [`CHECK_EPISODES`] episodes of
/// [`check_seed`], and the evaluations they count as (episodes over
/// [`Classic::EPISODES`], rounded up).
pub fn check<T: Classic>(net: &mut dyn Network, run_seed: u64) -> (Validation, u64) {
    let seed = check_seed(run_seed);
    let v = play::<T>(net, seed, CHECK_EPISODES, None).validation(seed, CHECK_EPISODES);
    (v, u64::from(CHECK_EPISODES.div_ceil(T::EPISODES)))
}

/// What episodes 0…`episodes` of the evaluation of `seed` gave.
struct Played {
    total: f64,
    worst: f64,
    best: f64,
    /// The sum of the returns' squares.
    squares: f64,
    steps: f64,
    place: [f64; 2],
}

impl Played {
    /// Its `episodes` episodes, drawn from `seed`, as a validation.
    fn validation(&self, seed: u64, episodes: u32) -> Validation {
        let n = f64::from(episodes);
        let mean = self.total / n;
        Validation {
            mean,
            worst: self.worst,
            episodes,
            best: self.best,
            std: (self.squares / n - mean * mean).max(0.0).sqrt(),
            seed,
        }
    }
}

/// Plays episodes 0…`episodes` of `T` started from `seed`, recording into `trace`.
fn play<T: Classic>(
    net: &mut dyn Network,
    seed: u64,
    episodes: u32,
    mut trace: Option<&mut Trace>,
) -> Played {
    let (mut total, mut worst, mut steps, mut place) = (0.0, f64::INFINITY, 0.0, [0.0; 2]);
    let (mut best, mut squares) = (f64::NEG_INFINITY, 0.0);
    let (mut inputs, mut outputs) = ([0.0; MOST], [0.0; MOST]);
    let (inputs, outputs) = (&mut inputs[..T::INPUTS], &mut outputs[..T::OUTPUTS]);
    for k in 0..episodes {
        let mut s = T::start(&mut Draws::new(seed, k));
        net.reset();
        let mut ret = 0.0;
        for _ in 0..T::MAX_STEPS {
            let obs = &mut inputs[..T::INPUTS - 1];
            T::observe(&s, obs);
            obs.iter_mut().for_each(|v| *v = single(*v));
            let [a, b] = T::place(obs);
            inputs[T::INPUTS - 1] = 1.0;
            net.activate(inputs, outputs);
            let (next, reward, terminated) = T::step(s, T::act(outputs));
            s = next;
            ret += reward;
            steps += 1.0;
            place[0] += a;
            place[1] += b;
            if let Some(t) = trace.as_deref_mut() {
                t.step(k, inputs, outputs, reward);
            }
            if terminated {
                break;
            }
        }
        total += ret;
        worst = f64::min(worst, ret);
        best = f64::max(best, ret);
        squares += ret * ret;
    }
    Played {
        total,
        worst,
        best,
        squares,
        steps,
        place,
    }
}

/// Episodes [`evaluate_lanes`] steps side by side, at most.
pub const LANES: usize = 8;

/// [`evaluate`] of a feed-forward network, its episodes stepped side by
/// side: each step activates the network once for every live episode
/// ([`FeedForwardNetwork::activate_lanes`], the same bits as one activation
/// each), and the sums are taken in [`evaluate`]'s order, so the
/// evaluation is the same to the bit. More than [`LANES`] episodes are
/// evaluated one by one.
pub fn evaluate_lanes<T: Classic>(net: &FeedForwardNetwork, seed: u64) -> Evaluation {
    let n = T::EPISODES as usize;
    if n > LANES {
        return evaluate::<T>(&mut net.clone(), seed, None);
    }
    let mut states: [Option<T::State>; LANES] = [None; LANES];
    for (k, s) in states[..n].iter_mut().enumerate() {
        *s = Some(T::start(&mut Draws::new(seed, k as u32)));
    }
    let mut returns = [0.0; LANES];
    // Each episode's steps' shares of the behaviour, summed at the end in
    // episode order as `evaluate` sums them.
    let mut places: Vec<Vec<[f64; 2]>> = (0..n)
        .map(|_| Vec::with_capacity(T::MAX_STEPS as usize))
        .collect();
    let (mut inputs, mut outputs) = ([[0.0; LANES]; MOST], [[0.0; LANES]; MOST]);
    let (mut obs, mut out) = ([0.0; MOST], [0.0; MOST]);
    let mut values = Vec::new();
    // The observation's values, then the bias input.
    let o = T::INPUTS - 1;
    for _ in 0..T::MAX_STEPS {
        let mut live = false;
        for (l, s) in states[..n].iter().enumerate() {
            let Some(s) = s else { continue };
            live = true;
            T::observe(s, &mut obs[..o]);
            for (i, v) in obs[..o].iter_mut().enumerate() {
                *v = single(*v);
                inputs[i][l] = *v;
            }
            inputs[o][l] = 1.0;
            places[l].push(T::place(&obs[..o]));
        }
        if !live {
            break;
        }
        // Ended episodes' lanes are stepped too (on their last inputs) and ignored.
        net.activate_lanes(
            &inputs[..T::INPUTS],
            &mut outputs[..T::OUTPUTS],
            &mut values,
        );
        for (l, state) in states[..n].iter_mut().enumerate() {
            let Some(s) = *state else { continue };
            for (k, v) in out[..T::OUTPUTS].iter_mut().enumerate() {
                *v = outputs[k][l];
            }
            let (next, reward, terminated) = T::step(s, T::act(&out[..T::OUTPUTS]));
            returns[l] += reward;
            *state = (!terminated).then_some(next);
        }
    }
    let (mut total, mut worst, mut steps, mut place) = (0.0, f64::INFINITY, 0.0, [0.0; 2]);
    for (ret, episode) in returns.iter().zip(&places) {
        for [a, b] in episode {
            steps += 1.0;
            place[0] += a;
            place[1] += b;
        }
        total += ret;
        worst = f64::min(worst, *ret);
    }
    Evaluation {
        fitness: total / f64::from(T::EPISODES),
        metrics: vec![worst, steps],
        behaviour: place.map(|p| p / steps).to_vec(),
    }
}

/// `T`'s episode from state `state` under `actions`, until it terminates, is
/// truncated or the actions run out; the error says what is wrong with the input.
pub fn episode<T: Classic>(state: &[f64], actions: &[f64]) -> Result<Vec<Step>, String> {
    let mut s = T::State::of(state).ok_or_else(|| {
        format!(
            "state {state:?} is not {} state (as env.unwrapped.state holds it)",
            crate::error::a(T::NAME)
        )
    })?;
    let mut obs = vec![0.0; T::INPUTS - 1];
    let mut out = Vec::new();
    for (n, &a) in actions.iter().enumerate() {
        let action = T::Action::of(a, T::OUTPUTS).ok_or_else(|| {
            format!(
                "action {a} (step {n}) is not {} action",
                crate::error::a(T::NAME)
            )
        })?;
        let (next, reward, terminated) = T::step(s, action);
        s = next;
        T::observe(&s, &mut obs);
        let truncated = n + 1 >= T::MAX_STEPS as usize;
        out.push(Step {
            state: s.values(),
            observation: obs.iter().map(|v| single(*v)).collect(),
            reward,
            terminated,
            truncated,
        });
        if terminated || truncated {
            break;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_task_s_default_run_has_its_own_generations() {
        let generations = |t: &str| {
            let name = crate::config::TaskName(t.into());
            (crate::tasks::default_config(Some(&name))
                .unwrap()
                .experiment)
                .generations
        };
        assert_eq!(generations("mountain-car"), 200);
        for t in ["cartpole", "acrobot", "mountain-car-continuous", "pendulum"] {
            assert_eq!(generations(t), 100, "{t}");
        }
    }

    #[test]
    fn argmax_takes_the_first_largest() {
        assert_eq!(argmax(&[0.1, 0.3, 0.3]), 1);
        assert_eq!(argmax(&[0.5, 0.5]), 0);
        assert_eq!(argmax(&[-1.0, -2.0, 0.0]), 2);
    }

    /// Genomes of `T`'s shape grown by 25 generations of its own fitness
    /// (hidden nodes, disabled links).
    fn grown<T: Classic>() -> Vec<vivae_neat::Genome> {
        let params = vivae_neat::NeatParams {
            add_node_probability: 0.2,
            add_link_probability: 0.4,
            population_size: 40,
            ..vivae_neat::NeatParams::plain_neat()
        };
        let spec = super::super::plain::spec::<T>();
        let mut pop = vivae_neat::Population::new(params, spec, 5).unwrap();
        let mut all = Vec::new();
        for _ in 0..25 {
            pop.evaluate(|g, ctx| {
                evaluate::<T>(&mut FeedForwardNetwork::from_genome(g), ctx.seed, None).fitness
            });
            all.extend(pop.genomes().iter().step_by(7).cloned());
            pop.next_generation();
        }
        all
    }

    /// Every genome's evaluation in lanes is its evaluation one episode at a time, to the bit.
    fn lanes_are_one_by_one<T: Classic>() {
        let bits = |e: &Evaluation| {
            let mut v = vec![e.fitness.to_bits()];
            v.extend(e.metrics.iter().chain(&e.behaviour).map(|x| x.to_bits()));
            v
        };
        let genomes = grown::<T>();
        assert!(
            genomes
                .iter()
                .any(|g| g.nodes().len() > T::INPUTS + T::OUTPUTS)
        );
        for (k, g) in genomes.iter().enumerate() {
            let net = FeedForwardNetwork::from_genome(g);
            let seed = splitmix64(k as u64);
            let one = evaluate::<T>(&mut net.clone(), seed, None);
            assert_eq!(
                bits(&evaluate_lanes::<T>(&net, seed)),
                bits(&one),
                "{}",
                T::NAME
            );
        }
    }

    #[test]
    fn lanes_give_every_tasks_evaluations_to_the_bit() {
        lanes_are_one_by_one::<super::super::cartpole::CartPole>();
        lanes_are_one_by_one::<super::super::acrobot::Acrobot>();
        lanes_are_one_by_one::<super::super::mountain_car::MountainCar>();
        lanes_are_one_by_one::<super::super::mountain_car_continuous::MountainCarContinuous>();
        lanes_are_one_by_one::<super::super::pendulum::Pendulum>();
    }

    #[test]
    fn validation_draws_from_its_own_stream_of_the_run_seed() {
        use crate::tasks::cartpole::CartPole;
        use vivae_neat::eval::eval_seed;
        for run in [0, 1, 7, u64::MAX] {
            let v = validation_seed(run);
            assert_eq!(v, splitmix64(run ^ u64::from_be_bytes(*b"validate")));
            // Not the seed of any evaluation of a default-sized run (and not the replay's).
            assert!((0..=100).all(|g| (0..150).all(|i| eval_seed(run, g, i) != v)));
            assert_ne!(v, super::super::plain::REPLAY_SEED);
        }
        assert_ne!(validation_seed(1), validation_seed(2));
        // A network that always pushes right: every episode falls within a few
        // dozen steps; its validation is the mean of its 100 episodes, each
        // started as a training episode of the validation seed is.
        let mut net = Always(1);
        let v = validate::<CartPole>(&mut net, 3);
        assert_eq!(v, validate::<CartPole>(&mut net, 3), "deterministic");
        assert_eq!(v.episodes, VALIDATION_EPISODES);
        let mut by_hand = Vec::new();
        for k in 0..VALIDATION_EPISODES {
            let p = play::<CartPole>(&mut net, validation_seed(3), k + 1, None);
            by_hand.push(p.total - by_hand.iter().sum::<f64>());
        }
        let mean = by_hand.iter().sum::<f64>() / f64::from(VALIDATION_EPISODES);
        let worst = by_hand.iter().copied().fold(f64::INFINITY, f64::min);
        assert_eq!((v.mean, v.worst), (mean, worst));
        assert!(v.worst < v.mean && v.mean < 60.0, "{v:?}");
        assert_ne!(
            v,
            validate::<CartPole>(&mut net, 4),
            "another run, other starts"
        );
    }

    /// A network whose largest output is always `k`.
    struct Always(usize);

    impl Network for Always {
        fn num_inputs(&self) -> usize {
            5
        }

        fn num_outputs(&self) -> usize {
            2
        }

        fn activate(&mut self, _inputs: &[f64], outputs: &mut [f64]) {
            outputs
                .iter_mut()
                .enumerate()
                .for_each(|(i, o)| *o = f64::from(u8::from(i == self.0)));
        }

        fn reset(&mut self) {}
    }

    #[test]
    fn the_check_draws_from_a_third_stream() {
        use crate::tasks::cartpole::CartPole;
        use vivae_neat::eval::eval_seed;
        for run in [0, 1, 7, u64::MAX] {
            let c = check_seed(run);
            assert_eq!(c, splitmix64(run ^ u64::from_be_bytes(*b"checking")));
            assert_ne!(c, validation_seed(run));
            assert!((0..=100).all(|g| (0..150).all(|i| eval_seed(run, g, i) != c)));
            assert_ne!(c, super::super::plain::REPLAY_SEED);
        }
        assert_ne!(check_seed(1), check_seed(2));
        // The check plays its own episodes: the same network validated and
        // checked gets other starts, so other returns.
        let mut net = Always(1);
        let (c, cost) = check::<CartPole>(&mut net, 3);
        assert_eq!(cost, 20, "100 episodes are 20 evaluations of 5");
        assert_eq!(c.episodes, CHECK_EPISODES);
        let p = play::<CartPole>(&mut net, check_seed(3), CHECK_EPISODES, None);
        assert_eq!(c.mean, p.total / 100.0);
        assert_ne!(c, validate::<CartPole>(&mut net, 3));
    }

    #[test]
    fn draws_stay_in_their_range_and_follow_the_seed() {
        let mut d = Draws::new(7, 2);
        let xs: Vec<f64> = (0..1000).map(|_| d.uniform(-0.6, -0.4)).collect();
        assert!(xs.iter().all(|x| (-0.6..-0.4).contains(x)));
        let mut again = Draws::new(7, 2);
        assert_eq!(again.uniform(-0.6, -0.4), xs[0]);
        assert_ne!(Draws::new(7, 3).uniform(-0.6, -0.4), xs[0]);
    }
}
