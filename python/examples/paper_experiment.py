"""The paper's experiment from Python: the run directory `vivae evolve` writes.

    python python/examples/paper_experiment.py [OUT] [GENERATIONS]

With no GENERATIONS, the paper's 400 (hours on two cores); try 10 first.
Then `vivae resume OUT` draws the figures and report.html (`--generations N` extends the run).
"""

import sys

import vivae

out = sys.argv[1] if len(sys.argv) > 1 else "runs/python-paper"
settings = {"generations": int(sys.argv[2])} if len(sys.argv) > 2 else {}
result = vivae.evolve(out=out, **settings)  # every other setting: the paper's
print(f"best {result['best']:.4f} px/step (generation {result['champion_generation']}), run in {result['out']}")
print("champion's behaviour:", vivae.replay(out))
