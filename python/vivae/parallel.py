"""PettingZoo: every robot of a scenario, one agent each."""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces
from pettingzoo import ParallelEnv  # type: ignore[import-untyped]

from vivae.envs import _PicklesBySettings, _action, _core, _options, _render_mode, _seed


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
        _render_mode(render_mode)
        self._init_args = dict(
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
        self.render_mode = render_mode
        self.render_scale = render_scale
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
