"""Gymnasium environments: one robot (`DriveEnv`), N worlds at once (`DriveVectorEnv`)."""

from __future__ import annotations

from typing import Any

import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.vector.utils import batch_space

from vivae._vivae import DriveCore


def _core(num_worlds: int, robots: int, scenario, sensors, config, threads, overrides):
    settings = dict(overrides)
    if scenario is not None:
        if isinstance(scenario, (list, tuple)):
            # One world has one map: a list would silently drive the default one.
            raise TypeError(
                f"scenario: one scenario (a file or a shipped name) per environment, got a "
                f"{type(scenario).__name__} of {len(scenario)}; several training maps are for "
                "vivae.evolve and vivae.DriveTask (scenario=[...])"
            )
        settings["scenario"] = scenario
    if sensors is not None:
        settings["sensors"] = sensors
    if robots == 1 and settings.get("robots") is not None:
        # A world of these environments has one robot: another count would be dropped silently.
        given = settings["robots"]
        if isinstance(given, (bool, np.bool_)) or not isinstance(given, (int, np.integer)):
            raise TypeError(f"robots: expected an integer, got {type(given).__name__}")
        if given != 1:
            raise ValueError(
                f"robots={given}: expected 1 (one robot per world); "
                "vivae.DriveParallelEnv drives several robots in one world"
            )
    settings["robots"] = robots
    return DriveCore(num_worlds, config=config, threads=threads, **settings)


def _count(name: str, value: Any, lowest: int) -> int:
    """`value` as an int: a TypeError naming `name` for anything else, a
    ValueError naming the range for a negative one (the core checks the
    rest, with its own bounds)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name}: expected an integer, got {type(value).__name__}")
    if value < 0:
        raise ValueError(f"{name}={value}: expected an integer from {lowest} up")
    return int(value)


def _action(action: Any, shape: tuple[int, ...], dtype: Any = np.float32) -> np.ndarray:
    """`action` as `dtype` (float32 unless told) of `shape`: real numbers only (a string, None, a
    complex number or a bool is a TypeError), a wrong shape a ValueError."""
    try:
        given = np.asarray(action)
    except (TypeError, ValueError) as e:
        raise TypeError(f"action: expected real numbers of shape {shape}: {e}") from None
    if given.dtype.kind not in "iuf":
        raise TypeError(
            f"action: expected real numbers (float or int) of shape {shape}, got dtype {given.dtype}"
        )
    a = np.ascontiguousarray(given, dtype=dtype)
    if a.shape != shape:
        raise ValueError(f"action has shape {a.shape}, expected {shape}")
    return a


def _seed(seed: Any) -> int | None:
    """`reset(seed=)` as a Python int: None, or a non-negative integer (numpy's included)."""
    if seed is None:
        return None
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)):
        raise TypeError(f"seed: expected a non-negative integer or None, got {type(seed).__name__}")
    if seed < 0:
        raise ValueError(f"seed={seed}: expected a non-negative integer")
    return int(seed)


def _options(options: Any) -> dict:
    """`reset(options=)`: a dict or None."""
    if options is None:
        return {}
    if not isinstance(options, dict):
        raise TypeError(f"options: expected a dict or None, got {type(options).__name__}")
    return options


def _reset_mask(mask: Any, num_envs: int) -> list[bool] | None:
    """`options['reset_mask']`: None, or one bool per environment (a list,
    tuple or numpy array of bools); anything else is an error naming the key."""
    if mask is None:
        return None
    key = "options['reset_mask']"
    expected = f"{num_envs} bools (one per environment)"
    if isinstance(mask, (str, bytes, dict)) or not hasattr(mask, "__len__") or not hasattr(mask, "__iter__"):
        raise TypeError(f"{key}: expected {expected}, got {type(mask).__name__}")
    if len(mask) != num_envs:
        raise ValueError(f"{key}: {len(mask)} entries for {num_envs} environments")
    items = list(mask)
    for i, m in enumerate(items):
        if not isinstance(m, (bool, np.bool_)):
            raise TypeError(f"{key}[{i}]: expected a bool, got {type(m).__name__}")
    return [bool(m) for m in items]


