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

from gym_classic_protocol import (
    EPISODES,
    TASKS,
    VALIDATION_EPISODES,
    eval_seed,
    mean_return,
    validation_seed,
)

# The lowest return each task can give: MultiNEAT's fitness is the mean
# return plus it, so that fitness is ≥ 0 as its selection wants.
OFFSET = {
    "cartpole": 0.0,
    "acrobot": 500.0,
    "mountain-car": 200.0,
    "mountain-car-continuous": 100.0,
    "pendulum": 200.0 * (math.pi ** 2 + 0.1 * 64.0 + 0.001 * 4.0),
}


def policy(net):
    """The network's outputs for an observation (plus the 1.0 bias input),
    one `Input` + `Activate` per step, and how it is flushed at an episode's
    start."""

    def outputs(obs):
        net.Input([float(x) for x in obs] + [1.0])
        net.Activate()
        return list(net.Output())

    return outputs, net.Flush


def phenotype(genome):
    net = multineat.NeuralNetwork()
    genome.BuildPhenotype(net)
    return net


def main(task, run_seed, budget, cpu_limit):
    env_id, threshold, start, act, inputs, outputs = TASKS[task]
    offset = OFFSET[task]
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
            outputs_of, flush = policy(phenotype(g))
            mean = mean_return(env, outputs_of, eval_seed(run_seed, generation, index),
                               EPISODES, start, act, flush)
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
    outputs_of, flush = policy(phenotype(champion))
    validated = mean_return(env, outputs_of, validation_seed(run_seed),
                            VALIDATION_EPISODES, start, act, flush)
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
