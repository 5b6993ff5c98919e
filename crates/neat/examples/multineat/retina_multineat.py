"""MultiNEAT (PyPI `multineat` 0.12) on the left & right retina of examples/retina.rs.

python retina_multineat.py --mode MODE --runs N --seed S --max-generations G

MODE: es (ES-HyperNEAT), es-leo (ES-HyperNEAT with MultiNEAT's `Leo`: a
point is expressed only where the last CPPN output exceeds `LeoThreshold` 0;
`LeoSeed` and `GeometrySeed` are set too, but MultiNEAT's genome constructor
does not read them in its current source, so there is no locality seed),
hyperneat (a fixed 8 -> 8 -> 4 -> 2 sheet, every queried link expressed),
leo (the same sheet, a link expressed where the first CPPN output is > 0 and
weighted by the second: MultiNEAT's two-output HyperNEAT, no seed).

Same task as the Rust example: 256 images of a 4x2 retina (0/1 pixels), the
same left and right object sets, outputs in (0, 1), E the summed
|output - label| over both outputs and all images, fitness 1000/(1 + E^2),
solved when all 512 answers are on the right side of 0.5; population 100;
evaluations counted up to and including the first solver. Coordinates are
MultiNEAT's 3-D ones with z = 0: inputs along y = -1 (left half at x < 0),
outputs at (-0.5, 1) and (0.5, 1). MultiNEAT needs a bias neuron as its last
input (at (0, -1), value 1). Prints
`multineat-retina-MODE: solved=a/b mean_evals=... wall_s_per_run=...` on stdout.

Note on the Substrate call: this wheel's binding wants each coordinate as an
iterator, `NEAT.Substrate([iter([x, y, z]), ...], ...)`; plain lists raise
"Object of type 'list' is not an instance of 'iterator'".
"""
import argparse
import statistics
import sys
import time

import multineat as NEAT

LEFT_OBJECTS = [0b1000, 0b0100, 0b1100, 0b1111, 0b1011, 0b0111, 0b1110, 0b1101]
RIGHT_OBJECTS = [0b1011, 0b0111, 0b1110, 0b1101, 0b0010, 0b0001, 0b0011, 0b1111]
POPULATION = 100
INPUT_X = [-1.0 + 2.0 * i / 7.0 for i in range(8)]
OUTPUTS = [(-0.5, 1.0, 0.0), (0.5, 1.0, 0.0)]
# Activation steps per image: enough for input -> hidden -> hidden -> output.
DEPTH = 4


def images():
    """The 256 images (left half first along x, then the bias) and their labels."""
    out = []
    for image in range(256):
        left, right = image >> 4, image & 0xF
        x = [0.0] * 8
        for bit in range(4):
            x[3 - bit] = float((left >> bit) & 1)
            x[7 - bit] = float((right >> bit) & 1)
        out.append((x + [1.0], (left in LEFT_OBJECTS, right in RIGHT_OBJECTS)))
    return out


def row(n, y):
    return [(-1.0 + 2.0 * i / (n - 1), y, 0.0) for i in range(n)]


def substrate(mode):
    inputs = [(x, -1.0, 0.0) for x in INPUT_X] + [(0.0, -1.0, 0.0)]
    hidden = [] if mode.startswith("es") else row(8, -1.0 / 3.0) + row(4, 1.0 / 3.0)
    s = NEAT.Substrate([iter(p) for p in inputs], [iter(p) for p in hidden],
                       [iter(p) for p in OUTPUTS])
    s.m_allow_input_hidden_links = True
    s.m_allow_hidden_hidden_links = True
    s.m_allow_hidden_output_links = True
    s.m_allow_input_output_links = False
    s.m_allow_output_hidden_links = False
    s.m_allow_output_output_links = False
    s.m_allow_looped_hidden_links = False
    s.m_allow_looped_output_links = False
    s.m_hidden_nodes_activation = NEAT.ActivationFunction.SIGNED_SIGMOID
    s.m_output_nodes_activation = NEAT.ActivationFunction.UNSIGNED_SIGMOID
    s.m_with_distance = False
    s.m_max_weight_and_bias = 3.0
    # hyperneat: one CPPN output, every queried link expressed with its weight;
    # leo, es-leo: a second output (MultiNEAT's link expression output).
    s.m_query_weights_only = mode in ("hyperneat", "es")
    return s


