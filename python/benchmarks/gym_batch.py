"""Environment steps per CPU-second of one batched generation of vivae.gym,
and the share of CPU time spent in vivae (the networks) and in the
environments: a population of random networks, one episode each, all in
this process.

    python python/benchmarks/gym_batch.py LunarLander-v3 [--population 100]
"""

from __future__ import annotations

import argparse
import time

import vivae
import vivae.gym


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("env")
    parser.add_argument("--population", type=int, default=100)
    a = parser.parse_args()
    section = vivae.gym.env_section(a.env, episodes=1)
    genomes = vivae.Population(section["inputs"], section["outputs"], seed=1, size=a.population).ask()
    seeds = vivae._vivae.gym_episode_seeds(list(range(a.population)), 1)
    vivae.gym._episodes(a.env, a.population)  # the environments are made before the clock starts
    vivae.gym._reset_clock()
    started = time.process_time()
    vivae.gym._play(section, genomes, seeds)
    total = time.process_time() - started
    k = vivae.gym._clock
    vivae.gym._close()
    print(
        f"{a.env}: {k['steps']} steps in {total:.2f} CPU s = {k['steps'] / total:.0f} steps/CPU-s; "
        f"environments {k['env'] / total:.1%} ({1e6 * k['env'] / k['steps']:.1f} us a step), "
        f"vivae {k['vivae'] / total:.1%} ({1e6 * k['vivae'] / k['steps']:.1f} us a step)"
    )


if __name__ == "__main__":
    main()
