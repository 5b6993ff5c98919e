"""The Gymnasium suite's table (scripts/gym-suite.sh) as Markdown, from the
runs under OUT: each run's ``config.toml`` (budget), ``generations.csv``
(progress), ``validation.json`` (the champion on 100 fresh episodes) and
the suite's ``cpu/<run>.csv`` (CPU seconds per generation).

    python scripts/gym_suite_table.py OUT > table.md      (Python 3.11 or later, with vivae)

One row per environment (seeds solved, validated means, the best), then one
per run: the champion's generation, the evaluations and CPU seconds it took
to reach it. A run without ``validation.json`` is listed as not finished,
with the generations it has played.
"""

import csv
import json
import re
import sys
import tomllib
from pathlib import Path

from vivae import _vivae

ORDER = ["InvertedPendulum-v5", "InvertedDoublePendulum-v5", "LunarLander-v3", "Swimmer-v5",
         "HalfCheetah-v5", "Hopper-v5", "BipedalWalker-v3"]


def rows_of(path: Path) -> list[dict]:
    if not path.exists():
        return []
    with path.open() as f:
        return list(csv.DictReader(f))


def run_record(run: Path, out: Path) -> dict:
    config = tomllib.loads((run / "config.toml").read_text())
    # A run's config.toml leaves out settings at their defaults (a LunarLander-v3
    # run of 3 episodes has no [gymnasium] section): vivae reads them back whole.
    config["gymnasium"] = _vivae.gym_section(str(run))
    gens = rows_of(run / "generations.csv")
    cpu = {r["generation"]: float(r["cpu_seconds"]) for r in rows_of(out / "cpu" / f"{run.name}.csv")}
    validation = None
    if (run / "validation.json").exists():
        validation = json.loads((run / "validation.json").read_text())
    played = int(gens[-1]["generation"]) if gens else 0
    budget = int(config["experiment"]["generations"])
    population = int(config["neat"]["population_size"])
    episodes = int(config["gymnasium"]["episodes"])
    finished = validation is not None and played >= budget
    champion = validation["generation"] if validation else None
    numbered = {int(g): s for g, s in cpu.items() if g.isdigit()}
    return {
        "env": config["gymnasium"]["env"],
        "seed": int(config["experiment"]["seed"]),
        "threshold": config["gymnasium"].get("reward_threshold"),
        "budget": budget, "population": population, "episodes": episodes,
        "played": played, "finished": finished, "validation": validation if finished else None,
        "champion": champion,
        # Generation g's genomes are the g-th population evaluated: g × population evaluations.
        "evaluations": champion * population if champion else None,
        "cpu_to_champion": sum(s for g, s in numbered.items() if g <= champion) if champion and numbered else None,
        "cpu": sum(numbered.values()) + cpu.get("validation", 0.0) if numbered else None,
        "cpu_complete": bool(numbered) and all(g in numbered for g in range(1, played + 1)),
    }


def fmt(x: float | None, digits: int = 1) -> str:
    return "–" if x is None else f"{x:.{digits}f}"


def table(out: Path) -> str:
    runs = [run_record(r, out) for r in out.iterdir() if r.is_dir() and re.search(r"-seed-\d+$", r.name)
            and (r / "config.toml").exists()]
    envs = sorted({r["env"] for r in runs}, key=lambda e: (ORDER.index(e) if e in ORDER else len(ORDER), e))
    lines = ["| environment | threshold | budget per seed | seeds solved / finished | validated mean per seed | best | not finished |",
             "|---|---|---|---|---|---|---|"]
    for env in envs:
        mine = sorted((r for r in runs if r["env"] == env), key=lambda r: r["seed"])
        done = [r for r in mine if r["finished"]]
        solved = [r for r in done if r["validation"]["solved"]]
        budgets = sorted({(r["budget"], r["population"], r["episodes"]) for r in mine})
        budget = "; ".join(f"{g} generations of {p}, {e} episodes" for g, p, e in budgets)
        means = ", ".join(f"{r['seed']}: {r['validation']['mean']:.1f}" for r in done) or "–"
        best = max((r["validation"]["mean"] for r in done), default=None)
        pending = ", ".join(f"{r['seed']} ({r['played']}/{r['budget']})" for r in mine if not r["finished"]) or "–"
        lines.append(f"| {env} | {fmt(mine[0]['threshold'], 0)} | {budget} | {len(solved)} / {len(done)} | "
                     f"{means} | {fmt(best)} | {pending} |")
    lines += ["", "| run | validated mean ± std | solved | champion's generation | training fitness | "
              "evaluations to the champion | CPU s to the champion | CPU s of the run |",
              "|---|---|---|---|---|---|---|---|"]
    for env in envs:
        for r in sorted((r for r in runs if r["env"] == env), key=lambda r: r["seed"]):
            v = r["validation"]
            if v is None:
                lines.append(f"| {env} seed {r['seed']} | not finished ({r['played']} of {r['budget']} generations) "
                             f"| | | | | | |")
                continue
            cpu_note = "" if r["cpu_complete"] else " (part)"
            lines.append(
                f"| {env} seed {r['seed']} | {v['mean']:.1f} ± {v['std']:.1f} | {'yes' if v['solved'] else 'no'} | "
                f"{v['generation']} | {v['fitness']:.1f} | {r['evaluations']} | "
                f"{fmt(r['cpu_to_champion'], 0)}{cpu_note} | {fmt(r['cpu'], 0)}{cpu_note} |")
    return "\n".join(lines) + "\n"


def main() -> int:
    if len(sys.argv) != 2 or not Path(sys.argv[1]).is_dir():
        print("usage: python scripts/gym_suite_table.py OUT (the suite's run folder)", file=sys.stderr)
        return 2
    sys.stdout.write(table(Path(sys.argv[1])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
