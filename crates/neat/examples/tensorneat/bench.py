"""TensorNEAT speed on CPU, for the side-by-side with vivae-neat.

    python bench.py xor3d  [--seeds 42]       TensorNEAT's own examples/func_fit/xor.py
    python bench.py xor2   [--seeds 1,2,3]    2-input XOR, population 150, vivae's solve rule
    python bench.py pole   [--seeds 1,2,3]    Markov double pole, the physics of
                                              crates/neat/src/benchmarks/pole.rs

Each run prints one line per generation on stderr and one summary line on
stdout: compile seconds (JAX tracing + XLA compilation of one generation,
timed apart), the generations run, evaluations, wall seconds of the evolution
after compilation, evaluations/s, and for the pole the network steps taken.

Threads: JAX's CPU backend runs on the main thread and a process-wide thread
pool; pin the process with `taskset -c 0` for one core. setup.sh makes the
venv (pinned versions). vivae_rate.py gives vivae's side from its examples'
per-run lines.

TensorNEAT evaluates a generation as one vmap over padded genomes; for the
pole, the episode's lax.while_loop under vmap steps every genome until the
last one fails, so `padded_network_steps` (population x the longest episode,
summed over generations) is what is computed and `network_steps` (the sum of
each genome's episode length, vivae's count) what is needed.
"""

import argparse
import json
import os
import sys
import time

import jax
import jax.numpy as jnp
import numpy as np

from tensorneat import algorithm as talg, genome as tgen, problem as tprob
from tensorneat.common import ACT, State
from tensorneat.pipeline import Pipeline
from tensorneat.problem.rl import RLEnv
from tensorneat.problem.func_fit import FuncFit


# --------------------------------------------------------------------------
# Double pole balancing with velocities (Markov), as in pole.rs.
# --------------------------------------------------------------------------

GRAVITY = -9.8
MASS_CART = 1.0
MASS_POLE_1 = 0.1
LENGTH_1 = 0.5  # half length
MASS_POLE_2 = 0.01
LENGTH_2 = 0.05
FORCE_MAG = 10.0
TAU = 0.01
MUP = 0.000002
FAIL_ANGLE = 36.0 * np.pi / 180.0
SUCCESS_STEPS = 100_000


def derivatives(force, s):
    sin1, cos1 = jnp.sin(s[2]), jnp.cos(s[2])
    sin2, cos2 = jnp.sin(s[4]), jnp.cos(s[4])
    gsin1 = GRAVITY * sin1
    gsin2 = GRAVITY * sin2
    ml1 = LENGTH_1 * MASS_POLE_1
    ml2 = LENGTH_2 * MASS_POLE_2
    temp1 = MUP * s[3] / ml1
    temp2 = MUP * s[5] / ml2
    fi1 = ml1 * s[3] * s[3] * sin1 + 0.75 * MASS_POLE_1 * cos1 * (temp1 + gsin1)
    fi2 = ml2 * s[5] * s[5] * sin2 + 0.75 * MASS_POLE_2 * cos2 * (temp2 + gsin2)
    mi1 = MASS_POLE_1 * (1.0 - 0.75 * cos1 * cos1)
    mi2 = MASS_POLE_2 * (1.0 - 0.75 * cos2 * cos2)
    xacc = (force + fi1 + fi2) / (mi1 + mi2 + MASS_CART)
    acc1 = -0.75 * (xacc * cos1 + gsin1 + temp1) / LENGTH_1
    acc2 = -0.75 * (xacc * cos2 + gsin2 + temp2) / LENGTH_2
    return jnp.stack([s[1], xacc, s[3], acc1, s[5], acc2])


def rk4(force, s):
    k1 = derivatives(force, s)
    k2 = derivatives(force, s + TAU / 2.0 * k1)
    k3 = derivatives(force, s + TAU / 2.0 * k2)
    k4 = derivatives(force, s + TAU * k3)
    return s + TAU / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)


def observe(s):
    return jnp.stack(
        [s[0] / 4.8, s[1] / 2.0, s[2] / 0.52, s[3] / 2.0, s[4] / 0.52, s[5] / 2.0,
         jnp.asarray(0.5, s.dtype)]
    )


def steep_sigmoid(z):
    """vivae's Activation::Sigmoid (Stanley's 1 / (1 + e^(-4.9 z)))."""
    return 1.0 / (1.0 + jnp.exp(-4.9 * z))


