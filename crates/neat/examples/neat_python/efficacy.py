"""neat-python 2.0 on the efficacy tasks of examples/{multiplexer,sinewave,prey_capture}.rs.

python efficacy.py TASK SECONDS RUNS [fixed]   (TASK: multiplexer | sinewave | prey_capture
                                               | xor | pole_markov | pole_nonmarkov)

`fixed` turns off every structural mutation (add/delete node and connection), so
every network keeps the full input-to-output start topology: the like-for-like
speed measurement, run beside the Rust examples with
`--set add_node_probability=0 --set add_link_probability=0`.

Same task definitions as the Rust examples' common/*_task.rs (SharpNEAT's), same
population sizes, fixed wall-clock runs on one process; prints the same summary line.

xor, pole_markov and pole_nonmarkov are vivae-neat's own tasks (benchmarks/xor.rs,
benchmarks/pole.rs), run beside examples/{xor_speed,pole_markov_speed,pole_nonmarkov_speed}.rs:
populations 150, 150 and 1,000; these runs never stop at a solution, and stop evaluating
mid-generation once their time is up (the rest of that generation is neither scored nor
counted). The pole tasks also print network activations (control steps) per evaluation
and per second. With `fixed` these three also keep every link enabled and give the
recurrent start no output self-link, so that the networks are vivae-neat's exactly.
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

def prey_weights(dx, dy):
    """The prey's weights of moving N, E, S, W with the agent at (dx, dy) from it."""
    r2, az = polar(dx, dy)
    d = math.sqrt(r2)
    k = (15 - d if d <= 4 else 9 - d * 0.5 if d <= 15 else 1.0) * 0.33
    w = lambda b: (1 + min(abs(az - b), 2 * math.pi - abs(az - b)) / math.pi * k / 29.5) ** 32
    return [w(math.pi / 2), w(0.0), w(1.5 * math.pi), w(math.pi)]

# Both are pure functions of an offset between two cells: looked up, as the
# Rust task does (common/prey_task.rs), not computed each step.
POLAR = {(dx, dy): polar(dx, dy) for dx in range(-23, 24) for dy in range(-23, 24)}
PREY_WEIGHTS = {(dx, dy): prey_weights(dx, dy) for dx in range(-23, 24) for dy in range(-23, 24)}

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
        r2, az = POLAR[(prey[0] - agent[0], prey[1] - agent[1])]
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
        p = PREY_WEIGHTS[(agent[0] - prey[0], agent[1] - prey[1])]
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

XOR_CASES = [((0.0, 0.0, 1.0), 0.0), ((0.0, 1.0, 1.0), 1.0), ((1.0, 0.0, 1.0), 1.0), ((1.0, 1.0, 1.0), 0.0)]

def xor(net):
    err = 0.0
    for x, t in XOR_CASES:
        err += abs(net.activate(x)[0] - t)
    return (4.0 - err) ** 2

# Double pole balancing as vivae-neat's benchmarks/pole.rs: Wieland's equations, RK4 in
# 0.01 s steps, the action held for two; failure at |x| > 2.4 m or a pole beyond 36 degrees.
GRAVITY, MASS_CART, MASS_POLE_1, LENGTH_1, MASS_POLE_2, LENGTH_2 = -9.8, 1.0, 0.1, 0.5, 0.01, 0.05
FORCE_MAG, TAU, MUP, FAIL_ANGLE = 10.0, 0.01, 0.000002, 36.0 * math.pi / 180.0
POLE_STEPS = [0]  # network activations of all pole evaluations so far

def pole_derivs(force, s):
    sin1, cos1, sin2, cos2 = math.sin(s[2]), math.cos(s[2]), math.sin(s[4]), math.cos(s[4])
    gsin1, gsin2 = GRAVITY * sin1, GRAVITY * sin2
    ml1, ml2 = LENGTH_1 * MASS_POLE_1, LENGTH_2 * MASS_POLE_2
    temp1, temp2 = MUP * s[3] / ml1, MUP * s[5] / ml2
    fi1 = ml1 * s[3] * s[3] * sin1 + 0.75 * MASS_POLE_1 * cos1 * (temp1 + gsin1)
    fi2 = ml2 * s[5] * s[5] * sin2 + 0.75 * MASS_POLE_2 * cos2 * (temp2 + gsin2)
    mi1 = MASS_POLE_1 * (1.0 - 0.75 * cos1 * cos1)
    mi2 = MASS_POLE_2 * (1.0 - 0.75 * cos2 * cos2)
    xacc = (force + fi1 + fi2) / (mi1 + mi2 + MASS_CART)
    acc1 = -0.75 * (xacc * cos1 + gsin1 + temp1) / LENGTH_1
    acc2 = -0.75 * (xacc * cos2 + gsin2 + temp2) / LENGTH_2
    return (s[1], xacc, s[3], acc1, s[5], acc2)

