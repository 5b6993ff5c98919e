from vivae._vivae import (
    OVERRIDES as OVERRIDES,
    Controller as Controller,
    DriveTask as DriveTask,
    Genome as Genome,
    Network as Network,
    MapElites as MapElites,
    NoveltySearch as NoveltySearch,
    Nsga2 as Nsga2,
    Population as Population,
    default_config as default_config,
    drive_image as drive_image,
    export as export,
    load_genome as load_genome,
    record_episode as record_episode,
    scenarios as scenarios,
)
from vivae.envs import DriveEnv as DriveEnv, DriveVectorEnv as DriveVectorEnv
from vivae.parallel import DriveParallelEnv as DriveParallelEnv
from vivae.run import evolve as evolve, replay as replay, report as report, resume as resume

__version__: str
__all__ = [
    "OVERRIDES",
    "Controller",
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
    "default_config",
    "drive_image",
    "export",
    "evolve",
    "load_genome",
    "record_episode",
    "replay",
    "report",
    "resume",
    "scenarios",
]
