"""neat-python 2.x on LunarLander-v3 under the Gymnasium suite's protocol
(docs/howto/gymnasium-python.md, "The protocol"; scripts/gym-suite.sh runs
vivae's side): an evaluation plays EPISODES episodes, each reset with a
Gymnasium seed drawn from the evaluation's seed (splitmix64 of the run seed,
generation, genome and episode), fitness is their mean return; the run plays
GENERATIONS generations; its champion (the best training fitness of the
run) is validated on 100 episodes reset with seeds 0 to 99, and the run is
solved when that mean is at least 200.

  python gym-lander-neat-python.py CONFIG RUN SEED GENERATIONS EPISODES

Resumable: RUN holds neat-python's own checkpoint (restored on the next
call), each generation's best genome (bests.pickle), each generation's best and CPU
seconds (generations.csv) and, once finished, validation.json; a finished run
is skipped. Prints one line: seed, generations, the champion's generation and
training fitness, CPU seconds and the validated mean.
"""

import csv
import json
import os
import pickle
import sys
import time
from pathlib import Path

import gymnasium as gym
import neat
import numpy as np

from gym_classic_protocol import splitmix64

ENV, THRESHOLD, VALIDATION = "LunarLander-v3", 200.0, 100
SEED_MASK = (1 << 63) - 1


def episode_seed(run_seed, generation, index, k):
    """The Gymnasium seed of episode k of genome `index`'s evaluation in `generation`."""
    return splitmix64(splitmix64(splitmix64(splitmix64(run_seed) ^ generation) ^ index) ^ k) & SEED_MASK


def episode_return(env, net, seed):
    obs, _ = env.reset(seed=int(seed))
    total = 0.0
    while True:
        obs, reward, terminated, truncated, _ = env.step(int(np.argmax(net.activate(obs))))
        total += float(reward)
        if terminated or truncated:
            return total


def write_atomic(path: Path, data: bytes) -> None:
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    tmp.write_bytes(data)
    os.replace(tmp, path)


def main(config_path, run, run_seed, generations, episodes):
    run = Path(run)
    run.mkdir(parents=True, exist_ok=True)
    env = gym.make(ENV)
    config = neat.Config(neat.DefaultGenome, neat.DefaultReproduction,
                         neat.DefaultSpeciesSet, neat.DefaultStagnation, config_path)
    progress = run / "generations.csv"
    rows = []
    if progress.exists():
        with progress.open() as f:
            rows = list(csv.DictReader(f))
    checkpoints = sorted(run.glob("neat-checkpoint-*"), key=lambda p: int(p.name.rsplit("-", 1)[1]))
    if checkpoints:
        population = neat.Checkpointer.restore_checkpoint(str(checkpoints[-1]))
    else:
        population = neat.Population(config, seed=run_seed)
    start = population.generation
    rows = [r for r in rows if int(r["generation"]) <= start]
    # Each generation's best genome, by generation: those a checkpoint has not yet
    # covered are played again, so only generations up to it are kept.
    bests = pickle.loads((run / "bests.pickle").read_bytes()) if (run / "bests.pickle").exists() else {}
    bests = {g: b for g, b in bests.items() if g <= start}
    population.add_reporter(neat.Checkpointer(1, filename_prefix=str(run / "neat-checkpoint-")))
    mark = [time.process_time()]

    def eval_genomes(genomes, config):
        generation = population.generation
        for index, (_, g) in enumerate(genomes):
            net = neat.nn.FeedForwardNetwork.create(g, config)
            g.fitness = float(np.mean([episode_return(env, net, episode_seed(run_seed, generation, index, k))
                                       for k in range(episodes)]))
        top = max((g for _, g in genomes), key=lambda g: g.fitness)
        bests[generation + 1] = {"genome": top, "fitness": top.fitness}
        now = time.process_time()
        rows.append({"generation": str(generation + 1),
                     "best": f"{max(g.fitness for _, g in genomes):.3f}",
                     "cpu_seconds": f"{now - mark[0]:.3f}"})
        mark[0] = now
        write_atomic(run / "bests.pickle", pickle.dumps(bests))
        write_atomic(progress, ("generation,best,cpu_seconds\n" + "".join(
            f"{r['generation']},{r['best']},{r['cpu_seconds']}\n" for r in rows)).encode())

    if start < generations and not (run / "validation.json").exists():
        try:
            population.run(eval_genomes, generations - start)
        except neat.CompleteExtinctionException:
            pass
        for old in sorted(run.glob("neat-checkpoint-*"), key=lambda p: int(p.name.rsplit("-", 1)[1]))[:-1]:
            old.unlink()
    if not (run / "validation.json").exists():
        t0 = time.process_time()
        # The champion: the best training fitness of the run, the earliest on a tie.
        generation = max(sorted(bests), key=lambda g: bests[g]["fitness"])
        best = dict(bests[generation], generation=generation)
        net = neat.nn.FeedForwardNetwork.create(best["genome"], config)
        returns = np.array([episode_return(env, net, s) for s in range(VALIDATION)])
        result = {"env": ENV, "episodes": VALIDATION, "seeds": [0, VALIDATION - 1],
                  "mean": float(returns.mean()), "std": float(returns.std()),
                  "min": float(returns.min()), "max": float(returns.max()),
                  "reward_threshold": THRESHOLD, "solved": bool(returns.mean() >= THRESHOLD),
                  "generation": best["generation"], "fitness": best["fitness"],
                  "generations": len(rows), "validation_cpu_seconds": time.process_time() - t0}
        write_atomic(run / "validation.json", (json.dumps(result, indent=2) + "\n").encode())
    result = json.loads((run / "validation.json").read_text())
    cpu = sum(float(r["cpu_seconds"]) for r in rows)
    print(f"env={ENV} seed={run_seed} generations={result['generations']} champion_generation={result['generation']} "
          f"fitness={result['fitness']:.1f} cpu_s={cpu:.1f} validated={result['mean']:.1f} "
          f"solved={'yes' if result['solved'] else 'no'}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5]))
