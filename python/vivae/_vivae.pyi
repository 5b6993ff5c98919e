"""Type stubs of the native module `vivae._vivae`."""

import os
from typing import Any, Callable, Optional, Sequence, Union, final

import numpy as np
import numpy.typing as npt

_Path = Union[str, os.PathLike]

__all__ = [
    "Controller",
    "Controllers",
    "DriveCore",
    "DriveTask",
    "Genome",
    "Network",
    "HOSTED_TASKS",
    "OVERRIDES",
    "STRATEGIES",
    "TASKS",
    "MapElites",
    "NoveltySearch",
    "Nsga2",
    "Population",
    "PredatorPreyCore",
    "PredatorPreyTask",
    "classic_episode",
    "default_config",
    "drive_image",
    "evolve",
    "export",
    "gym_episode_seeds",
    "gym_evolve",
    "gym_resume",
    "gym_section",
    "load_genome",
    "math_is_portable",
    "portable_math",
    "record_episode",
    "replay",
    "report",
    "reproduce",
    "reproduce_packs",
    "resume",
    "scenarios",
    "tournament",
]

OVERRIDES: list[str]
TASKS: list[str]
# The tasks whose episodes a host plays (the `vivae` program does not run them).
HOSTED_TASKS: list[str]
STRATEGIES: list[str]

@final
class DriveCore:
    """N copies of one driving world, stepped together."""

    def __new__(
        cls, num_worlds: int, config: Optional[_Path] = None, threads: int = 0, **overrides: Any
    ) -> DriveCore: ...
    @property
    def num_worlds(self) -> int: ...
    @property
    def robots(self) -> int: ...
    @property
    def obs_size(self) -> int: ...
    @property
    def max_steps(self) -> int: ...
    @property
    def threads(self) -> int: ...
    def reset(self, obs: npt.NDArray[np.float32], mask: Optional[Sequence[bool]] = None) -> None: ...
    def step(
        self,
        actions: npt.NDArray[np.float32],
        obs: npt.NDArray[np.float32],
        rewards: npt.NDArray[np.float64],
        truncated: npt.NDArray[np.bool_],
        autoreset: bool = True,
    ) -> None: ...
    def elapsed(self, index: int) -> int: ...
    def odometers(self, index: int) -> list[float]: ...
    def render(self, index: int = 0, scale: float = 1.0) -> npt.NDArray[np.uint8]: ...
    def run_random(self, steps: int, seed: int = 0) -> int: ...

@final
class PredatorPreyCore:
    """One predator-prey episode stepped a call at a time."""

    def __new__(cls, config: Optional[_Path] = None, **overrides: Any) -> PredatorPreyCore: ...
    @property
    def obs_size(self) -> int: ...
    @property
    def max_steps(self) -> int: ...
    @property
    def elapsed(self) -> int: ...
    def reset(self) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def step(
        self, hunter: tuple[float, float], prey: tuple[float, float]
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], float, float, bool, bool]: ...
    def distance(self) -> float: ...
    def outcome(self) -> dict[str, Any]: ...
    def render(self, scale: float = 1.0) -> npt.NDArray[np.uint8]: ...

@final
class Network:
    """A genome's network (feed-forward, or recurrent with state between calls)."""

    def activate(self, inputs: Sequence[float]) -> list[float]: ...
    def reset(self) -> None: ...
    @property
    def num_inputs(self) -> int: ...
    @property
    def num_outputs(self) -> int: ...

@final
class Genome:
    """A genome: a NEAT network's genes (for HyperNEAT, a CPPN)."""

    def network(self) -> Network: ...
    def to_json(self) -> str: ...
    @staticmethod
    def from_json(text: str, recurrent: bool = False) -> Genome: ...
    @property
    def recurrent(self) -> bool: ...
    @property
    def num_inputs(self) -> int: ...
    @property
    def num_outputs(self) -> int: ...
    @property
    def num_hidden(self) -> int: ...
    @property
    def num_links(self) -> int: ...

_Objective = tuple[Union[str, int], str]

class _AskTell:
    def ask(self) -> list[Genome]: ...
    def tell(
        self,
        fitnesses: Sequence[float],
        behaviours: Optional[Sequence[Sequence[float]]] = None,
        metrics: Optional[Sequence[Sequence[float]]] = None,
    ) -> None: ...
    @property
    def generation(self) -> int: ...
    @property
    def best_ever(self) -> Optional[tuple[Genome, float, int]]: ...
    @property
    def champion(self) -> Optional[tuple[Genome, float]]: ...
    def stats(self) -> dict[str, Any]: ...
    def to_json(self) -> str: ...