class DoublePoleMarkov(RLEnv):
    """pole.rs with velocities: inputs x, ẋ, θ1, θ̇1, θ2, θ̇2 scaled as Stanley's
    and a 0.5 bias input; start [0, 0, 0.07, 0, 0, 0]; the action (network
    output in [0, 1]) is held for two RK4 steps of 0.01 s, force (a − 0.5)·20 N;
    failure when |x| > 2.4 or a pole leaves ±36°. Reward 1 per step that does
    not fail, so the return is pole.rs's fitness (steps balanced); solved =
    100,000."""

    def __init__(self, max_step=SUCCESS_STEPS):
        super().__init__(max_step=max_step, repeat_times=1)

    def env_reset(self, randkey):
        s = jnp.array([0.0, 0.0, 0.07, 0.0, 0.0, 0.0], dtype=jnp.result_type(float))
        return observe(s), s

    def env_step(self, randkey, s, action):
        a = jnp.reshape(action, ())
        force = (a - 0.5) * FORCE_MAG * 2.0
        s = rk4(force, rk4(force, s))
        failed = (jnp.abs(s[0]) > 2.4) | (jnp.abs(s[2]) > FAIL_ANGLE) | (jnp.abs(s[4]) > FAIL_ANGLE)
        reward = jnp.where(failed, 0.0, 1.0)
        return observe(s), s, reward, failed, {}

    @property
    def input_shape(self):
        return (7,)

    @property
    def output_shape(self):
        return (1,)


# --------------------------------------------------------------------------
# 2-input XOR with vivae's fitness and solve rule.
# --------------------------------------------------------------------------


class XorVivae(FuncFit):
    """XOR on 2 inputs (TensorNEAT's nodes have their own biases, so no bias
    input); fitness (4 − Σ|error|)² and solved when all four outputs are on the
    right side of 0.5, as crates/neat/src/benchmarks/xor.rs. evaluate returns
    the fitness plus 100 for a solver, so the solve rule can be read from the
    fitness (selection is unaffected: solving ends the run)."""

    X = np.array([[0, 0], [0, 1], [1, 0], [1, 1]], dtype=np.float32)
    Y = np.array([[0], [1], [1], [0]], dtype=np.float32)

    def evaluate(self, state, randkey, act_func, params):
        y = jax.vmap(act_func, in_axes=(None, None, 0))(state, params, self.X)
        err = jnp.sum(jnp.abs(y - self.Y))
        solved = jnp.all((y > 0.5) == (self.Y > 0.5))
        return (4.0 - err) ** 2 + jnp.where(solved, 100.0, 0.0)

    @property
    def inputs(self):
        return self.X

    @property
    def targets(self):
        return self.Y

    @property
    def input_shape(self):
        return 4, 2

    @property
    def output_shape(self):
        return 4, 1


# --------------------------------------------------------------------------
# Setups
# --------------------------------------------------------------------------


def setup_xor3d(seed):
    """examples/func_fit/xor.py of TensorNEAT, unchanged but for the seed."""
    alg = talg.NEAT(
        pop_size=10000,
        species_size=20,
        survival_threshold=0.01,
        genome=tgen.DefaultGenome(
            num_inputs=3,
            num_outputs=1,
            max_nodes=7,
            output_transform=ACT.sigmoid,
        ),
    )
    pipe = Pipeline(alg, tprob.XOR3d(), generation_limit=200, fitness_target=-1e-6, seed=seed)
    return pipe, lambda f: f >= -1e-6


def setup_xor2(seed):
    """The XOR example's genome (max_nodes 7, sigmoid output), NEAT's defaults
    otherwise, population 150, at most 500 generations (vivae's xor default)."""
    alg = talg.NEAT(
        pop_size=150,
        genome=tgen.DefaultGenome(
            num_inputs=2,
            num_outputs=1,
            max_nodes=7,
            output_transform=ACT.sigmoid,
        ),
    )
    pipe = Pipeline(alg, XorVivae(), generation_limit=500, fitness_target=100.0, seed=seed)
    return pipe, lambda f: f >= 100.0


def setup_pole(seed):
    """Population 150 and at most 200 generations as vivae's --markov; the
    genome has 7 inputs (with the 0.5 bias input), 1 output, vivae's steep
    sigmoid on hidden nodes and on the output; NEAT's and the genome's
    TensorNEAT defaults otherwise (max_nodes 50, max_conns 100)."""
    alg = talg.NEAT(
        pop_size=150,
        genome=tgen.DefaultGenome(
            num_inputs=7,
            num_outputs=1,
            node_gene=tgen.DefaultNode(activation_options=steep_sigmoid),
            output_transform=steep_sigmoid,
        ),
    )
    pipe = Pipeline(alg, DoublePoleMarkov(), generation_limit=200,
                    fitness_target=float(SUCCESS_STEPS), seed=seed)
    return pipe, lambda f: f >= SUCCESS_STEPS


