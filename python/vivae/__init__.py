"""vivae: robots that learn to drive, from Python.

The ViVAE simulator as Gymnasium and PettingZoo environments, NEAT and
HyperNEAT driven ask/tell, and whole runs written byte for byte as the
``vivae`` command-line program writes them. Everything heavy runs in Rust
with the GIL released.

>>> import gymnasium, vivae
>>> env = gymnasium.make("vivae/Drive-v0", sensors="3x5")
>>> obs, info = env.reset(seed=0)
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import gymnasium

from vivae._vivae import (
    HOSTED_TASKS,
    OVERRIDES,
    STRATEGIES,
    TASKS,
    Controller,
    Controllers,
    DriveTask,
    Genome,
    Network,
    MapElites,
    NoveltySearch,
    Nsga2,
    Population,
    PredatorPreyTask,
    classic_episode,
    default_config,
    drive_image,
    export,
    load_genome,
    record_episode,
    reproduce,
    reproduce_packs,
    scenarios,
    tournament,
)
from vivae.envs import DriveEnv, DriveVectorEnv
from vivae.run import evolve, replay, report, resume

if TYPE_CHECKING:
    # Imported lazily at run time (by __getattr__ below): PettingZoo is optional.
    from vivae.parallel import DriveParallelEnv, PredatorPreyParallelEnv

__all__ = [
    "HOSTED_TASKS",
    "OVERRIDES",
    "STRATEGIES",
    "TASKS",
    "Controller",
    "Controllers",
    "DriveEnv",
    "DriveParallelEnv",
    "DriveTask",
    "DriveVectorEnv",
    "Genome",
    "MapElites",
    "Network",
    "NoveltySearch",
    "Nsga2",
    "Population",
    "PredatorPreyParallelEnv",
    "PredatorPreyTask",
    "classic_episode",
    "default_config",
    "drive_image",
    "export",
    "evolve",
    "load_genome",
    "record_episode",
    "replay",
    "report",
    "reproduce",
    "reproduce_packs",
    "resume",
    "scenarios",
    "tournament",
]

__version__ = "0.1.0"

if "vivae/Drive-v0" not in gymnasium.registry:
    gymnasium.register(
        id="vivae/Drive-v0",
        entry_point="vivae.envs:DriveEnv",
        vector_entry_point="vivae.envs:DriveVectorEnv",
    )


def __getattr__(name: str):
    # PettingZoo is optional: imported only when its environment is asked for.
    if name == "DriveParallelEnv":
        from vivae.parallel import DriveParallelEnv

        return DriveParallelEnv
    if name == "PredatorPreyParallelEnv":
        from vivae.parallel import PredatorPreyParallelEnv

        return PredatorPreyParallelEnv
    raise AttributeError(f"module 'vivae' has no attribute {name!r}")
