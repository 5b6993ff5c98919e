"""Co-evolve hunters and prey by ask/tell, then watch the champions meet in
the PettingZoo environment.

Each genome meets a sample of the other side's hall of fame (its champion of
every earlier generation, Rosin & Belew 1997), drawn with a seeded RNG;
afterwards the CIAO matrix (Cliff & Miller 1995) says whether later hunters
beat earlier prey more than earlier hunters did.

    python python/examples/predator_prey.py [generations]
"""

from __future__ import annotations

import random
import sys

import numpy as np

import vivae

GENERATIONS = int(sys.argv[1]) if len(sys.argv) > 1 else 20
SAMPLE = 3

task = vivae.PredatorPreyTask(scenario="predator-prey", steps=300, population=50, seed=1)
hunters, prey = task.population("hunter"), task.population("prey")
rng = random.Random(1)
hall_hunters: list[vivae.Genome] = []
hall_prey: list[vivae.Genome] = []
for generation in range(GENERATIONS):
    hs, ps = hunters.ask(), prey.ask()
    if hall_hunters:
        against_hunters = rng.choices(hall_prey, k=SAMPLE)
        against_prey = rng.choices(hall_hunters, k=SAMPLE)
    else:
        against_hunters, against_prey = [ps[0]], [hs[0]]
    hunters.tell(task.evaluate("hunter", hs, against_hunters))
    prey.tell(task.evaluate("prey", ps, against_prey))
    told_h, told_p = hunters.champion, prey.champion   # None only before a tell
    assert told_h is not None and told_p is not None
    (h, hf), (p, pf) = told_h, told_p
    hall_hunters.append(h)
    hall_prey.append(p)
    print(f"gen {generation + 1:3}  best hunter {hf:.3f}  best prey {pf:.3f}")

# The CIAO matrix: hunter champion of generation i against prey champion of j.
ciao = np.array([[task.meet(h, p)["hunter_fitness"] for p in hall_prey] for h in hall_hunters])
later = np.mean([ciao[i, j] for i in range(GENERATIONS) for j in range(i)]) if GENERATIONS > 1 else float("nan")
earlier = np.mean([ciao[i, j] for i in range(GENERATIONS) for j in range(i + 1, GENERATIONS)]) if GENERATIONS > 1 else float("nan")
print(f"hunters against earlier prey: {later:.3f}; against later prey: {earlier:.3f} (hunter fitness, 0..2)")

# The last champions meet in the environment; the summed rewards are the task's fitnesses.
env = vivae.PredatorPreyParallelEnv(scenario="predator-prey", steps=300)
nets = {"hunter_0": hall_hunters[-1].network(), "prey_0": hall_prey[-1].network()}
obs, _ = env.reset(seed=0)
returns = dict.fromkeys(env.possible_agents, 0.0)
while env.agents:
    obs, rewards, terms, truncs, infos = env.step(
        {a: np.array(nets[a].activate(list(obs[a]))) for a in env.agents}
    )
    for a, r in rewards.items():
        returns[a] += r
print("returns", returns, "caught" if infos["hunter_0"]["caught"] else "escaped")
print("task.meet", task.meet(hall_hunters[-1], hall_prey[-1]))