@final
class Population(_AskTell):
    """A NEAT population driven ask/tell."""

    def __new__(
        cls,
        inputs: int,
        outputs: int,
        *,
        seed: int = 1,
        size: Optional[int] = None,
        preset: str = "plain",
        recurrent: bool = False,
        params: Optional[dict[str, Any]] = None,
    ) -> Population: ...
    @staticmethod
    def from_json(text: str) -> Population: ...
    @property
    def size(self) -> int: ...

@final
class NoveltySearch(_AskTell):
    """Novelty search over a NEAT population (Lehman & Stanley 2011)."""

    def __new__(
        cls,
        inputs: int,
        outputs: int,
        *,
        seed: int = 1,
        size: Optional[int] = None,
        preset: str = "plain",
        recurrent: bool = False,
        params: Optional[dict[str, Any]] = None,
        novelty: Optional[dict[str, Any]] = None,
    ) -> NoveltySearch: ...
    @staticmethod
    def from_json(text: str) -> NoveltySearch: ...
    @property
    def archive(self) -> list[list[float]]: ...
    @property
    def threshold(self) -> float: ...
    @property
    def novelty(self) -> list[float]: ...

@final
class MapElites(_AskTell):
    """MAP-Elites over NEAT genomes (Mouret & Clune 2015), on a grid or a CVT."""

    def __new__(
        cls,
        inputs: int,
        outputs: int,
        *,
        lower: Sequence[float],
        upper: Sequence[float],
        bins: Optional[Sequence[int]] = None,
        cvt_cells: Optional[int] = None,
        cvt_samples: int = 100000,
        cvt_iterations: int = 10,
        seed: int = 1,
        preset: str = "plain",
        recurrent: bool = False,
        params: Optional[dict[str, Any]] = None,
        map: Optional[dict[str, Any]] = None,
    ) -> MapElites: ...
    @staticmethod
    def from_json(text: str) -> MapElites: ...
    @property
    def cells(self) -> int: ...
    def cell_of(self, behaviour: Sequence[float]) -> int: ...
    def elites(self) -> list[dict[str, Any]]: ...
    def archive_stats(self) -> dict[str, Any]: ...

@final
class Nsga2(_AskTell):
    """NSGA-II (Deb et al. 2002) over NEAT genomes, on fitness and metrics."""

    def __new__(
        cls,
        inputs: int,
        outputs: int,
        *,
        objectives: Sequence[_Objective],
        size: int = 100,
        crossover_probability: float = 0.5,
        seed: int = 1,
        preset: str = "plain",
        recurrent: bool = False,
        params: Optional[dict[str, Any]] = None,
    ) -> Nsga2: ...
    @staticmethod
    def from_json(text: str) -> Nsga2: ...
    def pareto_front(self) -> list[tuple[Genome, list[float], float]]: ...

@final
class Controller:
    """A decoded substrate driving robots from their readings."""

    def act(self, obs: npt.ArrayLike) -> npt.NDArray[np.float64]: ...
    def reset(self) -> None: ...

@final
class Controllers:
    """The networks of many genomes, activated together (one row each)."""

    def __new__(cls, genomes: Sequence[Genome]) -> Controllers: ...
    def __len__(self) -> int: ...
    @property
    def obs_size(self) -> int: ...
    @property
    def outputs(self) -> int: ...
    def act(
        self, obs: npt.NDArray[np.float64], rows: Optional[npt.NDArray[np.int64]] = None
    ) -> npt.NDArray[np.float64]: ...
    def reset(self, rows: Optional[Sequence[int]] = None) -> None: ...

@final
class DriveTask:
    """The driving task of a config: CPPNs evaluated, decoded, turned into controllers."""

    def __new__(cls, config: Optional[_Path] = None, **overrides: Any) -> DriveTask: ...
    @staticmethod
    def from_config_toml(text: str) -> DriveTask: ...
    def config_toml(self) -> str: ...
    @property
    def cppn_shape(self) -> tuple[int, int]: ...
    @property
    def robots(self) -> int: ...
    @property
    def steps(self) -> int: ...
    def population(
        self, seed: Optional[int] = None, size: Optional[int] = None, params: Optional[dict[str, Any]] = None
    ) -> Population: ...
    def evaluate(self, genomes: Sequence[Genome]) -> list[float]: ...
    def decode(self, genome: Genome) -> dict[str, Any]: ...
    def controller(self, genome: Genome, robots: int = 1) -> Controller: ...
    def episode(self, genome: Genome) -> dict[str, Any]: ...
    def save_champion(self, genome: Genome, path: _Path, fitness: float, generation: int = 1) -> None: ...