def params(mode):
    p = NEAT.Parameters()
    p.PopulationSize = POPULATION
    p.DynamicCompatibility = True
    p.MinSpecies = 5
    p.MaxSpecies = 15
    p.RouletteWheelSelection = False
    p.MutateAddLinkProb = 0.3
    p.MutateAddNeuronProb = 0.1
    p.MutateWeightsProb = 0.8
    p.MaxWeight = 3.0
    p.CrossoverRate = 0.75
    p.MutateNeuronActivationTypeProb = 0.1
    for name in ("SignedSigmoid", "SignedGauss", "SignedSine", "Linear", "Abs"):
        setattr(p, "ActivationFunction_%s_Prob" % name, 1.0)
    for name in ("UnsignedSigmoid", "Tanh", "TanhCubic", "SignedStep", "UnsignedStep",
                 "UnsignedGauss", "UnsignedSine"):
        setattr(p, "ActivationFunction_%s_Prob" % name, 0.0)
    # ES-HyperNEAT settings of MultiNEAT's own ES examples, as in EsParams::default()
    # except DivisionThreshold (theirs 0.5; ours 0.03, as its ES settings file).
    p.InitialDepth = 3
    p.MaxDepth = 3
    p.DivisionThreshold = 0.03
    p.VarianceThreshold = 0.03
    p.BandThreshold = 0.3
    p.Qtree_X, p.Qtree_Y, p.Width, p.Height = 0.0, 0.0, 1.0, 1.0
    p.CPPN_Bias = 1.0
    p.Leo = mode == "es-leo"
    p.LeoSeed = mode == "es-leo"
    p.GeometrySeed = mode == "es-leo"
    p.LeoThreshold = 0.0
    return p


def evaluate(net, data):
    error, right = 0.0, 0
    flush, feed, activate, output = net.Flush, net.Input, net.Activate, net.Output
    for x, labels in data:
        flush()
        feed(x)
        for _ in range(DEPTH):
            activate()
        out = output()
        for a, label in zip(out, labels):
            error += abs(a - (1.0 if label else 0.0))
            right += (a > 0.5) == label
    return 1000.0 / (1.0 + error * error), right


def run(mode, seed, gens, data):
    subst = substrate(mode)
    par = params(mode)
    g = NEAT.Genome(0, subst.GetMinCPPNInputs(), 0, subst.GetMinCPPNOutputs(), False,
                    NEAT.ActivationFunction.TANH, NEAT.ActivationFunction.TANH, 0, par, 0)
    pop = NEAT.Population(g, par, True, 1.0, seed)
    rng = NEAT.RNG()
    rng.Seed(seed)
    best_right, best_hidden = 0, 0
    for gen in range(gens):
        for i, genome in enumerate(NEAT.GetGenomeList(pop)):
            net = NEAT.NeuralNetwork()
            if mode.startswith("es"):
                genome.BuildESHyperNEATPhenotype(net, subst, par, rng)
            else:
                genome.BuildHyperNEATPhenotype(net, subst, rng)
            fitness, right = evaluate(net, data)
            genome.SetFitness(fitness)
            genome.SetEvaluated()
            if right > best_right:
                best_right = right
                best_hidden = len(net.neurons) - net.NumInputs() - net.NumOutputs()
            if right == 512:
                return gen * POPULATION + i + 1, best_right, best_hidden
        pop.Epoch()
    return None, best_right, best_hidden


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mode", default="es", choices=["es", "es-leo", "hyperneat", "leo"])
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--max-generations", type=int, default=500)
    a = ap.parse_args()
    data = images()
    evals, accuracy, hidden, walls = [], [], [], []
    for seed in range(a.seed, a.seed + a.runs):
        t0 = time.time()
        e, right, h = run(a.mode, seed, a.max_generations, data)
        walls.append(time.time() - t0)
        accuracy.append(right / 512.0)
        hidden.append(h)
        if e is not None:
            evals.append(e)
        print("seed=%d evals=%s best_accuracy=%.3f substrate_hidden=%d wall_s=%.1f"
              % (seed, e, right / 512.0, h, walls[-1]), file=sys.stderr, flush=True)
    mean_evals = "%.0f" % statistics.mean(evals) if evals else "-"
    print("multineat-retina-%s: solved=%d/%d mean_evals=%s mean_best_accuracy=%.3f "
          "mean_substrate_hidden=%.1f wall_s_per_run=%.1f"
          % (a.mode, len(evals), a.runs, mean_evals, statistics.mean(accuracy),
             statistics.mean(hidden), statistics.mean(walls)))


if __name__ == "__main__":
    main()
