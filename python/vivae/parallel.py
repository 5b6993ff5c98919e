"""PettingZoo: every robot of a scenario, one agent each (`DriveParallelEnv`);
a hunter and a prey of the predator-prey task (`PredatorPreyParallelEnv`)."""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces
from pettingzoo import ParallelEnv  # type: ignore[import-untyped]

from vivae._vivae import PredatorPreyCore
from vivae.envs import _PicklesBySettings, _action, _core, _options, _seed


class DriveParallelEnv(_PicklesBySettings, ParallelEnv):
    """All robots of a scenario driving at once, one PettingZoo agent each.

    Agents are ``robot_0`` … ``robot_{n-1}`` in the scenario's order. Each
    observes its own sensors (float32 in [0, 1]), acts with its two wheel
    commands in [-1, 1] (an agent left out of the actions stands still) and
    is rewarded with the distance it drove in the step. All agents are
    truncated together at the step limit.

    Args:
        scenario, sensors, render_mode, config, render_scale, **overrides:
            as :class:`vivae.DriveEnv`.
        robots: how many of the scenario's robots drive (0 = all of them).
    """

    metadata = {"name": "vivae_drive_v0", "render_modes": ["rgb_array"], "is_parallelizable": True}

    def __init__(
        self,
        scenario: str | None = None,
        sensors: str | None = "3x5",
        robots: int = 0,
        render_mode: str | None = None,
        config: str | None = None,
        render_scale: float = 0.5,
        **overrides: Any,
    ) -> None:
        self._keep_settings(
            scenario=scenario, sensors=sensors, robots=robots, render_mode=render_mode,
            config=config, render_scale=render_scale, **overrides,
        )
        self._core = _core(1, robots, scenario, sensors, config, 1, overrides)
        n, r = self._core.obs_size, self._core.robots
        self.possible_agents = [f"robot_{i}" for i in range(r)]
        self.agents: list[str] = []
        self._index = {a: i for i, a in enumerate(self.possible_agents)}
        self._obs_space = spaces.Box(0.0, 1.0, shape=(n,), dtype=np.float32)
        self._act_space = spaces.Box(-1.0, 1.0, shape=(2,), dtype=np.float32)
        self.max_steps = self._core.max_steps
        self._obs = np.zeros((1, r, n), dtype=np.float32)
        self._act = np.zeros((1, r, 2), dtype=np.float32)
        self._rew = np.zeros((1, r), dtype=np.float64)
        self._trunc = np.zeros(1, dtype=bool)

    def observation_space(self, agent: str) -> spaces.Box:
        """Every agent's observation space (the same object each call)."""
        return self._obs_space

    def action_space(self, agent: str) -> spaces.Box:
        """Every agent's action space (the same object each call)."""
        return self._act_space

    def _observations(self) -> dict[str, np.ndarray]:
        return {a: self._obs[0, self._index[a]].copy() for a in self.agents}

    def reset(self, seed: int | None = None, options: dict | None = None):
        seed = _seed(seed)
        _options(options)
        if seed is not None:
            for i, a in enumerate(self.possible_agents):
                self._act_space.seed(seed + i)
        self.agents = list(self.possible_agents)
        self._core.reset(self._obs)
        return self._observations(), {a: {} for a in self.agents}

    def step(self, actions: dict[str, Any]):
        if not self.agents:
            # Before reset or after the episode ended the world does not move.
            raise RuntimeError("step: no live agents; call reset() first (the episode has ended or not begun)")
        self._act.fill(0.0)
        for agent, action in actions.items():
            if agent not in self._index:
                raise ValueError(f"no agent {agent!r}; the agents are {', '.join(self.possible_agents)}")
            self._act[0, self._index[agent]] = _action(action, (2,))
        self._core.step(self._act, self._obs, self._rew, self._trunc, autoreset=False)
        live = self.agents
        obs = self._observations()
        rewards = {a: float(self._rew[0, self._index[a]]) for a in live}
        done = bool(self._trunc[0])
        terminations = {a: False for a in live}
        truncations = {a: done for a in live}
        infos: dict[str, dict] = {a: {} for a in live}
        if done:
            self.agents = []
        return obs, rewards, terminations, truncations, infos

    def render(self):
        if self.render_mode == "rgb_array":
            return self._core.render(0, self.render_scale)
        return None

    def state(self) -> np.ndarray:
        """Every robot's readings, robot after robot."""
        return self._obs[0].reshape(-1).copy()

    def close(self) -> None:
        pass