@final
class PredatorPreyTask:
    """The predator-prey task for two ask/tell populations: starting populations and meetings."""

    def __new__(cls, config: Optional[_Path] = None, **overrides: Any) -> PredatorPreyTask: ...
    @staticmethod
    def from_config_toml(text: str) -> PredatorPreyTask: ...
    def config_toml(self) -> str: ...
    @property
    def shape(self) -> tuple[int, int]: ...
    @property
    def steps(self) -> int: ...
    def population(
        self,
        side: str,
        seed: Optional[int] = None,
        size: Optional[int] = None,
        params: Optional[dict[str, Any]] = None,
    ) -> Population: ...
    def meet(self, hunter: Genome, prey: Genome) -> dict[str, Any]: ...
    def evaluate(self, side: str, genomes: Sequence[Genome], opponents: Sequence[Genome]) -> list[float]: ...

def evolve(
    out: Optional[_Path] = None,
    config: Optional[_Path] = None,
    force: bool = False,
    on_generation: Optional[Callable[[dict[str, Any]], Any]] = None,
    **overrides: Any,
) -> dict[str, Any]: ...
def resume(
    out: _Path,
    generations: Optional[int] = None,
    threads: Optional[int] = None,
    on_generation: Optional[Callable[[dict[str, Any]], Any]] = None,
    precision: Optional[str] = None,
) -> dict[str, Any]: ...
def report(out: _Path) -> str: ...
def replay(source: _Path, **overrides: Any) -> dict[str, Any]: ...
def load_genome(source: _Path) -> tuple[Genome, float, int]: ...
def scenarios() -> list[tuple[str, str]]: ...
def default_config() -> str: ...
def reproduce(
    name: str,
    runs: int | None = None,
    seed: int = 1,
    quick: bool = False,
    evaluations: int | None = None,
    threads: int = 0,
    progress: bool = False,
    methods: list[str] | None = None,
    journal: _Path | None = None,
) -> dict[str, Any]: ...
def reproduce_packs() -> list[tuple[str, str]]: ...
def tournament(
    a: _Path,
    b: _Path,
    threads: int | None = None,
    csv: _Path | None = None,
) -> list[dict[str, Any]]: ...
def export(
    source: _Path,
    format: str,
    out: _Path,
    *,
    generation: int | None = None,
    elite: int | None = None,
    front: int | None = None,
    sensors: str | None = None,
    neurons: str | None = None,
    precision: str | None = None,
    force: bool = False,
) -> list[str]: ...
def record_episode(
    source: _Path,
    *,
    robot: int = 0,
    steps: int | None = None,
    generation: int | None = None,
    elite: int | None = None,
    front: int | None = None,
    sensors: str | None = None,
    neurons: str | None = None,
    precision: str | None = None,
) -> dict[str, Any]: ...
def drive_image(
    source: _Path,
    frames: Sequence[_Path | Any],
    *,
    poses: Sequence[tuple[float, float, float]] | None = None,
    centre: tuple[float, float] | None = None,
    scale: float = 1.0,
    heading: float = 0.0,
    radius: float | None = None,
    generation: int | None = None,
    elite: int | None = None,
    front: int | None = None,
    sensors: str | None = None,
    neurons: str | None = None,
    precision: str | None = None,
) -> list[tuple[float, float]]: ...
def math_is_portable() -> bool: ...
def classic_episode(task: str, state: Sequence[float], actions: Sequence[float]) -> list[dict[str, Any]]:
    """The episode of classic-control task `task` from `state` (as Gymnasium's
    `env.unwrapped.state` holds it) under `actions`, until it terminates, is
    truncated or the actions run out: one dict a step (`state`, `observation`,
    `reward`, `terminated`, `truncated`)."""
def portable_math(function: str, x: float) -> float:
    """vivae's portable `sin` or `cos` of `x` (the bits its tasks compute)."""

def gym_evolve(
    env: dict[str, Any],
    out: Optional[_Path] = None,
    config: Optional[_Path] = None,
    force: bool = False,
    on_generation: Optional[Callable[[dict[str, Any]], Any]] = None,
    **overrides: Any,
) -> dict[str, Any]: ...
def gym_resume(
    out: _Path,
    generations: Optional[int] = None,
    on_generation: Optional[Callable[[dict[str, Any]], Any]] = None,
) -> dict[str, Any]: ...
def gym_episode_seeds(seeds: Sequence[int], episodes: int) -> list[list[int]]: ...
def gym_section(out: _Path) -> dict[str, Any]: ...
