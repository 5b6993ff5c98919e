"""Gymnasium environments (Box2D, MuJoCo, any with a vector observation)
evolved as ordinary vivae runs, a whole generation at a time.

Each generation's genomes play all their episodes together: the
environments step in a Gymnasium vector environment (in this process, or
spread over worker processes with ``processes=N``), and one Rust call per
step activates every live episode's network (:class:`vivae.Controllers`).
The run directory is the one every vivae run writes (``config.toml`` with
its ``[gymnasium]`` section, ``generations.csv``, ``champion.json``,
``checkpoints/``): :func:`resume` continues it, :func:`vivae.report` (or
``vivae report RUN``) draws its curves.

>>> import vivae.gym
>>> result = vivae.gym.evolve("LunarLander-v3", out="runs/lander", generations=50, seed=1)
>>> result["validation"]["mean"], result["validation"]["solved"]
"""

from __future__ import annotations

import base64
import contextlib
import functools
import json
import multiprocessing
import os
import signal
import struct
import sys
import threading
import warnings
import zlib
from pathlib import Path
import time
from typing import Any, Callable, Sequence

import gymnasium
import numpy as np

from vivae import _vivae
from vivae.run import _with_bar

#: Episodes of the champion's validation, each reset with a fresh seed.
VALIDATION_EPISODES = 100

#: Gymnasium seeds of the validation episodes: 0, 1, 2, … (training resets
#: with 63-bit seeds hashed from each evaluation's seed, never these).
VALIDATION_FIRST_SEED = 0

#: The film of the champion's first validation episode: at most this many
#: frames, each at most this many pixels wide (report.html animates them).
FILM_FRAMES = 150
FILM_WIDTH = 240

# Worker processes of the run under way (set by `evolve` and `resume`).
_processes = 1
# Open vector environments, by (env id, episodes, processes); closed at a run's end.
_open: dict[tuple[str, int, int], "_Episodes"] = {}
# Seconds spent stepping environments and activating networks since `_reset_clock`.
_clock = {"env": 0.0, "vivae": 0.0, "steps": 0}


# Set by a Ctrl-C during a run or a validation (see `_ctrl_c_as_a_flag`).
_ctrl_c = False


def _on_ctrl_c(signum, frame) -> None:
    global _ctrl_c
    _ctrl_c = True
    # A second Ctrl-C raises at once, as Python's own handler does.
    signal.signal(signal.SIGINT, signal.default_int_handler)


def _stop_if_ctrl_c() -> None:
    """Raises KeyboardInterrupt if Ctrl-C was pressed since the last call."""
    global _ctrl_c
    if _ctrl_c:
        _ctrl_c = False
        raise KeyboardInterrupt


@contextlib.contextmanager
def _ctrl_c_as_a_flag():
    """Within it, Ctrl-C sets a flag that the episode loop and each
    generation's end turn into KeyboardInterrupt, instead of raising
    wherever Python happens to be. Python raises a signal's exception at
    the next bytecode, which may be a destructor's: pybox2d's
    ``b2BodyDef.__del__`` runs at every LunarLander and BipedalWalker reset,
    and an exception raised in a destructor is printed and dropped, so a
    Ctrl-C landing there was lost and the run went on (2 in 300 in a
    measurement). Only Python's own handler is replaced, and only in the
    main thread; a caller's handler, or SIGINT ignored, is left alone."""
    global _ctrl_c
    ours = (threading.current_thread() is threading.main_thread()
            and signal.getsignal(signal.SIGINT) is signal.default_int_handler)
    if not ours:
        yield
        return
    _ctrl_c = False
    signal.signal(signal.SIGINT, _on_ctrl_c)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    # A Ctrl-C after the last check still stops the caller, as it would have.
    _stop_if_ctrl_c()


def _reset_clock() -> None:
    _clock.update(env=0.0, vivae=0.0, steps=0)


