"""Gymnasium's Box2D and MuJoCo environments evolved as vivae runs
(vivae.gym), and the batched controllers they step with (vivae.Controllers)."""

from __future__ import annotations

import importlib.util
import json
import os
from pathlib import Path
import signal
import subprocess
import sys

import numpy as np
import pytest

import vivae
from conftest import vivae_binary


def needs(module: str, extra: str):
    """Skips (saying why) unless `module` is installed."""
    if importlib.util.find_spec(module) is None:
        reason = f"{module} is not installed (pip install 'gymnasium[{extra}]')"
        print(f"skipped: {reason}")
        return pytest.mark.skip(reason=reason)
    return pytest.mark.skipif(False, reason=f"{module} is installed")


box2d = needs("Box2D", "box2d")
mujoco = needs("mujoco", "mujoco")


def grown_genomes(recurrent: bool) -> list:
    """Genomes of 9 inputs and 4 outputs grown for 25 generations (hidden
    nodes, disabled links; recurrent links when allowed)."""
    pop = vivae.Population(
        9, 4, seed=4, size=30, recurrent=recurrent,
        params={"add_node_probability": 0.3, "add_link_probability": 0.5},
    )
    for _ in range(25):
        genomes = pop.ask()
        pop.tell([float(g.num_links + (i % 5)) for i, g in enumerate(genomes)])
    return pop.ask()


@pytest.mark.parametrize("recurrent", [False, True])
def test_controllers_give_each_networks_bits(recurrent):
    genomes = grown_genomes(recurrent)
    assert any(g.num_hidden > 0 for g in genomes)
    rng = np.random.default_rng(1)
    batch = vivae.Controllers(genomes)
    nets = [g.network() for g in genomes]
    assert len(batch) == len(genomes) and batch.obs_size == 8 and batch.outputs == 4
    for _ in range(4):
        obs = rng.normal(size=(len(genomes), 8))
        got = batch.act(obs)
        want = np.array([n.activate(list(o) + [1.0]) for n, o in zip(nets, obs)])
        assert got.tobytes() == want.tobytes()
    # Some rows only, in any order: each to its own network.
    rows = np.array([5, 2, 17], dtype=np.int64)
    obs = rng.normal(size=(3, 8))
    got = batch.act(obs, rows)
    want = np.array([nets[k].activate(list(o) + [1.0]) for k, o in zip(rows, obs)])
    assert got.tobytes() == want.tobytes()


def test_controllers_refuse_wrong_shapes_by_name():
    genomes = grown_genomes(False)[:3]
    batch = vivae.Controllers(genomes)
    with pytest.raises(ValueError, match="obs has 7 values a row"):
        batch.act(np.zeros((3, 7)))
    with pytest.raises(ValueError, match="say which with rows="):
        batch.act(np.zeros((2, 8)))
    with pytest.raises(ValueError, match="rows: 3 is not a network"):
        batch.act(np.zeros((1, 8)), np.array([3], dtype=np.int64))
    with pytest.raises(ValueError, match="genomes\\[1\\] has 4 inputs"):
        vivae.Controllers([genomes[0], vivae.Population(4, 1, seed=1, size=5).ask()[0]])
    with pytest.raises(ValueError, match="at least one"):
        vivae.Controllers([])


def files(out) -> dict:
    return {n: (out / n).read_bytes() for n in ("generations.csv", "population.csv", "best-genomes.jsonl", "champion.json")}


@box2d
def test_a_lunar_lander_run_is_an_ordinary_run_that_resumes_to_the_same_files(tmp_path):
    import vivae.gym

    settings = dict(generations=3, population=12, seed=5, episodes=2, validate=5, progress=False)
    whole = vivae.gym.evolve("LunarLander-v3", tmp_path / "whole", **settings)
    assert whole["finished"] and whole["generations"] == 3
    assert whole["env_steps"] > 0 and whole["env_seconds"] > 0 and whole["vivae_seconds"] > 0
    out = tmp_path / "whole"
    for name in ("config.toml", "champion.json", "generations.csv", "checkpoints", "validation.json"):
        assert (out / name).exists(), name
    assert '[gymnasium]\nenv = "LunarLander-v3"' in (out / "config.toml").read_text()
    assert len((out / "generations.csv").read_text().splitlines()) == 4
    v = json.loads((out / "validation.json").read_text())
    assert v == whole["validation"] and v["episodes"] == 5 and v["reward_threshold"] == 200.0
    assert v["solved"] == (v["mean"] >= 200.0)
    assert vivae.report(out).is_file()
    # Stopped after generation 2, then resumed: the same files as the whole run.
    part = dict(settings, generations=2)
    vivae.gym.evolve("LunarLander-v3", tmp_path / "part", **part)
    resumed = vivae.gym.resume(tmp_path / "part", generations=3, validate=0, progress=False)
    assert resumed["generations"] == 3
    assert files(tmp_path / "part") == files(out)
    # Spread over two worker processes: the same results.
    two = vivae.gym.evolve("LunarLander-v3", tmp_path / "two", processes=2, **dict(settings, validate=0))
    assert files(tmp_path / "two") == files(out)


