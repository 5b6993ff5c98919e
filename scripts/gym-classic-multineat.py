"""MultiNEAT (the `multineat` package) on Gymnasium's classic control under
vivae's protocol, as scripts/gym-classic-neat-python.py runs neat-python: an
evaluation is 5 episodes whose starts are drawn from the evaluation's seed
(the same splitmix64 draws and seeds vivae uses, put into Gymnasium's
environment after its reset), fitness the mean return; a run stops at the
first evaluation whose mean reaches the threshold (no check), or at its
budget; that genome (or, unsolved, the best one) is validated on the 100
starts of the run seed's validation stream, and the run is solved when the
validated mean reaches the threshold.

  python gym-classic-multineat.py TASK SEED EVALUATIONS CPU_SECONDS

prints one line: task, seed, stopped (yes/no), evaluations, CPU and wall
seconds, the validated mean and solved=yes|no.

MultiNEAT settings: `multineat.Parameters()` left at its defaults
(population 300, dynamic compatibility, recurrent links allowed), and the
start genome and population built as MultiNEAT's XOR example builds them:
inputs plus a constant 1.0 bias input, no hidden neurons, unsigned-sigmoid
hidden and output neurons, `Population(genome, params, True, 1.0, seed)`.
Each environment step is one `Input` + `Activate` (the network is flushed at
an episode's start), so deeper paths act with a delay, as MultiNEAT's
recurrent networks do. MultiNEAT's selection wants fitness ≥ 0, so its
fitness is the mean return plus a per-task offset (the lowest return the
task can give); the stopping rule and validation use the return itself.
"""

import math
import sys
import time

import gymnasium as gym
import multineat
import numpy as np

MASK = (1 << 64) - 1
# "validate" in ASCII: the validation stream's tag (vivae's tasks::classic::VALIDATION_TAG).
VALIDATION_TAG = 0x7661_6C69_6461_7465
EPISODES, VALIDATION_EPISODES = 5, 100


def splitmix64(z):
    z = (z + 0x9E3779B97F4A7C15) & MASK
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
    return z ^ (z >> 31)


class Draws:
    """vivae's tasks::classic::Draws: episode k of the evaluation of `seed`."""

    def __init__(self, seed, k):
        self.s = splitmix64(seed ^ k)

    def uniform(self, low, high):
        self.s = splitmix64(self.s)
        return low + (high - low) * ((self.s >> 11) / float(1 << 53))


def eval_seed(run_seed, generation, index):
    return splitmix64(splitmix64(splitmix64(run_seed) ^ generation) ^ index)


def validation_seed(run_seed):
    return splitmix64(run_seed ^ VALIDATION_TAG)


def cartpole_start(d):
    return np.array([d.uniform(-0.05, 0.05) for _ in range(4)])


def acrobot_start(d):
    return np.array([d.uniform(-0.1, 0.1) for _ in range(4)], dtype=np.float32)


def car_start(d):
    return np.array([d.uniform(-0.6, -0.4), 0.0])


def pendulum_start(d):
    return np.array([d.uniform(-math.pi, math.pi), d.uniform(-1.0, 1.0)])


def argmax(out):
    return int(np.argmax(out))


# Per task: Gymnasium id, threshold, start draw, how outputs act, inputs,
# outputs, fitness offset (the lowest return the task can give, so fitness ≥ 0).
TASKS = {
    "cartpole": ("CartPole-v1", 475.0, cartpole_start, argmax, 4, 2, 0.0),
    "acrobot": ("Acrobot-v1", -100.0, acrobot_start, argmax, 6, 3, 500.0),
    "mountain-car": ("MountainCar-v0", -110.0, car_start, argmax, 2, 3, 200.0),
    # Unsigned-sigmoid outputs lie in [0, 1]: rescaled to the action's range.
    "mountain-car-continuous": (
        "MountainCarContinuous-v0", 90.0, car_start,
        lambda out: np.array([2.0 * out[0] - 1.0], dtype=np.float32), 2, 1, 100.0),
    "pendulum": (
        "Pendulum-v1", -200.0, pendulum_start,
        lambda out: np.array([4.0 * out[0] - 2.0], dtype=np.float32), 3, 1,
        200.0 * (math.pi ** 2 + 0.1 * 64.0 + 0.001 * 4.0)),
}


def observation(env):
    u = env.unwrapped
    for name in ("_get_ob", "_get_obs"):
        if hasattr(u, name):
            return getattr(u, name)()
    return np.array(u.state, dtype=np.float32)


def episode_return(env, net, start, act):
    env.reset(seed=0)
    env.unwrapped.state = start
    obs, total = observation(env), 0.0
    net.Flush()
    while True:
        net.Input([float(x) for x in obs] + [1.0])
        net.Activate()
        obs, reward, terminated, truncated, _ = env.step(act(list(net.Output())))
        total += float(reward)
        if terminated or truncated:
            return total


def mean_return(env, net, seed, episodes, start, act):
    returns = [episode_return(env, net, start(Draws(seed, k)), act) for k in range(episodes)]
    return sum(returns) / episodes


def phenotype(genome):
    net = multineat.NeuralNetwork()
    genome.BuildPhenotype(net)
    return net


def main(task, run_seed, budget, cpu_limit):
    env_id, threshold, start, act, inputs, outputs, offset = TASKS[task]
    env = gym.make(env_id)
    params = multineat.Parameters()
    sigmoid = multineat.ActivationFunction.UNSIGNED_SIGMOID
    genome = multineat.Genome(0, inputs + 1, 0, outputs, False, sigmoid, sigmoid, 0, params, 0)
    cpu0, wall0 = time.process_time(), time.perf_counter()
    population = multineat.Population(genome, params, True, 1.0, run_seed)
    evaluations, solver, best = 0, None, None
    generation = 0
    while solver is None:
        for index, g in enumerate(multineat.GetGenomeList(population)):
            mean = mean_return(env, phenotype(g), eval_seed(run_seed, generation, index),
                               EPISODES, start, act)
            g.SetFitness(mean + offset)
            g.SetEvaluated()
            evaluations += 1
            if best is None or mean > best[0]:
                best = (mean, multineat.Genome(g))
            if mean >= threshold:
                solver = multineat.Genome(g)
                break
            if evaluations >= budget or time.process_time() - cpu0 >= cpu_limit:
                break
        if solver is not None or evaluations >= budget or time.process_time() - cpu0 >= cpu_limit:
            break
        population.Epoch()
        generation += 1
    cpu, wall = time.process_time() - cpu0, time.perf_counter() - wall0
    champion = solver if solver is not None else best[1]
    validated = mean_return(env, phenotype(champion), validation_seed(run_seed),
                            VALIDATION_EPISODES, start, act)
    cpu_all, wall_all = time.process_time() - cpu0, time.perf_counter() - wall0
    print(
        f"task={task} seed={run_seed} stopped={'yes' if solver is not None else 'no'} "
        f"evaluations={evaluations} generations={generation + 1} cpu_s={cpu:.2f} "
        f"wall_s={wall:.2f} cpu_with_validation_s={cpu_all:.2f} "
        f"wall_with_validation_s={wall_all:.2f} "
        f"validated={validated:.2f} solved={'yes' if validated >= threshold else 'no'}",
        flush=True,
    )


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]))
