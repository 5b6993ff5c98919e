"""The driving task evaluated on a Ray cluster through ask/tell: NEAT breeds
in this process, each genome's episodes run in a Ray task (the task and the
genomes travel pickled: the task by its settings, genomes by their JSON).
The generations are the same, bit for bit, as `task.evaluate` here.

    pip install ray
    python python/examples/ray_ask_tell.py          # a local cluster of 2 CPUs
    RAY_ADDRESS=auto python python/examples/ray_ask_tell.py   # an existing cluster
"""

import os

import ray

import vivae

ray.init(address=os.environ.get("RAY_ADDRESS"), num_cpus=None if os.environ.get("RAY_ADDRESS") else 2)

task = vivae.DriveTask(scenario="oval", steps=200, population=24, threads=1)
task_ref = ray.put(task)


@ray.remote
def fitness(task: vivae.DriveTask, genome: vivae.Genome) -> float:
    """One genome's fitness: the driving task's episodes, in a Ray worker."""
    return task.evaluate([genome])[0]


pop = task.population()
for generation in range(1, 6):
    genomes = pop.ask()
    scores = ray.get([fitness.remote(task_ref, g) for g in genomes])
    assert scores == task.evaluate(genomes), "remote and local evaluation differ"
    pop.tell(scores)
    print(f"generation {generation}: best {max(scores):.4f}")
ray.shutdown()