@box2d
def test_the_episodes_are_gymnasiums_own_under_the_evaluations_seeds(tmp_path):
    import gymnasium
    import vivae.gym

    section = vivae.gym.env_section("LunarLander-v3", episodes=2)
    assert (section["inputs"], section["outputs"], section["max_steps"]) == (9, 4, 1000)
    genome = vivae.Population(9, 4, seed=3, size=5).ask()[1]
    seeds = vivae._vivae.gym_episode_seeds([11, 12], 2)
    (fitness, worst, steps), _ = vivae.gym._play(section, [genome, genome], seeds)
    vivae.gym._close()
    # The same episodes played one step at a time with the genome's own network.
    returns, total = [], 0
    for s in seeds[0]:
        env, net = gymnasium.make("LunarLander-v3"), genome.network()
        obs, _ = env.reset(seed=s)
        ret, done = 0.0, False
        while not done:
            out = net.activate([float(x) for x in obs] + [1.0])
            obs, r, term, trunc, _ = env.step(int(np.argmax(out)))
            ret, done, total = ret + r, term or trunc, total + 1
        returns.append(ret)
    assert fitness == np.mean(returns) and worst == min(returns) and steps == total


@box2d
def test_the_program_reports_a_gymnasium_run_and_refuses_to_resume_it(tmp_path):
    import vivae.gym

    cli = vivae_binary()
    if cli is None:
        pytest.skip("no vivae binary (set VIVAE_BIN)")
    out = tmp_path / "run"
    vivae.gym.evolve("LunarLander-v3", out, generations=1, population=6, episodes=1, validate=0, progress=False)
    done = subprocess.run([cli, "report", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    refused = subprocess.run([cli, "resume", str(out), "--generations", "2"], capture_output=True, text=True)
    assert refused.returncode == 2 and "vivae.gym.resume" in refused.stderr, refused.stderr


@mujoco
@pytest.mark.parametrize("env_id", ["InvertedPendulum-v5", "Hopper-v5"])
def test_mujoco_environments_run_with_scaled_continuous_actions(tmp_path, env_id):
    import vivae.gym

    r = vivae.gym.evolve(env_id, tmp_path / "run", generations=2, population=6, seed=2, episodes=1,
                         validate=3, progress=False)
    assert r["finished"] and r["validation"]["episodes"] == 3
    assert r["validation"]["reward_threshold"] is not None


RESUMED_RUN = """
import signal
import sys
import vivae.gym

# As started from a terminal: a process started in the background of a
# non-interactive shell (as a CI step may be) inherits SIGINT ignored.
signal.signal(signal.SIGINT, signal.default_int_handler)

def said(record):
    print("generation", record["generation"], flush=True)

vivae.gym.resume(sys.argv[1], generations=10_000, processes=int(sys.argv[2]), validate=0,
                 progress=False, on_generation=said)
"""


@box2d
@pytest.mark.skipif(not hasattr(os, "killpg"), reason="needs POSIX process groups (os.killpg)")
@pytest.mark.parametrize("processes", [1, 2])
def test_ctrl_c_stops_a_resumed_run_at_a_checkpoint_saying_how_to_resume(tmp_path, processes):
    import vivae.gym

    out = tmp_path / "run"
    vivae.gym.evolve("LunarLander-v3", out, generations=1, population=12, seed=3, episodes=2,
                     validate=0, progress=False)
    # Ctrl-C in a terminal: SIGINT to the whole process group, worker processes included.
    child = subprocess.Popen([sys.executable, "-c", RESUMED_RUN, str(out), str(processes)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             start_new_session=True)
    assert child.stdout is not None
    first = child.stdout.readline()
    assert first.startswith("generation "), first + child.stderr.read()
    os.killpg(child.pid, signal.SIGINT)
    # The timeout only turns a hang (the failure this test is about) into a failure.
    try:
        rest, err = child.communicate(timeout=600)
    except subprocess.TimeoutExpired:
        os.killpg(child.pid, signal.SIGKILL)
        child.communicate()
        raise
    done = int((first + rest).split()[-1])
    assert child.returncode != 0 and done < 10_000
    last = err.strip().splitlines()[-1]
    assert last == f"KeyboardInterrupt: interrupted after generation {done}; resume with: vivae.gym.resume({str(out)!r})".replace("'", '"'), err
    assert (out / "checkpoints" / f"gen-{done:06d}.ckpt").is_file()
    assert "Worker" not in err, err
    # And it resumes from there.
    again = vivae.gym.resume(out, generations=done + 1, validate=0, progress=False)
    assert again["generations"] == done + 1 and again["finished"]


class _SignalInDestructor:
    """An object whose destructor receives Ctrl-C, as pybox2d's
    ``b2BodyDef.__del__`` (run at every LunarLander reset) sometimes did: an
    exception raised in a destructor is printed and dropped by Python."""

    def __del__(self) -> None:
        signal.raise_signal(signal.SIGINT)


@pytest.mark.parametrize("where", ["episode", "generation end"])
def test_ctrl_c_received_in_a_destructor_still_stops_the_run(tmp_path, where, monkeypatch):
    import vivae.gym

    if where == "episode":
        # During the second generation's episodes, in a destructor run by an environment's step.
        import gymnasium.envs.classic_control.cartpole as cartpole

        step, calls = cartpole.CartPoleEnv.step, []

        def step_then_signal(self, action):
            calls.append(1)
            if len(calls) == 300:
                _SignalInDestructor()
            return step(self, action)

        monkeypatch.setattr(cartpole.CartPoleEnv, "step", step_then_signal)
        on_generation = None
    else:
        def on_generation(record):
            if record["generation"] == 1:
                _SignalInDestructor()

    with pytest.raises(KeyboardInterrupt) as stopped:
        vivae.gym.evolve("CartPole-v1", tmp_path / "run", generations=50, population=8, seed=1,
                         episodes=1, validate=0, progress=False, on_generation=on_generation)
    done = int(str(stopped.value).split("after generation ")[1].split(";")[0])
    assert 1 <= done < 50 and (tmp_path / "run" / "checkpoints" / f"gen-{done:06d}.ckpt").is_file()
    # Python's own handler is back once the run has stopped.
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def png_size(data_url: str) -> tuple[int, int]:
    """Width and height of a PNG data URL, from its IHDR (checking the signature)."""
    import base64
    import struct

    prefix = "data:image/png;base64,"
    assert data_url.startswith(prefix)
    png = base64.b64decode(data_url[len(prefix):], validate=True)
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and png[12:16] == b"IHDR" and png[-8:-4] == b"IEND"
    return struct.unpack(">II", png[16:24])


@box2d
def test_validation_films_the_champions_first_episode_for_the_report(tmp_path):
    import vivae.gym

    out = tmp_path / "run"
    vivae.gym.evolve("LunarLander-v3", out, generations=1, population=6, seed=4, episodes=1,
                     validate=2, progress=False)
    film = json.loads((out / "film.json").read_text())
    frames = film["frames"]
    assert film["env"] == "LunarLander-v3" and film["seed"] == vivae.gym.VALIDATION_FIRST_SEED
    assert 2 <= len(frames) <= vivae.gym.FILM_FRAMES and film["width"] <= vivae.gym.FILM_WIDTH
    assert all(png_size(f["image"]) == (film["width"], film["height"]) for f in frames)
    # LunarLander renders 600 x 400: shrunk by the smallest whole factor that fits.
    k = -(-600 // vivae.gym.FILM_WIDTH)
    assert (film["width"], film["height"]) == (600 // k, 400 // k)
    steps = [f["step"] for f in frames]
    assert steps[0] == 0 and steps[-1] == film["steps"] and steps == sorted(set(steps))
    assert all(b - a <= film["every"] for a, b in zip(steps, steps[1:]))
    # The episode filmed is validation's first: its return, its steps.
    alone = vivae.gym.validate(out, episodes=1, film=False)
    assert film["return"] == pytest.approx(alone["mean"], rel=1e-12, abs=1e-9)
    assert sum(f["reward"] for f in frames) == pytest.approx(film["return"], rel=1e-12, abs=1e-9)
    # Fewer frames than steps: evenly spaced, the last step always shown.
    few = json.loads(vivae.gym.film(out, frames=5, width=30).read_text())
    assert len(few["frames"]) <= 5 and few["frames"][-1]["step"] == film["steps"]
    assert few["width"] <= 30 and few["return"] == pytest.approx(film["return"], rel=1e-12, abs=1e-9)
    with pytest.raises(ValueError, match="frames=1"):
        vivae.gym.film(out, frames=1)
    # The report animates it.
    page = vivae.report(out).read_text()
    assert all(f["image"] in page for f in few["frames"])


# A tiny LunarLander run with its film, stored for the program's browser test
# (crates/vivae/tests/it: the program cannot play Gymnasium to make one).
FIXTURE = Path(__file__).resolve().parents[2] / "crates/vivae/tests/data/gymnasium-run"
FIXTURE_FILES = ("config.toml", "generations.csv", "population.csv", "best-genomes.jsonl",
                 "champion.json", "validation.json", "film.json")


@box2d
def test_the_stored_gymnasium_run_is_what_vivae_gym_writes(tmp_path):
    """Rewrite it with VIVAE_WRITE_FIXTURES=1 (Gymnasium's pictures may change between versions)."""
    import vivae.gym

    out = tmp_path / "run"
    vivae.gym.evolve("LunarLander-v3", out, generations=3, population=8, seed=2, episodes=1,
                     validate=3, progress=False)
    vivae.gym.film(out, frames=12, width=100)
    if os.environ.get("VIVAE_WRITE_FIXTURES") == "1":
        FIXTURE.mkdir(parents=True, exist_ok=True)
        for name in FIXTURE_FILES:
            (FIXTURE / name).write_bytes((out / name).read_bytes())
    for name in FIXTURE_FILES:
        assert (FIXTURE / name).read_bytes() == (out / name).read_bytes(), \
            f"{name} differs: rewrite the fixture with VIVAE_WRITE_FIXTURES=1"


@pytest.mark.parametrize("env, obs_size, actions, kind", [
    pytest.param("Swimmer-v5", 8, 2, "continuous", marks=mujoco),
    pytest.param("LunarLander-v3", 8, 4, "discrete", marks=box2d),
    pytest.param("InvertedPendulum-v5", 4, 1, "continuous", marks=mujoco),
])
def test_a_champion_exports_to_the_networks_bits(tmp_path, env, obs_size, actions, kind):
    # A champion of any number of actions exports with one output per
    # action (discrete: the caller takes the largest; continuous: the caller
    # scales [-1, 1] to the action's bounds), to the network's bits.
    import vivae.gym
    from test_export import ONNX_BOUNDS, JsonController, onnx_steps

    out = tmp_path / "run"
    vivae.gym.evolve(env, out, generations=2, population=6, seed=1, episodes=1,
                     validate=0, progress=False)
    genome, _, _ = vivae.load_genome(out)
    assert (genome.num_inputs, genome.num_outputs) == (obs_size + 1, actions)
    # Observations as Gymnasium gives them, well outside [0, 1].
    obs = np.random.default_rng(5).normal(scale=3.0, size=(40, obs_size))
    want = vivae.Controllers([genome]).act(obs[:, :], np.zeros(len(obs), dtype=np.int64))
    assert want.shape == (len(obs), actions)
    inputs = np.hstack([obs, np.ones((len(obs), 1))])
    name = env.split("-")[0].lower()
    vivae.export(out, "json", tmp_path / f"{name}.json")
    doc = json.loads((tmp_path / f"{name}.json").read_text())
    assert doc["version"] == 4 and len(doc["net"]["outputs"]) == actions
    assert doc["outputs"].startswith(f"{actions} output") and f"{kind} action" in doc["outputs"], doc["outputs"]
    reader = JsonController(doc)
    got = np.array([reader.step(x) for x in inputs.tolist()])
    print(f"JSON reader, {env}: {int(np.sum(np.all(got == want, axis=1)))} of {len(want)} steps bit-equal to vivae")
    assert got.tobytes() == want.tobytes()
    vivae.export(out, "onnx", tmp_path / f"{name}.onnx")
    worst = float(np.max(np.abs(onnx_steps(tmp_path / f"{name}.onnx", inputs) - want)))
    print(f"onnxruntime vs vivae, {env}: largest difference {worst:.3e}")
    assert worst <= ONNX_BOUNDS[("exact", "recorded")]
    # The program exports it too (it cannot play the episodes, but needs not).
    cli = vivae_binary()
    if cli is None:
        pytest.skip("no vivae binary (set VIVAE_BIN)")
    done = subprocess.run([cli, "export", str(out), "--format", "c", "-o", str(tmp_path / f"{name}.c")],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    header = (tmp_path / f"{name}.h").read_text()
    assert f"#define VIVAE_OUTPUTS {actions}\n" in header and f"{kind} action" in header
