"""Species over generations for several `target_species` values (issue 23).

Reads the stderr of the xor / parity / pole examples run with their trace
variable set (XOR_TRACE, PARITY_TRACE, POLE_TRACE print one `GenerationStats
{ ... }` line per generation, then one `NAME seed=... evals=...` line per run)
and draws the mean species count and compatibility threshold over generations,
one column per task, one line per target. Runs stop when solved, so each mean
is over the runs still going at that generation.

    python species.py OUT.png TASK:TARGET:FILE.err [TASK:TARGET:FILE.err ...]

(an underscore in TASK is shown as a space; TARGET `null` is the fixed threshold)

Needs matplotlib.
"""

import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STATS = re.compile(r"species: (\d+), compatibility_threshold: ([0-9.e+-]+)")


def runs(path):
    """Per run, the list of (species, threshold) per generation."""
    out, cur = [], []
    with open(path) as f:
        for line in f:
            m = STATS.search(line)
            if m:
                cur.append((int(m.group(1)), float(m.group(2))))
            elif " seed=" in line:
                out.append(cur)
                cur = []
    return out


def mean_series(rs, k):
    """Mean of field k over the runs still going, and how many are."""
    n = max((len(r) for r in rs), default=0)
    xs, ys = [], []
    for g in range(n):
        vals = [r[g][k] for r in rs if len(r) > g]
        if len(vals) * 4 < len(rs):  # fewer than a quarter left: too noisy
            break
        xs.append(g)
        ys.append(sum(vals) / len(vals))
    return xs, ys


def color(target):
    """A fixed colour per target count."""
    known = ["5", "10", "20", "40"]
    return f"C{known.index(target)}" if target in known else f"C{4 + int(target) % 5}"


def main():
    out = sys.argv[1]
    series = {}
    for spec in sys.argv[2:]:
        task, target, path = spec.split(":", 2)
        series.setdefault(task, []).append((target, runs(path)))
    tasks = list(series)
    fig, axes = plt.subplots(2, len(tasks), figsize=(4.2 * len(tasks), 6.4), squeeze=False)
    for col, task in enumerate(tasks):
        for target, rs in series[task]:
            label = "fixed threshold" if target == "null" else f"target {target}"
            # The same colour for a target in every column.
            style = {"color": "k", "ls": "--"} if target == "null" else {"color": color(target)}
            for row in range(2):
                xs, ys = mean_series(rs, row)
                axes[row][col].plot(xs, ys, label=f"{label} ({len(rs)} runs)", **style)
        axes[0][col].set_title(task.replace("_", " "))
        axes[0][col].set_ylabel("species (mean over running runs)")
        axes[1][col].set_ylabel("compatibility threshold")
        axes[1][col].set_xlabel("generation")
        axes[0][col].legend(fontsize=7)
        axes[0][col].set_yscale("log")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
