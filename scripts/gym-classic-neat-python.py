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

import sys
import time

import gymnasium as gym
import neat

from gym_classic_protocol import (
    EPISODES,
    TASKS,
    VALIDATION_EPISODES,
    eval_seed,
    mean_return,
    validation_seed,
)

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
            g.fitness = mean_return(env, net.activate, seed, EPISODES, start, act)
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
    validated = mean_return(env, net.activate, validation_seed(run_seed), VALIDATION_EPISODES,
                            start, act)
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