def env_section(env_id: str, episodes: int = 3) -> dict:
    """The ``[gymnasium]`` section of a run of ``env_id``: its spaces give
    the networks' shape (observation values and a bias in; one output per
    discrete action or per continuous action dimension)."""
    env = gymnasium.make(env_id)
    try:
        obs, act = env.observation_space, env.action_space
        if not isinstance(obs, gymnasium.spaces.Box):
            raise ValueError(f"{env_id}: its observations are {obs}, not a vector (a Box)")
        if isinstance(act, gymnasium.spaces.Discrete):
            outputs = int(act.n)
        elif isinstance(act, gymnasium.spaces.Box):
            outputs = int(np.prod(act.shape))
            if not (np.all(np.isfinite(act.low)) and np.all(np.isfinite(act.high))):
                raise ValueError(f"{env_id}: its actions {act} are unbounded")
        else:
            raise ValueError(f"{env_id}: its actions are {act}, neither Discrete nor Box")
        spec = env.spec
        max_steps = spec.max_episode_steps if spec is not None else None
        if not max_steps:
            raise ValueError(f"{env_id}: it has no max_episode_steps (an episode might never end)")
        threshold = spec.reward_threshold if spec is not None else None
        return {
            "env": env_id,
            "episodes": int(episodes),
            "inputs": int(np.prod(obs.shape)) + 1,
            "outputs": outputs,
            "max_steps": int(max_steps),
            "reward_threshold": None if threshold is None else float(threshold),
        }
    finally:
        env.close()


def _shape(space: gymnasium.spaces.Space) -> tuple[int, ...]:
    """The shape of a space that has one (a Box, a Discrete's empty one)."""
    if space.shape is None:
        raise ValueError(f"{space}: a space without a shape")
    return space.shape


class _Chunk(gymnasium.Env):
    """Some of a batch's episodes, one environment each, as one Gymnasium
    environment: its observation holds every episode's observation, then
    the reward of its last step and whether it has ended; its action, every
    episode's. An ended episode stands still. Reset with
    ``options={"seeds": S}``: row ``r`` plays the episode of seed
    ``S[index][r]`` (none: the row stays ended)."""

    def __init__(self, env_id: str, rows: int, index: int) -> None:
        if multiprocessing.parent_process() is not None:
            # A worker of an AsyncVectorEnv. Ctrl-C reaches the terminal's whole
            # process group: a worker it interrupted mid-reply would leave the
            # run's process reading half a message for ever. The run's process
            # alone stops on it, at a checkpoint, and then stops the workers.
            signal.signal(signal.SIGINT, signal.SIG_IGN)
        self.envs = [gymnasium.make(env_id) for _ in range(rows)]
        self.index = index
        self.obs_size = int(np.prod(_shape(self.envs[0].observation_space)))
        act = self.envs[0].action_space
        self.discrete = isinstance(act, gymnasium.spaces.Discrete)
        self.action_shape = () if self.discrete else _shape(act)
        width = 1 if self.discrete else int(np.prod(self.action_shape))
        self.observation_space = gymnasium.spaces.Box(
            -np.inf, np.inf, shape=(rows, self.obs_size + 2), dtype=np.float64
        )
        self.action_space = gymnasium.spaces.Box(-np.inf, np.inf, shape=(rows, width), dtype=np.float64)
        self.state = np.zeros((rows, self.obs_size + 2))

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        if not options or "seeds" not in options:
            # A vector environment's own reset: nothing to play.
            return self.state.copy(), {}
        seeds = options["seeds"][self.index]
        self.state[:] = 0.0
        for r, env in enumerate(self.envs):
            s = seeds[r] if r < len(seeds) else None
            if s is None:
                self.state[r, -1] = 1.0
                continue
            obs, _ = env.reset(seed=int(s))
            self.state[r, : self.obs_size] = np.ravel(obs)
        return self.state.copy(), {}

    def step(self, action):
        for r, env in enumerate(self.envs):
            if self.state[r, -1]:
                self.state[r, -2] = 0.0
                continue
            a = int(action[r, 0]) if self.discrete else action[r].reshape(self.action_shape)
            obs, reward, terminated, truncated, _ = env.step(a)
            self.state[r, : self.obs_size] = np.ravel(obs)
            self.state[r, -2] = reward
            self.state[r, -1] = float(terminated or truncated)
        # The vector environment never resets a chunk itself: its rows end one by one.
        return self.state.copy(), 0.0, False, False, {}

    def close(self) -> None:
        for env in self.envs:
            env.close()


