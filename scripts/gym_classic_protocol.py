"""vivae's classic-control protocol for peer libraries run through Gymnasium
(docs/howto/classic-control.md, "The protocol"), shared by the neat-python
and MultiNEAT drivers beside it: the splitmix64 draws and seeds vivae uses,
each task's Gymnasium id, threshold, start draw and how outputs in [0, 1]
act, and an episode with the drawn start put into the environment after its
reset.
"""

import math

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


# Per task: Gymnasium id, threshold, how a start is drawn, how outputs act,
# inputs, outputs. Sigmoid outputs lie in [0, 1]: a continuous action is
# rescaled to its range.
TASKS = {
    "cartpole": ("CartPole-v1", 475.0, cartpole_start, argmax, 4, 2),
    "acrobot": ("Acrobot-v1", -100.0, acrobot_start, argmax, 6, 3),
    "mountain-car": ("MountainCar-v0", -110.0, car_start, argmax, 2, 3),
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


def episode_return(env, outputs, start, act, begin=None):
    """One episode from `start`: `outputs(observation)` gives the network's
    outputs, `act` turns them into the action, `begin()` (if given) clears
    the network's state first."""
    env.reset(seed=0)
    env.unwrapped.state = start
    obs, total = observation(env), 0.0
    if begin is not None:
        begin()
    while True:
        obs, reward, terminated, truncated, _ = env.step(act(outputs(obs)))
        total += float(reward)
        if terminated or truncated:
            return total


def mean_return(env, outputs, seed, episodes, start, act, begin=None):
    """The mean return over `episodes` episodes of the evaluation of `seed`."""
    returns = [
        episode_return(env, outputs, start(Draws(seed, k)), act, begin)
        for k in range(episodes)
    ]
    return sum(returns) / episodes
