"""XOR by ask/tell: NEAT in Rust, the fitness function in Python.

    python python/examples/xor_ask_tell.py
"""

import vivae

CASES = [((0.0, 0.0), 0.0), ((0.0, 1.0), 1.0), ((1.0, 0.0), 1.0), ((1.0, 1.0), 0.0)]


def fitness(genome: vivae.Genome) -> float:
    """(4 - total error)^2: 16 is perfect."""
    net = genome.network()
    error = sum(abs(net.activate([a, b, 1.0])[0] - want) for (a, b), want in CASES)  # 1.0: bias
    return (4.0 - error) ** 2


pop = vivae.Population(inputs=3, outputs=1, seed=1)  # Stanley's XOR settings, 150 genomes
for generation in range(300):
    scores = [fitness(g) for g in pop.ask()]
    pop.tell(scores)
    if max(scores) >= 15.0:
        break

genome, best, found_in = pop.best_ever
print(f"solved in generation {found_in}: fitness {best:.3f}, {genome}")
net = genome.network()
for (a, b), want in CASES:
    print(f"  {a:.0f} xor {b:.0f} = {net.activate([a, b, 1.0])[0]:.3f} (want {want:.0f})")
