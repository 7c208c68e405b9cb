#!/usr/bin/python3
"""plot_postpro.py -- the POSTPRO series and the overlap series of a run, against time, to a PNG.

Reads a steps.csv or cycles.csv (or the output directory that holds one) of `deposit`, `ballast`
or `datbox_run` and draws one panel per group of columns that the file has (docs/output.md,
"Time series: the POSTPRO columns"):
  energy      kinetic_energy, contact_dissipation, damper_dissipation (J/m)
  network     coordination_number, sliding_share
  shares      strong_force_share, weak_force_share
  points      strong_contacts, weak_contacts
  overlap     mean_overlap, max_overlap (m, log scale)
  solver      sweeps
The x axis is `time` when the file has it, else `cycle`, else `step`. A group none of whose
columns is in the file is left out (and said so); a file with none of them is an error.

Examples
  contrib/plots/plot_postpro.py out/deposit -o deposit_postpro.png
  contrib/plots/plot_postpro.py out/ballast/cycles.csv -o cycles.png
  contrib/plots/plot_postpro.py out/datbox_disks --every 10

Needs python3 and matplotlib (Debian: apt-get install python3-matplotlib; pip: pip install
matplotlib); without matplotlib it says so and exits with status 3.
"""
import argparse
import csv
import math
import os
import sys

GROUPS = (
    ("energy (J/m)", ("kinetic_energy", "contact_dissipation", "damper_dissipation"), False),
    ("network", ("coordination_number", "sliding_share"), False),
    ("force shares", ("strong_force_share", "weak_force_share"), False),
    ("strong / weak points", ("strong_contacts", "weak_contacts"), False),
    ("overlap (m)", ("mean_overlap", "max_overlap"), True),
    ("sweeps per step", ("sweeps",), False),
)
AXES = ("time", "cycle", "step")


def fail(message, status=2):
    print(f"plot_postpro.py: error: {message}", file=sys.stderr)
    sys.exit(status)


def resolve(path):
    if os.path.isdir(path):
        for name in ("steps.csv", "cycles.csv"):
            if os.path.isfile(os.path.join(path, name)):
                return os.path.join(path, name)
        fail(f"directory '{path}' has neither steps.csv nor cycles.csv")
    if not os.path.isfile(path):
        fail(f"no such file: '{path}'")
    return path


def read_columns(path, every):
    """{column: [floats]} of every `every`-th row; a cell that is not a number reads as nan."""
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = [h.strip() for h in next(reader, [])]
        if not header:
            fail(f"'{path}' is empty")
        data = {h: [] for h in header}
        for i, row in enumerate(reader):
            if i % every or len(row) != len(header):
                continue
            for h, v in zip(header, row):
                try:
                    data[h].append(float(v))
                except ValueError:
                    data[h].append(math.nan)
    return data


def import_pyplot():
    try:
        import matplotlib
    except ImportError:
        fail("matplotlib is not installed for " + sys.executable +
             " (Debian: apt-get install python3-matplotlib; pip: pip install matplotlib)", 3)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("input", help="steps.csv, cycles.csv or the run's output directory")
    p.add_argument("-o", "--output", default="postpro.png", help="the PNG to write (default postpro.png)")
    p.add_argument("--every", type=int, default=1, help="plot every N-th row (default 1)")
    a = p.parse_args()
    if a.every < 1:
        fail("--every must be >= 1")
    path = resolve(a.input)
    data = read_columns(path, a.every)
    axis = next((c for c in AXES if c in data), None)
    if axis is None:
        fail(f"'{path}' has no column {', '.join(AXES)} for the x axis")
    panels = [(title, [c for c in cols if c in data], log) for title, cols, log in GROUPS]
    for title, cols, _ in panels:
        if not cols:
            print(f"plot_postpro.py: note: '{path}' has no {title} column, panel left out")
    panels = [x for x in panels if x[1]]
    if not panels:
        fail(f"'{path}' has none of the POSTPRO or overlap columns (docs/output.md)")
    plt = import_pyplot()
    fig, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(8, 2.2 * len(panels)), squeeze=False)
    for ax, (title, cols, log) in zip(axes[:, 0], panels):
        log = log and any(y > 0 for c in cols for y in data[c])  # all zero: a linear axis shows it
        for c in cols:
            ys = data[c]
            if log:
                ys = [y if y > 0 else math.nan for y in ys]  # a log axis cannot show 0
            ax.plot(data[axis], ys, label=c, linewidth=1)
        if log:
            ax.set_yscale("log")
        ax.set_ylabel(title)
        ax.legend(fontsize=7, loc="best")
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel(axis + (" (s)" if axis == "time" else ""))
    fig.suptitle(os.path.relpath(path), fontsize=9)
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)
    print(f"plot_postpro.py: wrote {a.output} ({len(panels)} panels, {len(data[axis])} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
