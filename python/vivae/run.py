"""Whole runs from Python: `evolve` writes a run as `vivae evolve` does; `replay` measures a champion."""

from __future__ import annotations

import os
from pathlib import Path
import sys
from typing import Any, Callable

from vivae import _vivae


class _TextBar:
    """A progress bar on stderr for when tqdm is not installed: redrawn in a
    terminal, one line per generation elsewhere (as the CLI prints)."""

    def __init__(self, total: int) -> None:
        self.total = total
        self.tty = sys.stderr.isatty()

    def update(self, r: dict) -> None:
        text = f"best {r['best']:.4f} mean {r['mean']:.4f} species {r['species']}"
        if self.tty:
            done = int(30 * r["generation"] / max(r["total"], 1))
            bar = "=" * done + " " * (30 - done)
            sys.stderr.write(f"\rgen {r['generation']}/{r['total']} [{bar}] {text}")
        else:
            sys.stderr.write(f"gen {r['generation']}/{r['total']} {text} best-ever {r['best_ever']:.4f}\n")
        sys.stderr.flush()

    def close(self) -> None:
        if self.tty:
            sys.stderr.write("\n")


class _TqdmBar:
    def __init__(self, total: int) -> None:
        from tqdm.auto import tqdm  # type: ignore[import-untyped]

        self.bar = tqdm(total=total, unit="gen", desc="evolve")

    def update(self, r: dict) -> None:
        self.bar.total = r["total"]
        self.bar.n = r["generation"]
        self.bar.set_postfix(best=f"{r['best']:.4f}", mean=f"{r['mean']:.4f}", species=r["species"])

    def close(self) -> None:
        self.bar.close()


def _bar(total: int):
    try:
        return _TqdmBar(total)
    except ImportError:
        return _TextBar(total)


def evolve(
    config: str | os.PathLike | None = None,
    out: str | os.PathLike | None = None,
    *,
    force: bool = False,
    progress: bool = True,
    on_generation: Callable[[dict], Any] | None = None,
    **overrides: Any,
) -> dict:
    """Runs the driving experiment and writes its run directory.

    The same run as ``vivae evolve [--config CONFIG] --out OUT [flags]``:
    with the same settings, ``config.toml``, ``scenario.svg``,
    ``generations.csv``, ``population.csv``, ``best-genomes.jsonl``,
    ``champion.json`` and ``checkpoints/`` are byte for byte the CLI's
    (``timing.csv`` holds wall times). The figures and ``report.html`` are
    drawn by :func:`report` (the program's code, built into this package); :func:`resume` continues an
    interrupted run or extends a finished one.

    Args:
        config: a config TOML file (default: the paper's settings).
        out: the new run directory (default ``runs/<timestamp>``).
        force: replace the vivae run already at ``out``: the new run is
            written beside it and swapped in, so a failure leaves the old one.
            Any other non-empty folder (files vivae did not write), the
            working directory, its parents and the home directory are
            refused with a ValueError.
        progress: show a progress bar (tqdm's, in a terminal or a
            notebook, when tqdm is installed; else a plain one on stderr).
        on_generation: called with each generation's record (a dict:
            generation, total, best, mean, median, worst, species,
            best_ever, seconds, robot_steps_per_second).
        **overrides: settings by the CLI's flag names: ``scenario`` (a path,
            a shipped name, or a list for several maps), ``generations``,
            ``population``, ``seed``, ``sensors="3x5"``, ``neurons="3x3"``,
            ``steps``, ``robots``, ``threads``, ``precision="fast"`` (the f32
            controller step), … (``vivae.OVERRIDES``);
            ``task="maze"`` runs Lehman & Stanley's maze (default
            ``hard-maze``) as ``vivae evolve --task maze`` does.

    Returns:
        A dict: ``out``, ``generations``, ``finished``, ``best``,
        ``champion_generation``, ``champion`` (a Genome), ``wall_s``; a maze
        run adds ``solved``, ``evals_to_solve`` (None unsolved) and
        ``evaluations``, the summary line's fields; a finished run of a task
        that validates its champion (a classic-control task) adds
        ``validation``, what it wrote to ``validation.json`` (the champion
        on 100 fresh episodes: ``mean``, ``std``, ``min``, ``max``,
        ``reward_threshold``, ``solved``…, :func:`vivae.gym.validate`'s keys).

    Raises:
        ValueError: bad settings, config, scenario (the CLI's one-line message).
        OSError: a file that cannot be read or written.
        KeyboardInterrupt: interrupted; the run stops after the current
            generation with a checkpoint (``vivae.resume(OUT)`` continues it).
    """
    total = overrides.get("generations")
    return _with_bar(
        progress, total if isinstance(total, int) else 0, on_generation,
        lambda each: _vivae.evolve(out=out, config=config, force=force, on_generation=each, **overrides),
    )