class PredatorPreyParallelEnv(_PicklesBySettings, ParallelEnv):
    """The predator-prey task (``vivae evolve --task predator-prey``) as a
    PettingZoo parallel environment: a hunter and a prey in one arena.

    Agents are ``hunter_0`` and ``prey_0`` (a team's robots numbered from 0;
    the task's arenas have one of each). Each agent observes exactly the
    inputs the task's networks see, read by the Rust task itself: the
    opponent radar's four slices (left, ahead, right, behind; the slice
    holding the opponent reads 1 - d/diagonal), the six rangefinders
    (1 - d/100 px) and a bias of 1; float64 in [0, 1], shape (11,). Its
    action is the task's two outputs, (turn, forward), float64 in [0, 1]
    (0.5 = straight on and keep the speed; values outside are clamped, NaN
    is a ``ValueError``). Every live agent must act in every step.

    The episode ends at the catch (the hunter touches the prey: both agents
    ``terminated``) or after ``steps`` steps (both ``truncated``).

    Rewards: in a step that does not end the episode the hunter gets
    ``(1 - d)/T`` and the prey ``(1 + d)/T``, d the hunter-prey distance
    after the step as a share of the arena's diagonal and T = ``steps``;
    the final step gives each side its task fitness minus its rewards so
    far. So an episode's summed rewards are the task's fitnesses (to
    floating-point rounding): the hunter's ``2 - t/T`` after a catch
    at step t, else ``1 - mean d``; the prey's ``2 - hunter`` (constant-sum:
    the two sum to 2/T in each non-final step and to 2 over the episode).
    The last step's ``infos`` hold the exact figures (``fitness``) and
    ``caught``. Because observations and actions are float64, networks of
    the task's genomes driven from Python reproduce
    ``vivae.PredatorPreyTask.meet`` bit for bit.

    The simulator has no randomness: every reset puts both robots at the
    scenario's starts, whatever the seed (which seeds the action spaces).
    Pickles by its arguments.

    Args:
        scenario: the arena: ``"predator-prey"`` (default),
            ``"predator-prey-obstacles"`` or an SVG file with one robot of
            ``data-team="hunter"`` and one of ``data-team="prey"``.
        steps: steps per episode (the task's 500 by default).
        render_mode: ``"rgb_array"`` or None.
        config: a vivae config TOML file the settings start from.
        render_scale: pixels per px of the arena in rendered images.
        **overrides: further settings by the CLI's flag names.
    """

    metadata = {"name": "vivae_predator_prey_v0", "render_modes": ["rgb_array"], "is_parallelizable": True}

    def __init__(
        self,
        scenario: str | None = None,
        steps: int | None = None,
        render_mode: str | None = None,
        config: str | None = None,
        render_scale: float = 1.0,
        **overrides: Any,
    ) -> None:
        self._keep_settings(
            scenario=scenario, steps=steps, render_mode=render_mode, config=config,
            render_scale=render_scale, **overrides,
        )
        if isinstance(scenario, (list, tuple)):
            raise TypeError(
                f"scenario: one arena (a file or a shipped name), got a {type(scenario).__name__}"
            )
        settings = dict(overrides)
        if scenario is not None:
            settings["scenario"] = scenario
        if steps is not None:
            settings["steps"] = steps
        self._core = PredatorPreyCore(config=config, **settings)
        n = self._core.obs_size
        self.possible_agents = ["hunter_0", "prey_0"]
        self.agents: list[str] = []
        self._obs_space = spaces.Box(0.0, 1.0, shape=(n,), dtype=np.float64)
        self._act_spaces = {a: spaces.Box(0.0, 1.0, shape=(2,), dtype=np.float64) for a in self.possible_agents}
        self.max_steps = self._core.max_steps
        self._last: tuple[np.ndarray, np.ndarray] | None = None

    def observation_space(self, agent: str) -> spaces.Box:
        """Every agent's observation space (the same object each call)."""
        return self._obs_space

    def action_space(self, agent: str) -> spaces.Box:
        """The agent's action space, (turn, forward) in [0, 1] (one object per agent)."""
        if agent not in self._act_spaces:
            raise ValueError(f"no agent {agent!r}; the agents are {', '.join(self.possible_agents)}")
        return self._act_spaces[agent]

    def reset(self, seed: int | None = None, options: dict | None = None):
        seed = _seed(seed)
        _options(options)
        if seed is not None:
            for i, a in enumerate(self.possible_agents):
                self._act_spaces[a].seed(seed + i)
        self.agents = list(self.possible_agents)
        hunter, prey = self._core.reset()
        self._last = (hunter, prey)
        infos = {a: {"step": 0, "distance": self._core.distance()} for a in self.agents}
        return {"hunter_0": hunter.copy(), "prey_0": prey.copy()}, infos

    def step(self, actions: dict[str, Any]):
        if not self.agents:
            # Before reset or after the episode ended the world does not move.
            raise RuntimeError("step: no live agents; call reset() first (the episode has ended or not begun)")
        if not isinstance(actions, dict):
            raise TypeError(f"actions: expected a dict of agent -> action, got {type(actions).__name__}")
        for agent in actions:
            if agent not in self.possible_agents:
                raise ValueError(f"no agent {agent!r}; the agents are {', '.join(self.possible_agents)}")
        missing = [a for a in self.agents if a not in actions]
        if missing:
            raise ValueError(f"actions: none for {', '.join(missing)}; every live agent acts in every step")
        h = _action(actions["hunter_0"], (2,), np.float64)
        p = _action(actions["prey_0"], (2,), np.float64)
        hunter, prey, rh, rp, caught, over = self._core.step(
            (float(h[0]), float(h[1])), (float(p[0]), float(p[1]))
        )
        self._last = (hunter, prey)
        live = self.agents
        obs = {"hunter_0": hunter.copy(), "prey_0": prey.copy()}
        rewards = {"hunter_0": rh, "prey_0": rp}
        terminations = {a: bool(caught) for a in live}
        truncations = {a: bool(over and not caught) for a in live}
        step = self._core.elapsed
        distance = self._core.distance()
        infos: dict[str, dict] = {a: {"step": step, "distance": distance} for a in live}
        if over:
            outcome = self._core.outcome()
            for a, side in (("hunter_0", "hunter"), ("prey_0", "prey")):
                infos[a].update(
                    caught=outcome["caught"],
                    fitness=outcome[f"{side}_fitness"],
                    mean_distance=outcome["mean_distance"],
                )
            self.agents = []
        return obs, rewards, terminations, truncations, infos

    def render(self):
        if self.render_mode == "rgb_array":
            return self._core.render(self.render_scale)
        return None

    def state(self) -> np.ndarray:
        """Both agents' observations, the hunter's first (zeros before the first reset)."""
        if self._last is None:
            return np.zeros(2 * self._core.obs_size, dtype=np.float64)
        return np.concatenate(self._last)

    def close(self) -> None:
        pass
