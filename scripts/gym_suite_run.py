"""One run of the Gymnasium suite (scripts/gym-suite.sh), brought to its end
whatever state an earlier, killed session left it in:

- finished (``validation.json`` written after its last generation): skipped;
- killed during the validation: validated again;
- interrupted mid-run (a checkpoint): continued by ``vivae.gym.resume``,
  whose files are byte for byte those of an uninterrupted run;
- killed before its first checkpoint: started again (``force``);
- absent: started by ``vivae.gym.evolve``.

Each generation's CPU seconds (this process's, environments and networks
alike with ``processes=1``) go to ``cpu/<run>.csv`` beside the run, for the
table's CPU time to the champion; a generation played again after a resume
replaces its row, so the file holds the CPU of one uninterrupted run.

    python scripts/gym_suite_run.py ENV SEED OUT GENERATIONS POPULATION EPISODES [CONFIG]

CONFIG (a whole config TOML file: a Gymnasium run's config.toml with a line
changed, e.g. ``target_species = 10`` added under ``[neat]``) is what a new
run's settings start from; a resumed run keeps its own.
"""

import csv
import os
import sys
import time
from pathlib import Path

import vivae.gym


def last_generation(run: Path) -> int:
    """The last generation in the run's ``generations.csv`` (0: none)."""
    path = run / "generations.csv"
    if not path.exists():
        return 0
    with path.open() as f:
        rows = list(csv.DictReader(f))
    return int(rows[-1]["generation"]) if rows else 0


class CpuLog:
    """``cpu/<run>.csv``: generation, CPU seconds of that generation."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.rows: dict[str, float] = {}
        if path.exists():
            with path.open() as f:
                for row in csv.DictReader(f):
                    self.rows[row["generation"]] = float(row["cpu_seconds"])
        self.mark = time.process_time()

    def lap(self, generation: str) -> None:
        now = time.process_time()
        self.rows[generation] = now - self.mark
        self.mark = now
        self.write()

    def write(self) -> None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        tmp = self.path.with_name(f".{self.path.name}.tmp-{os.getpid()}")
        with tmp.open("w") as f:
            f.write("generation,cpu_seconds\n")
            numbered = sorted((int(g), s) for g, s in self.rows.items() if g.isdigit())
            for g, s in numbered:
                f.write(f"{g},{s:.3f}\n")
            if "validation" in self.rows:
                f.write(f"validation,{self.rows['validation']:.3f}\n")
        os.replace(tmp, self.path)


def main() -> int:
    if len(sys.argv) not in (7, 8):
        print(__doc__.strip().splitlines()[-1].strip(), file=sys.stderr)
        return 2
    env, out = sys.argv[1], sys.argv[3]
    seed, generations, population, episodes = (int(a) for a in (sys.argv[2], *sys.argv[4:7]))
    config = sys.argv[7] if len(sys.argv) == 8 and sys.argv[7] else None
    run = Path(out) / f"{env}-seed-{seed}"
    log = CpuLog(Path(out) / "cpu" / f"{run.name}.csv")
    each = lambda record: log.lap(str(record["generation"]))  # noqa: E731
    done = last_generation(run)
    checkpoints = sorted((run / "checkpoints").glob("gen-*.ckpt")) if run.exists() else []
    if done >= generations and (run / "validation.json").exists():
        print(f"{run.name}: finished ({done} generations), skipped", flush=True)
        return 0
    if done >= generations:
        what = "validated again"
        vivae.gym.validate(run)
        log.lap("validation")
    elif checkpoints:
        what = f"resumed after generation {done}"
        # A generation's CPU is counted from its start: the resume's own set-up goes to the first.
        vivae.gym.resume(run, generations=generations, processes=1, validate=0,
                         progress=False, on_generation=each)
        vivae.gym.validate(run)
        log.lap("validation")
    else:
        what = "started" if not run.exists() else "started again (killed before its first checkpoint)"
        vivae.gym.evolve(env, out=run, generations=generations, population=population, seed=seed,
                         episodes=episodes, config=config, processes=1, validate=0, force=run.exists(),
                         progress=False, on_generation=each)
        vivae.gym.validate(run)
        log.lap("validation")
    print(f"{run.name}: {what}, finished", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