class _Episodes:
    """``episodes`` episodes of ``env_id`` played together: a Gymnasium vector
    environment of ``processes`` chunks (``SyncVectorEnv`` for one, else
    ``AsyncVectorEnv``, one worker process each)."""

    def __init__(self, env_id: str, episodes: int, processes: int) -> None:
        processes = max(1, min(processes, episodes))
        self.rows = -(-episodes // processes)
        self.episodes = episodes
        makers = [functools.partial(_Chunk, env_id, self.rows, i) for i in range(processes)]
        self.vec: gymnasium.vector.VectorEnv
        if processes == 1:
            self.vec = gymnasium.vector.SyncVectorEnv(makers)
        else:
            self.vec = gymnasium.vector.AsyncVectorEnv(makers, context="spawn" if os.name == "nt" else None)
        probe = gymnasium.make(env_id)
        act = probe.action_space
        probe.close()
        self.discrete = isinstance(act, gymnasium.spaces.Discrete)
        if isinstance(act, gymnasium.spaces.Box):
            self.low = np.ravel(act.low).astype(np.float64)
            self.span = np.ravel(act.high).astype(np.float64) - self.low

    def play(self, controllers, seeds: Sequence[int], rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Returns and steps of the episodes of ``seeds``, episode ``e``
        driven by network ``rows[e]`` of ``controllers``."""
        n, k = len(seeds), self.rows
        chunks = self.vec.num_envs
        table: list[list[int | None]] = [[None] * k for _ in range(chunks)]
        for e, s in enumerate(seeds):
            table[e // k][e % k] = int(s)
        t0 = time.process_time()
        state, _ = self.vec.reset(options={"seeds": table})
        env_s, vivae_s = time.process_time() - t0, 0.0
        d = state.shape[-1] - 2
        flat = state.reshape(chunks * k, d + 2)
        owner = np.full(chunks * k, -1, dtype=np.int64)
        owner[:n] = rows
        returns = np.zeros(n)
        steps = np.zeros(n)
        actions = np.zeros((chunks * k, _shape(self.vec.single_action_space)[-1]))
        live = np.flatnonzero(flat[:, -1] == 0.0)
        while live.size:
            _stop_if_ctrl_c()
            t0 = time.process_time()
            out = controllers.act(np.ascontiguousarray(flat[live, :d]), owner[live])
            if self.discrete:
                actions[live, 0] = np.argmax(out, axis=1)
            else:
                actions[live] = self.low + (np.clip(out, -1.0, 1.0) + 1.0) * 0.5 * self.span
            t1 = time.process_time()
            state, *_ = self.vec.step(actions.reshape(chunks, k, -1))
            t2 = time.process_time()
            vivae_s += t1 - t0
            env_s += t2 - t1
            flat = state.reshape(chunks * k, d + 2)
            returns[live] += flat[live, -2]
            steps[live] += 1
            _clock["steps"] += live.size
            live = live[flat[live, -1] == 0.0]
        _clock["env"] += env_s
        _clock["vivae"] += vivae_s
        return returns, steps

    def close(self, abort: bool = False) -> None:
        """Closes the environments; with ``abort`` (an exception is under way,
        which may have cut a message to or from a worker in half), ends the
        worker processes without talking to them."""
        processes = getattr(self.vec, "processes", None)
        if not abort or processes is None:
            self.vec.close()
            return
        for process in processes:
            if process.is_alive():
                process.terminate()
            process.join()
        for pipe in getattr(self.vec, "parent_pipes", []):
            if pipe is not None:
                pipe.close()
        # Nothing left for the vector environment's own close (or its finaliser) to do.
        self.vec.closed = True


def _episodes(env_id: str, episodes: int) -> _Episodes:
    key = (env_id, episodes, _processes)
    if key not in _open:
        # A batch of another size (a strategy whose batches vary): one open at a time.
        _close()
        _open[key] = _Episodes(env_id, episodes, _processes)
    return _open[key]


def _close(abort: bool = False) -> None:
    while _open:
        _open.popitem()[1].close(abort)


def _play(section: dict, genomes: list, seeds: list[list[int]]) -> list[tuple[float, float, float]]:
    """Evaluations of ``genomes``, genome ``i`` on the episodes of
    ``seeds[i]``: (mean return, worst return, steps) each. The player the
    Rust side calls once a generation."""
    per = section["episodes"]
    flat = [s for row in seeds for s in row]
    controllers = _vivae.Controllers([g for g in genomes for _ in range(per)])
    rows = np.arange(len(flat), dtype=np.int64)
    returns, steps = _episodes(section["env"], len(flat)).play(controllers, flat, rows)
    returns = returns.reshape(len(genomes), per)
    steps = steps.reshape(len(genomes), per)
    return [(float(r.mean()), float(r.min()), float(s.sum())) for r, s in zip(returns, steps)]


def _run(call, progress: bool, total: int, on_generation, processes: int) -> dict:
    global _processes
    if not isinstance(processes, int) or isinstance(processes, bool) or processes < 1:
        raise ValueError(f"processes={processes!r}: expected a positive integer")
    _processes = processes
    _reset_clock()

    def at_generation_end(record: dict) -> None:
        if on_generation is not None:
            on_generation(record)
        _stop_if_ctrl_c()

    try:
        with _ctrl_c_as_a_flag():
            result = _with_bar(progress, total, at_generation_end, call)
    except BaseException:
        _close(abort=True)
        raise
    _close()
    result["env_seconds"] = _clock["env"]
    result["vivae_seconds"] = _clock["vivae"]
    result["env_steps"] = _clock["steps"]
    return result


def evolve(
    env_id: str = "LunarLander-v3",
    out: str | os.PathLike | None = None,
    *,
    episodes: int = 3,
    processes: int = 1,
    validate: int = VALIDATION_EPISODES,
    config: str | os.PathLike | None = None,
    force: bool = False,
    progress: bool = True,
    on_generation: Callable[[dict], Any] | None = None,
    **overrides: Any,
) -> dict:
    """Evolves NEAT networks for the Gymnasium environment ``env_id`` and
    writes the run directory ``out`` (default ``runs/<timestamp>``).

    Args:
        env_id: a Gymnasium id with a vector observation and a Discrete or
            bounded Box action ("LunarLander-v3", "BipedalWalker-v3",
            "Hopper-v5", …).
        episodes: episodes per evaluation, each reset with a seed drawn
            from the evaluation's seed; fitness is their mean return.
        processes: worker processes the environments are spread over (1:
            all in this process). Results do not depend on it.
        validate: episodes of the champion's validation at the end (0: none).
        config: a config TOML file the settings start from.
        force, progress, on_generation: as :func:`vivae.evolve`.
        **overrides: ``generations``, ``population``, ``seed``,
            ``strategy`` (``"neat"``, ``"nsga2"``, …), ``threads``, … as
            :func:`vivae.evolve`.

    Returns:
        :func:`vivae.evolve`'s dict, with ``validation`` (see
        :func:`validate`), ``env_steps`` (steps of training episodes),
        ``env_seconds`` and ``vivae_seconds``: this process's CPU seconds
        stepping the environments (with ``processes=1``, their own cost;
        else sending and receiving) and activating the networks.
    """
    section = env_section(env_id, episodes)
    total = overrides.get("generations")
    result = _run(
        lambda each: _vivae.gym_evolve(
            section, out=out, config=config, force=force, on_generation=each, **overrides
        ),
        progress, total if isinstance(total, int) else 0, on_generation, processes,
    )
    if validate:
        result["validation"] = globals()["validate"](result["out"], episodes=validate, processes=processes)
    return result


def resume(
    out: str | os.PathLike,
    *,
    generations: int | None = None,
    processes: int = 1,
    validate: int = VALIDATION_EPISODES,
    progress: bool = True,
    on_generation: Callable[[dict], Any] | None = None,
) -> dict:
    """Continues the interrupted Gymnasium run in ``out`` (or extends a
    finished one to ``generations``), as :func:`evolve` ran it: the finished
    files are those of an uninterrupted run. Returns :func:`evolve`'s dict."""
    result = _run(
        lambda each: _vivae.gym_resume(out, generations=generations, on_generation=each),
        progress, generations or 0, on_generation, processes,
    )
    if validate:
        result["validation"] = globals()["validate"](out, episodes=validate, processes=processes)
    return result


def validate(
    source: str | os.PathLike,
    *,
    episodes: int = VALIDATION_EPISODES,
    processes: int = 1,
    film: bool = True,
) -> dict:
    """The champion of the Gymnasium run ``source`` on ``episodes`` fresh
    episodes (Gymnasium seeds 0, 1, …, never trained on), written to the
    run's ``validation.json``; with ``film``, the first of them rendered
    too (:func:`film`), for ``report.html`` to show.

    Returns:
        ``env``, ``episodes``, ``seeds`` (first and last), ``mean``, ``std``,
        ``min``, ``max`` of the returns, ``reward_threshold`` and ``solved``
        (the mean ≥ the threshold; None without one), ``generation`` and
        ``fitness`` of the champion.
    """
    section = _vivae.gym_section(source)
    genome, fitness, generation = _vivae.load_genome(source)
    seeds = list(range(VALIDATION_FIRST_SEED, VALIDATION_FIRST_SEED + episodes))
    player = _Episodes(section["env"], len(seeds), processes)
    try:
        controllers = _vivae.Controllers([genome] * len(seeds))
        with _ctrl_c_as_a_flag():
            returns, _ = player.play(controllers, seeds, np.arange(len(seeds), dtype=np.int64))
    except BaseException:
        player.close(abort=True)
        raise
    player.close()
    threshold = section["reward_threshold"]
    mean = float(returns.mean())
    result = {
        "env": section["env"],
        "episodes": len(seeds),
        "seeds": [seeds[0], seeds[-1]],
        "mean": mean,
        "std": float(returns.std()),
        "min": float(returns.min()),
        "max": float(returns.max()),
        "reward_threshold": threshold,
        "solved": None if threshold is None else mean >= threshold,
        "generation": generation,
        "fitness": fitness,
    }
    path = Path(source) / "validation.json"
    tmp = path.with_name(f".validation.json.tmp-{os.getpid()}")
    tmp.write_text(json.dumps(result, indent=2) + "\n")
    os.replace(tmp, path)
    if film:
        try:
            globals()["film"](source)
        except Exception as e:  # noqa: BLE001 - the validation stands without its film
            warnings.warn(f"{source}: no film of the champion's episode ({type(e).__name__}: {e}); "
                          f"for MuJoCo without a display, set MUJOCO_GL=egl", stacklevel=2)
    return result


def _png(rgb: np.ndarray) -> bytes:
    """``rgb`` (height × width × 3, uint8) as a PNG file, each row filtered
    by the one above (a rendered scene's flat areas then compress to little),
    with no dependency beyond zlib."""
    h, w, _ = rgb.shape
    rows = rgb.reshape(h, w * 3).astype(np.int16)
    up = np.empty_like(rows)
    up[0] = rows[0]
    up[1:] = rows[1:] - rows[:-1]
    filters = np.full((h, 1), 2, dtype=np.uint8)
    filters[0] = 0
    raw = np.hstack([filters, (up % 256).astype(np.uint8)]).tobytes()

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def _shrink(frame: np.ndarray, width: int) -> np.ndarray:
    """``frame`` made at most ``width`` pixels wide: the mean of each
    k × k block (k the smallest whole factor that fits)."""
    h, w, _ = frame.shape
    k = max(1, -(-w // width))
    h, w = h - h % k, w - w % k
    blocks = frame[:h, :w, :3].reshape(h // k, k, w // k, k, 3).astype(np.float64)
    return np.rint(blocks.mean(axis=(1, 3))).astype(np.uint8)


def film(
    source: str | os.PathLike,
    *,
    seed: int = VALIDATION_FIRST_SEED,
    frames: int = FILM_FRAMES,
    width: int = FILM_WIDTH,
) -> Path:
    """Renders the champion of the Gymnasium run ``source`` playing the
    episode of Gymnasium seed ``seed`` (the first validation episode) with
    ``render_mode="rgb_array"``, at most ``frames`` frames evenly spaced
    over it and at most ``width`` pixels wide, into the run's ``film.json``
    (PNG frames), which ``report.html`` animates beside the curves.

    Returns:
        The path of ``film.json``.
    """
    for name, value in (("frames", frames), ("width", width)):
        if not isinstance(value, int) or isinstance(value, bool) or value < 2:
            raise ValueError(f"{name}={value!r}: expected an integer of at least 2")
    section = _vivae.gym_section(source)
    genome, fitness, generation = _vivae.load_genome(source)
    controllers = _vivae.Controllers([genome])
    env = gymnasium.make(section["env"], render_mode="rgb_array")
    try:
        mujoco = type(env.unwrapped).__module__.startswith("gymnasium.envs.mujoco")
        if mujoco and sys.platform.startswith("linux") and not (os.environ.get("MUJOCO_GL") or os.environ.get("DISPLAY")):
            # Its default OpenGL (GLFW) aborts the whole process without a display.
            raise RuntimeError("MuJoCo renders through OpenGL and there is no display: "
                               "set MUJOCO_GL=egl (or osmesa) before Python starts")
        act = env.action_space
        discrete = isinstance(act, gymnasium.spaces.Discrete)
        if isinstance(act, gymnasium.spaces.Box):
            low = np.ravel(act.low).astype(np.float64)
            span = np.ravel(act.high).astype(np.float64) - low
            shape = _shape(act)

        def episode(keep):
            """Plays the episode, calling ``keep(step, reward, done)`` at its start and
            after each step; returns its steps."""
            obs, _ = env.reset(seed=int(seed))
            keep(0, 0.0, False)
            done, t = False, 0
            while not done:
                out = controllers.act(np.ascontiguousarray(np.ravel(obs), dtype=np.float64)[None, :])[0]
                a = int(np.argmax(out)) if discrete else (low + (np.clip(out, -1.0, 1.0) + 1.0) * 0.5 * span).reshape(shape)
                obs, reward, terminated, truncated, _ = env.step(a)
                t += 1
                done = terminated or truncated
                keep(t, float(reward), done)
            return t

        # Played once to learn its length, then again (the same episode:
        # the same seed and network) rendering the frames kept.
        steps = episode(lambda *_: None)
        every = max(1, -(-steps // (frames - 1)))
        kept: list[dict] = []
        owed = [0.0]

        def keep(t: int, reward: float, done: bool) -> None:
            owed[0] += reward
            if t % every == 0 or done:
                png = _png(_shrink(np.asarray(env.render()), width))
                kept.append({"step": t, "reward": owed[0],
                             "image": "data:image/png;base64," + base64.b64encode(png).decode("ascii")})
                owed[0] = 0.0

        again = episode(keep)
        if again != steps:
            raise RuntimeError(f"{section['env']}: the episode of seed {seed} took {steps} steps, then {again}")
    finally:
        env.close()
    # The size is the first PNG's own (its header, after the 8-byte signature and IHDR's length and kind).
    w, h = struct.unpack(">II", base64.b64decode(kept[0]["image"].split(",", 1)[1])[16:24])
    record = {
        "env": section["env"], "seed": int(seed), "generation": generation, "fitness": fitness,
        "width": w, "height": h, "every": every, "steps": steps,
        "return": float(sum(k["reward"] for k in kept)), "frames": kept,
    }
    path = Path(source) / "film.json"
    tmp = path.with_name(f".film.json.tmp-{os.getpid()}")
    tmp.write_text(json.dumps(record, separators=(",", ":")) + "\n")
    os.replace(tmp, path)
    return path