def _with_bar(progress: bool, total: int, on_generation, call) -> dict:
    """`call(each)` with `each` updating a progress bar (when `progress`) and calling `on_generation`."""
    bar = _bar(total) if progress else None

    def each(record: dict) -> None:
        if bar is not None:
            bar.update(record)
        if on_generation is not None:
            on_generation(record)

    try:
        return call(each)
    finally:
        if bar is not None:
            bar.close()


def resume(
    out: str | os.PathLike,
    *,
    generations: int | None = None,
    threads: int | None = None,
    progress: bool = True,
    on_generation: Callable[[dict], Any] | None = None,
    precision: str | None = None,
) -> dict:
    """Continues an interrupted run as ``vivae resume OUT [--generations N]`` does.

    The finished files are byte for byte those of an uninterrupted run (at
    any thread count); ``generations`` extends a finished run. ``precision``
    (``"exact"`` or ``"fast"``), when given, must be the one the run started
    with (its checkpoint records it); another is refused.

    Returns:
        The dict :func:`evolve` returns.

    Raises:
        ValueError: not a run, a damaged checkpoint, ``generations`` below
            the generations it already has, or another ``precision``.
        OSError: a file that cannot be read or written.
        KeyboardInterrupt: as in :func:`evolve`.
    """
    return _with_bar(
        progress, generations or 0, on_generation,
        lambda each: _vivae.resume(
            out, generations=generations, threads=threads, on_generation=each, precision=precision
        ),
    )


def report(out: str | os.PathLike) -> Path:
    """Draws a run's figures (``figures/``) and ``report.html``.

    What the ``vivae`` program draws at the end of ``vivae evolve`` (and
    ``vivae resume`` draws when they are missing or stale), by the same code
    built into this package: no separate program is needed. Changes no
    result file. A plain task's run (``task="cartpole"``) gets its curves
    alone; a run of another task that draws no figures (the maze) is refused.

    Returns:
        The path of ``report.html``.

    Raises:
        ValueError: ``out`` is not a run, or its task draws no figures.
        OSError: a file could not be read or written.
    """
    return Path(_vivae.report(out))


def replay(source: str | os.PathLike, **overrides: Any) -> dict:
    """Replays a champion as ``vivae replay SOURCE`` does, without the figure.

    Args:
        source: a run directory or a ``champion.json``.
        **overrides: ``scenario``, ``steps``, ``robots``, ``sensors``,
            ``neurons``, … as :func:`evolve` (another scenario drives all of
            its robots unless ``robots`` says otherwise); and
            ``placement_seed`` (as ``vivae replay --placement-seed``): the
            placement of a scenario's random obstacles and traffic (default 0);
            ``blind_rays=True`` (as ``vivae replay --blind-rays``): every
            distance ray reads "nothing in range" whatever is in front of it;
            ``meetings=True`` (as ``vivae replay --meetings``): the result also
            holds ``meetings``, a dict per robot's meeting with a block placed
            for the episode (the columns of ``meetings-pN.csv``).

    Returns:
        The episode's measures: ``fitness`` (px/step), ``on_road`` (fraction),
        ``speed`` (average speed in px/step, whatever the run's fitness),
        ``collisions`` (per 1,000 robot-steps), ``left_turns``,
        ``right_turns``, ``loops``, ``side`` (None off roads), and contacts
        by kind per 1,000 robot-steps: ``contacts_robot``,
        ``contacts_traffic`` (scripted robots), ``contacts_obstacle``,
        ``contacts_wall``, ``contacts_placed`` (the obstacles placed for the
        episode, also in ``contacts_obstacle``).
    """
    return _vivae.replay(source, **overrides)
