"""neat-python 2.x on Gymnasium's classic control under vivae's protocol
(docs/howto/classic-control.md, "The protocol"): an evaluation is 5
episodes whose starts are drawn from the evaluation's seed (the same
splitmix64 draws and seeds vivae uses, put into Gymnasium's environment after
its reset), fitness the mean return; a run stops at the first evaluation whose
mean reaches the threshold, or at its budget; that genome (or, unsolved, the
best one) is validated on the 100 starts of the run seed's validation stream,
and the run is solved when the validated mean reaches the threshold.

  python gym-classic-neat-python.py CONFIG TASK SEED EVALUATIONS CPU_SECONDS

prints one line: task, seed, stopped (yes/no), evaluations, CPU and wall
seconds, the validated mean and solved=yes|no. CONFIG is neat-python's
single-pole-balancing config-feedforward with its inputs and outputs set
(scripts/gym-classic-neat-python.sh writes it).
"""

import math
import sys
import time

import gymnasium as gym
import neat
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


# Per task: Gymnasium id, threshold, how a start is drawn, how outputs act.
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


TASKS = {
    "cartpole": ("CartPole-v1", 475.0, cartpole_start, argmax, 4, 2),
    "acrobot": ("Acrobot-v1", -100.0, acrobot_start, argmax, 6, 3),
    "mountain-car": ("MountainCar-v0", -110.0, car_start, argmax, 2, 3),
    # neat-python's sigmoid outputs lie in [0, 1]: rescaled to the action's range.
    "mountain-car-continuous": (
        "MountainCarContinuous-v0", 90.0, car_start,
        lambda out: np.array([2.0 * out[0] - 1.0], dtype=np.float32), 2, 1),
    "pendulum": (
        "Pendulum-v1", -200.0, pendulum_start,
        lambda out: np.array([4.0 * out[0] - 2.0], dtype=np.float32), 3, 1),
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
    while True:
        obs, reward, terminated, truncated, _ = env.step(act(net.activate(obs)))
        total += float(reward)
        if terminated or truncated:
            return total


def mean_return(env, net, seed, episodes, start, act):
    returns = [episode_return(env, net, start(Draws(seed, k)), act) for k in range(episodes)]
    return sum(returns) / episodes


class Stop(Exception):
    pass


def main(config_path, task, run_seed, budget, cpu_limit):
    env_id, threshold, start, act, _, _ = TASKS[task]
    env = gym.make(env_id)
    config = neat.Config(neat.DefaultGenome, neat.DefaultReproduction,
                         neat.DefaultSpeciesSet, neat.DefaultStagnation, config_path)
    state = {"evaluations": 0, "solver": None, "best": None}
    cpu0, wall0 = time.process_time(), time.perf_counter()

    def eval_genomes(genomes, config):
        generation = population.generation
        for index, (_, g) in enumerate(genomes):
            net = neat.nn.FeedForwardNetwork.create(g, config)
            seed = eval_seed(run_seed, generation, index)
            g.fitness = mean_return(env, net, seed, EPISODES, start, act)
            state["evaluations"] += 1
            if state["best"] is None or g.fitness > state["best"][0]:
                state["best"] = (g.fitness, g)
            if g.fitness >= threshold:
                state["solver"] = g
                raise Stop()
            if state["evaluations"] >= budget or time.process_time() - cpu0 >= cpu_limit:
                raise Stop()

    population = neat.Population(config, seed=run_seed)
    try:
        population.run(eval_genomes, None)
    except (Stop, neat.CompleteExtinctionException):
        pass
    cpu, wall = time.process_time() - cpu0, time.perf_counter() - wall0
    champion = state["solver"] or state["best"][1]
    net = neat.nn.FeedForwardNetwork.create(champion, config)
    validated = mean_return(env, net, validation_seed(run_seed), VALIDATION_EPISODES, start, act)
    cpu_all, wall_all = time.process_time() - cpu0, time.perf_counter() - wall0
    print(
        f"task={task} seed={run_seed} stopped={'yes' if state['solver'] else 'no'} "
        f"evaluations={state['evaluations']} cpu_s={cpu:.2f} wall_s={wall:.2f} "
        f"cpu_with_validation_s={cpu_all:.2f} wall_with_validation_s={wall_all:.2f} "
        f"validated={validated:.2f} solved={'yes' if validated >= threshold else 'no'}",
        flush=True,
    )


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5]))
