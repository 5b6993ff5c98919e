"""Evolve a driver by ask/tell (episodes simulated in Rust), then drive the
Gymnasium environment with the champion's decoded substrate.

    python python/examples/champion_driver.py
"""

import gymnasium
import numpy as np

import vivae

# The paper's substrate (3x5 sensors, 3x3 neurons), shorter episodes and a small population.
task = vivae.DriveTask(scenario="roads", sensors="3x5", neurons="3x3", steps=400, robots=1)
pop = task.population(seed=1, size=60)
for generation in range(15):
    genomes = pop.ask()
    scores = task.evaluate(genomes)  # every episode in Rust threads, without the GIL
    pop.tell(scores)
    print(f"gen {generation + 1}: best {max(scores):.3f} px/step")

champion, fitness, _ = pop.best_ever
weights = task.decode(champion)
print("substrate:", {k: getattr(v, "shape", v) for k, v in weights.items()})

env = gymnasium.make("vivae/Drive-v0", scenario="roads", sensors="3x5", steps=400)
controller = task.controller(champion)
obs, _ = env.reset(seed=0)
total, steps = 0.0, 0
while True:
    wheels = controller.act(obs[None, :].astype(np.float64))[0]
    obs, reward, _, truncated, _ = env.step(wheels.astype(np.float32))
    total += reward
    steps += 1
    if truncated:
        break
# The environment's readings are float32: close to, not bit for bit, the run's own episode.
print(f"in the environment: {total / steps:.3f} px/step (evolution measured {fitness:.3f})")