def _render_mode(render_mode: Any) -> None:
    if render_mode is not None and render_mode != "rgb_array":
        raise ValueError(f"render_mode={render_mode!r}: expected 'rgb_array' or None")


class _PicklesBySettings:
    """Pickling by the arguments the object was made with: it is rebuilt,
    fresh (as after ``__init__``), in the process that unpickles it."""

    _init_args: dict[str, Any]
    render_mode: str | None
    render_scale: float

    def _keep_settings(self, **init_args: Any) -> None:
        """Checks ``render_mode`` and keeps the arguments ``__init__`` was
        called with (``render_mode`` and ``render_scale`` among them, which
        are also kept as attributes)."""
        _render_mode(init_args["render_mode"])
        self._init_args = init_args
        self.render_mode = init_args["render_mode"]
        self.render_scale = init_args["render_scale"]

    def __getstate__(self) -> dict[str, Any]:
        return {"init_args": self._init_args}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__init__(**state["init_args"])  # type: ignore[misc]


class DriveEnv(_PicklesBySettings, gymnasium.Env):
    """One robot driving on a ViVAE scenario.

    Observation: the robot's surface sensors (then its distance rays, with
    ``distance_rays=N``), each reading in [0, 1], float32. Action: the two
    wheel commands (left, right) in [-1, 1]. Reward: the distance driven in
    the step, px (an episode's rewards sum to the robot's odometer; their
    mean is the paper's fitness, average speed). ``truncated`` at the step
    limit (``steps=``, the paper's 1000); never ``terminated``.

    The simulator has no randomness: every reset puts the robot at the
    scenario's start, whatever the seed (the seed seeds ``np_random`` and
    the action space only). Pickles by its arguments (unpickled fresh, as
    after ``__init__``), so it crosses into ``multiprocessing`` and Ray workers.

    Args:
        scenario: a scenario SVG file, or the name of a shipped one
            (``vivae.scenarios()``); default the paper's road scenario.
        sensors: the surface-sensor grid as ``"RINGSxANGLES"`` (paper: ``"3x5"``).
        render_mode: ``"rgb_array"`` or None.
        config: a vivae config TOML file the settings start from.
        render_scale: pixels per px of the arena in rendered images.
        **overrides: further settings by the CLI's flag names
            (``steps``, ``distance_rays``, …; ``vivae.OVERRIDES``).
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 30}

    def __init__(
        self,
        scenario: str | None = None,
        sensors: str | None = "3x5",
        render_mode: str | None = None,
        config: str | None = None,
        render_scale: float = 0.5,
        **overrides: Any,
    ) -> None:
        self._keep_settings(
            scenario=scenario, sensors=sensors, render_mode=render_mode, config=config,
            render_scale=render_scale, **overrides,
        )
        self._core = _core(1, 1, scenario, sensors, config, 1, overrides)
        n = self._core.obs_size
        self.observation_space = spaces.Box(0.0, 1.0, shape=(n,), dtype=np.float32)
        self.action_space = spaces.Box(-1.0, 1.0, shape=(2,), dtype=np.float32)
        self.max_steps = self._core.max_steps
        self._obs = np.zeros((1, 1, n), dtype=np.float32)
        self._act = np.zeros((1, 1, 2), dtype=np.float32)
        self._rew = np.zeros((1, 1), dtype=np.float64)
        self._trunc = np.zeros(1, dtype=bool)

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        seed = _seed(seed)
        _options(options)
        super().reset(seed=seed)
        if seed is not None:
            self.action_space.seed(seed)
        self._core.reset(self._obs)
        return self._obs[0, 0].copy(), {"step": 0}

    def step(self, action):
        self._act[0, 0] = _action(action, (2,))
        self._core.step(self._act, self._obs, self._rew, self._trunc, autoreset=False)
        info = {"step": self._core.elapsed(0), "odometer": self._core.odometers(0)[0]}
        return self._obs[0, 0].copy(), float(self._rew[0, 0]), False, bool(self._trunc[0]), info

    def render(self):
        if self.render_mode == "rgb_array":
            return self._core.render(0, self.render_scale)
        return None


class DriveVectorEnv(_PicklesBySettings, gymnasium.vector.VectorEnv):
    """``num_envs`` worlds of one robot each, stepped together in Rust threads.

    The same environment as :class:`DriveEnv`, batched: observations
    (num_envs × readings, float32), rewards, terminations and truncations
    are numpy arrays, and one ``step`` call simulates every world in Rust
    (no Python object per robot per step). Episodes reset automatically in
    the step after they end (Gymnasium's next-step autoreset).

    Args:
        num_envs: number of worlds.
        threads: worker threads stepping them (0 = one per core).
        copy: return copies of the observation buffer (else the buffer itself,
            overwritten by the next call).
        The rest as :class:`DriveEnv`.
    """

    metadata = {
        "render_modes": ["rgb_array"],
        "render_fps": 30,
        "autoreset_mode": gymnasium.vector.AutoresetMode.NEXT_STEP,
    }

    def __init__(
        self,
        num_envs: int = 1,
        scenario: str | None = None,
        sensors: str | None = "3x5",
        render_mode: str | None = None,
        config: str | None = None,
        threads: int = 0,
        copy: bool = True,
        render_scale: float = 0.5,
        **overrides: Any,
    ) -> None:
        _render_mode(render_mode)
        num_envs, threads = _count("num_envs", num_envs, 1), _count("threads", threads, 0)
        self._keep_settings(
            num_envs=num_envs, scenario=scenario, sensors=sensors, render_mode=render_mode,
            config=config, threads=threads, copy=copy, render_scale=render_scale, **overrides,
        )
        self._core = _core(num_envs, 1, scenario, sensors, config, threads, overrides)
        n = self._core.obs_size
        self.num_envs = num_envs
        self.single_observation_space = spaces.Box(0.0, 1.0, shape=(n,), dtype=np.float32)
        self.single_action_space = spaces.Box(-1.0, 1.0, shape=(2,), dtype=np.float32)
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.action_space = batch_space(self.single_action_space, num_envs)
        self.copy = copy
        self.max_steps = self._core.max_steps
        self._obs = np.zeros((num_envs, 1, n), dtype=np.float32)
        self._rew = np.zeros((num_envs, 1), dtype=np.float64)
        self._trunc = np.zeros(num_envs, dtype=bool)
        self._term = np.zeros(num_envs, dtype=bool)

    def reset(self, *, seed: int | list[int] | None = None, options: dict | None = None):
        if isinstance(seed, (list, tuple)):
            if len(seed) != self.num_envs:
                raise ValueError(f"seed: a list of {len(seed)} seeds for {self.num_envs} environments")
            seeds = [_seed(x) for x in seed]
            first = seeds[0]
        else:
            first = _seed(seed)
        if first is not None:
            self._np_random, self._np_random_seed = gymnasium.utils.seeding.np_random(first)
            self.action_space.seed(first)
        mask = _reset_mask(_options(options).get("reset_mask"), self.num_envs)
        self._core.reset(self._obs, mask)
        obs = self._obs[:, 0]
        return (obs.copy() if self.copy else obs), {}

    def step(self, actions):
        a = _action(actions, (self.num_envs, 2)).reshape(self.num_envs, 1, 2)
        self._core.step(a, self._obs, self._rew, self._trunc)
        obs = self._obs[:, 0]
        rew = self._rew[:, 0]
        if self.copy:
            obs, rew = obs.copy(), rew.copy()
        return obs, rew, self._term.copy(), self._trunc.copy(), {}

    def render(self):
        if self.render_mode == "rgb_array":
            return tuple(self._core.render(i, self.render_scale) for i in range(self.num_envs))
        return None

    @property
    def threads(self) -> int:
        """Worker threads stepping the worlds."""
        return self._core.threads