def rk4(force, s):
    k1 = pole_derivs(force, s)
    k2 = pole_derivs(force, [a + TAU / 2.0 * k for a, k in zip(s, k1)])
    k3 = pole_derivs(force, [a + TAU / 2.0 * k for a, k in zip(s, k2)])
    k4 = pole_derivs(force, [a + TAU * k for a, k in zip(s, k3)])
    return [a + TAU / 6.0 * (p + 2.0 * q + 2.0 * r + u) for a, p, q, r, u in zip(s, k1, k2, k3, k4)]

def balance(net, markov, s, max_steps):
    """Steps survived and Gruau's stability term over the last 100 steps."""
    last = [0.0] * 100
    for t in range(max_steps):
        if markov:
            obs = [s[0] / 4.8, s[1] / 2.0, s[2] / 0.52, s[3] / 2.0, s[4] / 0.52, s[5] / 2.0, 0.5]
        else:
            obs = [s[0] / 4.8, s[2] / 0.52, s[4] / 0.52, 0.5]
        force = (net.activate(obs)[0] - 0.5) * FORCE_MAG * 2.0
        s = rk4(force, rk4(force, s))
        if abs(s[0]) > 2.4 or abs(s[2]) > FAIL_ANGLE or abs(s[4]) > FAIL_ANGLE:
            POLE_STEPS[0] += t + 1
            return t, sum(last)
        last[t % 100] = abs(s[0]) + abs(s[1]) + abs(s[2]) + abs(s[3])
    POLE_STEPS[0] += max_steps
    return max_steps, sum(last)

def pole_markov(net):
    return float(balance(net, True, [0.0, 0.0, 0.07, 0.0, 0.0, 0.0], 100000)[0])

def pole_nonmarkov(net):
    net.reset()
    t, wiggle = balance(net, False, [0.0, 0.0, math.radians(4.5), 0.0, 0.0, 0.0], 1000)
    return 0.1 * (t / 1000.0) + 0.9 * (0.0 if t < 100 else 0.75 / max(wiggle, 1e-9))

TASKS = {  # name: (fitness, inputs, outputs, feed_forward, population, max fitness)
    "multiplexer": (mux, 12, 1, True, 600, 2048.0),
    "sinewave": (sine, 1, 1, False, 600, 1000.0),
    "prey_capture": (prey_capture, 14, 4, False, 225, 100.0),
    "xor": (xor, 3, 1, True, 150, math.inf),
    "pole_markov": (pole_markov, 7, 1, True, 150, math.inf),
    "pole_nonmarkov": (pole_nonmarkov, 4, 1, False, 1000, math.inf),
}
CUT = {"xor", "pole_markov", "pole_nonmarkov"}  # stop mid-generation when the time is up

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
        if name in CUT:
            # vivae-neat's start networks exactly: no link toggled (plain_neat never toggles)
            # and no output self-link (its recurrent start has none; `make` stays recurrent).
            g.enabled_mutate_rate = 0.0
            g.feed_forward = True
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
                if name in CUT and ("cut" in state or time.time() - start >= seconds):
                    state.setdefault("cut", time.time())
                    g.fitness = 0.0  # not evaluated, not counted
                    continue
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
        s = state.get("cut", time.time()) - start
        n = max(state["n"], 1)
        print(f"{name} seed={1 + r} best={state['best']} evals={state['n']} s={s:.1f} "
              f"mean_links={state['links'] / n:.1f} mean_hidden={state['hidden'] / n:.1f}", file=sys.stderr)
        bests.append(state["best"]); evals.append(state["n"]); secs += s
    print(f"neat-python {name}: runs={runs} best_fitness(min/median/max)={min(bests):.2f}/"
          f"{statistics.median(bests):.2f}/{max(bests):.2f} evals_per_run(median)="
          f"{statistics.median(evals):.0f} evals_per_s={sum(evals) / secs:.2f}")
    if name.startswith("pole"):
        print(f"neat-python {name}: steps_per_eval={POLE_STEPS[0] / max(sum(evals), 1):.1f} "
              f"steps_per_s={POLE_STEPS[0] / secs:.0f}")

if __name__ == "__main__":
    main()
