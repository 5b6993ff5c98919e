"""neat-python 2.0 on the efficacy tasks of examples/{multiplexer,sinewave,prey_capture}.rs.

python efficacy.py TASK SECONDS RUNS [fixed]   (TASK: multiplexer | sinewave | prey_capture)

`fixed` turns off every structural mutation (add/delete node and connection), so
every network keeps the full input-to-output start topology: the like-for-like
speed measurement, run beside the Rust examples with
`--set add_node_probability=0 --set add_link_probability=0`.

Same task definitions as the Rust examples' common/*_task.rs (SharpNEAT's), same
population sizes, fixed wall-clock runs on one process; prints the same summary line.
"""
import math, os, random, statistics, sys, time
import neat

def mux(net):
    f = 0.0
    for i in range(2048):
        y = min(1.0, max(0.0, net.activate([1.0] + [(i >> k) & 1 for k in range(11)])[0]))
        f += 1.0 - (1.0 - y) ** 2 if (1 << (3 + (i & 7))) & i else 1.0 - y * y
    return f

XS = [25.13274123 / 79 * k for k in range(80)]
YS = [math.sin(x) for x in XS]
MID, SCALE = (max(YS) + min(YS)) / 2, (max(YS) - min(YS)) / 0.8

def grad(y):
    n = len(y) - 1
    return [(y[1] - y[0]) / (XS[1] - XS[0])] + [
        (y[k + 1] - y[k - 1]) / (XS[k + 1] - XS[k - 1]) for k in range(1, n)
    ] + [(y[n] - y[n - 1]) / (XS[n] - XS[n - 1])]

DYS = grad(YS)

def sine(net):
    net.reset()
    for _ in range(3):
        net.activate([1.0])
    got = [(net.activate([1.0])[0] - 0.5) * SCALE + MID for _ in XS]
    if not all(math.isfinite(v) for v in got):
        return 0.0
    mse = lambda a, b: sum((p - q) ** 2 for p, q in zip(a, b)) / len(a)
    return 20.0 / (0.1 * mse(got, YS) + 0.9 * mse(grad(got), DYS) + 0.02)

def polar(dx, dy):
    a = math.atan2(dy, dx)
    return dx * dx + dy * dy, a + 2 * math.pi if a < 0 else a

def step(p, d):
    x, y = p
    return [(x, min(y + 1, 23)), (min(x + 1, 23), y), (x, max(y - 1, 0)), (max(x - 1, 0), y)][d]

def prey_trial(net, rng):
    prey = (4 + rng.randrange(16), 4 + rng.randrange(16))
    t, r = 2 * math.pi * rng.random(), 2 + 2 * rng.random()
    agent = (prey[0] + int(math.cos(t) * r), prey[1] + int(math.sin(t) * r))
    net.reset()
    near = lambda d: (4 - d) / 4 if d <= 4 else 0.0
    for t in range(70):
        r2, az = polar(prey[0] - agent[0], prey[1] - agent[1])
        v = [1.0] + [0.0] * 13
        if r2 <= 16:
            a = az - math.pi / 8
            v[1 + min(7, int(math.floor((a + 2 * math.pi if a < 0 else a) * 4 / math.pi)))] = 1.0
        v[9] = 1.0 if r2 <= 4 else 0.0
        v[10:14] = [near(23 - agent[1]), near(23 - agent[0]), near(agent[1]), near(agent[0])]
        out = net.activate(v)
        if t >= 4:
            b = max(range(4), key=lambda i: out[i])
            if out.count(out[b]) == 1 and out[b] >= 0.1:
                agent = step(agent, b)
            if agent == prey:
                return True
        r2, az = polar(agent[0] - prey[0], agent[1] - prey[1])
        d = math.sqrt(r2)
        k = (15 - d if d <= 4 else 9 - d * 0.5 if d <= 15 else 1.0) * 0.33
        w = lambda b: (1 + min(abs(az - b), 2 * math.pi - abs(az - b)) / math.pi * k / 29.5) ** 32
        p = [w(math.pi / 2), w(0.0), w(1.5 * math.pi), w(math.pi)]
        th, acc, dirn = rng.random() * sum(p), 0.0, 3
        for i, q in enumerate(p):
            acc += q
            if acc > th:
                dirn = i
                break
        prey = step(prey, dirn)
        if agent == prey and t >= 4:
            return True
    return False

def prey_capture(net):
    rng = random.Random(random.getrandbits(64))
    return float(sum(prey_trial(net, rng) for _ in range(100)))

TASKS = {  # name: (fitness, inputs, outputs, feed_forward, population, max fitness)
    "multiplexer": (mux, 12, 1, True, 600, 2048.0),
    "sinewave": (sine, 1, 1, False, 600, 1000.0),
    "prey_capture": (prey_capture, 14, 4, False, 225, 100.0),
}

def main():
    name, seconds, runs = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
    fit, nin, nout, ff, pop_size, top = TASKS[name]
    cfg = neat.Config(neat.DefaultGenome, neat.DefaultReproduction, neat.DefaultSpeciesSet,
                      neat.DefaultStagnation, os.path.join(os.path.dirname(__file__), "efficacy_config.ini"))
    cfg.pop_size = pop_size
    cfg.genome_config.num_inputs, cfg.genome_config.num_outputs = nin, nout
    cfg.genome_config.input_keys = [-i - 1 for i in range(nin)]
    cfg.genome_config.output_keys = list(range(nout))
    cfg.genome_config.feed_forward = ff
    if sys.argv[4:] == ["fixed"]:
        g = cfg.genome_config
        g.conn_add_prob = g.conn_delete_prob = g.node_add_prob = g.node_delete_prob = 0.0
    elif sys.argv[4:]:
        print(f"efficacy.py: unknown argument {sys.argv[4]!r} (only `fixed`)", file=sys.stderr)
        sys.exit(2)
    make = neat.nn.FeedForwardNetwork.create if ff else neat.nn.RecurrentNetwork.create
    bests, evals, secs = [], [], 0.0
    for r in range(runs):
        random.seed(1 + r)
        state = {"n": 0, "best": 0.0, "links": 0, "hidden": 0}
        def eval_genomes(genomes, config):
            for _, g in genomes:
                g.fitness = fit(make(g, config))
                state["n"] += 1
                state["best"] = max(state["best"], g.fitness)
                # Network size, to compare work per evaluation with vivae-neat's.
                state["links"] += sum(1 for c in g.connections.values() if c.enabled)
                state["hidden"] += len(g.nodes) - nout
        p = neat.Population(cfg)
        start = time.time()
        while time.time() - start < seconds and state["best"] < top:
            p.run(eval_genomes, 1)
        s = time.time() - start
        n = max(state["n"], 1)
        print(f"{name} seed={1 + r} best={state['best']} evals={state['n']} s={s:.1f} "
              f"mean_links={state['links'] / n:.1f} mean_hidden={state['hidden'] / n:.1f}", file=sys.stderr)
        bests.append(state["best"]); evals.append(state["n"]); secs += s
    print(f"neat-python {name}: runs={runs} best_fitness(min/median/max)={min(bests):.2f}/"
          f"{statistics.median(bests):.2f}/{max(bests):.2f} evals_per_run(median)="
          f"{statistics.median(evals):.0f} evals_per_s={sum(evals) / secs:.0f}")

if __name__ == "__main__":
    main()