SETUPS = {"xor3d": setup_xor3d, "xor2": setup_xor2, "pole": setup_pole}


def run(task, seed, quiet, max_generations=None):
    pipe, solved_by = SETUPS[task](seed)
    if max_generations is not None:
        pipe.generation_limit = max_generations
    t0 = time.perf_counter()
    state = pipe.setup(State())
    jax.block_until_ready(state)
    t_setup = time.perf_counter() - t0

    t0 = time.perf_counter()
    compiled = jax.jit(pipe.step).lower(state).compile()
    t_compile = time.perf_counter() - t0

    pop = pipe.pop_size
    evals = 0
    solved_at = None
    first_solver_evals = None
    steps = 0  # network steps actually needed (pole: Σ per genome of steps run)
    padded_steps = 0  # pole: pop × the longest episode (what the batch computes)
    gen_times = []
    t_start = time.perf_counter()
    for g in range(pipe.generation_limit):
        tg = time.perf_counter()
        state, _, fit = compiled(state)
        fit = np.asarray(jax.device_get(fit))
        gen_times.append(time.perf_counter() - tg)
        evals += pop
        if task == "pole":
            # fitness t = steps balanced; a failing episode ran t + 1 steps.
            run_steps = np.where(fit >= SUCCESS_STEPS, SUCCESS_STEPS, fit + 1)
            steps += int(run_steps.sum())
            padded_steps += pop * int(run_steps.max())
        if not quiet:
            extra = (f" steps={int(run_steps.sum())} longest={int(run_steps.max())}"
                     if task == "pole" else "")
            print(f"{task} seed={seed} gen={g} best={fit.max():.6g} "
                  f"ms={gen_times[-1] * 1e3:.1f}{extra}", file=sys.stderr, flush=True)
        hits = np.nonzero(solved_by(fit))[0]
        if hits.size:
            solved_at = g + 1
            first_solver_evals = g * pop + int(hits[0]) + 1
            break
    wall = time.perf_counter() - t_start
    out = {
        "task": task,
        "seed": seed,
        "pop": pop,
        "setup_s": round(t_setup, 3),
        "compile_s": round(t_compile, 3),
        "solved": solved_at is not None,
        "generations": len(gen_times),
        "evals": evals,
        "evals_to_first_solver": first_solver_evals,
        "wall_s": round(wall, 3),
        "first_gen_s": round(gen_times[0], 4),
        "evals_per_s": round(evals / wall, 1),
        "median_gen_ms": round(float(np.median(gen_times)) * 1e3, 2),
    }
    if task != "pole":
        # Evaluation alone (transform + forward + loss of the last population,
        # no reproduction), compiled apart and timed over 20 calls.
        pop_now = pipe.algorithm.ask(state)
        keys = jax.random.split(state.randkey, pop)

        def eval_only(state, pop_now, keys):
            tr = jax.vmap(pipe.algorithm.transform, in_axes=(None, 0))(state, pop_now)
            return jax.vmap(pipe.problem.evaluate, in_axes=(None, 0, None, 0))(
                state, keys, pipe.algorithm.forward, tr)

        ev = jax.jit(eval_only).lower(state, pop_now, keys).compile()
        jax.block_until_ready(ev(state, pop_now, keys))
        te = time.perf_counter()
        for _ in range(20):
            jax.block_until_ready(ev(state, pop_now, keys))
        out["eval_only_evals_per_s"] = round(20 * pop / (time.perf_counter() - te), 1)
    if task == "pole":
        out["network_steps"] = steps
        out["padded_network_steps"] = padded_steps
        out["network_steps_per_s"] = round(steps / wall, 1)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("task", choices=sorted(SETUPS))
    ap.add_argument("--seeds", default="42")
    ap.add_argument("--max-generations", type=int, default=None,
                    help="stop after G generations (default: the setup's limit)")
    ap.add_argument("--quiet", action="store_true", help="no per-generation lines")
    args = ap.parse_args()
    print(json.dumps({
        "jax": jax.__version__,
        "devices": [str(d) for d in jax.devices()],
        "x64": bool(jax.config.jax_enable_x64),
        "XLA_FLAGS": os.environ.get("XLA_FLAGS", ""),
        "affinity": sorted(os.sched_getaffinity(0)),
    }), flush=True)
    for s in args.seeds.split(","):
        print(json.dumps(run(args.task, int(s), args.quiet, args.max_generations)), flush=True)


if __name__ == "__main__":
    main()
